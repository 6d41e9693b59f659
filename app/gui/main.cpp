// skein-gui: the artist's app (label, tessellate, paint stitches, tile patterns, relax and look).
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>

#include "common/cpu_threads.hpp"
#include "main_window.hpp"
#include "skein/config.hpp"

int main(int argc, char** argv) {
  skein::wait_passively(argv);  // issue 28: relaxations steady beside other work
  skein::follow_free_cores(true);
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  format.setSamples(4);
  QSurfaceFormat::setDefaultFormat(format);

  QApplication app(argc, argv);
  QApplication::setApplicationName("skein-gui");
  QApplication::setApplicationVersion(SKEIN_VERSION);
  QCommandLineParser parser;
  parser.setApplicationDescription("skein-gui: label a garment mesh, tessellate it into stitches, paint them and relax the yarn.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("FILE", "a mesh (OBJ, PLY, glTF, FBX, ...) or a .skein project to open");
  parser.process(app);

  skein::gui::MainWindow window;
  window.show();
  if (!parser.positionalArguments().isEmpty()) window.open_file(parser.positionalArguments().front());
  return QApplication::exec();
}

// skein-gui workflows, driven the way a user drives them: actions, clicks and drags in the 3D view. Runs under
// xvfb-run (QOpenGLWidget needs a real GL display; Qt's offscreen platform cannot host it). Each stage saves
// a screenshot to $SKEIN_GUI_SHOTS (or a temporary folder) and checks that it is not blank.
#include <cmath>
#include <numeric>

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QElapsedTimer>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QPushButton>
#include <QSpinBox>
#include <QStatusBar>
#include <QDir>
#include <QImage>
#include <QLabel>
#include <QMouseEvent>
#include <QSignalSpy>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include "common/error.hpp"
#include "cuda/device.hpp"
#include "main_window.hpp"
#include "smocking_dialog.hpp"
#include "woven/exemplar.hpp"
#include "woven_dialog.hpp"
#include "render/stitch_view.hpp"
#include "stitchmesh/fabric.hpp"
#include "stitchmesh/labeling.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_options.hpp"
#include "viewport.hpp"
#include "yarn_settings.hpp"

using namespace skein;
using gui::MainWindow;

namespace {

const QString kModels = QStringLiteral(SKEIN_MODELS_DIR);
const QString kPatterns = QStringLiteral(SKEIN_PATTERNS_DIR);

QString shots_dir() {
  const QString dir = qEnvironmentVariableIsSet("SKEIN_GUI_SHOTS") ? qEnvironmentVariable("SKEIN_GUI_SHOTS") : QDir::temp().filePath("skein-gui-shots");
  QDir().mkpath(dir);
  return dir;
}

/// Saves the view as `name`.png and checks it is not blank: the model covers at least `min_cover` of the pixels,
/// and each expected colour shows in at least 150 pixels. Colours are compared by chromaticity, since the
/// shading scales them.
void check_shot(MainWindow& w, const QString& name, const std::vector<Eigen::Vector3f>& colors, double min_cover = 0.08) {
  QApplication::processEvents();
  const QImage image = w.viewport().grabFramebuffer().convertToFormat(QImage::Format_RGB888);
  QVERIFY(!image.isNull());
  QVERIFY(image.save(QDir(shots_dir()).filePath(name + ".png")));
  const QColor background = QColor::fromRgbF(0.93f, 0.94f, 0.96f);
  long covered = 0;
  std::vector<long> found(colors.size(), 0);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (std::abs(c.red() - background.red()) + std::abs(c.green() - background.green()) + std::abs(c.blue() - background.blue()) > 12) ++covered;
      const Eigen::Vector3f rgb(c.redF(), c.greenF(), c.blueF());
      if (rgb.sum() < 0.2f) continue;
      for (size_t k = 0; k < colors.size(); ++k)
        if ((rgb / rgb.sum() - colors[k] / colors[k].sum()).cwiseAbs().sum() < 0.02f) ++found[k];
    }
  const double cover = static_cast<double>(covered) / (image.width() * image.height());
  QVERIFY2(cover >= min_cover, qPrintable(QString("%1: the model covers %2 of the view").arg(name).arg(cover)));
  for (size_t k = 0; k < colors.size(); ++k)
    QVERIFY2(found[k] >= 150, qPrintable(QString("%1: colour %2 shows in %3 pixels").arg(name).arg(k).arg(found[k])));
}

QAction* action(MainWindow& w, const char* name) {
  auto* a = w.findChild<QAction*>(name);
  if (!a) qFatal("no action %s", name);
  return a;
}

/// A left-button stroke through the given model points, as a user drags.
void drag_through(gui::Viewport& view, const std::vector<Eigen::Vector3d>& points) {
  const auto send = [&](QEvent::Type type, const QPoint& at, Qt::MouseButtons buttons) {
    QMouseEvent event(type, QPointF(at), view.mapToGlobal(QPointF(at)), Qt::LeftButton, buttons, Qt::NoModifier);
    QApplication::sendEvent(&view, &event);
  };
  send(QEvent::MouseButtonPress, view.to_screen(points.front()), Qt::LeftButton);
  for (size_t i = 1; i < points.size(); ++i) send(QEvent::MouseMove, view.to_screen(points[i]), Qt::LeftButton);
  send(QEvent::MouseButtonRelease, view.to_screen(points.back()), Qt::NoButton);
}

Eigen::Vector3d centroid(const mesh::StitchMesh& s, int f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : s.faces[f].vertices) c += s.vertices[v];
  return c / s.faces[f].size();
}

/// The stitch in the middle of the middle row.
int middle_face(const mesh::StitchMesh& s) {
  const auto rows = mesh::faces_by_row(s);
  const auto& row = rows[rows.size() / 2];
  return row[row.size() / 2];
}

/// Shows `w` with the swatch's stitch mesh and its emitted yarn, the CPU chosen for the yarn.
bool swatch_yarn_shown(MainWindow& w) {
  w.show();
  if (!QTest::qWaitForWindowExposed(&w) || !w.open_file(kModels + "/swatch.obj")) return false;
  action(w, "autoLabel")->trigger();
  action(w, "generate")->trigger();
  if (!w.emit_yarn()) return false;
  w.findChild<QAction*>("backendCpu")->trigger();
  return true;
}

/// `name` in `dir` holding `text`; empty when it could not be written.
QString write_file(const QTemporaryDir& dir, const QString& name, const QByteArray& text) {
  QFile file(dir.filePath(name));
  if (!file.open(QIODevice::WriteOnly) || file.write(text) != text.size()) return {};
  return file.fileName();
}

bool same(const gui::EditState& a, const gui::EditState& b) {
  const bool labels = a.labels.has_value() == b.labels.has_value() &&
                      (!a.labels || (a.labels->edges == b.labels->edges && a.labels->rows == b.labels->rows &&
                                     std::equal(a.labels->faces.begin(), a.labels->faces.end(), b.labels->faces.begin(), b.labels->faces.end(),
                                                [](const auto& x, const auto& y) { return x.row == y.row && x.left == y.left && x.right == y.right; })));
  const bool values = a.values.has_value() == b.values.has_value() && (!a.values || (a.values->edge == b.values->edge && a.values->marked == b.values->marked));
  const bool yarn = a.yarn.has_value() == b.yarn.has_value() && (!a.yarn || a.yarn->points == b.yarn->points);
  return labels && values && yarn && a.stitch == b.stitch && a.rest == b.rest && a.yarn_relaxed == b.yarn_relaxed &&
         a.stitch_size.width == b.stitch_size.width && a.stitch_size.height == b.stitch_size.height;
}

}  // namespace

class GuiTest : public QObject {
  Q_OBJECT

private slots:
  void a_bad_file_shows_an_error() {
    MainWindow w;
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QTemporaryDir dir;
    const QString bad = write_file(dir, "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    QVERIFY(!bad.isEmpty());
    QVERIFY(!w.open_file(bad));
    QVERIFY2(w.last_error().contains("broken.obj"), qPrintable(w.last_error()));
    QVERIFY(w.status_text().startsWith("Error"));
    QVERIFY(!w.document().input());
    QVERIFY(!w.open_file(dir.filePath("missing.skein")));
    QVERIFY2(w.last_error().contains("missing.skein"), qPrintable(w.last_error()));
    // An edit that breaks a rule is refused with its reason, and changes nothing.
    QVERIFY(w.open_file(kModels + "/swatch.obj"));
    action(w, "generate")->trigger();
    QVERIFY2(w.last_error().contains("label"), qPrintable(w.last_error()));
    QCOMPARE(w.document().undo_stack()->count(), 0);
    QVERIFY(!w.export_yarn(dir.filePath("yarn.bcc")));
    QVERIFY(!QFile::exists(dir.filePath("yarn.bcc")));
    // Asking for the GPU where none answers is an error message, not a crash; the yarn stays as emitted.
    if (!cuda::query_devices().available()) {
      action(w, "autoLabel")->trigger();
      action(w, "generate")->trigger();
      QVERIFY(w.emit_yarn());
      action(w, "backendCuda")->trigger();
      QSignalSpy finished(&w, &MainWindow::job_finished);
      QVERIFY(w.relax_yarn());
      QVERIFY(finished.wait(60000));
      QVERIFY2(w.last_error().contains("GPU") || w.last_error().contains("CUDA"), qPrintable(w.last_error()));
      QVERIFY(!w.document().state().yarn_relaxed);
      QVERIFY(!w.job_running());
    }
  }

  void a_smocking_pattern_is_previewed_and_gathered() {
    // Issue 30: File > Smocking preview: a pattern drawn on its grid, gathered at the chosen gamma.
    MainWindow w;
    w.show();
    action(w, "smockingPreview")->trigger();
    auto* dialog = w.findChild<gui::SmockingDialog*>();
    QVERIFY(dialog);
    QTemporaryDir dir;
    const QString bad = write_file(dir, "bad.smock", "format smocking\ngrid 4 4\npath 0,0 5,0\n");
    QVERIFY(!bad.isEmpty());
    QVERIFY(!dialog->open_pattern(bad));
    auto* summary = dialog->findChild<QLabel*>("summary");
    QVERIFY2(summary->text().contains("bad.smock: line 3: point 2 (5,0) is off the grid"), qPrintable(summary->text()));
    QVERIFY(dialog->open_pattern(kPatterns + "/smocking/zigzag.smock"));
    QCOMPARE(dialog->findChild<QDoubleSpinBox*>("gamma")->value(), 0.3);
    const int flat_width = dialog->findChild<QLabel*>("picture")->pixmap().width();
    QVERIFY(flat_width > 100);
    dialog->findChild<QDoubleSpinBox*>("gamma")->setValue(0.5);
    QTest::mouseClick(dialog->findChild<QPushButton*>("gather"), Qt::LeftButton);
    QVERIFY(dialog->embedding());
    QCOMPARE(dialog->embedding()->stopped, smocking::EmbedStop::Reached);
    QVERIFY(dialog->embedding()->shrinkage() <= 0.5 * 1.01);
    QCOMPARE(dialog->findChild<QLabel*>("picture")->pixmap().width(), 2 * flat_width);  // the flat pattern and the gathered fabric
    QVERIFY2(summary->text().startsWith("reached"), qPrintable(summary->text()));
    // A drawing: four stitches of a zigzag, every second one dashed (a back stitch).
    const QString drawing = write_file(dir, "d.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<line x1=\"0\" y1=\"10\" x2=\"10\" y2=\"0\"/>\n"
                                                    "<line x1=\"10\" y1=\"0\" x2=\"20\" y2=\"10\" stroke-dasharray=\"2\"/>\n"
                                                    "<line x1=\"20\" y1=\"10\" x2=\"30\" y2=\"0\"/>\n</svg>\n");
    QVERIFY(dialog->open_pattern(drawing));
    QVERIFY2(summary->text().contains("italian smocking, 6 x 4 grid points, 1 threads, 3 stitches"), qPrintable(summary->text()));
    QVERIFY(dialog->open_pattern(kPatterns + "/smocking/zigzag.smock"));
    dialog->findChild<QDoubleSpinBox*>("gamma")->setValue(0.5);
    // The fabric in 3-D, on a worker thread: front and side, never through itself.
    QTest::mouseClick(dialog->findChild<QPushButton*>("cloth"), Qt::LeftButton);
    QVERIFY(dialog->busy());
    QVERIFY(!dialog->findChild<QPushButton*>("gather")->isEnabled());
    QTRY_VERIFY_WITH_TIMEOUT(!dialog->busy(), 60000);
    QVERIFY2(dialog->has_fabric(), qPrintable(summary->text()));
    QVERIFY2(summary->text().contains("861 points") && summary->text().contains(", 0 intersecting triangle pairs"), qPrintable(summary->text()));
    QCOMPARE(dialog->findChild<QLabel*>("picture")->pixmap().width(), 2 * flat_width);  // front and side, as large
    QVERIFY(dialog->findChild<QPushButton*>("gather")->isEnabled());
    // Closed while a finer fabric is being made (about 20 s), the window goes at once: the run stops at its next
    // Newton step.
    dialog->findChild<QComboBox*>("subdivisions")->setCurrentText("4");
    QTest::mouseClick(dialog->findChild<QPushButton*>("cloth"), Qt::LeftButton);
    QVERIFY(dialog->busy());
    QVERIFY(!dialog->findChild<QPushButton*>("openPattern")->isEnabled());
    QElapsedTimer closing;
    closing.start();
    delete dialog;
    QVERIFY2(closing.elapsed() < 3000, qPrintable(QString::number(closing.elapsed())));
  }

  void a_woven_design_is_synthesized_and_rendered() {
    // Issue 29: File > Woven preview: a design synthesized from exemplars and path traced on a worker thread.
    MainWindow w;
    w.show();
    action(w, "wovenPreview")->trigger();
    auto* dialog = w.findChild<gui::WovenDialog*>();
    QVERIFY(dialog);
    QTemporaryDir dir;
    woven::ExemplarOptions small;
    small.crossings = 4;
    small.voxels_per_crossing = 8;
    for (const char* name : {"plain-weave", "twill-3-2"})
      woven::write_exemplar(woven::make_exemplar(mesh::read_pattern((kPatterns + "/" + name + ".weave").toStdString()), small),
                            (dir.path() + "/" + name + ".vdb").toStdString());
    auto* summary = dialog->findChild<QLabel*>("summary");
    QVERIFY(!dialog->open_exemplars(dir.path() + "/missing"));
    QVERIFY2(summary->text().contains("is not a folder of exemplars"), qPrintable(summary->text()));
    QVERIFY2(dialog->open_exemplars(dir.path()), qPrintable(summary->text()));
    QVERIFY(!dialog->open_design(kPatterns + "/rib-2x2.knit"));
    QVERIFY2(summary->text().contains("is knitted, not woven"), qPrintable(summary->text()));
    QVERIFY(dialog->open_design(kPatterns + "/twill-2-1.weave"));
    dialog->findChild<QSpinBox*>("warps")->setValue(6);
    dialog->findChild<QSpinBox*>("wefts")->setValue(6);
    dialog->findChild<QSpinBox*>("samples")->setValue(1);
    dialog->findChild<QSpinBox*>("width")->setValue(48);
    QTest::mouseClick(dialog->findChild<QPushButton*>("render"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(dialog->has_picture(), 60000);
    QCOMPARE(dialog->findChild<QLabel*>("picture")->pixmap().width(), 48);
    QVERIFY2(summary->text().contains("6 x 6 crossings from 2 exemplars"), qPrintable(summary->text()));
  }

  void a_triangle_mesh_is_traced_from_the_knitting_field() {
    // Issue 25: Label > Trace rows: a triangle sheet nobody can auto-label gets its rows, labels and stitch mesh.
    MainWindow w;
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QTemporaryDir dir;
    QString obj;
    for (int y = 0; y <= 6; ++y)
      for (int x = 0; x <= 6; ++x) obj += QString("v %1 %2 0\n").arg(10 * x).arg(10 * y);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) {
        const int a = y * 7 + x + 1, b = a + 1, c = a + 8, d = a + 7;
        obj += QString("f %1 %2 %3\nf %1 %3 %4\n").arg(a).arg(b).arg(c).arg(d);
      }
    QFile file(dir.filePath("tris.obj"));
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(obj.toUtf8());
    file.close();
    QVERIFY(w.open_file(dir.filePath("tris.obj")));
    action(w, "traceField")->trigger();
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    const auto& state = w.document().state();
    QVERIFY(state.labels && state.stitch);
    QVERIFY(mesh::validate_labels(*w.document().input(), *state.labels).valid());
    QCOMPARE(static_cast<int>(state.stitch->faces.size()), 110);  // 10 stitches a row, 11 rows (6 x 5 mm)
    QVERIFY(w.emit_yarn());
    check_shot(w, "traced-triangles", {}, 0.05);

    // Label > Trace rows from here: a click near a border edge starts the rows there; Shift+click first names
    // where they end. From the left side, the first row runs up the left side.
    const auto near_border = [&](const Eigen::Vector3d& middle) {
      const auto& input = *w.document().input();
      for (int e = 0; e < input.num_edges(); ++e) {
        const auto [a, b] = input.edge_vertices(e);
        if (!input.is_border(e) || (0.5 * (input.point(a) + input.point(b)) - middle).norm() > 1e-9) continue;
        const int face = input.edge_uses(e).front().face;
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (int v : input.face(face)) c += input.point(v);
        return w.viewport().to_screen(0.8 * middle + 0.2 * c / input.face(face).size());
      }
      return QPoint(-1, -1);
    };
    QVERIFY(w.open_file(dir.filePath("tris.obj")));
    w.set_tool(gui::Tool::TraceFrom);
    QTest::mouseClick(&w.viewport(), Qt::LeftButton, {}, near_border({0, 35, 0}));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(w.document().state().stitch);
    const auto& left = *w.document().state().stitch;
    QCOMPARE(static_cast<int>(left.faces.size()), 110);
    const auto left_rows = mesh::faces_by_row(left);
    for (int f : left_rows.front()) QVERIFY(centroid(left, f).x() < 10);
    // From the bottom toward the top, named by a Shift+click first: traced, labeled, the status saying so first.
    QVERIFY(w.open_file(dir.filePath("tris.obj")));
    QTest::mouseClick(&w.viewport(), Qt::LeftButton, Qt::ShiftModifier, near_border({25, 60, 0}));
    QVERIFY(w.statusBar()->currentMessage().contains("now click where they start"));
    QVERIFY(!w.document().state().stitch);
    QTest::mouseClick(&w.viewport(), Qt::LeftButton, {}, near_border({25, 0, 0}));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(w.document().state().labels && w.document().state().stitch);
    QVERIFY(mesh::validate_labels(*w.document().input(), *w.document().state().labels).valid());
    const auto& up = *w.document().state().stitch;
    const auto up_rows = mesh::faces_by_row(up);
    for (int f : up_rows.front()) QVERIFY(centroid(up, f).y() < 10);
    for (int f : up_rows.back()) QVERIFY(centroid(up, f).y() > 50);
  }

  void a_pattern_in_colour_colours_the_garment_and_its_yarn() {
    // Issue 26: stripes tiled onto a swatch give its stitches and its yarn their colours (View > Colour by yarn
    // colour, and the yarn layer), and the project keeps them.
    MainWindow w;
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto& doc = w.document();
    QVERIFY(w.open_file(kModels + "/swatch.obj"));
    action(w, "autoLabel")->trigger();
    doc.set_stitch_size({12, 10});
    action(w, "generate")->trigger();
    QVERIFY(doc.state().stitch);
    std::vector<int> all(doc.state().stitch->faces.size());
    std::iota(all.begin(), all.end(), 0);
    w.set_selection(all);
    QVERIFY2(w.tile_pattern_file(kPatterns + "/written/garter-stripes.txt"), qPrintable(w.last_error()));
    w.set_selection({});
    const auto& palette = doc.state().stitch->palette;
    QCOMPARE(static_cast<int>(palette.size()), 2);
    // As the view shows them: the palette's sRGB (cream and a navy light enough for the shot's dark cut-off).
    QVERIFY(palette[1].description == "navy");
    const auto shown = [](const std::array<double, 3>& c) { return Eigen::Vector3f(c[0], c[1], c[2]); };
    const std::vector<Eigen::Vector3f> colours{shown(palette[0].srgb), shown(palette[1].srgb)};
    action(w, "colorYarn")->trigger();
    check_shot(w, "colour-stitches", colours);
    QVERIFY(w.emit_yarn());
    QVERIFY(!doc.state().yarn->point_colour.empty());
    check_shot(w, "colour-yarn", colours, 0.05);
  }

  void open_label_tessellate_paint_relax_export() {
    MainWindow w;
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.viewport().gl_error().isEmpty());
    auto& doc = w.document();
    QVERIFY(w.open_file(kModels + "/swatch.obj"));
    check_shot(w, "1-open", {});

    // Label the first row by clicking a border edge, then the rest with auto-label.
    const auto& input = *doc.input();
    const int edge = mesh::default_start_edge(input);
    const auto [a, b] = input.edge_vertices(edge);
    const int face = input.edge_uses(edge).front().face;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : input.face(face)) c += input.point(v);
    c /= input.face(face).size();
    const Eigen::Vector3d near_edge = 0.8 * 0.5 * (input.point(a) + input.point(b)) + 0.2 * c;
    w.set_tool(gui::Tool::FirstRow);
    QTest::mouseClick(&w.viewport(), Qt::LeftButton, {}, w.viewport().to_screen(near_edge));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(doc.state().labels);
    QCOMPARE(doc.state().labels->faces[face].row, 0);
    action(w, "autoLabel")->trigger();
    QVERIFY(mesh::validate_labels(input, *doc.state().labels).valid());
    // Faces are tinted by row: the row colour mixed with white.
    check_shot(w, "2-labeled", {0.55f * render::row_color(0) + Eigen::Vector3f::Constant(0.45f)});

    // Bigger stitches keep the swatch small, then the stitch mesh.
    doc.set_stitch_size({12, 10});
    action(w, "generate")->trigger();
    QVERIFY(doc.state().stitch);
    QCOMPARE(w.layer(), gui::Layer::Stitch);
    const auto& knit = render::stitch_color("k");
    check_shot(w, "3-stitches", {knit}, 0.2);

    // Paint purl with a drag across the middle row.
    const auto stitch = *doc.state().stitch;
    const auto rows = mesh::faces_by_row(stitch);
    const auto& row = rows[rows.size() / 2];
    std::vector<Eigen::Vector3d> stroke;
    for (size_t i = 2; i + 2 < row.size(); ++i) stroke.push_back(centroid(stitch, row[i]));
    w.set_tool(gui::Tool::Paint);
    w.set_paint_type("p");
    const int undo_before = doc.undo_stack()->count();
    drag_through(w.viewport(), stroke);
    QCOMPARE(doc.undo_stack()->count(), undo_before + 1);  // one stroke, one undo step
    for (size_t i = 2; i + 2 < row.size(); ++i) QCOMPARE(doc.state().stitch->faces[row[i]].type, std::string("p"));
    check_shot(w, "4-painted", {knit, render::stitch_color("p")}, 0.2);

    // A rib over the border rows.
    action(w, "selectBorder")->trigger();
    QVERIFY(!w.selection().empty());
    QVERIFY(w.fill_selection("rib"));
    w.set_selection({});
    check_shot(w, "5-rib", {knit, render::stitch_color("p")}, 0.2);

    // Mesh relaxation in a worker thread; the stretch colours after it.
    QSignalSpy finished(&w, &MainWindow::job_finished);
    QVERIFY(w.relax_mesh());
    QVERIFY(w.job_running());
    QVERIFY(finished.wait(120000));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(doc.state().rest);
    check_shot(w, "6-stretch", {}, 0.2);

    // Yarn, emitted and relaxed.
    QVERIFY(w.emit_yarn());
    QCOMPARE(w.layer(), gui::Layer::Yarn);
    const auto emitted = *doc.state().yarn;
    check_shot(w, "7-yarn", {knit}, 0.1);
    w.findChild<QAction*>("backendCpu")->trigger();
    QVERIFY(w.relax_yarn());
    QVERIFY(finished.wait(240000));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(doc.state().yarn_relaxed);
    QVERIFY(doc.state().yarn->points != emitted.points);
    check_shot(w, "8-relaxed", {knit, render::stitch_color("p")}, 0.1);

    // Exports, and the project read back.
    QTemporaryDir dir;
    QVERIFY(w.export_yarn(dir.filePath("yarn.bcc")));
    QCOMPARE(workflow::read_bcc(dir.filePath("yarn.bcc").toStdString()).points.size(), emitted.points.size());
    QVERIFY(w.export_yarn(dir.filePath("yarn.obj")));
    QVERIFY(QFileInfo(dir.filePath("yarn.obj")).size() > 1000);
    QVERIFY(w.export_stitch_ply(dir.filePath("stitches.ply")));
    QVERIFY(QFileInfo(dir.filePath("stitches.ply")).size() > 1000);
    QVERIFY(w.export_picture(dir.filePath("view.png")));
    QCOMPARE(QImage(dir.filePath("view.png")).size(), w.viewport().grabFramebuffer().size());
    QVERIFY(w.save_project(dir.filePath("garment.skein")));
    const auto project = mesh::read_project(dir.filePath("garment.skein").toStdString());
    QVERIFY(project.stitch && *project.stitch == *doc.state().stitch);
    MainWindow again;
    QVERIFY(again.open_file(dir.filePath("garment.skein")));
    QVERIFY(*again.document().state().stitch == *doc.state().stitch);
    QCOMPARE(again.layer(), gui::Layer::Stitch);
  }

  /// The user guide's pictures (docs/gui.md): a beanie from mesh to relaxed yarn, each stage as the whole window.
  void tour_of_a_beanie() {
    MainWindow w;
    w.resize(1400, 900);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto& doc = w.document();
    const auto window_shot = [&](const QString& name) {
      QApplication::processEvents();
      QVERIFY(w.grab().save(QDir(shots_dir()).filePath(name + ".png")));
    };
    QVERIFY(w.open_file(kModels + "/beanie.obj"));
    window_shot("gui-open");
    action(w, "autoLabel")->trigger();
    QVERIFY(mesh::validate_labels(*doc.input(), *doc.state().labels).valid());
    check_shot(w, "beanie-labels", {}, 0.15);
    window_shot("gui-labels");

    doc.set_stitch_size({10, 8});
    action(w, "generate")->trigger();
    const auto& stitch = *doc.state().stitch;
    // Ribbing at the brim, moss stitch over the middle rows, by selection.
    w.set_selection(mesh::faces_near_border(stitch, 3));
    QVERIFY(w.fill_selection("rib2x2"));
    const auto grid = mesh::stitch_grid(*doc.state().stitch);
    std::vector<int> band;
    for (int f = 0; f < static_cast<int>(grid.level.size()); ++f)
      if (grid.level[f] >= 8 && grid.level[f] < 14) band.push_back(f);
    w.set_selection(band);
    QVERIFY(w.tile_pattern_file(kPatterns + "/moss.knit"));
    w.set_tool(gui::Tool::Select);
    window_shot("gui-select");
    w.set_selection({});
    check_shot(w, "beanie-paint", {render::stitch_color("k"), render::stitch_color("p")}, 0.15);
    window_shot("gui-paint");

    QSignalSpy finished(&w, &MainWindow::job_finished);
    QVERIFY(w.relax_mesh());
    QVERIFY(finished.wait(300000));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    window_shot("gui-stretch");

    w.set_coloring(gui::Coloring::StitchType);
    QVERIFY(w.emit_yarn());
    w.findChild<QAction*>("backendCpu")->trigger();
    QVERIFY(w.relax_yarn());
    QTest::qWait(2000);
    window_shot("gui-relaxing");
    // A whole beanie takes minutes on two cores: the tour stops the run after SKEIN_GUI_TOUR_SECONDS (15 by
    // default; scripts/gui-pictures.sh gives it time to converge), as a user presses Stop.
    const int seconds = qEnvironmentVariableIsSet("SKEIN_GUI_TOUR_SECONDS") ? qEnvironmentVariableIntValue("SKEIN_GUI_TOUR_SECONDS") : 15;
    if (!finished.wait(1000 * seconds)) {
      action(w, "stop")->trigger();
      QVERIFY(finished.wait(60000));
    }
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(doc.state().yarn_relaxed);
    check_shot(w, "beanie-yarn", {render::stitch_color("k"), render::stitch_color("p")}, 0.15);
    window_shot("gui-yarn");
  }

  void yarn_relaxes_locally_after_painting() {
    MainWindow w;
    QVERIFY(swatch_yarn_shown(w));
    QSignalSpy finished(&w, &MainWindow::job_finished);
    QVERIFY(w.relax_yarn());
    QVERIFY(finished.wait(300000));
    auto& doc = w.document();
    QVERIFY(doc.state().yarn_relaxed);
    QVERIFY(!w.job_text().contains("locally"));
    // Painting drops the yarn but keeps the relaxed one for the next relaxation, which relaxes only the
    // painted stitch and rings around it.
    doc.paint({middle_face(*doc.state().stitch)}, "p", "Paint");
    QVERIFY(!doc.state().yarn);
    QVERIFY(doc.state().previous.has_value());
    QVERIFY(w.emit_yarn());
    QVERIFY(w.relax_yarn());
    QVERIFY(finished.wait(300000));
    QVERIFY2(w.last_error().isEmpty(), qPrintable(w.last_error()));
    QVERIFY(doc.state().yarn_relaxed);
    QVERIFY2(w.job_text().contains("1 changed stitches relaxed locally") && w.job_text().contains(", 0 pull-through events"), qPrintable(w.job_text()));
    // A new stitch mesh has no yarn to start from.
    action(w, "generate")->trigger();
    QVERIFY(!doc.state().previous.has_value());
  }

  void yarn_settings_reach_the_relaxation() {
    // The dialog shows the settings and gives back what its fields hold; Restore Defaults resets them.
    gui::YarnSettings chosen;
    chosen.take_up = 0.95;
    gui::YarnSettingsDialog dialog(chosen);
    QCOMPARE(dialog.findChild<QDoubleSpinBox*>("takeUp")->value(), 0.95);
    QVERIFY(!dialog.findChild<QDoubleSpinBox*>("contactSpacing")->isEnabled());
    dialog.findChild<QCheckBox*>("activeSet")->setChecked(true);
    dialog.findChild<QCheckBox*>("adaptiveSamples")->setChecked(true);
    QVERIFY(dialog.findChild<QDoubleSpinBox*>("contactSpacing")->isEnabled());
    dialog.findChild<QDoubleSpinBox*>("contactSpacing")->setValue(2.5);
    dialog.findChild<QSpinBox*>("rings")->setValue(2);
    QCOMPARE(dialog.findChild<QSpinBox*>("jamSteps")->value(), 100);
    dialog.findChild<QSpinBox*>("jamSteps")->setValue(250);
    dialog.findChild<QCheckBox*>("clippedScale")->setChecked(true);
    QVERIFY(dialog.grab().save(QDir(shots_dir()).filePath("gui-yarn-settings.png")));
    const auto settings = dialog.settings();
    QVERIFY(settings.relax.active_set.enabled);
    QCOMPARE(settings.relax.sampling.spacing, 2.5);
    QCOMPARE(settings.take_up, 0.95);
    QCOMPARE(settings.local.rings, 2);
    QCOMPARE(settings.relax.jam_steps, 250);
    QVERIFY(settings.relax.clipped_scale);
    dialog.findChild<QDialogButtonBox*>()->button(QDialogButtonBox::RestoreDefaults)->click();
    QVERIFY(!dialog.settings().relax.active_set.enabled);
    QCOMPARE(dialog.settings().relax.sampling.spacing, 0.0);
    QCOMPARE(dialog.settings().take_up, 1.0);
    QCOMPARE(dialog.settings().relax.jam_steps, 100);
    QVERIFY(!dialog.settings().relax.clipped_scale);

    MainWindow w;
    QVERIFY(swatch_yarn_shown(w));
    // Values out of range are refused with the rule broken, and the settings stay.
    auto bad = settings;
    bad.relax.sampling.spacing = 3.5;
    QVERIFY(!w.set_yarn_settings(bad));
    QVERIFY2(w.last_error().contains("spacing"), qPrintable(w.last_error()));
    QCOMPARE(w.yarn_settings().relax.sampling.spacing, 0.0);
    QVERIFY(w.set_yarn_settings(settings));
    // The active set is the CPU relaxer's: with the CUDA backend chosen the relaxation is refused.
    action(w, "backendCuda")->trigger();
    QVERIFY(!w.relax_yarn());
    QVERIFY2(w.last_error().contains("CPU only"), qPrintable(w.last_error()));
    action(w, "backendCpu")->trigger();
    QSignalSpy finished(&w, &MainWindow::job_finished);
    QVERIFY(w.relax_yarn());
    QVERIFY(finished.wait(300000));
    QVERIFY2(w.job_text().contains("(active set)") && w.job_text().contains(", 0 pull-through events"), qPrintable(w.job_text()));
    // The preview takes the settings too (the patches' take-up and samples).
    QVERIFY(w.emit_yarn());
    QVERIFY2(w.preview_yarn(), qPrintable(w.last_error()));
  }

  void the_yarn_dialogs_boxes_take_the_ranges_the_command_line_does() {
    // One schema (relax/yarn_options.hpp) for the dialog, the CLI, jobs and projects.
    gui::YarnSettingsDialog dialog(gui::YarnSettings{});
    for (const auto& [name, key] : std::vector<std::pair<const char*, const char*>>{{"tolerance", "tolerance"}, {"takeUp", "take_up"}, {"contactSpacing", "contact_spacing"}}) {
      const auto& spec = workflow::yarn_option(key);
      auto* box = dialog.findChild<QDoubleSpinBox*>(name);
      QVERIFY2(box, name);
      // Its range rounded inward to the digits the box shows.
      const double digit = std::pow(10.0, -box->decimals());
      QVERIFY(box->minimum() >= spec.low && box->minimum() < spec.low + digit);
      QVERIFY2(box->maximum() <= spec.high && box->maximum() > spec.high - digit, name);
      QCOMPARE(box->toolTip().toStdString(), spec.help);
    }
    for (const auto& [name, key] : std::vector<std::pair<const char*, const char*>>{{"maxSteps", "max_steps"}, {"jamSteps", "jam_steps"}, {"rings", "rings"}, {"halo", "halo"}}) {
      const auto& spec = workflow::yarn_option(key);
      auto* box = dialog.findChild<QSpinBox*>(name);
      QVERIFY2(box, name);
      QCOMPARE(box->minimum(), static_cast<int>(spec.low));
      QCOMPARE(box->maximum(), static_cast<int>(spec.high));
    }
  }

  void a_yarn_weight_relaxes_the_garment_as_that_yarn() {
    // The dialog offers the weight classes; with one, the take-up is Munden's and its field is off.
    gui::YarnSettingsDialog dialog(gui::YarnSettings{});
    auto* weight = dialog.findChild<QComboBox*>("weight");
    QVERIFY(weight && dialog.findChild<QDoubleSpinBox*>("takeUp")->isEnabled());
    weight->setCurrentIndex(weight->findData(QString("dk")));
    QVERIFY(!dialog.findChild<QDoubleSpinBox*>("takeUp")->isEnabled());
    auto settings = dialog.settings();
    QCOMPARE(settings.weight, std::string("dk"));
    dialog.findChild<QDialogButtonBox*>()->button(QDialogButtonBox::RestoreDefaults)->click();
    QCOMPARE(dialog.settings().weight, std::string());

    MainWindow w;
    QVERIFY(swatch_yarn_shown(w));
    auto& doc = w.document();
    settings.relax.max_steps = 20;
    QVERIFY(w.set_yarn_settings(settings));
    // Emitted at dk's compressed contact radius and drawn at its full one; the preview keeps the emitted radius: refused.
    const double full = 25.4 / 13 / 2;
    QVERIFY(w.emit_yarn());
    QCOMPARE(doc.state().yarn->radius, full);
    const auto emitted = doc.state().yarn->points;
    QVERIFY(!w.preview_yarn());
    QVERIFY2(w.last_error().contains("Yarn weight"), qPrintable(w.last_error()));
    QSignalSpy finished(&w, &MainWindow::job_finished);
    QVERIFY(w.relax_yarn());
    QVERIFY(finished.wait(300000));
    QCOMPARE(doc.state().yarn->radius, full);
    QVERIFY(doc.state().yarn_relaxed);
    QVERIFY(doc.state().yarn->points != emitted);
    QVERIFY2(w.job_text().contains(", 0 pull-through events") && w.job_text().contains("as dk yarn (take-up "), qPrintable(w.job_text()));
    // Yarn emitted before the weight was chosen is emitted again for it when the relaxation starts.
    settings.weight.clear();
    QVERIFY(w.set_yarn_settings(settings));
    QVERIFY(w.emit_yarn());
    QCOMPARE(doc.state().yarn->radius, 0.6);
    settings.weight = "dk";
    QVERIFY(w.set_yarn_settings(settings));
    QVERIFY(w.relax_yarn());
    QVERIFY(finished.wait(300000));
    QCOMPARE(doc.state().yarn->radius, full);
    // Stitch > Stitch size from needle: the gauge dk knits on a 4 mm needle (mesh::needle_gauge); none without a weight.
    QVERIFY(w.set_stitch_size_from_needle(4));
    const auto on_4mm = mesh::needle_gauge(mesh::find_yarn_weight("dk"), 4).stitch_size();
    QCOMPARE(doc.state().stitch_size.width, on_4mm.width);
    QCOMPARE(doc.state().stitch_size.height, on_4mm.height);
    settings.weight.clear();
    QVERIFY(w.set_yarn_settings(settings));
    QVERIFY(!w.set_stitch_size_from_needle(4));
    QVERIFY2(w.last_error().contains("choose a Yarn weight first"), qPrintable(w.last_error()));
  }

  void yarn_settings_are_saved_with_the_project() {
    QTemporaryDir dir;
    MainWindow w;
    QVERIFY(swatch_yarn_shown(w));
    auto settings = w.yarn_settings();
    settings.relax.tolerance = 0.004;
    settings.take_up = 0.92;
    settings.local.rings = 2;
    settings.weight = "sport";
    QVERIFY(w.set_yarn_settings(settings));
    const QString path = dir.filePath("swatch.skein");
    QVERIFY2(w.save_project(path), qPrintable(w.last_error()));
    MainWindow other;
    QVERIFY2(other.open_file(path), qPrintable(other.last_error()));
    QCOMPARE(other.yarn_settings().relax.tolerance, 0.004);
    QCOMPARE(other.yarn_settings().take_up, 0.92);
    QCOMPARE(other.yarn_settings().local.rings, 2);
    QCOMPARE(other.yarn_settings().weight, std::string("sport"));
    // A project with a setting this skein does not know is refused, naming its line; what is open stays.
    QFile saved(path);
    QVERIFY(saved.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(saved.readAll()).replace("set yarn.halo 1", "set yarn.colour red");
    const QString bad = dir.filePath("bad.skein");
    QFile out(bad);
    QVERIFY(out.open(QIODevice::WriteOnly));
    out.write(text.toUtf8());
    out.close();
    QVERIFY(!other.open_file(bad));
    QVERIFY2(other.last_error().contains("'yarn.colour' is not a setting") && other.last_error().contains("line "), qPrintable(other.last_error()));
    QCOMPARE(other.yarn_settings().relax.tolerance, 0.004);
  }

  void yarn_preview_maps_stand_ins_without_relaxing() {
    MainWindow w;
    QVERIFY(swatch_yarn_shown(w));
    const auto emitted = *w.document().state().yarn;
    QVERIFY2(w.preview_yarn(), qPrintable(w.last_error()));
    const auto& state = w.document().state();
    QVERIFY(state.yarn && !state.yarn_relaxed);
    QCOMPARE(state.yarn->points.size(), emitted.points.size());
    QVERIFY(state.yarn->points != emitted.points);
    QVERIFY2(w.job_text().contains("stand-in preview (not a relaxation)") && w.job_text().contains("patches of k"), qPrintable(w.job_text()));
    // One undo step back to the emitted yarn.
    action(w, "undo")->trigger();
    QVERIFY(w.document().state().yarn->points == emitted.points);
    // A lace tiled over the swatch re-meshes it; the preview finds its repeats from the tiling.
    std::vector<int> all(w.document().state().stitch->faces.size());
    std::iota(all.begin(), all.end(), 0);
    w.set_selection(all);
    QVERIFY2(w.tile_pattern_file(kPatterns + "/eyelet-lace.knit"), qPrintable(w.last_error()));
    QVERIFY(w.emit_yarn());
    QVERIFY2(w.preview_yarn(), qPrintable(w.last_error()));
    QVERIFY2(w.job_text().contains("Eyelet lace"), qPrintable(w.job_text()));
  }

  void yarn_relaxation_pauses_resumes_and_stops() {
    MainWindow w;
    QVERIFY(swatch_yarn_shown(w));
    QVERIFY(w.relax_yarn());
    auto* pause = action(w, "pause");
    QVERIFY(pause->isEnabled());
    QVERIFY(!action(w, "generate")->isEnabled());  // no edits while a job runs
    QTest::qWait(1500);  // the window stays responsive meanwhile: this wait runs its event loop
    pause->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(w.findChild<QAction*>("pause")->text().contains("Resume"), 1000);
    QTest::qWait(300);
    QVERIFY(w.job_running());  // paused, not finished
    QVERIFY(!w.document().state().yarn_relaxed);
    // Watched from the resume on: on a fast machine the swatch may converge before the stop comes.
    QSignalSpy finished(&w, &MainWindow::job_finished);
    pause->trigger();  // resume
    QTest::qWait(500);
    action(w, "stop")->trigger();
    QVERIFY(finished.count() > 0 || finished.wait(60000));
    QVERIFY(!w.job_running());
    QVERIFY(w.document().state().yarn_relaxed);
    QVERIFY(action(w, "generate")->isEnabled());
    // Undo takes the relaxed yarn back to the emitted one.
    w.document().undo_stack()->undo();
    QVERIFY(!w.document().state().yarn_relaxed);
  }

  void every_edit_undoes_and_redoes() {
    gui::Document doc;
    doc.open((kModels + "/swatch.obj").toStdString());
    const auto check = [&](const char* what, auto&& edit) {
      const gui::EditState before = doc.state();
      const int index = doc.undo_stack()->index();
      edit();
      const gui::EditState after = doc.state();
      QVERIFY2(doc.undo_stack()->index() == index + 1, what);
      QVERIFY2(!same(before, after), what);
      doc.undo_stack()->undo();
      QVERIFY2(same(doc.state(), before), what);
      doc.undo_stack()->redo();
      QVERIFY2(same(doc.state(), after), what);
    };
    const auto& input = *doc.input();
    const int start = mesh::default_start_edge(input);
    check("first row", [&] { doc.label_first_row(start); });
    const int face0 = input.edge_uses(start).front().face;
    const auto top = mesh::top_edges(input, doc.state().labels->faces[face0], face0);
    check("next row", [&] { doc.label_next_row(input.face_edge(face0, top.front())); });
    check("flip row", [&] { doc.flip_row(1); });
    check("auto-label", [&] { doc.auto_label(); });
    check("stitch size", [&] { doc.set_stitch_size({8, 7}); });
    check("generate", [&] { doc.generate_stitch_mesh(); });
    int course = -1, wale = -1;
    for (int e = 0; e < input.num_edges(); ++e) (doc.state().labels->edges[e] == mesh::EdgeLabel::Course ? course : wale) = e;
    check("course value", [&] { doc.set_edge_value(course, doc.state().values->edge[course] + 2); });
    check("row value", [&] { doc.set_edge_value(wale, doc.state().values->edge[wale] + 1); });
    check("wale mark", [&] { doc.toggle_wale_mark(wale); });
    const auto& s = *doc.state().stitch;
    const int f = middle_face(s);
    check("paint", [&] { doc.paint({f}, "p", "paint"); });
    check("fill", [&] { doc.fill(mesh::faces_near_border(s, 2), mesh::parse_fill("seed"), "seed"); });
    const auto rows = mesh::faces_by_row(doc.state().stitch.value());
    std::vector<int> all(doc.state().stitch->faces.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    check("tile pattern", [&] { doc.tile_pattern(all, mesh::read_pattern((kPatterns + "/seed.knit").toStdString()), rows[0][0]); });
    const auto path = mesh::top_edge_path(*doc.state().stitch, static_cast<int>(rows.size() / 2), 2, 4);
    check("mark cable", [&] { doc.mark_cable(path, 1, 1); });
    check("unmark cable", [&] { doc.unmark_cable(path); });
    const auto face = doc.state().stitch->faces[f];
    const int u = face.vertex(face.bottom + 1), v = face.vertex(face.bottom + 2);
    check("split", [&] { doc.split_course_edge(u, v); });
    const auto g = doc.state().stitch->faces[f];
    check("shift wale edge", [&] { doc.shift_wale_edge(g.vertex(g.bottom), g.vertex(g.bottom + 1), mesh::WaleEnd::Top, -1); });
    doc.undo_stack()->undo();
    const int m = static_cast<int>(doc.state().stitch->vertices.size()) - 1;  // the split's new vertex
    check("collapse", [&] { doc.collapse_course_edge(u, m); });
    check("add wale edge", [&] { doc.add_wale_edge(f); });
    const auto h = doc.state().stitch->faces[f];
    check("remove wale edge", [&] { doc.remove_wale_edge(h.vertex(h.bottom), h.vertex(h.bottom + 1)); });
    auto moved = *doc.state().stitch;
    moved.vertices[0].x() += 0.5;
    check("relaxed mesh", [&] { doc.set_relaxed_mesh(moved, {3, 2.5}); });
    relax::YarnCurves yarn;
    yarn.points = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
    yarn.curve_start = {0, 2};
    yarn.closed = {0};
    check("yarn", [&] { doc.set_yarn(yarn, false, "yarn"); });
    // A refused edit leaves no undo step.
    const int count = doc.undo_stack()->count();
    bool refused = false;
    try {
      doc.remove_wale_edge(0, 999999);
    } catch (const skein::Error&) {
      refused = true;
    }
    QVERIFY(refused);
    QCOMPARE(doc.undo_stack()->count(), count);
  }
};

int main(int argc, char** argv) {
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);
  QApplication app(argc, argv);
  GuiTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "test_gui.moc"

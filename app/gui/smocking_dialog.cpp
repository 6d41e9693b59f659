#include "smocking_dialog.hpp"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QPushButton>

#include <chrono>

#include "common/error.hpp"
#include "preview_layout.hpp"
#include "render/smocking_view.hpp"
#include "smocking/smocking_svg.hpp"

namespace skein::gui {

SmockingDialog::SmockingDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Smocking preview"));
  m_open = new QPushButton(tr("&Open pattern..."), this);
  m_open->setObjectName("openPattern");
  connect(m_open, &QPushButton::clicked, this, [this] {
    const auto path = QFileDialog::getOpenFileName(this, tr("Open smocking pattern"), {},
                                                   tr("Smocking patterns and drawings (*.smock *.svg);;All files (*)"));
    if (!path.isEmpty()) open_pattern(path);
  });
  m_gamma = new QDoubleSpinBox(this);
  m_gamma->setObjectName("gamma");
  m_gamma->setRange(0.01, 1.0);
  m_gamma->setSingleStep(0.05);
  m_gamma->setValue(0.3);
  m_gamma->setToolTip(tr("Pull the threads to this fraction of their sewn length (Zhou 2024 eq. 1c)"));
  m_pull = new QComboBox(this);
  m_pull->setObjectName("pull");
  m_pull->addItems({tr("Across (horizontal)"), tr("Down (vertical)"), tr("Along each stitch")});
  m_pull->setToolTip(tr("The pulling direction: stitches along it shorten, stitches across it do not (eq. 5)"));
  m_gather = new QPushButton(tr("&Gather"), this);
  m_gather->setObjectName("gather");
  connect(m_gather, &QPushButton::clicked, this, [this] { gather(); });
  m_subdivisions = new QComboBox(this);
  m_subdivisions->setObjectName("subdivisions");
  m_subdivisions->addItems({"2", "4"});  // 4: the zigzag in 20 s on two cores; finer from the command line (--subdivisions)
  m_subdivisions->setToolTip(tr("Fine squares per side of a pattern square in the 3-D fabric"));
  m_cloth = new QPushButton(tr("Smock in &3-D"), this);
  m_cloth->setObjectName("cloth");
  m_cloth->setToolTip(tr("Drape a fine fabric to the gathered pattern, never through itself (Zhou 2024 §4.2)"));
  connect(m_cloth, &QPushButton::clicked, this, [this] { smock_in_3d(); });
  auto* controls = new QHBoxLayout;
  controls->addWidget(m_open);
  auto* form = new QFormLayout;
  form->addRow(tr("Gamma"), m_gamma);
  form->addRow(tr("Pull"), m_pull);
  form->addRow(tr("Subdivisions"), m_subdivisions);
  controls->addLayout(form);
  controls->addWidget(m_gather);
  controls->addWidget(m_cloth);
  const auto preview = lay_out_preview(this, controls, tr("Open a smocking pattern (.smock), then Gather."));
  m_picture = preview.picture;
  m_summary = preview.summary;
  resize(1100, 560);
}

SmockingDialog::~SmockingDialog() {
  m_stop = true;  // the worker stops at its next Newton step
  m_worker.join();
}

void SmockingDialog::set_busy(bool busy) {
  for (QWidget* w : std::initializer_list<QWidget*>{m_open, m_gamma, m_pull, m_subdivisions, m_gather, m_cloth}) w->setEnabled(!busy);
}

bool SmockingDialog::open_pattern(const QString& path) {
  if (busy()) return false;
  try {
    // A drawing (front stitches solid, back dashed) is read as Italian smocking with its grid found from it.
    m_pattern = path.endsWith(".svg", Qt::CaseInsensitive) ? smocking::read_smocking_svg(path.toStdString())
                                                           : smocking::read_smocking_pattern(path.toStdString());
  } catch (const Error& e) {
    m_summary->setText(QString::fromStdString(e.what()));
    return false;
  }
  m_embedding.reset();
  m_gamma->setValue(m_pattern->gamma);
  m_summary->setText(tr("%1: %2 smocking, %3 x %4 grid points, %5 threads, %6 stitches")
                         .arg(QString::fromStdString(m_pattern->name.empty() ? path.toStdString() : m_pattern->name))
                         .arg(smocking::style_name(m_pattern->style))
                         .arg(m_pattern->columns)
                         .arg(m_pattern->rows)
                         .arg(m_pattern->threads.size())
                         .arg(m_pattern->num_stitches()));
  show_picture();
  return true;
}

void SmockingDialog::gather() {
  if (busy()) return;
  if (!m_pattern) {
    m_summary->setText(tr("Open a smocking pattern first."));
    return;
  }
  smocking::EmbedOptions options;
  options.gamma = m_gamma->value();
  options.pull = m_pull->currentIndex() == 1 ? Eigen::Vector2d(0, 1) : Eigen::Vector2d(1, 0);
  options.pull_along_stitches = m_pull->currentIndex() == 2;
  m_embedding = smocking::embed(*m_pattern, options);
  const auto& e = *m_embedding;
  m_summary->setText(tr("%1 after %2 iterations: the threads at %3 of their sewn length (gamma %4); the fabric stretched at most %5 %")
                         .arg(smocking::stop_name(e.stopped))
                         .arg(e.iterations)
                         .arg(e.shrinkage(), 0, 'f', 3)
                         .arg(options.gamma)
                         .arg(100 * e.largest_stretch, 0, 'f', 2));
  show_picture();
}

void SmockingDialog::smock_in_3d() {
  if (busy()) return;
  gather();
  if (!m_embedding) return;
  set_busy(true);
  m_summary->setText(tr("Smocking in 3-D..."));
  smocking::ClothOptions options;
  options.subdivisions = m_subdivisions->currentText().toInt();
  m_worker.start(this, [this, pattern = *m_pattern, embedding = *m_embedding, options]() -> std::function<void()> {
    QImage picture;
    QString summary;
    try {
      const auto start = std::chrono::steady_clock::now();
      const auto cloth = smocking::smock_cloth(pattern, embedding, smocking::lift(embedding), options, &m_stop);
      const long crossings = smocking::exact_intersections(cloth);
      const auto image = render::draw_smocked_fabric(cloth, 500);  // the flat and gathered panels' size
      picture = QImage(image.rgb.data(), image.width, image.height, image.width * 3, QImage::Format_RGB888).copy();
      summary = tr("3-D fabric: %1 points, %2 Newton steps in %3 frames, %4 s; the stitching points %5 mm (RMS) from their places, "
                   "closest non-neighbours %6 mm, %7 intersecting triangle pairs")
                    .arg(cloth.positions.cols())
                    .arg(cloth.newton_iterations)
                    .arg(cloth.frames)
                    .arg(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0, 'f', 1)
                    .arg(cloth.target_error, 0, 'f', 2)
                    .arg(cloth.smallest_distance, 0, 'f', 3)
                    .arg(crossings);
    } catch (const std::exception& e) {
      summary = QString::fromStdString(e.what());
    }
    return [this, picture, summary] { finish(picture, summary); };
  });
}

void SmockingDialog::finish(const QImage& image, const QString& summary) {
  if (!image.isNull()) {
    m_picture->setPixmap(QPixmap::fromImage(image));
    m_has_fabric = true;
  }
  m_summary->setText(summary);
  set_busy(false);
}

void SmockingDialog::show_picture() {
  m_has_fabric = false;
  // The flat pattern alone until gathered: an embedding with no steps taken draws the pattern twice.
  const auto e = m_embedding ? *m_embedding : smocking::make_mass_spring_system(*m_pattern, -1);
  const auto image = render::draw_smocking(*m_pattern, e, 500);
  const QImage picture(image.rgb.data(), image.width, image.height, image.width * 3, QImage::Format_RGB888);
  m_picture->setPixmap(QPixmap::fromImage(m_embedding ? picture : picture.copy(0, 0, image.width / 2, image.height)));
}

}  // namespace skein::gui

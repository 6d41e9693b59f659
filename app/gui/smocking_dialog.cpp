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

#include "common/error.hpp"
#include "preview_layout.hpp"
#include "render/smocking_view.hpp"
#include "smocking/smocking_svg.hpp"

namespace skein::gui {

SmockingDialog::SmockingDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Smocking preview"));
  auto* open = new QPushButton(tr("&Open pattern..."), this);
  open->setObjectName("openPattern");
  connect(open, &QPushButton::clicked, this, [this] {
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
  auto* gather_button = new QPushButton(tr("&Gather"), this);
  gather_button->setObjectName("gather");
  connect(gather_button, &QPushButton::clicked, this, [this] { gather(); });
  auto* controls = new QHBoxLayout;
  controls->addWidget(open);
  auto* form = new QFormLayout;
  form->addRow(tr("Gamma"), m_gamma);
  form->addRow(tr("Pull"), m_pull);
  controls->addLayout(form);
  controls->addWidget(gather_button);
  const auto preview = lay_out_preview(this, controls, tr("Open a smocking pattern (.smock), then Gather."));
  m_picture = preview.picture;
  m_summary = preview.summary;
  resize(1100, 560);
}

bool SmockingDialog::open_pattern(const QString& path) {
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

void SmockingDialog::show_picture() {
  // The flat pattern alone until gathered: an embedding with no steps taken draws the pattern twice.
  const auto e = m_embedding ? *m_embedding : smocking::make_mass_spring_system(*m_pattern, -1);
  const auto image = render::draw_smocking(*m_pattern, e, 500);
  const QImage picture(image.rgb.data(), image.width, image.height, image.width * 3, QImage::Format_RGB888);
  m_picture->setPixmap(QPixmap::fromImage(m_embedding ? picture : picture.copy(0, 0, image.width / 2, image.height)));
}

}  // namespace skein::gui

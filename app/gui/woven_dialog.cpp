#include "woven_dialog.hpp"

#include <chrono>

#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include "common/error.hpp"
#include "preview_layout.hpp"
#include "skein/config.hpp"
#include "woven/synthesis.hpp"
#include "woven/volume.hpp"
#include "woven/woven_render.hpp"

namespace skein::gui {
namespace {

QSpinBox* spin(QWidget* parent, const char* name, int low, int high, int value, const QString& tip) {
  auto* s = new QSpinBox(parent);
  s->setObjectName(name);
  s->setRange(low, high);
  s->setValue(value);
  s->setToolTip(tip);
  return s;
}

}  // namespace

WovenDialog::WovenDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Woven preview"));
  auto* open = new QPushButton(tr("&Open design..."), this);
  open->setObjectName("openDesign");
  connect(open, &QPushButton::clicked, this, [this] {
    const auto path = QFileDialog::getOpenFileName(this, tr("Open woven design"), QString::fromLatin1(SKEIN_SOURCE_DIR "/patterns"),
                                                   tr("Woven patterns and WIF drafts (*.weave *.wif);;All files (*)"));
    if (!path.isEmpty()) open_design(path);
  });
  auto* exemplars = new QPushButton(tr("&Exemplars..."), this);
  exemplars->setObjectName("openExemplars");
  exemplars->setToolTip(tr("A folder of exemplars from skein weave-exemplar (default: the bundled set, made on the first render)"));
  connect(exemplars, &QPushButton::clicked, this, [this] {
    const auto folder = QFileDialog::getExistingDirectory(this, tr("Exemplar folder"));
    if (!folder.isEmpty()) open_exemplars(folder);
  });
  m_warps = spin(this, "warps", 1, 4096, 24, tr("Crossings across: the design's repeat tiled over them"));
  m_wefts = spin(this, "wefts", 1, 4096, 16, tr("Crossings up"));
  m_samples = spin(this, "samples", 1, 4096, 8, tr("Paths per pixel of the volume path tracer"));
  m_width = spin(this, "width", 16, 4096, 480, tr("Picture width in pixels (the height is two thirds of it)"));
  m_field = new QDoubleSpinBox(this);
  m_field->setObjectName("field");
  m_field->setRange(0, 1e4);
  m_field->setValue(0);
  m_field->setSuffix(tr(" mm"));
  m_field->setToolTip(tr("The picture's width on the cloth, for close-ups; 0: the whole cloth"));
  m_render = new QPushButton(tr("&Render"), this);
  m_render->setObjectName("render");
  connect(m_render, &QPushButton::clicked, this, [this] { render(); });
  auto* form = new QFormLayout;
  auto* size = new QHBoxLayout;
  size->addWidget(m_warps);
  size->addWidget(new QLabel(tr("x"), this));
  size->addWidget(m_wefts);
  form->addRow(tr("Crossings"), size);
  form->addRow(tr("Samples"), m_samples);
  form->addRow(tr("Width"), m_width);
  form->addRow(tr("Close-up"), m_field);
  auto* controls = new QHBoxLayout;
  auto* buttons = new QVBoxLayout;
  buttons->addWidget(open);
  buttons->addWidget(exemplars);
  controls->addLayout(buttons);
  controls->addLayout(form);
  controls->addWidget(m_render);
  const auto preview = lay_out_preview(this, controls, tr("Open a woven design (.weave or .wif), then Render."));
  m_picture = preview.picture;
  m_summary = preview.summary;
  resize(900, 600);
}

WovenDialog::~WovenDialog() { m_worker.join(); }

bool WovenDialog::open_design(const QString& path) {
  try {
    const auto pattern = mesh::read_pattern(path.toStdString());
    m_design = woven::from_pattern(pattern);
    m_design_name = QString::fromStdString(pattern.name);
  } catch (const Error& e) {
    m_summary->setText(QString::fromStdString(e.what()));
    return false;
  }
  m_summary->setText(tr("%1: a %2 x %3 repeat").arg(m_design_name).arg(m_design->warps).arg(m_design->wefts));
  return true;
}

bool WovenDialog::open_exemplars(const QString& folder) {
  try {
    m_exemplars = std::make_shared<const std::vector<woven::Exemplar>>(woven::read_exemplars(folder.toStdString()));
  } catch (const Error& e) {
    m_summary->setText(QString::fromStdString(e.what()));
    return false;
  }
  m_summary->setText(tr("%1 exemplars from %2").arg(m_exemplars->size()).arg(folder));
  return true;
}

void WovenDialog::render() {
  if (!m_design) {
    m_summary->setText(tr("Open a woven design first."));
    return;
  }
  if (busy()) return;
  m_render->setEnabled(false);
  m_summary->setText(m_exemplars ? tr("Rendering...") : tr("Making the bundled exemplars, then rendering..."));
  const woven::Weave design = woven::tiled(*m_design, m_warps->value(), m_wefts->value());
  woven::WovenRenderOptions options;
  options.samples = m_samples->value();
  options.width = m_width->value();
  options.height = std::max(8, 2 * options.width / 3);
  options.field = m_field->value();
  auto exemplars = m_exemplars;
  m_worker.start(this, [this, design, options, exemplars]() mutable -> std::function<void()> {
    QImage picture;
    QString summary;
    try {
      const auto start = std::chrono::steady_clock::now();
      if (!exemplars) {
        std::vector<woven::Exemplar> made;
        for (const char* name : {"plain-weave", "twill-3-2", "twill-4-1", "satin-5-2", "basket-2x2"})
          made.push_back(woven::make_exemplar(mesh::read_pattern(std::string(SKEIN_SOURCE_DIR) + "/patterns/" + name + ".weave")));
        exemplars = std::make_shared<const std::vector<woven::Exemplar>>(std::move(made));
      }
      std::vector<woven::Weave> weaves;
      for (const auto& e : *exemplars) weaves.push_back(e.weave);
      const auto assignment = woven::synthesize(design, weaves);
      const auto score = woven::score(design, weaves, assignment);
      const auto volume = woven::make_volume(*exemplars, design, assignment, 15);
      const auto image = woven::render_woven(volume, options);
      picture = QImage(image.rgb.data(), image.width, image.height, image.width * 3, QImage::Format_RGB888).copy();
      summary = tr("%1 x %2 crossings from %3 exemplars: %4 of %5 crossings with every neighbour matched, %6 neighbouring pairs continuous; %7 s")
                    .arg(design.warps)
                    .arg(design.wefts)
                    .arg(exemplars->size())
                    .arg(score.consistent)
                    .arg(score.crossings)
                    .arg(score.continuity)
                    .arg(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0, 'f', 1);
    } catch (const std::exception& e) {
      summary = QString::fromStdString(e.what());
    }
    return [this, picture, summary, exemplars] {
      if (!m_exemplars) m_exemplars = exemplars;
      finish(picture, summary);
    };
  });
}

void WovenDialog::finish(const QImage& image, const QString& summary) {
  if (!image.isNull()) {
    m_picture->setPixmap(QPixmap::fromImage(image));
    m_has_picture = true;
  }
  m_summary->setText(summary);
  m_render->setEnabled(true);
}

}  // namespace skein::gui

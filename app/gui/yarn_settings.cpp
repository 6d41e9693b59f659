#include "yarn_settings.hpp"

#include <algorithm>
#include <cmath>

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include "stitchmesh/fabric.hpp"
#include "workflow/yarn_options.hpp"


namespace skein::gui {

namespace {

/// A yarn option's box, its range and tooltip from the schema (relax/yarn_options.hpp), as on the command line.
QDoubleSpinBox* number(const char* name, const char* key, double step, int decimals, double value) {
  const auto& spec = workflow::yarn_option(key);
  auto* box = new QDoubleSpinBox;
  box->setObjectName(name);
  // The box shows `decimals` digits and rounds its range to them: inside the schema's range, never past it
  // (2√2 would round up to 2.83, which the relaxer refuses).
  const double unit = std::pow(10.0, -decimals);
  const double low = std::ceil(spec.low / unit) * unit, high = std::floor(spec.high / unit) * unit;
  box->setDecimals(decimals);
  box->setRange(spec.above_low && low == spec.low ? low + unit : low, high);
  box->setSingleStep(step);
  box->setValue(value);
  box->setToolTip(QString::fromStdString(spec.help));
  return box;
}

QSpinBox* count(const char* name, const char* key, int value) {
  const auto& spec = workflow::yarn_option(key);
  auto* box = new QSpinBox;
  box->setObjectName(name);
  box->setRange(static_cast<int>(spec.low), static_cast<int>(spec.high));
  box->setValue(value);
  box->setToolTip(QString::fromStdString(spec.help));
  return box;
}

QCheckBox* flag(const char* name, const QString& text, bool value, const QString& tip) {
  auto* box = new QCheckBox(text);
  box->setObjectName(name);
  box->setChecked(value);
  box->setToolTip(tip);
  return box;
}

}  // namespace

YarnSettingsDialog::YarnSettingsDialog(const YarnSettings& settings, QWidget* parent) : QDialog(parent), m_base(settings) {
  setWindowTitle(tr("Yarn settings"));
  const auto& r = settings.relax;
  m_method = new QComboBox;
  m_method->setObjectName("method");
  m_method->addItem(tr("FIRE (quasi-static, fast)"), static_cast<int>(relax::YarnMethod::Fire));
  m_method->addItem(tr("Euler (Leaf 2018, Algorithm 1)"), static_cast<int>(relax::YarnMethod::Euler));
  m_method->addItem(tr("L-BFGS (quasi-Newton, CPU, fewest steps)"), static_cast<int>(relax::YarnMethod::Lbfgs));
  m_method->setCurrentIndex(m_method->findData(static_cast<int>(r.method)));
  m_tolerance = number("tolerance", "tolerance", 0.005, 4, r.tolerance);
  m_max_steps = count("maxSteps", "max_steps", static_cast<int>(r.max_steps));
  m_jam_steps = count("jamSteps", "jam_steps", static_cast<int>(r.jam_steps));
  m_take_up = number("takeUp", "take_up", 0.01, 3, settings.take_up);
  m_weight = new QComboBox;
  m_weight->setObjectName("weight");
  m_weight->addItem(tr("none (a tenth of the stitch width)"), QString());
  for (const auto& w : mesh::yarn_weights())
    m_weight->addItem(tr("%1 (CYC %2, %3 mm)").arg(QString::fromStdString(w.name)).arg(w.category).arg(w.diameter(), 0, 'f', 2), QString::fromStdString(w.name));
  m_weight->setCurrentIndex(std::max(0, m_weight->findData(QString::fromStdString(settings.weight))));
  m_weight->setToolTip(QString::fromStdString(workflow::yarn_option("weight").help) +
                       tr("; the stand-in preview and local re-relaxation after edits keep the emitted radius and need none"));
  const auto weight_set = [this] { m_take_up->setEnabled(m_weight->currentIndex() == 0); };
  weight_set();
  connect(m_weight, &QComboBox::currentIndexChanged, this, weight_set);
  m_clipped = flag("clippedScale", tr("Stop scale without the largest 0.1 % of the first forces (CPU)"), r.clipped_scale,
                   tr("Leaf's stop rule measures |∇E| against |∇E₀|; clipped, a few kinks of the emitted yarn do not set that scale, and "
                      "the run relaxes further (and longer)"));
  m_audit = flag("audit", tr("Audit every step for pull-through"), r.audit,
                 tr("The independent topology auditor checks every step; off, the guard still prevents pull-through but no count is reported"));
  m_active_set = flag("activeSet", tr("Active set: converged points stop being integrated (CPU)"), r.active_set.enabled,
                      tr("Points whose force and moves have settled sleep until their force grows or a neighbour moves; the stop rule still "
                         "sees every point"));
  m_adaptive = flag("adaptiveSamples", tr("Adaptive contact samples"), r.sampling.spacing > 0,
                    tr("The fewest contact samples per segment that leave no gap of yarn longer than the spacing; off, Leaf's odd count over L / 2r"));
  m_spacing = number("contactSpacing", "contact_spacing", 0.1, 2, r.sampling.spacing > 0 ? r.sampling.spacing : 2.5);
  m_spacing->setEnabled(m_adaptive->isChecked());
  connect(m_adaptive, &QCheckBox::toggled, m_spacing, &QWidget::setEnabled);
  m_rings = count("rings", "rings", settings.local.rings);
  m_halo = count("halo", "halo", settings.local.halo);

  auto* form = new QFormLayout;
  form->addRow(tr("Method"), m_method);
  form->addRow(tr("Stop tolerance"), m_tolerance);
  form->addRow(tr("Step cap"), m_max_steps);
  form->addRow(tr("Stop when jammed for [steps]"), m_jam_steps);
  form->addRow(m_clipped);
  form->addRow(tr("Yarn weight"), m_weight);
  form->addRow(tr("Take-up"), m_take_up);
  form->addRow(m_audit);
  form->addRow(m_active_set);
  form->addRow(m_adaptive);
  form->addRow(tr("Contact spacing [r]"), m_spacing);
  form->addRow(tr("Rings after edits"), m_rings);
  form->addRow(tr("Held rings"), m_halo);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel | QDialogButtonBox::RestoreDefaults);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(buttons->button(QDialogButtonBox::RestoreDefaults), &QPushButton::clicked, this, [this] {
    const YarnSettings defaults;
    m_method->setCurrentIndex(m_method->findData(static_cast<int>(defaults.relax.method)));
    m_tolerance->setValue(defaults.relax.tolerance);
    m_max_steps->setValue(static_cast<int>(defaults.relax.max_steps));
    m_jam_steps->setValue(static_cast<int>(defaults.relax.jam_steps));
    m_clipped->setChecked(defaults.relax.clipped_scale);
    m_take_up->setValue(defaults.take_up);
    m_weight->setCurrentIndex(0);
    m_audit->setChecked(defaults.relax.audit);
    m_active_set->setChecked(defaults.relax.active_set.enabled);
    m_adaptive->setChecked(false);
    m_rings->setValue(defaults.local.rings);
    m_halo->setValue(defaults.local.halo);
  });
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(buttons);
}

YarnSettings YarnSettingsDialog::settings() const {
  YarnSettings s = m_base;
  s.relax.method = static_cast<relax::YarnMethod>(m_method->currentData().toInt());
  s.relax.tolerance = m_tolerance->value();
  s.relax.max_steps = m_max_steps->value();
  s.relax.jam_steps = m_jam_steps->value();
  s.relax.clipped_scale = m_clipped->isChecked();
  s.take_up = m_take_up->value();
  s.weight = m_weight->currentData().toString().toStdString();
  s.relax.audit = m_audit->isChecked();
  s.relax.active_set.enabled = m_active_set->isChecked();
  s.relax.sampling.spacing = m_adaptive->isChecked() ? m_spacing->value() : 0;
  s.local.rings = m_rings->value();
  s.local.halo = m_halo->value();
  return s;
}

}  // namespace skein::gui

#pragma once

#include <QDialog>

#include "workflow/yarn_settings.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QSpinBox;

namespace skein::gui {

/// What Relax yarn (whole or local after edits) and the stand-in preview run with; saved with the project.
using YarnSettings = workflow::YarnSettings;

/// The dialog behind Relax > Yarn settings. Its fields carry object names (method, tolerance, maxSteps, jamSteps,
/// clippedScale, weight, takeUp, audit, activeSet, adaptiveSamples, contactSpacing, rings, halo) for tests.
class YarnSettingsDialog final : public QDialog {
  Q_OBJECT
public:
  explicit YarnSettingsDialog(const YarnSettings& settings, QWidget* parent = nullptr);
  /// The settings as the fields show them; what they do not show stays as given.
  YarnSettings settings() const;

private:
  YarnSettings m_base;
  QComboBox *m_method = nullptr, *m_weight = nullptr;
  QDoubleSpinBox *m_tolerance = nullptr, *m_take_up = nullptr, *m_spacing = nullptr;
  QSpinBox *m_max_steps = nullptr, *m_jam_steps = nullptr, *m_rings = nullptr, *m_halo = nullptr;
  QCheckBox *m_clipped = nullptr, *m_audit = nullptr, *m_active_set = nullptr, *m_adaptive = nullptr;
};

}  // namespace skein::gui

#pragma once
// File > Smocking preview (issue 30): a smocking pattern drawn on its grid and gathered by its threads
// (Zhou 2024 §4.1; docs/smocking.md), with γ and the pulling direction to try.

#include <optional>

#include <QDialog>

#include "smocking/smocking_embed.hpp"

class QComboBox;
class QDoubleSpinBox;
class QLabel;

namespace skein::gui {

/// Its fields carry object names (gamma, pull, gather, picture, summary) for tests.
class SmockingDialog final : public QDialog {
  Q_OBJECT
public:
  explicit SmockingDialog(QWidget* parent = nullptr);
  /// Reads a .smock file or an .svg drawing (as Italian smocking) and draws it flat; a bad file shows its error in
  /// the summary and keeps the last pattern.
  bool open_pattern(const QString& path);
  /// Gathers the open pattern at the fields' γ and pull and shows it beside the flat pattern.
  void gather();
  const std::optional<smocking::Embedding>& embedding() const { return m_embedding; }

private:
  void show_picture();
  std::optional<smocking::SmockingPattern> m_pattern;
  std::optional<smocking::Embedding> m_embedding;
  QDoubleSpinBox* m_gamma = nullptr;
  QComboBox* m_pull = nullptr;
  QLabel *m_picture = nullptr, *m_summary = nullptr;
};

}  // namespace skein::gui

#pragma once
// File > Smocking preview (issue 30): a smocking pattern drawn on its grid and gathered by its threads
// (Zhou 2024 §4.1; docs/smocking.md), with γ and the pulling direction to try, and the smocked fabric in 3-D
// (§4.2), made on a worker thread.

#include <atomic>
#include <optional>

#include <QDialog>

#include "preview_layout.hpp"
#include "smocking/smocking_embed.hpp"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;

namespace skein::gui {

/// Its fields carry object names (openPattern, gamma, pull, gather, subdivisions, cloth, picture, summary) for tests.
/// Closing it while the 3-D fabric is being made stops that at its next Newton step.
class SmockingDialog final : public QDialog {
  Q_OBJECT
public:
  explicit SmockingDialog(QWidget* parent = nullptr);
  ~SmockingDialog() override;
  /// Reads a .smock file or an .svg drawing (as Italian smocking) and draws it flat; a bad file shows its error in
  /// the summary and keeps the last pattern.
  bool open_pattern(const QString& path);
  /// Gathers the open pattern at the fields' γ and pull and shows it beside the flat pattern.
  void gather();
  const std::optional<smocking::Embedding>& embedding() const { return m_embedding; }
  /// Gathers the pattern (as gather()) and drapes the fine fabric in 3-D on a worker thread (smock_cloth); the
  /// picture, front and side, appears when it is done.
  void smock_in_3d();
  bool busy() const { return m_worker.busy(); }
  bool has_fabric() const { return m_has_fabric; }

private:
  void show_picture();
  void set_busy(bool busy);
  void finish(const QImage& image, const QString& summary);
  std::atomic<bool> m_stop{false};
  bool m_has_fabric = false;
  QComboBox* m_subdivisions = nullptr;
  QPushButton *m_open = nullptr, *m_gather = nullptr, *m_cloth = nullptr;
  std::optional<smocking::SmockingPattern> m_pattern;
  std::optional<smocking::Embedding> m_embedding;
  QDoubleSpinBox* m_gamma = nullptr;
  QComboBox* m_pull = nullptr;
  QLabel *m_picture = nullptr, *m_summary = nullptr;
  PreviewWorker m_worker;  ///< last: joined before the members its thread reads are gone
};

}  // namespace skein::gui

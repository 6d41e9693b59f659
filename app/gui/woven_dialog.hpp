#pragma once
// File > Woven preview (issue 29): a woven design synthesized from exemplars and rendered (Zhao 2012; docs/woven.md).
// The synthesis and the path tracing run on a worker thread; the picture appears when it is done.

#include <memory>
#include <optional>
#include <vector>

#include <QDialog>

#include "preview_layout.hpp"
#include "woven/exemplar.hpp"
#include "woven/weave.hpp"

class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;

namespace skein::gui {

/// Its fields carry object names (warps, wefts, samples, width, field, render, picture, summary) for tests.
class WovenDialog final : public QDialog {
  Q_OBJECT
public:
  explicit WovenDialog(QWidget* parent = nullptr);
  ~WovenDialog() override;
  /// Reads a woven pattern (.weave or .wif); a bad file shows its error in the summary and keeps the last design.
  bool open_design(const QString& path);
  /// Reads a folder of exemplars (.vdb); without one, the bundled set is made on the first render.
  bool open_exemplars(const QString& folder);
  /// Synthesizes the design at the fields' size and renders it on a worker thread.
  void render();
  bool busy() const { return m_worker.busy(); }
  bool has_picture() const { return m_has_picture; }

private:
  void finish(const QImage& image, const QString& summary);
  std::optional<woven::Weave> m_design;
  QString m_design_name;
  std::shared_ptr<const std::vector<woven::Exemplar>> m_exemplars;
  PreviewWorker m_worker;
  bool m_has_picture = false;
  QSpinBox *m_warps = nullptr, *m_wefts = nullptr, *m_samples = nullptr, *m_width = nullptr;
  QDoubleSpinBox* m_field = nullptr;
  QPushButton* m_render = nullptr;
  QLabel *m_picture = nullptr, *m_summary = nullptr;
};

}  // namespace skein::gui

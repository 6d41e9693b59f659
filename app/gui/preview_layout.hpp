#pragma once
// The body the preview windows share (File > Smocking preview, File > Woven preview).

#include <QString>

class QDialog;
class QLabel;
class QLayout;

namespace skein::gui {

struct PreviewWidgets {
  QLabel* picture = nullptr;  ///< object name "picture"
  QLabel* summary = nullptr;  ///< object name "summary": what happened, or the error of a bad file
};

/// Lays out `dialog`: its `controls` on top, the picture below them (scrolling when larger than the window) and
/// a summary line at the bottom that starts as `prompt`.
PreviewWidgets lay_out_preview(QDialog* dialog, QLayout* controls, const QString& prompt);

}  // namespace skein::gui

#pragma once
// The body the preview windows share (File > Smocking preview, File > Woven preview): their layout and the worker
// thread that makes their picture.

#include <atomic>
#include <functional>
#include <thread>

#include <QString>

class QDialog;
class QLabel;
class QLayout;
class QObject;

namespace skein::gui {

struct PreviewWidgets {
  QLabel* picture = nullptr;  ///< object name "picture"
  QLabel* summary = nullptr;  ///< object name "summary": what happened, or the error of a bad file
};

/// Lays out `dialog`: its `controls` on top, the picture below them (scrolling when larger than the window) and
/// a summary line at the bottom that starts as `prompt`.
PreviewWidgets lay_out_preview(QDialog* dialog, QLayout* controls, const QString& prompt);

/// One picture made at a time on a worker thread, so the window stays live while it is made.
class PreviewWorker {
public:
  PreviewWorker() = default;
  PreviewWorker(const PreviewWorker&) = delete;
  PreviewWorker& operator=(const PreviewWorker&) = delete;
  ~PreviewWorker() { join(); }
  /// Runs `work` on a new thread once the last one has ended. What `work` returns then runs on `owner`'s thread,
  /// where it may touch widgets; `work` must not throw.
  void start(QObject* owner, std::function<std::function<void()>()> work);
  /// A picture is being made: `work` or what it returned has not finished.
  bool busy() const { return m_thread.joinable() && !m_done; }
  /// Waits for the worker thread (its closing owner has told it to stop, or lets it finish).
  void join();

private:
  std::thread m_thread;
  std::atomic<bool> m_done{true};
};

}  // namespace skein::gui

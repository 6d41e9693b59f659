#include "preview_layout.hpp"

#include <QDialog>
#include <QLabel>
#include <QMetaObject>
#include <QScrollArea>
#include <QVBoxLayout>

namespace skein::gui {

PreviewWidgets lay_out_preview(QDialog* dialog, QLayout* controls, const QString& prompt) {
  PreviewWidgets w;
  w.picture = new QLabel(dialog);
  w.picture->setObjectName("picture");
  w.picture->setAlignment(Qt::AlignCenter);
  auto* scroll = new QScrollArea(dialog);
  scroll->setWidget(w.picture);
  scroll->setWidgetResizable(true);
  w.summary = new QLabel(prompt, dialog);
  w.summary->setObjectName("summary");
  w.summary->setWordWrap(true);
  auto* layout = new QVBoxLayout(dialog);
  layout->addLayout(controls);
  layout->addWidget(scroll, 1);
  layout->addWidget(w.summary);
  return w;
}

void PreviewWorker::start(QObject* owner, std::function<std::function<void()>()> work) {
  join();
  m_done = false;
  m_thread = std::thread([this, owner, work = std::move(work)] {
    auto then = work();
    QMetaObject::invokeMethod(owner, [this, then = std::move(then)] {
      then();
      m_done = true;
    });
  });
}

void PreviewWorker::join() {
  if (m_thread.joinable()) m_thread.join();
}

}  // namespace skein::gui

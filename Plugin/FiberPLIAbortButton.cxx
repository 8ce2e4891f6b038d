#include "FiberPLIAbortButton.h"

#include "FiberExecutions.h"

#include <pqApplicationCore.h>
#include <pqCoreConfiguration.h>
#include <pqCoreUtilities.h>
#include <pqProgressManager.h>

#include <QCoreApplication>
#include <QEvent>
#include <QPointer>
#include <QWidget>
#include <QWindow>

namespace
{
// While events are processed inside a running filter, only the presses pqProgressManager lets
// through (those on the abort button) may act. Keys and shortcuts (Delete, Ctrl+Z, Ctrl+S), the
// wheel over a property widget or a view, context menus, drops and closing a window would change,
// render or delete the pipeline that is executing: they are swallowed until the filter returns.
class PipelineChangeBlocker : public QObject
{
public:
  bool eventFilter(QObject*, QEvent* event) override
  {
    switch (event->type())
    {
      case QEvent::ShortcutOverride:
        event->accept(); // "the focus widget takes this key": no shortcut fires for it
        return true;
      case QEvent::Close:
        event->ignore(); // a swallowed close event that stays accepted would still close
        return true;
      case QEvent::Shortcut:
      case QEvent::KeyPress:
      case QEvent::KeyRelease:
      case QEvent::MouseButtonDblClick:
      case QEvent::Wheel:
      case QEvent::ContextMenu:
      case QEvent::DragEnter:
      case QEvent::DragMove:
      case QEvent::Drop:
      case QEvent::TabletPress:
      case QEvent::TouchBegin:
      case QEvent::TouchUpdate:
      case QEvent::TouchEnd:
        return true;
      default:
        return false;
    }
  }
};
} // namespace

void FiberPLIAbortButton::startup()
{
  pqProgressManager* progress = pqApplicationCore::instance()->getProgressManager();
  // Direct connections: the slots run inside the progress report, i.e. inside the filter.
  QObject::connect(progress, &pqProgressManager::progress, this, &FiberPLIAbortButton::onProgress);
  QObject::connect(progress, &pqProgressManager::abort, this, &FiberPLIAbortButton::onAbort);
  QObject::connect(
    progress, &pqProgressManager::progressEndEvent, this, &FiberPLIAbortButton::onProgressEnd);
}

void FiberPLIAbortButton::shutdown()
{
  if (pqApplicationCore* core = pqApplicationCore::instance())
  {
    QObject::disconnect(core->getProgressManager(), nullptr, this, nullptr);
  }
}

void FiberPLIAbortButton::onProgress(const QString&, int percent)
{
  if (!fiberpli::FiberExecutions::Running())
  {
    return; // not ours, or in another process: ParaView's behaviour unchanged
  }
  pqProgressManager* progress = pqApplicationCore::instance()->getProgressManager();
  progress->setEnableAbort(true);
  // Not at 0 %: ParaView avoids processing events there (QTimers expected to expire in order).
  // Not while an XML test script plays: its player would play the next event in the middle of the
  // filter. pqProgressManager emits no progress while this runs, so this never nests.
  if (percent > 0 && pqCoreConfiguration::instance()->testScriptCount() == 0)
  {
    letClicksReachTheButton(progress);
    // Installed last, so it sees every event before pqProgressManager's own filter.
    PipelineChangeBlocker blocker;
    QCoreApplication::instance()->installEventFilter(&blocker);
    pqCoreUtilities::processEvents();
    QCoreApplication::instance()->removeEventFilter(&blocker);
  }
}

void FiberPLIAbortButton::letClicksReachTheButton(pqProgressManager* progress)
{
  // pqProgressManager's event filter drops presses sent to any object not listed as non-blockable,
  // and a click from the window system is first sent to the top-level QWindow, which then routes it
  // to the widget under the mouse: unless the window holding the abort button is listed too, the
  // click dies there. The routed press is filtered again at its widget, so every widget but the
  // progress bar and its button stays blocked.
  QList<QObject*> windows;
  for (const QPointer<QObject>& object : progress->nonBlockableObjects())
  {
    if (auto* widget = qobject_cast<QWidget*>(object.data()))
    {
      if (QWindow* window = widget->window()->windowHandle())
      {
        windows.push_back(window);
      }
    }
  }
  for (QObject* window : windows)
  {
    if (!progress->nonBlockableObjects().contains(window))
    {
      progress->addNonBlockableObject(window);
    }
  }
}

void FiberPLIAbortButton::onAbort()
{
  fiberpli::FiberExecutions::Abort();
}

void FiberPLIAbortButton::onProgressEnd()
{
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(false);
}

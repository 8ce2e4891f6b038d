// The GUI's abort button (the x beside the progress bar) stops a running FiberPLI filter.
#ifndef FiberPLIAbortButton_h
#define FiberPLIAbortButton_h

#include <QObject>

/// ParaView 5.11 leaves its abort button without effect: pqProgressManager::triggerAbort() only
/// emits abort(), which nothing in the client is connected to, the button is never enabled, and no
/// events are processed while a filter executes (the processEvents call in
/// pqProgressManager::setProgress is commented out), so a click could not even arrive.
/// This auto-start part of the plugin (paraview_add_plugin UI_INTERFACES) closes the three gaps
/// for FiberPLI filters in the built-in session, where they run in the GUI thread:
/// - on every progress report of a running FiberPLI execution it enables the button and lets Qt
///   process the pending events; pqProgressManager's event filter still drops every key and mouse
///   press except those on the progress widget and its abort button (whose window is added to
///   its list, see letClicksReachTheButton), and a filter of ours swallows keys, shortcuts, the
///   wheel, context menus, drops and window closes meanwhile, so nothing can change, render or
///   delete the executing pipeline (ParaView 5.12 processes events in
///   pqProgressManager::onProgress the same way, without that second filter);
/// - the abort() signal asks the running FiberPLI executions to stop
/// (Conversion/FiberExecutions.h);
///   each stops at its next progress check, and the abort applies to that execution only;
/// - when the progress ends, the button is disabled again.
/// With a remote server the filters run in the server process, none is listed here, and nothing
/// changes (the button stays as ParaView leaves it).
class FiberPLIAbortButton : public QObject
{
  Q_OBJECT
public:
  void startup();
  void shutdown();

private:
  static void letClicksReachTheButton(class pqProgressManager* progress);

private Q_SLOTS:
  void onProgress(const QString& message, int percent);
  void onAbort();
  void onProgressEnd();
};

#endif

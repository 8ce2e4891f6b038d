// GUI test: the abort button beside ParaView's progress bar stops a running solve within a second
// with one click, leaves a message "aborted by the user" in the output window (the GUI's Output
// Messages), does not start a new run at the next pipeline request (the view's update right after
// Apply), and the pipeline stays usable; the same for FiberMetrics (README "Solver",
// Plugin/FiberPLIAbortButton.h, Conversion/FiberProgress.h AbortScope).
//
// The window is built from ParaView's own client parts (pqPVApplicationCore, the builtin server,
// pqStatusBar with its pqProgressWidget), the plugin is loaded through pqPluginManager as File →
// Load Plugin does, so its auto-start part runs. A long solve (the default 1000-fiber cube) is
// started as Apply starts it (vtkSMSourceProxy::UpdatePipeline in the GUI thread); a timer, which
// can only fire if events are processed while the solver runs, clicks the abort button through
// Qt's window-system input path (QTest on the QWindow: the same route an X11 click takes, so
// ParaView's event filter that blocks presses during progress is passed as for a user).
//
// Usage: FiberPLIGuiAbort <path to FiberPLI.so>   (needs a display: xvfb-run)
#include "FiberExecutions.h"

#include <pqApplicationCore.h>
#include <pqObjectBuilder.h>
#include <pqPVApplicationCore.h>
#include <pqPluginManager.h>
#include <pqProgressWidget.h>
#include <pqServer.h>
#include <pqServerResource.h>
#include <pqStatusBar.h>

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPVDataInformation.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMParaViewPipelineController.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSourceProxy.h>
#include <vtkSmartPointer.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QMainWindow>
#include <QTimer>
#include <QToolButton>
#include <QtTest/QTest>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
int failures = 0;
void check(bool ok, const char* what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
  failures += ok ? 0 : 1;
}

// What reaches the output window (in the GUI: the Output Messages panel).
class MessageLog : public vtkOutputWindow
{
public:
  static MessageLog* New();
  vtkTypeMacro(MessageLog, vtkOutputWindow);
  std::string Text;
  void DisplayText(const char* text) override
  {
    this->Text += text ? text : "";
    this->Text += "\n";
  }
};
vtkStandardNewMacro(MessageLog);

void countStart(vtkObject*, unsigned long, void* clientData, void*)
{
  ++*static_cast<int*>(clientData);
}

/// Runs `proxy`'s update, clicks the abort button `afterMs` after the start through Qt's
/// window-system input path, and checks the abort: the update stops soon, one click suffices, the
/// next pipeline request runs nothing, the output is empty and the log says why.
void abortOnce(QMainWindow& window, QToolButton* abortButton, vtkSMSourceProxy* proxy,
  MessageLog* log, const char* name, int afterMs)
{
  bool clicked = false, enabledAtClick = false;
  QElapsedTimer sinceClick;
  QTimer::singleShot(afterMs,
    [&]()
    {
      enabledAtClick = abortButton->isEnabled();
      clicked = true;
      sinceClick.start();
      const QPoint at = abortButton->mapTo(&window, abortButton->rect().center());
      QTest::mouseClick(window.windowHandle(), Qt::LeftButton, Qt::NoModifier, at);
    });
  log->Text.clear();
  proxy->UpdatePipeline();
  const qint64 afterClick = clicked ? sinceClick.elapsed() : -1;
  std::printf(
    "%s: update returned %lld ms after the click\n", name, static_cast<long long>(afterClick));
  const std::string what = name;
  check(
    clicked && enabledAtClick, (what + ": the abort button was enabled during the run").c_str());
  check(clicked && afterClick >= 0 && afterClick < 10000,
    (what + ": one click stopped the run soon").c_str());
  auto* algorithm = vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject());
  check(algorithm->GetAbortExecute() == 0, (what + ": no abort request is left").c_str());
  check(log->Text.find("aborted by the user") != std::string::npos,
    (what + ": the output window says the run was aborted by the user").c_str());
  // What the GUI does right after Apply: the view asks the pipeline for the data again. An output
  // left marked aborted would start a new run from 0 % here.
  int starts = 0;
  vtkNew<vtkCallbackCommand> onStart;
  onStart->SetCallback(countStart);
  onStart->SetClientData(&starts);
  const unsigned long tag = algorithm->AddObserver(vtkCommand::StartEvent, onStart);
  QElapsedTimer again;
  again.start();
  algorithm->Update();
  proxy->UpdatePipeline();
  algorithm->RemoveObserver(tag);
  std::printf(
    "%s: the next requests took %lld ms\n", name, static_cast<long long>(again.elapsed()));
  check(starts == 0, (what + ": the next pipeline request started no new run").c_str());
  check(algorithm->GetOutputDataObject(0)->GetNumberOfElements(vtkDataObject::POINT) == 0,
    (what + ": the aborted output is empty").c_str());
}

vtkSmartPointer<vtkSMSourceProxy> makeProxy(
  vtkSMSessionProxyManager* pxm, const char* group, const char* name)
{
  vtkSmartPointer<vtkSMSourceProxy> proxy;
  proxy.TakeReference(vtkSMSourceProxy::SafeDownCast(pxm->NewProxy(group, name)));
  return proxy;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s <FiberPLI plugin>\n", argv[0]);
    return 2;
  }
  const QString plugin = QString::fromLocal8Bit(argv[1]);
  char* qtArgv[] = { argv[0], nullptr }; // ParaView's options must not see the plugin path
  int qtArgc = 1;
  QApplication app(qtArgc, qtArgv);
  pqPVApplicationCore core(qtArgc, qtArgv);

  QMainWindow window;
  window.setStatusBar(
    new pqStatusBar(&window)); // ParaView's status bar: progress widget + abort button
  window.resize(900, 300);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window))
  {
    std::fprintf(stderr, "the window was never shown\n");
    return 1;
  }
  vtkNew<MessageLog> log; // after the application core, which may install its own window
  vtkOutputWindow::SetInstance(log);
  pqServer* server = core.getObjectBuilder()->createServer(pqServerResource("builtin:"));
  QString error;
  if (!server ||
    core.getPluginManager()->loadExtension(server, plugin, &error, false) !=
      pqPluginManager::LOADED)
  {
    std::fprintf(stderr, "cannot load %s: %s\n", argv[1], error.toLocal8Bit().data());
    return 1;
  }
  QToolButton* abortButton = window.findChild<pqProgressWidget*>()->abortButton();

  vtkSMSessionProxyManager* pxm = server->proxyManager();
  vtkNew<vtkSMParaViewPipelineController> controller;
  auto cube = makeProxy(pxm, "sources", "FiberCubeSource"); // 1000 fibers: a solve of minutes
  controller->InitializeProxy(cube);
  cube->UpdateVTKObjects();
  controller->RegisterPipelineProxy(cube);
  auto solver = makeProxy(pxm, "filters", "FiberCollisionSolver");
  controller->PreInitializeProxy(solver);
  vtkSMPropertyHelper(solver, "Input").Set(cube, 0);
  vtkSMPropertyHelper(solver, "MaxSteps").Set(1000000);
  controller->PostInitializeProxy(solver);
  solver->UpdateVTKObjects();
  controller->RegisterPipelineProxy(solver);
  cube->UpdatePipeline(); // the fibers exist before the clock starts

  // Closing the window during the solve must be refused: it would delete the executing pipeline
  // (the plugin swallows closes, keys, shortcuts, the wheel, context menus and drops meanwhile; of
  // these only the close can be delivered in this harness: Xvfb without a window manager delivers
  // no shortcut even outside a filter).
  bool windowOpenAfterClose = false;
  QTimer::singleShot(1000,
    [&]()
    {
      window.close();
      windowOpenAfterClose = window.isVisible();
    });

  // Click after 2 s of solving (the solve would run for minutes with MaxSteps 10^6).
  abortOnce(window, abortButton, solver, log, "FiberCollisionSolver", 2000);
  check(windowOpenAfterClose, "closing the window during the solve was refused");
  auto* algorithm = vtkAlgorithm::SafeDownCast(solver->GetClientSideObject());
  check(!fiberpli::FiberExecutions::Running(), "no FiberPLI execution is listed as running");
  QApplication::processEvents();
  check(!abortButton->isEnabled(), "the abort button is disabled again after the solve");

  // Usable afterwards: the next update solves again (2 steps), with every fiber in its output.
  vtkSMPropertyHelper(solver, "MaxSteps").Set(2);
  solver->UpdateVTKObjects();
  solver->UpdatePipeline();
  const vtkIdType fibers = solver->GetDataInformation()->GetNumberOfCells();
  std::printf("after the abort: %lld fibers\n", static_cast<long long>(fibers));
  check(fibers == 1000, "the next update gives all 1000 fibers");
  check(algorithm->GetAbortExecute() == 0, "that update was not aborted");

  // FiberMetrics with a Monte Carlo volume fraction of 2·10^9 samples (minutes): aborted the same
  // way.
  auto metrics = makeProxy(pxm, "filters", "FiberMetrics");
  controller->PreInitializeProxy(metrics);
  vtkSMPropertyHelper(metrics, "Input").Set(solver, 0);
  vtkSMPropertyHelper(metrics, "VolumeFractionMethod").Set(1);
  vtkSMPropertyHelper(metrics, "Samples").Set(2000000000);
  controller->PostInitializeProxy(metrics);
  metrics->UpdateVTKObjects();
  controller->RegisterPipelineProxy(metrics);
  abortOnce(window, abortButton, metrics, log, "FiberMetrics", 1500);

  controller->UnRegisterProxy(metrics);
  controller->UnRegisterProxy(solver);
  controller->UnRegisterProxy(cube);
  std::printf("%s\n", failures == 0 ? "gui abort checks passed" : "gui abort checks FAILED");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// GUI test: the Properties panel shows FiberPLI's labels with their units ("Edge Length (µm)"),
// PLISimulation's angle lists with their names ("Rotation Angles (°)", not only a "Value"
// header), while the XML labels, and so the pvpython names, stay without units
// (Plugin/FiberPLIUnitLabels.h). FiberFieldSource shows the guide properties, with their units, for
// guide lines (polydata) and the orientation arrays for an image, never the other kind's.
//
// The panel is ParaView's own pqProxyWidget for a proxy, shown in a window; the plugin is loaded
// through pqPluginManager as File → Load Plugin does, so its auto-start parts run.
//
// Usage: FiberPLIGuiUnitLabels <path to FiberPLI.so>   (needs a display: xvfb-run)
#include <pqApplicationCore.h>
#include <pqInterfaceTracker.h>
#include <pqObjectBuilder.h>
#include <pqPVApplicationCore.h>
#include <pqPluginManager.h>
#include <pqProxyWidget.h>
#include <pqServer.h>
#include <pqServerResource.h>
#include <pqStandardPropertyWidgetInterface.h>

#include <vtkNew.h>
#include <vtkSMParaViewPipelineController.h>
#include <vtkSMProperty.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMProxy.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSmartPointer.h>

#include <QApplication>
#include <QLabel>
#include <QStringList>
#include <QTextDocumentFragment>
#include <QtTest/QTest>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
int failures = 0;
void check(bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
  failures += ok ? 0 : 1;
}

// The labels a user sees in the panel of a new `name` proxy (advanced properties included).
QStringList panelLabels(vtkSMProxy* proxy)
{
  pqProxyWidget panel(proxy);
  panel.filterWidgets(true); // show the advanced properties too
  panel.resize(500, 1500);
  panel.show();
  QTest::qWaitForWindowExposed(&panel);
  QApplication::processEvents();
  QStringList labels;
  for (QLabel* label : panel.findChildren<QLabel*>())
  {
    if (label->isVisible())
    {
      labels << QTextDocumentFragment::fromHtml(label->text()).toPlainText().trimmed();
    }
  }
  std::printf("labels: %s\n", labels.join(" | ").toUtf8().data());
  return labels;
}

void expect(const QStringList& labels, const char* proxy, const QString& text)
{
  check(labels.contains(text), std::string(proxy) + " shows '" + text.toStdString() + "'");
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
  char dr[] = "--dr";
  char* qtArgv[] = { argv[0], dr, nullptr };
  int qtArgc = 2;
  QApplication app(qtArgc, qtArgv);
  pqPVApplicationCore core(qtArgc, qtArgv);
  pqServer* server = core.getObjectBuilder()->createServer(pqServerResource("builtin:"));
  QString error;
  if (!server ||
    core.getPluginManager()->loadExtension(server, plugin, &error, false) !=
      pqPluginManager::LOADED)
  {
    std::fprintf(stderr, "cannot load %s: %s\n", argv[1], error.toLocal8Bit().data());
    return 1;
  }
  // The panel's standard widgets and decorators, as the paraview application registers them.
  core.interfaceTracker()->addInterface(new pqStandardPropertyWidgetInterface(&core));
  vtkSMSessionProxyManager* pxm = server->proxyManager();
  vtkNew<vtkSMParaViewPipelineController> controller;
  vtkSmartPointer<vtkSMProxy> source;
  source.TakeReference(pxm->NewProxy("sources", "FiberCubeSource"));
  controller->InitializeProxy(source);
  controller->RegisterPipelineProxy(source);
  vtkSmartPointer<vtkSMProxy> filter;
  filter.TakeReference(pxm->NewProxy("filters", "PLISimulation"));
  controller->PreInitializeProxy(filter);
  vtkSMPropertyHelper(filter, "Input").Set(source, 0);
  controller->PostInitializeProxy(filter);
  controller->RegisterPipelineProxy(filter);

  const QStringList cube = panelLabels(source);
  expect(cube, "FiberCubeSource", QString::fromUtf8("Edge Length (µm)"));
  expect(cube, "FiberCubeSource", QString::fromUtf8("Fiber Radius (µm)"));
  expect(cube, "FiberCubeSource", QString::fromUtf8("Crossing Angle (°)"));
  expect(cube, "FiberCubeSource", "Populations"); // no unit, no suffix
  const QStringList sim = panelLabels(filter);
  expect(sim, "PLISimulation", "Wavelength (nm)");
  expect(sim, "PLISimulation", QString::fromUtf8("Rotation Angles (°) Value Range: [0, 180]"));
  expect(sim, "PLISimulation", QString::fromUtf8("Tilt Azimuths (°) Value Range: [0, 360]"));
  expect(sim, "PLISimulation", "Absorption (1/mm)");

  // FiberFieldSource on fibers (guide lines) and on an image with a vector array (Swirl).
  vtkSmartPointer<vtkSMProxy> grid;
  grid.TakeReference(pxm->NewProxy("sources", "FastUniformGrid"));
  controller->InitializeProxy(grid);
  controller->RegisterPipelineProxy(grid);
  QStringList onGuides, onImage;
  for (vtkSMProxy* input : { source.GetPointer(), grid.GetPointer() })
  {
    vtkSmartPointer<vtkSMProxy> field;
    field.TakeReference(pxm->NewProxy("filters", "FiberFieldSource"));
    controller->PreInitializeProxy(field);
    vtkSMPropertyHelper(field, "Input").Set(input, 0);
    controller->PostInitializeProxy(field);
    controller->RegisterPipelineProxy(field);
    (input == source ? onGuides : onImage) = panelLabels(field);
    controller->UnRegisterProxy(field);
  }
  controller->UnRegisterProxy(grid);
  expect(onGuides, "FiberFieldSource on guides", QString::fromUtf8("Guide Radius (µm)"));
  expect(onGuides, "FiberFieldSource on guides", QString::fromUtf8("Guide Spacing (µm)"));
  expect(onGuides, "FiberFieldSource on guides", "Guide Populations");
  check(
    !onGuides.contains("Orientation Array"), "FiberFieldSource on guides hides Orientation Array");
  expect(onImage, "FiberFieldSource on an image", "Orientation Array");
  check(!onImage.contains(QString::fromUtf8("Guide Radius (µm)")),
    "FiberFieldSource on an image hides Guide Radius");
  check(!onImage.contains("Guides"), "FiberFieldSource on an image hides the Guides group");

  // The XML label (the pvpython name's source) has no unit.
  const std::string xmlLabel = source->GetProperty("EdgeLength")->GetXMLLabel();
  check(xmlLabel == "Edge Length", "the XML label stays '" + xmlLabel + "' (pvpython EdgeLength)");

  controller->UnRegisterProxy(filter);
  controller->UnRegisterProxy(source);
  std::printf(
    "%s\n", failures == 0 ? "gui unit label checks passed" : "gui unit label checks FAILED");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

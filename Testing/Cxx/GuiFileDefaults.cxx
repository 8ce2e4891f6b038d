// GUI test: the plugin's file defaults in the ParaView client (Plugin/FiberPLIFileDefaults.h).
// File → Open of a fastPLI .dat with the file dialog's "Supported Files" filter
// (pqLoadDataReaction::loadFilesForSupportedTypes, what the dialog calls) opens it with
// FiberReader without asking to choose between FiberReader and ParaView's Tecplot readers; Save
// Data's writer for .vtp and .vti defaults to binary data, which Debian's expat reads back.
//
// The client parts are ParaView's own (pqPVApplicationCore, the builtin server); the plugin is
// loaded through pqPluginManager as File → Load Plugin does, so its auto-start parts run. A reader
// prompt would be a modal dialog: a timer closes any that appears and the test fails.
//
// Usage: FiberPLIGuiFileDefaults <path to FiberPLI.so> <a fastPLI .dat file>   (needs xvfb-run)
#include <pqActiveObjects.h>
#include <pqApplicationCore.h>
#include <pqLoadDataReaction.h>
#include <pqObjectBuilder.h>
#include <pqPVApplicationCore.h>
#include <pqPipelineSource.h>
#include <pqPluginManager.h>
#include <pqServer.h>
#include <pqServerResource.h>
#include <vtkSMSessionProxyManager.h>

#include <vtkSMPropertyHelper.h>
#include <vtkSMProxy.h>
#include <vtkSMProxyManager.h>
#include <vtkSMSourceProxy.h>
#include <vtkSMWriterFactory.h>
#include <vtkSmartPointer.h>

#include <QApplication>
#include <QDialog>
#include <QFileInfo>
#include <QTimer>

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
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: %s <FiberPLI plugin> <fastPLI .dat>\n", argv[0]);
    return 2;
  }
  const QString plugin = QString::fromLocal8Bit(argv[1]);
  const QString dat = QString::fromLocal8Bit(argv[2]);
  // --dr: the user's settings are neither read nor written (the test must not change them).
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

  pqActiveObjects::instance().setActiveServer(server); // File > Open opens on the active server

  // A reader prompt is modal: note and close it, so the test ends either way.
  bool prompted = false;
  QTimer closer;
  QObject::connect(&closer, &QTimer::timeout,
    [&]()
    {
      if (auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget()))
      {
        prompted = true;
        dialog->reject();
      }
    });
  closer.start(200);
  QList<QStringList> files;
  files << QStringList(dat);
  const QVector<pqPipelineSource*> opened = pqLoadDataReaction::loadFilesForSupportedTypes(files);
  closer.stop();
  check(!prompted, "File > Open of a .dat opened it without asking which reader to use");
  // (ParaView 5.11 registers the reader but returns an empty list here: look it up by name.)
  (void)opened;
  vtkSMSessionProxyManager* pxm = server->proxyManager();
  const std::string name = QFileInfo(dat).fileName().toStdString();
  vtkSMProxy* openedProxy = pxm->GetProxy("sources", name.c_str());
  const std::string reader = openedProxy ? openedProxy->GetXMLName() : "";
  check(reader == "FiberReader", "the .dat opened with FiberReader (got '" + reader + "')");

  // Save Data: the writer the dialog would create for .vtp / .vti, and its DataMode.
  if (auto* source = vtkSMSourceProxy::SafeDownCast(openedProxy))
  {
    source->UpdatePipeline();
    vtkSMWriterFactory* writers = vtkSMProxyManager::GetProxyManager()->GetWriterFactory();
    vtkSmartPointer<vtkSMProxy> writer;
    writer.TakeReference(writers->CreateWriter("fibers.vtp", source, 0));
    const int mode = writer && writer->GetProperty("DataMode")
      ? vtkSMPropertyHelper(writer, "DataMode").GetAsInt()
      : -1;
    check(mode == 1,
      "Save Data's .vtp writer defaults to Binary (DataMode " + std::to_string(mode) + ")");
  }

  std::printf(
    "%s\n", failures == 0 ? "gui file defaults checks passed" : "gui file defaults checks FAILED");
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// The GUI's file defaults for FiberPLI users: .dat opens with FiberReader, XML writers write
// binary.
#ifndef FiberPLIFileDefaults_h
#define FiberPLIFileDefaults_h

#include <QObject>

/// An auto-start part of the plugin's Qt side (paraview_add_plugin UI_INTERFACES), so it acts in
/// the GUI only; pvpython and pvbatch keep ParaView's defaults.
/// - File → Open of a `.dat` would ask each time whether FiberReader or one of ParaView's two
///   Tecplot readers should read it. ParaView 5.11 has no reader priority in the XML, but it has
///   default readers by file pattern (the setting RepresentedArrayListSettings.ReaderDetails, what
///   the dialog's "Set reader as default" adds, used when the file dialog's filter is "Supported
///   Files"). FiberReader is added there for `*.dat`, the same way, unless some entry already
///   covers `*.dat` (the user's own choice stays; removing ours and choosing another reader with
///   "Set reader as default" keeps that one).
/// - Save Data's XML writers (.vtp, .vti, .vtu, …) default to raw appended data, which Debian's
///   expat cannot read back (the file then does not reopen in the same ParaView). Their default
///   DataMode becomes Binary through a settings collection of the lowest priority: the user's own
///   settings and the dialog's choice still win.
class FiberPLIFileDefaults : public QObject
{
  Q_OBJECT
public:
  void startup();
  void shutdown() {}

private:
  static void writeXMLBinary();
  static void openDatWithFiberReader();
};

#endif

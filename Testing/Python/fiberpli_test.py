"""Helpers shared by the pvpython tests: plugin loading and argument parsing."""
import sys


def load_plugin(ns):
    """Loads the plugin given as argv[1] into the namespace ns (the test's globals())."""
    from paraview.simple import LoadPlugin
    LoadPlugin(sys.argv[1], remote=False, ns=ns)


def option(flag, default=None):
    """Value after a command-line flag such as -T or -V."""
    if flag in sys.argv:
        return sys.argv[sys.argv.index(flag) + 1]
    return default


def check(condition, message):
    """Like assert, but never disabled by -O."""
    if not condition:
        raise AssertionError(message)


class ErrorCatcher:
    """Collects the VTK error/warning messages of a proxy's algorithm and its executive, so that a
    bad-input test asserts them instead of printing them (a printed "ERR|" fails every test)."""

    def __init__(self, proxy):
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING

        self.errors = []
        self.warnings = []

        @calldata_type(VTK_STRING)
        def on_error(obj, event, message=None):
            self.errors.append(str(message))

        @calldata_type(VTK_STRING)
        def on_warning(obj, event, message=None):
            self.warnings.append(str(message))

        # A proxy, or a VTK algorithm itself (e.g. the inner writer of a parallel writer).
        algorithm = proxy.GetClientSideObject() if hasattr(proxy, "GetClientSideObject") else proxy
        for obj in (algorithm, algorithm.GetExecutive()):
            obj.AddObserver("ErrorEvent", on_error)
            obj.AddObserver("WarningEvent", on_warning)

    def text(self):
        return "\n".join(self.errors)

    def clear(self):
        self.errors.clear()
        self.warnings.clear()


def compare_image(proxy, cell_array, position, up=(0, 1, 0), focal=(0, 0, 0)):
    """Renders proxy (coloured by a cell array) in a fixed 400x300 view with an explicit camera and
    compares it with the baseline given by -V (smtesting); raises when it differs."""
    from paraview.simple import ColorBy, CreateView, Render, Show
    from paraview import smtesting

    smtesting.ProcessCommandLineArguments()
    view = CreateView("RenderView")
    view.ViewSize = [400, 300]
    view.OrientationAxesVisibility = 0
    view.Background = [0.1, 0.1, 0.15]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = Show(proxy, view)
    ColorBy(display, ("CELLS", cell_array))
    view.CameraPosition = list(position)
    view.CameraFocalPoint = list(focal)
    view.CameraViewUp = list(up)
    Render(view)
    if not smtesting.DoRegressionTesting(view.SMProxy):
        raise RuntimeError("image differs from the baseline")

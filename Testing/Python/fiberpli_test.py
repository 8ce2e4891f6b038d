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

        algorithm = proxy.GetClientSideObject()
        for obj in (algorithm, algorithm.GetExecutive()):
            obj.AddObserver("ErrorEvent", on_error)
            obj.AddObserver("WarningEvent", on_warning)

    def text(self):
        return "\n".join(self.errors)

    def clear(self):
        self.errors.clear()
        self.warnings.clear()

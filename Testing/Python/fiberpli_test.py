"""Helpers shared by the pvpython tests: plugin loading, argument parsing, error capture, images, MPI inputs."""
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


# Script of a ProgrammableSource (it runs on every rank under MPI) giving the MPI error tests their
# input: CELLS is a Python expression in `rank`, a list of polylines (lists of points); every
# point's radius is BAD on rank 1 and 1.0 on the other ranks.
_RANK_FIBERS_SCRIPT = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
out = self.GetPolyDataOutput()
points = vtkPoints()
radius = vtkDoubleArray()
radius.SetName("radius")
lines = vtkCellArray()
for cell in CELLS:
    lines.InsertNextCell(len(cell))
    for p in cell:
        lines.InsertCellPoint(points.InsertNextPoint(p))
        radius.InsertNextValue(BAD if rank == 1 else 1.0)
out.SetPoints(points)
out.SetLines(lines)
out.GetPointData().AddArray(radius)
"""


def rank_fibers_script(cells, radius_on_rank1):
    """ProgrammableSource script of the polylines `cells` (an expression in `rank`) whose radius
    is `radius_on_rank1` on rank 1 and 1.0 elsewhere."""
    return _RANK_FIBERS_SCRIPT.replace("CELLS", cells).replace("BAD", repr(float(radius_on_rank1)))

"""pvbatch --symmetric under mpiexec -n 2: FiberFieldSource makes its pieces. Every rank builds the
same orientation field (a bend and a crossing second field), and the same guide lines (two crossing
bundles, one population each), and runs the source; the pipeline
update gives it piece r of 2, which must hold exactly the fibers [N·r/2, N·(r+1)/2) of the
one-piece output, bit for bit, with their global fiber ids and the same field data."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData  # noqa: E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(100)  # a rank stuck in a collective dies instead of hanging
load_plugin(globals())
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")

img = vtkImageData()
img.SetDimensions(31, 31, 6)
z, y, x = np.meshgrid(np.arange(6.0), np.arange(31.0), np.arange(31.0), indexing="ij")
x, y = x.ravel(), y.ravel()
rho = np.maximum(np.hypot(x, y), 1e-9)
bend = np.c_[-y / rho, x / rho, np.zeros_like(x)]
bend[(rho < 8) | (rho > 26)] = 0.0
for name, values in (("bend", bend), ("across", np.tile([0.0, 0.0, 1.0], (len(x), 1)))):
    a = numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    a.SetName(name)
    img.GetPointData().AddArray(a)
producer = TrivialProducer()
producer.GetClientSideObject().SetOutput(img)


def fibers(poly):
    """[(fiber_id, bundle_id, points, radii)] of every line, in cell order."""
    out = []
    if poly.GetNumberOfCells() == 0:
        return out
    pts = vtk_to_numpy(poly.GetPoints().GetData())
    radius = vtk_to_numpy(poly.GetPointData().GetArray("radius"))
    ids = poly.GetCellData().GetArray("fiber_id")
    bundles = poly.GetCellData().GetArray("bundle_id")
    for c in range(poly.GetNumberOfCells()):
        cell = poly.GetCell(c).GetPointIds()
        k = [cell.GetId(i) for i in range(cell.GetNumberOfIds())]
        out.append((int(ids.GetTuple1(c)), int(bundles.GetTuple1(c)), pts[k].tolist(), radius[k].tolist()))
    return out


def field(poly):
    fd = poly.GetFieldData()
    return {fd.GetArrayName(i): [fd.GetArray(i).GetTuple1(k) for k in range(fd.GetArray(i).GetNumberOfTuples())]
            for i in range(fd.GetNumberOfArrays())}


def check_pieces(proxy, what):
    proxy.UpdatePipeline()
    local = vtkPolyData()
    local.DeepCopy(proxy.GetClientSideObject().GetOutputDataObject(0))
    algorithm = proxy.GetClientSideObject()
    algorithm.UpdatePiece(0, 1, 0)  # the serial output, on this rank alone
    whole = algorithm.GetOutputDataObject(0)
    mine, everything = fibers(local), fibers(whole)
    n = len(everything)
    check(n >= 4, "%s: %d fibers is too few to split" % (what, n))
    begin, end = n * rank // 2, n * (rank + 1) // 2
    check(mine == everything[begin:end],
          "%s: rank %d's %d fibers differ from fibers %d..%d of the serial output" % (what, rank, len(mine), begin, end - 1))
    check(field(local) == field(whole), "%s: rank %d field data %r, serial %r" % (what, rank, field(local), field(whole)))
    print("%s: rank %d holds fibers %d..%d of %d" % (what, rank, begin, end - 1, n))
    Delete(proxy)


one = FiberFieldSource(Input=producer, VolumeFraction=0.2, FiberRadius=0.5, SegmentLength=1.0, Seed=2)
one.OrientationArray = ["POINTS", "bend"]
check_pieces(one, "bend")
two = FiberFieldSource(Input=producer, VolumeFraction=0.2, FiberRadius=0.5, SegmentLength=1.0, Seed=2,
                       RadiusSpread=0.3, RadiusDistribution="Gamma", IntegrationScheme="RK2")
two.OrientationArray = ["POINTS", "bend"]
two.SecondOrientationArray = ["POINTS", "across"]
check_pieces(two, "bend and crossing")

# Guide lines: arcs about the z axis (bundle_id 0) and straight lines along z (bundle_id 1).
points, lines, bundle_ids = vtkPoints(), vtkCellArray(), []
guides = [[(r * np.cos(t), r * np.sin(t), z) for t in np.linspace(0, np.pi / 2, 40)] for r in (14.0, 16.0) for z in (1.0, 3.0)]
guides += [[(x, 10.0, z) for z in np.linspace(-4, 8, 13)] for x in (6.0, 8.0)]
for k, guide in enumerate(guides):
    lines.InsertNextCell(len(guide))
    for p in guide:
        lines.InsertCellPoint(points.InsertNextPoint(*p))
    bundle_ids.append(0 if k < 4 else 1)
guide_data = vtkPolyData()
guide_data.SetPoints(points)
guide_data.SetLines(lines)
ids = numpy_to_vtk(np.asarray(bundle_ids, dtype=np.int32), deep=1)
ids.SetName("bundle_id")
guide_data.GetCellData().AddArray(ids)
guide_producer = TrivialProducer()
guide_producer.GetClientSideObject().SetOutput(guide_data)
three = FiberFieldSource(Input=guide_producer, GuideRadius=2.0, GuideSpacing=0.5, GuidePopulations="ByBundle",
                         VolumeFraction=0.2, FiberRadius=0.3, SegmentLength=1.0, Seed=2, NumberOfThreads=2)
check_pieces(three, "guides")
print("mpi_field_pieces passed on rank %d" % rank)

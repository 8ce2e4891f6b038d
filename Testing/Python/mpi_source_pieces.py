"""pvbatch --symmetric under mpiexec -n 2: FiberCubeSource and FiberBundleSource make their pieces
(docs/tissue-models.md §9). Every rank runs this script: the pipeline update gives it piece r of
2, which must hold exactly the fibers [N·r/2, N·(r+1)/2) of the one-piece output, bit for bit, with
their global fiber ids and the same field data (periodic_cell, seed, segment_length). Together the
two ranks check the whole model, in its serial order, also with the realism knobs on."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(100)  # a rank stuck in a collective dies instead of hanging
load_plugin(globals())
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")


def fibers(poly):
    """[(fiber_id, bundle_id, points, radii)] of every line, in cell order."""
    ids = poly.GetCellData().GetArray("fiber_id")
    bundles = poly.GetCellData().GetArray("bundle_id")
    radius = poly.GetPointData().GetArray("radius")
    out = []
    lines = poly.GetLines()
    it = lines.NewIterator()
    it.GoToFirstCell()
    c = 0
    while not it.IsDoneWithTraversal():
        cell = it.GetCurrentCell()
        pts = [poly.GetPoint(cell.GetId(k)) for k in range(cell.GetNumberOfIds())]
        rad = [radius.GetValue(cell.GetId(k)) for k in range(cell.GetNumberOfIds())]
        out.append((int(ids.GetTuple1(c)), int(bundles.GetTuple1(c)), pts, rad))
        it.GoToNextCell()
        c += 1
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
    check(len(mine) == end - begin, "%s: rank %d holds %d fibers, its share is %d" % (what, rank, len(mine), end - begin))
    check(mine == everything[begin:end],
          "%s: rank %d's fibers differ from fibers %d..%d of the serial output" % (what, rank, begin, end - 1))
    check(field(local) == field(whole), "%s: rank %d field data %r, serial %r" % (what, rank, field(local), field(whole)))
    print("%s: rank %d holds fibers %d..%d of %d" % (what, rank, begin, end - 1, n))
    Delete(proxy)


check_pieces(FiberCubeSource(Populations=2, NumberOfFibers=25, EdgeLength=20.0, Seed=3), "open cube")
periodic = FiberCubeSource(Populations=3, EdgeLength=20.0, Periodic=1, VolumeFraction=0.3, RadiusSpread=0.2,
                           RadiusDistribution="LogNormal", Seed=8)
check_pieces(periodic, "periodic cube")
check_pieces(FiberBundleSource(Shape="Chiasm", NumberOfFibers=20, BundleRadius=6.0, Length=40.0, Seed=5), "chiasm")
# The realism knobs (docs/tissue-models.md §10) draw from per-fiber streams: the same pieces.
realistic = FiberCubeSource(Populations=2, EdgeLength=16.0, Periodic=1, VolumeFraction=0.3, FiberRadius=1.0,
                            RadiusSpread=0.5, RadiusDistribution="Gamma", Displacement=0.05, Seed=6,
                            Tortuosity=1.06, UndulationWavelength=8.0, DispersionC2=0.9, BeadingCV=0.2,
                            BeadingLength=3.0, GRatio=0.65, CrossingAngle=45.0, PopulationShares=[2, 1, 1])
check_pieces(realistic, "realistic periodic cube")
check_pieces(FiberBundleSource(Shape="Crossing", NumberOfFibers=12, BundleRadius=5.0, Length=30.0, Seed=5,
                               Tortuosity=1.1, UndulationWavelength=10.0, DispersionC2=0.85, BeadingCV=0.3),
             "realistic crossing")
print("mpi_source_pieces passed on rank %d" % rank)

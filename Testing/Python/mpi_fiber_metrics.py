"""pvbatch under mpiexec -n 2: FiberMetrics measures all fibers whatever piece a rank holds, and
fills its outputs on piece 0 only, so the gathered Summary has one row and the fibers come once."""
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(sys.argv[1], remote=False, ns=globals())
pm = servermanager.vtkProcessModule.GetProcessModule()
if pm.GetNumberOfLocalPartitions() != 2:
    raise RuntimeError("expected 2 MPI ranks, got %d" % pm.GetNumberOfLocalPartitions())

cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=20, Seed=5)
metrics = FiberMetrics(Input=cube, NumberOfThreads=1, VolumeFractionMethod="MonteCarlo", Samples=100000, Seed=2)
metrics.UpdatePipeline()
summary = servermanager.Fetch(metrics, idx=1)
fibers = servermanager.Fetch(metrics, idx=0)
bundles = servermanager.Fetch(metrics, idx=2)
if summary.GetNumberOfRows() != 1 or bundles.GetNumberOfRows() != 2:
    raise RuntimeError("gathered tables: %d summary rows, %d bundle rows" % (summary.GetNumberOfRows(), bundles.GetNumberOfRows()))
if summary.GetColumnByName("fibers").GetValue(0) != 60 or fibers.GetNumberOfCells() != 60:
    raise RuntimeError("fibers: %d measured, %d passed" % (summary.GetColumnByName("fibers").GetValue(0), fibers.GetNumberOfCells()))

# The same numbers as one piece on this rank alone.
single = metrics.GetClientSideObject()
single.UpdatePiece(0, 1, 0)
serial = single.GetOutputDataObject(1)
for name in ("collisions", "min_gap", "volume_fraction", "c2"):
    if serial.GetColumnByName(name).GetValue(0) != summary.GetColumnByName(name).GetValue(0):
        raise RuntimeError("%s: parallel %s, serial %s" % (name, summary.GetColumnByName(name).GetValue(0),
                                                           serial.GetColumnByName(name).GetValue(0)))
print("mpi_fiber_metrics passed: %d collisions, volume fraction %.4f" % (
    summary.GetColumnByName("collisions").GetValue(0), summary.GetColumnByName("volume_fraction").GetValue(0)))

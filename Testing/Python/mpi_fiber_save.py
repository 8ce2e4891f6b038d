"""pvbatch under mpiexec -n 2: SaveData through FiberWriter gathers the fibers of all ranks and
writes one file; reading it back gives every fiber of the one-piece source."""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(sys.argv[1], remote=False, ns=globals())
out_dir = sys.argv[2]
pm = servermanager.vtkProcessModule.GetProcessModule()
if pm.GetNumberOfLocalPartitions() != 2:
    raise RuntimeError("expected 2 MPI ranks, got %d" % pm.GetNumberOfLocalPartitions())

cube = FiberCubeSource(Populations=2, NumberOfFibers=12, EdgeLength=20.0, FiberRadius=0.8, SegmentLength=2.0,
                       Displacement=0.5, Seed=4)
expected = servermanager.Fetch(cube)
for ext in ("dat", "h5", "tck"):
    path = os.path.join(out_dir, "cube." + ext)
    if os.path.exists(path):
        os.remove(path)
    SaveData(path, proxy=cube)
    reader = OpenDataFile(path)
    if reader is None or reader.GetXMLName() != "FiberReader":
        raise RuntimeError("no FiberReader for ." + ext)
    back = servermanager.Fetch(reader)
    if back.GetNumberOfLines() != 12 or back.GetNumberOfPoints() != expected.GetNumberOfPoints():
        raise RuntimeError(".%s: %d fibers, %d points read back" % (ext, back.GetNumberOfLines(), back.GetNumberOfPoints()))
    Delete(reader)
print("mpi_fiber_save passed")

"""pvbatch under mpiexec -n 2: cube -> solver -> tubes. The source makes its two pieces, the solver
solves them together (docs/solver.md §13) and the tubes follow; the gathered result equals a
one-piece run of the same pipeline."""
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(sys.argv[1], remote=False, ns=globals())
pm = servermanager.vtkProcessModule.GetProcessModule()
if pm.GetNumberOfLocalPartitions() != 2:
    raise RuntimeError("expected 2 MPI ranks, got %d" % pm.GetNumberOfLocalPartitions())

cube = FiberCubeSource(Populations=2, NumberOfFibers=24, EdgeLength=51.96 * (24 / 1000.0) ** 0.5, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.5, Seed=5)
solver = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=4.0, MaxSteps=20000,
                              NumberOfThreads=1)
tubes = FiberTubes(Input=solver, NumberOfSides=6, Capping=1, NumberOfThreads=1)
tubes.UpdatePipeline()
parallel = servermanager.Fetch(tubes)
# Before the one-piece run below re-executes rank 0's source alone: a pipeline update after it
# would find the distributed solver out of date on rank 0 only.
solved = servermanager.Fetch(solver).GetFieldData().GetArray("solved").GetValue(0)

# The same pipeline as one piece, computed on rank 0 only (client-side objects).
single_cube = cube.GetClientSideObject()
single_solver = solver.GetClientSideObject()
single_tubes = tubes.GetClientSideObject()
single_tubes.UpdatePiece(0, 1, 0)
serial = single_tubes.GetOutput()

if parallel.GetNumberOfCells() != serial.GetNumberOfCells() or parallel.GetNumberOfCells() == 0:
    raise RuntimeError("cells: parallel %d, serial %d" % (parallel.GetNumberOfCells(), serial.GetNumberOfCells()))
if parallel.GetNumberOfPoints() != serial.GetNumberOfPoints():
    raise RuntimeError("points differ")
for i in range(0, serial.GetNumberOfPoints(), 97):
    if parallel.GetPoint(i) != serial.GetPoint(i):
        raise RuntimeError("point %d differs" % i)
if solved != 1:
    raise RuntimeError("not solved")
print("mpi_fiber_pipeline passed: %d triangles on 2 ranks" % parallel.GetNumberOfCells())

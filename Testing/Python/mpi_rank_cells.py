"""pvbatch --symmetric under mpiexec -n 2: input that only one rank's piece gets wrong.
(1) A periodic_cell that differs on rank 1, then one that is malformed there (its edge overflows):
PLISimulation, FiberOrientationGroundTruth and SaveData used to take rank 0's cell and ignore
rank 1's; now every rank fails naming rank 1, as the solver does, and the existing file stays.
(2) A piece at x = 3e16 um on rank 1 only: the distributed solver used to split its links forever
while rank 0 waited; now every rank reports rank 1's fiber and coordinate and nobody hangs (an
alarm kills a stuck rank long before the ctest timeout). Every rank runs this script and checks
itself."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, rank_fibers_script  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(120)
load_plugin(globals())
out_dir = sys.argv[2]
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")

# One closed fiber along x per rank in the cell [-5, 5]^3; rank 1's cell is CELL1.
CELL_SCRIPT = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
out = self.GetPolyDataOutput()
points = vtkPoints()
radius = vtkDoubleArray()
radius.SetName("radius")
lines = vtkCellArray()
lines.InsertNextCell(6)
for k in range(6):
    lines.InsertCellPoint(points.InsertNextPoint(-5.0 + 2.0 * k, -2.0 + 4.0 * rank, 0.0))
    radius.InsertNextValue(1.0)
out.SetPoints(points)
out.SetLines(lines)
out.GetPointData().AddArray(radius)
cell = vtkDoubleArray()
cell.SetName("periodic_cell")
for v in (CELL1 if rank == 1 else [-5.0, 5.0, -5.0, 5.0, -5.0, 5.0]):
    cell.InsertNextValue(v)
out.GetFieldData().AddArray(cell)
"""
GOOD = "[-5.0, 5.0, -5.0, 5.0, -5.0, 5.0]"
fibers = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=CELL_SCRIPT.replace("CELL1", GOOD))
voi = [-8, 8, -8, 8, -2, 2]
sim = PLISimulation(Input=fibers, VolumeOfInterest=voi, VoxelSize=0.5, PixelSize=1.0, NumberOfRotations=6,
                    NoiseGain=0.0, NumberOfThreads=1)
truth = FiberOrientationGroundTruth(Input=fibers, VolumeOfInterest=voi, VoxelSize=0.5, PixelSize=1.0,
                                    NumberOfThreads=1)
sim_errors = ErrorCatcher(sim)
truth_errors = ErrorCatcher(truth)
target = os.path.join(out_dir, "cells.h5")
if rank == 0 and os.path.exists(target):
    os.remove(target)
controller.Barrier()
SaveData(target, proxy=fibers)  # the good pair of pieces: written
controller.Barrier()
with open(target, "rb") as f:
    before = f.read()
for name, cell1, expected in (
        ("different", "[-5.0, 5.0, -5.0, 5.0, -5.0, 6.0]", "rank 1 has -5 5 -5 5 -5 6"),
        ("malformed", "[-1e308, 1e308, -5.0, 5.0, -5.0, 5.0]", "rank 1's input field data periodic_cell axis x is [-1e+308, 1e+308]")):
    fibers.Script = CELL_SCRIPT.replace("CELL1", cell1)
    for proxy, errors in ((sim, sim_errors), (truth, truth_errors)):
        errors.clear()
        proxy.UpdatePipeline()
        text = errors.text()
        check(expected in text, "rank %d, %s cell: %s must name rank 1's cell: %r" % (rank, name, proxy.GetXMLName(), text))
        check(proxy.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0,
              "rank %d: %s gave output" % (rank, proxy.GetXMLName()))
    writer = CreateWriter(target, fibers)
    outer = ErrorCatcher(writer.GetClientSideObject())
    inner = ErrorCatcher(writer.GetClientSideObject().GetWriter())
    writer.UpdatePipeline()
    text = outer.text() + inner.text()
    check(expected in text, "rank %d, %s cell: SaveData must name rank 1's cell: %r" % (rank, name, text))
    Delete(writer)
    controller.Barrier()
    with open(target, "rb") as f:
        check(f.read() == before, "rank %d: the existing file was changed" % rank)

# The same cell everywhere: all work again.
fibers.Script = CELL_SCRIPT.replace("CELL1", GOOD)
for proxy, errors in ((sim, sim_errors), (truth, truth_errors)):
    errors.clear()
    proxy.UpdatePipeline()
    check(not errors.errors, "rank %d: %s errors after the fix: %r" % (rank, proxy.GetXMLName(), errors.text()))

# (2) A far piece on rank 1 only: the distributed solve fails on both ranks, naming it.
CELLS = ("[[(3e16 * rank + 2.0 * k, 0.0, 3.0 * rank) for k in range(5)],"
         " [(3e16 * rank + 4.3, -4.0 + 2.0 * k, 3.0 * rank + 0.5) for k in range(5)]]")
far = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=rank_fibers_script(CELLS, 1.0))
solver = FiberCollisionSolver(Input=far, MaxSteps=0, NumberOfThreads=1)
solver_errors = ErrorCatcher(solver)
solver.UpdatePipeline()
text = solver_errors.text()
check("has coordinate 30000000817692672 um" in text, "rank %d: the solver must name the far coordinate: %r" % (rank, text))
check("rank 1: " in text, "rank %d: the solver must name rank 1: %r" % (rank, text))
check(solver.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0, "rank %d: solver output" % rank)
signal.alarm(0)
print("mpi_rank_cells passed on rank %d" % rank)

"""pvbatch --symmetric under mpiexec -n 2: FiberCollisionSolver distributed (docs/solver.md §13)
with bad input on rank 1 only (a negative radius): every rank reports rank 1's error and gives an
empty output, nobody hangs (an alarm kills a stuck rank long before the ctest timeout); once the
input is fixed the same pipeline solves again. Every rank runs this script and checks itself."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, rank_fibers_script  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(100)
load_plugin(globals())
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")

# Two crossing fibers per rank; the radius is BAD on rank 1 only (ProgrammableSource runs on every rank).
CELLS = ("[[(-4.0 + 2.0 * k, 0.0, 3.0 * rank) for k in range(5)],"
         " [(0.3, -4.0 + 2.0 * k, 3.0 * rank + 0.5) for k in range(5)]]")
fibers = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=rank_fibers_script(CELLS, -1.0))
solver = FiberCollisionSolver(Input=fibers, MaxSteps=200, NumberOfThreads=1)
errors = ErrorCatcher(solver)
solver.UpdatePipeline()
text = errors.text()
check("radius -1" in text, "rank %d: the solver must report rank 1's bad radius: %r" % (rank, text))
out = solver.GetClientSideObject().GetOutputDataObject(0)
check(out.GetNumberOfPoints() == 0, "rank %d: output after the error" % rank)

fibers.Script = rank_fibers_script(CELLS, 1.0)
errors.clear()
solver.UpdatePipeline()
check(errors.text() == "", "rank %d: errors after the fix: %r" % (rank, errors.text()))
out = solver.GetClientSideObject().GetOutputDataObject(0)
fd = out.GetFieldData()
check(out.GetNumberOfLines() == 2 and fd.GetArray("solved").GetTuple1(0) == 1,
      "rank %d: its two fibers solved: %d lines" % (rank, out.GetNumberOfLines()))
check(fd.GetArray("rank_points") is not None, "rank %d: the solve was distributed" % rank)
print("mpi_solver_error passed on rank %d" % rank)

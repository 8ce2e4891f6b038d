"""pvbatch --symmetric under mpiexec -n 2: FiberCollisionSolver checkpoints under MPI (docs/solver.md
§13). The solve runs on piece 0, whose rank writes the checkpoint; resuming from it gives the same
output; a checkpoint that cannot be written fails the solve on piece 0 naming the file, and nobody
hangs (an alarm kills a hung rank long before the ctest timeout). (Errors shared by all ranks of a
distributed solve: core.SolverCheckpoint.Distributed*.)"""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(150)
load_plugin(globals())
out_dir = sys.argv[2]
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")
checkpoint = os.path.join(out_dir, "solve.ckpt")
if rank == 0 and os.path.exists(checkpoint):
    os.remove(checkpoint)
controller.Barrier()


def solve(**properties):
    cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=51.96 * 0.06 ** 0.5, Seed=6)
    solver = FiberCollisionSolver(Input=cube, MinCurvatureRadius=4.0, MaxSteps=400, NumberOfThreads=1, **properties)
    errors = ErrorCatcher(solver)
    solver.UpdatePipeline()
    poly = solver.GetClientSideObject().GetOutputDataObject(0)
    data = poly.GetPoints().GetData() if poly.GetPoints() else None
    return [data.GetValue(i) for i in range(data.GetNumberOfValues())] if data else [], errors.text()


first, text = solve(CheckpointFile=checkpoint, CheckpointInterval=5)
check(text == "", "rank %d: %r" % (rank, text))
check((len(first) > 0) == (rank == 0), "rank %d: the solve belongs to piece 0" % rank)
controller.Barrier()
check(os.path.exists(checkpoint), "rank %d: no checkpoint written" % rank)
again, text = solve(CheckpointFile=checkpoint, ResumeFromCheckpoint=1)
check(text == "" and again == first, "rank %d: the resumed output differs (%r)" % (rank, text))

bad = os.path.join(out_dir, "missing-dir", "solve.ckpt")
empty, text = solve(CheckpointFile=bad, CheckpointInterval=5)
check(empty == [], "rank %d: a failed solve gives no output" % rank)
if rank == 0:
    check(bad in text and "at step 5" in text, "rank 0 must name the file: %r" % text)
else:
    check(text == "", "rank 1 does not solve: %r" % text)
fixed, text = solve(CheckpointFile=checkpoint, CheckpointInterval=5)
check(text == "" and fixed == first, "rank %d: the pipeline is not usable again (%r)" % (rank, text))
print("mpi_solver_checkpoint passed on rank %d" % rank)

"""pvbatch --symmetric under mpiexec -n 2: FiberCollisionSolver checkpoints of the distributed solve
(docs/solver.md §14). Every rank writes its own file <CheckpointFile>.<rank>-of-2; resuming from them
gives the same output on every rank; a damaged file on rank 1 only fails the resume on both ranks
naming it; a file only rank 1 cannot write (a directory stands in its
place) fails the solve on both ranks at the same step, and nobody hangs (an alarm kills a hung
rank long before the ctest timeout); the pipeline works again afterwards."""
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
check(len(first) > 0, "rank %d: every rank holds its share of the distributed solve" % rank)
own = "%s.%d-of-2" % (checkpoint, rank)
check(os.path.exists(own), "rank %d: no checkpoint %s" % (rank, own))
again, text = solve(CheckpointFile=checkpoint, ResumeFromCheckpoint=1)
check(text == "" and again == first, "rank %d: the resumed output differs (%r)" % (rank, text))

# Only rank 1's checkpoint is damaged (one byte changed, its previous generation removed): every
# rank fails naming that file and nobody waits for the other (the alarm), rank 0 saying it was
# rank 1.
damaged = "%s.1-of-2" % checkpoint
if rank == 1:
    if os.path.exists(damaged + ".prev"):
        os.remove(damaged + ".prev")
    with open(damaged, "r+b") as f:
        middle = os.path.getsize(damaged) // 2
        f.seek(middle)
        byte = f.read(1)[0]
        f.seek(middle)
        f.write(bytes([byte ^ 0xFF]))
controller.Barrier()
broken, text = solve(CheckpointFile=checkpoint, ResumeFromCheckpoint=1)
check(broken == [], "rank %d: a failed resume gives no output" % rank)
check(damaged in text and "damaged" in text, "rank %d must name rank 1's damaged file: %r" % (rank, text))
if rank == 0:
    check("rank 1" in text, "rank 0 must say that rank 1 failed: %r" % text)

bad = os.path.join(out_dir, "bad.ckpt")
blocked = bad + ".1-of-2"
if rank == 1 and not os.path.isdir(blocked):
    os.mkdir(blocked)
controller.Barrier()
empty, text = solve(CheckpointFile=bad, CheckpointInterval=5)
check(empty == [], "rank %d: a failed solve gives no output" % rank)
check(blocked in text and "at step 5" in text, "rank %d must name rank 1's file: %r" % (rank, text))
if rank == 0:
    check("rank 1" in text, "rank 0 must say that rank 1 failed: %r" % text)
fixed, text = solve(CheckpointFile=checkpoint, CheckpointInterval=5)
check(text == "" and fixed == first, "rank %d: the pipeline is not usable again (%r)" % (rank, text))
print("mpi_solver_checkpoint passed on rank %d" % rank)

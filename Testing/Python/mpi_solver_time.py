"""pvbatch --symmetric under mpiexec -n 2: FiberCollisionSolver with IterationsAsTime, which is not
distributed (docs/solver.md §9): every rank solves the whole model alone (no collective, so the
ranks cannot wait for each other) and gets the same time steps, piece 0 shows the snapshots and the
final state, bit for bit the distributed solve's pieces joined, the other piece is empty. An alarm
kills a hung rank long before the ctest timeout."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkCommonCore import vtkDoubleArray  # noqa: E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(150)
load_plugin(globals())
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")


def points(proxy):
    poly = proxy.GetClientSideObject().GetOutputDataObject(0)
    data = poly.GetPoints().GetData() if poly.GetPoints() else None
    return [data.GetValue(i) for i in range(data.GetNumberOfValues())] if data else []


def to_rank0(values):
    """Rank 1's list of numbers, received on rank 0 (rank 1 gets None)."""
    array = vtkDoubleArray()
    if rank == 1:
        for v in values:
            array.InsertNextValue(v)
        controller.Send(array, 0, 4711)
        return None
    controller.Receive(array, 1, 4711)
    return [array.GetValue(i) for i in range(array.GetNumberOfTuples())]


def field(proxy, name):
    return proxy.GetClientSideObject().GetOutputDataObject(0).GetFieldData().GetArray(name).GetTuple1(0)


cube = FiberCubeSource(Populations=1, NumberOfFibers=60, EdgeLength=51.96 * 0.06 ** 0.5, Seed=6)
options = dict(MinCurvatureRadius=4.0, MaxSteps=400, NumberOfThreads=1)
distributed = FiberCollisionSolver(Input=cube, **options)
distributed.UpdatePipeline()
joined = points(distributed)
other = to_rank0(joined)

timed = FiberCollisionSolver(Input=cube, IterationsAsTime=1, TimeStepInterval=5, **options)
errors = ErrorCatcher(timed)
timed.UpdatePipelineInformation()
times = list(timed.TimestepValues)
check(len(times) > 2 and times[0] == 0, "rank %d: time steps %s" % (rank, times[:3]))
times_of_rank1 = to_rank0(times)
if rank == 0:
    check(times_of_rank1 == times, "the ranks' time steps differ: %s / %s" % (times[-3:], times_of_rank1[-3:]))
timed.UpdatePipeline(times[-1])
final = points(timed)
check(errors.text() == "", "rank %d: %r" % (rank, errors.text()))
if rank == 0:
    check(field(timed, "steps") == times[-1] and field(timed, "solved") == 1, "rank 0: the last time step is solved")
    check(final == joined + other, "rank 0: the final state differs from the distributed solve's pieces joined")
else:
    check(final == [], "rank 1: piece 1 of a solve with IterationsAsTime is empty")
timed.UpdatePipeline(0.0)
if rank == 0:
    check(field(timed, "steps") == 0 and field(timed, "collisions") > 0, "rank 0: time 0 is the input")
print("mpi_solver_time passed on rank %d" % rank)

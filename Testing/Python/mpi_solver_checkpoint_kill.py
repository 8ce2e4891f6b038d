"""A distributed solve (mpiexec -n 2 pvbatch --symmetric) killed in the middle and resumed
(docs/solver.md §14). The driver (plain python3: driver.py MPIEXEC PVBATCH PLUGIN DIR) runs the
uninterrupted solve, then the same solve with CheckpointInterval, kills the whole mpiexec job
(SIGKILL to its process group) once every rank has written at least two checkpoints — the ranks
may then hold files of different steps — resumes from the files and requires every rank's output
to equal the uninterrupted run's bit for bit. Under mpiexec the same file is the job (--job MODE)."""
import os
import signal
import subprocess
import sys
import time

INTERVAL = 5


def job(mode, out_dir):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from fiberpli_test import ErrorCatcher, check, load_plugin
    ns = {}
    exec("from paraview.simple import *", ns)  # the proxies as the tests use them, then the plugin's
    from vtkmodules.vtkParallelCore import vtkMultiProcessController

    signal.alarm(300)  # a hung rank ends long before the ctest timeout
    load_plugin(ns)
    rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
    checkpoint = os.path.join(out_dir, "solve.ckpt")
    properties = {"reference": {}, "killed": dict(CheckpointFile=checkpoint, CheckpointInterval=INTERVAL),
                  "resume": dict(CheckpointFile=checkpoint, ResumeFromCheckpoint=1)}[mode]
    cube = ns["FiberCubeSource"](Populations=2, NumberOfFibers=150, EdgeLength=51.96 * 0.15 ** 0.5, FiberRadius=0.8,
                                 SegmentLength=2.0, Displacement=0.5, Seed=3)
    solver = ns["FiberCollisionSolver"](Input=cube, MinCurvatureRadius=4.0, MaxSteps=5000, NumberOfThreads=1,
                                        **properties)
    errors = ErrorCatcher(solver)
    solver.UpdatePipeline()
    check(errors.text() == "", "rank %d (%s): %r" % (rank, mode, errors.text()))
    poly = solver.GetClientSideObject().GetOutputDataObject(0)
    data = poly.GetPoints().GetData() if poly.GetPoints() else None
    values = [data.GetValue(i) for i in range(data.GetNumberOfValues())] if data else []
    steps = poly.GetFieldData().GetArray("steps")
    with open(os.path.join(out_dir, "%s.%d.txt" % (mode, rank)), "w") as f:
        f.write("%d\n" % (steps.GetValue(0) if steps else -1))
        f.write("\n".join(repr(v) for v in values))
    print("mpi_solver_checkpoint_kill %s done on rank %d" % (mode, rank))


def check(condition, message):
    if not condition:
        print("FAILED: " + message)
        sys.exit(1)


def drive(mpiexec, pvbatch, plugin, out_dir):
    def start(mode):
        return subprocess.Popen([mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", "2", pvbatch, "--dr",
                                 "--symmetric", os.path.abspath(__file__), plugin, out_dir, "--job", mode],
                                start_new_session=True)  # its own process group: killed as a whole

    def read(mode, rank):
        with open(os.path.join(out_dir, "%s.%d.txt" % (mode, rank))) as f:
            return f.read()

    for name in os.listdir(out_dir):
        os.remove(os.path.join(out_dir, name))
    started = time.time()
    check(start("reference").wait(timeout=400) == 0, "the uninterrupted run failed")
    steps = int(read("reference", 0).split("\n", 1)[0])
    check(steps > 4 * INTERVAL, "the solve is too short to be killed in the middle: %d steps" % steps)
    print("uninterrupted: %d steps in %.1f s" % (steps, time.time() - started))

    # Killed once every rank has kept a previous generation (two checkpoints written).
    killed = start("killed")
    previous = [os.path.join(out_dir, "solve.ckpt.%d-of-2.prev" % r) for r in range(2)]
    deadline = time.time() + 300
    while time.time() < deadline and killed.poll() is None and not all(os.path.exists(p) for p in previous):
        time.sleep(0.02)
    check(killed.poll() is None, "the job ended before it could be killed (exit %s)" % killed.poll())
    os.killpg(killed.pid, signal.SIGKILL)
    killed.wait()
    check(not os.path.exists(os.path.join(out_dir, "killed.0.txt")), "the killed job must not have finished")
    print("killed after %.1f s" % (time.time() - started))

    check(start("resume").wait(timeout=400) == 0, "the resumed run failed")
    for r in range(2):
        check(read("resume", r) == read("reference", r), "rank %d: the resumed output differs from the uninterrupted one" % r)
    print("mpi_solver_checkpoint_kill passed")


if "--job" in sys.argv:
    job(sys.argv[sys.argv.index("--job") + 1], sys.argv[2])
else:
    drive(*sys.argv[1:5])

"""FiberCollisionSolver checkpoints (docs/solver.md §14): a pvpython child solves with
CheckpointInterval and is killed (SIGKILL) in the middle of the solve; resuming from its file gives
the uninterrupted run's output bit for bit. A checkpoint of other options or another input is an
error naming the file and what differs, and the pipeline works again afterwards."""
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
tmp = option("-T")
checkpoint = os.path.join(tmp, "solve.ckpt")
INTERVAL = 10


def pipeline(seed=3, **solver):
    cube = FiberCubeSource(Populations=2, NumberOfFibers=150, EdgeLength=51.96 * 0.15 ** 0.5, FiberRadius=0.8,
                           SegmentLength=2.0, Displacement=0.5, Seed=seed)
    settings = dict(MinCurvatureRadius=4.0, MaxSteps=5000, NumberOfThreads=1)
    settings.update(solver)
    return FiberCollisionSolver(Input=cube, **settings)


def points(proxy):
    poly = servermanager.Fetch(proxy)
    data = poly.GetPoints().GetData() if poly.GetPoints() else None
    values = [data.GetValue(i) for i in range(data.GetNumberOfValues())] if data else []
    steps = poly.GetFieldData().GetArray("steps")
    return values, (steps.GetValue(0) if steps else -1)


if "--child" in sys.argv:  # the job that gets killed
    pipeline(CheckpointFile=checkpoint, CheckpointInterval=INTERVAL).UpdatePipeline()
    print("child finished")
    sys.exit(0)

# (1) The uninterrupted run.
started = time.time()
reference, reference_steps = points(pipeline())
print("uninterrupted: %d steps in %.1f s" % (reference_steps, time.time() - started))
check(reference_steps > 4 * INTERVAL, "the solve is too short to be killed in the middle: %d steps" % reference_steps)

# (2) The same solve in a child process, killed after its second checkpoint.
if os.path.exists(checkpoint):
    os.remove(checkpoint)
child = subprocess.Popen([option("--pvpython"), "--dr", "--force-offscreen-rendering", os.path.abspath(__file__),
                          sys.argv[1], "-T", tmp, "--child"])
deadline = time.time() + 200
first = None
while time.time() < deadline and child.poll() is None:
    if os.path.exists(checkpoint):
        stamp = os.stat(checkpoint).st_mtime_ns
        if first is None:
            first = stamp
        elif stamp != first:
            break
    time.sleep(0.05)
check(child.poll() is None, "the child ended before it could be killed (exit %s)" % child.poll())
child.send_signal(signal.SIGKILL)
child.wait()
check(os.path.exists(checkpoint), "no checkpoint was written")
print("killed after %.1f s" % (time.time() - started))

# (3) Resumed from the killed job's file: the uninterrupted result, bit for bit.
resumed_solver = pipeline(CheckpointFile=checkpoint, ResumeFromCheckpoint=1, NumberOfThreads=2)
resumed, resumed_steps = points(resumed_solver)
check(resumed_steps == reference_steps, "steps: resumed %d, uninterrupted %d" % (resumed_steps, reference_steps))
check(resumed == reference, "the resumed output differs from the uninterrupted one")
print("resumed after %.1f s" % (time.time() - started))

# (4) A checkpoint of another run is refused by name; the pipeline stays usable.
other = pipeline(CheckpointFile=checkpoint, ResumeFromCheckpoint=1, SeparationSpeed=0.05)
errors = ErrorCatcher(other)
other.UpdatePipeline()
text = errors.text()
check(checkpoint in text and "SeparationSpeed is 0.025 there and 0.05 now" in text, "other options: %r" % text)
check(other.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0, "an error must give no output")
other.SeparationSpeed = 0.025
errors.clear()
other.UpdatePipeline()
check(errors.text() == "", "after the fix: %r" % errors.text())
check(points(other)[0] == reference, "the pipeline is not usable again after the error")

moved = pipeline(seed=4, CheckpointFile=checkpoint, ResumeFromCheckpoint=1)
errors = ErrorCatcher(moved)
moved.UpdatePipeline()
check(checkpoint in errors.text() and "another input" in errors.text(), "other input: %r" % errors.text())
print("test_solver_checkpoint passed")

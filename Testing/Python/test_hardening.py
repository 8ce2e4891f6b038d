"""pvpython: an abort applies to one execution only and is not redone by the next request; NumberOfThreads follows one rule on
every proxy; negative solver SegmentLength means off (not automatic); DefaultRadius 0 is an error;
solver stacks of identical fibers are refused in bounded memory."""
import os
import resource
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
tmp = option("-T", ".")

# --- Sticky abort: a progress observer aborts the solver once; later updates work again, and so
# does everything downstream.
src = FiberCubeSource(NumberOfFibers=50, EdgeLength=20.0)
sol = FiberCollisionSolver(Input=src, MaxSteps=300)
tub = FiberTubes(Input=sol, NumberOfSides=6)
alg = sol.GetClientSideObject()
aborts = {"n": 0}


def abort_once(obj, event):
    if aborts["n"] == 0:
        obj.SetAbortExecute(1)
    aborts["n"] += 1


tag = alg.AddObserver("ProgressEvent", abort_once)
sol.UpdatePipeline()
check(aborts["n"] > 0, "the solver reported no progress")
check(alg.GetOutputDataObject(0).GetNumberOfPoints() == 0, "an aborted solve passes nothing on")
check(not alg.GetAbortExecute(), "the abort request must end with the execution")
alg.RemoveObserver(tag)
# The aborted execution counts as done: the next pipeline request (what a render or Fetch does,
# and in the GUI the view's update right after Apply) must not start the solve again from 0 %;
# a property change does.
starts = {"n": 0}


def count_start(obj, event):
    starts["n"] += 1


start_tag = alg.AddObserver("StartEvent", count_start)
alg.Update()
check(starts["n"] == 0, "the request after an abort ran the solver again")
check(alg.GetOutputDataObject(0).GetNumberOfPoints() == 0, "the aborted output must stay empty")
alg.RemoveObserver(start_tag)
sol.MaxSteps = 301
sol.UpdatePipeline()
solved = alg.GetOutputDataObject(0).GetNumberOfPoints()
check(solved > 0, "the update after an abort and a property change must solve again")
tub.GetClientSideObject().Update()
check(tub.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() > 0, "downstream works again")
tag = alg.AddObserver("ProgressEvent", abort_once)
aborts["n"] = 0
sol.MaxSteps = 299
tub.UpdatePipeline()
alg.RemoveObserver(tag)
sol.MaxSteps = 300
tub.UpdatePipeline()
check(tub.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() > 0,
      "after an abort and a property change the pipeline works again")
# An abort requested on a source that never checks it must not stop downstream filters forever.
src.GetClientSideObject().SetAbortExecute(1)
src.Seed = 5
tub.UpdatePipeline()
src.Seed = 6
tub.UpdatePipeline()
check(tub.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() > 0,
      "an abort on the source applies to one execution only")

sol.UpdatePipeline()
solved = alg.GetOutputDataObject(0).GetNumberOfPoints()

# --- NumberOfThreads: above 1024 an error naming the value (no silent 1024); 4 x cores < n <= 1024
# a warning, result unchanged.
for proxy in (sol, tub):
    catcher = ErrorCatcher(proxy)
    proxy.NumberOfThreads = 10000
    proxy.UpdatePipeline()
    check("NumberOfThreads is 10000, must be in [0, 1024]" in catcher.text(), catcher.text())
    catcher.clear()
    proxy.NumberOfThreads = 1000
    proxy.UpdatePipeline()
    check(catcher.text() == "", catcher.text())
    check(any("NumberOfThreads 1000 is more than 4 x the" in w for w in catcher.warnings), catcher.warnings)
    proxy.NumberOfThreads = 0
sol.UpdatePipeline()
check(alg.GetOutputDataObject(0).GetNumberOfPoints() == solved, "same result for any thread count")

# --- Solver SegmentLength -1: off (links keep their lengths), not 0 = automatic.
sol.SegmentLength = -1.0
sol.UpdatePipeline()
out = alg.GetOutputDataObject(0)
check(out.GetFieldData().GetArray("segment_length").GetValue(0) < 0, "SegmentLength -1 must mean off")
check(out.GetNumberOfPoints() == servermanager.Fetch(src).GetNumberOfPoints(), "off: no split or merge")
sol.SegmentLength = 2.0

# --- FiberReader DefaultRadius 0: an error naming it (it used to become 1e-12 silently).
here = os.path.dirname(os.path.abspath(__file__))
tck = os.path.join(here, "..", "Data", "tracks", "sample.tck")
reader = FiberReader(FileName=tck, DefaultRadius=0.0)
catcher = ErrorCatcher(reader)
reader.UpdatePipeline()
check("DefaultRadius 0 must be finite and > 0" in catcher.text(), catcher.text())
catcher.clear()
reader.DefaultRadius = 0.5
reader.UpdatePipeline()
check(catcher.text() == "" and servermanager.Fetch(reader).GetNumberOfLines() > 0, "reader recovers")

# --- 1000 copies of one 10-point fiber (repeated streamlines): refused, bounded memory.
copies = ProgrammableSource(OutputDataSetType="vtkPolyData")
copies.Script = """
import vtk
pts = vtk.vtkPoints(); lines = vtk.vtkCellArray(); r = vtk.vtkDoubleArray(); r.SetName("radius")
for c in range(1000):
    lines.InsertNextCell(10)
    for k in range(10):
        lines.InsertCellPoint(pts.InsertNextPoint(2.0 * k, 0.1 * k, 0.0)); r.InsertNextValue(0.8)
out = self.GetPolyDataOutput(); out.SetPoints(pts); out.SetLines(lines); out.GetPointData().AddArray(r)
"""
stack = FiberCollisionSolver(Input=copies)
catcher = ErrorCatcher(stack)
stack.UpdatePipeline()
check("fiber id 0 has 999 exact copies" in catcher.text(), catcher.text())
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0
check(peak < 1.0e9, "peak memory %.0f MB" % (peak / 1e6))
# --- IterationsAsTime with MaxSteps 2^31 - 1: no allocation in RequestInformation, the timeline
# ends where the solve ended, at most MaximumSnapshots + 1 time steps; progress never goes back.
anim = FiberCollisionSolver(Input=src, IterationsAsTime=1, TimeStepInterval=1, MaximumSnapshots=16,
                            MaxSteps=2147483647)  # creating the proxy solves (pipeline information)
progress = []
anim.GetClientSideObject().AddObserver(
    "ProgressEvent", lambda obj, event: progress.append(obj.GetProgress()))
anim.MaximumSnapshots = 8
anim.UpdatePipelineInformation()
solving = [p for p in progress if p < 1.0]  # the solve's progress (before the data pass)
times = list(anim.TimestepValues)
check(2 <= len(times) <= 9, "time steps %r" % times)
anim.UpdatePipeline(times[-1])
fd = servermanager.Fetch(anim).GetFieldData()
check(fd.GetArray("solved").GetValue(0) == 1, "the last time step is the solved state")
check(fd.GetArray("steps").GetValue(0) == times[-1], "the timeline ends at the solve's last step")
check(times[-1] < 2147483647, "not at MaxSteps")
monotone = [b >= a for a, b in zip(solving, solving[1:])].count(False) == 0  # (simple's * shadows all())
check(len(solving) > 1 and monotone, "progress %r" % progress)
# With MaxSteps 2^31 - 1 the steps' share stays ~0: the progress shown comes from the collisions.
check(sorted(solving)[-1] > 0.5, "progress must follow the resolved collisions: %r" % solving)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0
check(peak < 1.0e9, "peak memory %.0f MB" % (peak / 1e6))
print("test_hardening passed")

"""pvpython: FiberCollisionSolver on a small cube and on a crossing pair; field data, invariants,
iterations as time, and a regression image of the solved crossing as tubes."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, compare_image, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())


def field(proxy, name):
    return servermanager.Fetch(proxy).GetFieldData().GetArray(name).GetValue(0)


# A 30-fiber, 2-population cube at the paper's density.
cube = FiberCubeSource(Populations=2, NumberOfFibers=30, EdgeLength=51.96 * (30 / 1000.0) ** 0.5,
                       FiberRadius=0.8, SegmentLength=2.0, Displacement=0.5, Seed=3)
solver = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=4.0, MaxSteps=20000,
                              SeparationSpeed=0.025, NumberOfThreads=2)
solver.UpdatePipeline()
check(field(solver, "solved") == 1, "cube not solved")
check(field(solver, "collisions") == 0, "collisions left")
out = servermanager.Fetch(solver)
inp = servermanager.Fetch(cube)
check(out.GetNumberOfLines() == inp.GetNumberOfLines() == 30, "fiber count changed")
for c in range(30):
    check(out.GetCellData().GetArray("fiber_id").GetValue(c) == inp.GetCellData().GetArray("fiber_id").GetValue(c),
          "fiber order changed")

# PushBoost (default 3): input at the paper's density (< 6 colliding pairs per link) is solved
# exactly as without it (1 = off); heavily overlapping input is boosted and still solved; a bad
# value names the property.
def points(proxy):
    data = servermanager.Fetch(proxy).GetPoints().GetData()
    return [data.GetValue(i) for i in range(data.GetNumberOfValues())]


check(solver.PushBoost == 3.0, "PushBoost default must be 3, is %g" % solver.PushBoost)
plain = points(solver)
solver.PushBoost = 1.0
solver.UpdatePipeline()
check(points(solver) == plain, "PushBoost changed a paper-density solve")
crowded = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=9.0, FiberRadius=0.8,
                          SegmentLength=2.0, Displacement=0.5, Seed=3)
runs = {}
for boost in (1.0, 3.0):
    crowd = FiberCollisionSolver(Input=crowded, SegmentLength=2.0, MinCurvatureRadius=4.0, MaxSteps=20000,
                                 NumberOfThreads=2, PushBoost=boost)
    crowd.UpdatePipeline()
    check(field(crowd, "solved") == 1 and field(crowd, "collisions") == 0, "crowded cube not solved (%g)" % boost)
    runs[boost] = (field(crowd, "steps"), points(crowd))
print("crowded cube steps: PushBoost 1 -> %d, 3 -> %d" % (runs[1.0][0], runs[3.0][0]))
check(runs[1.0][1] != runs[3.0][1], "PushBoost 3 had no effect on heavily overlapping input")
catcher = ErrorCatcher(solver)
solver.PushBoost = 5.0
solver.UpdatePipeline()
check("PushBoost" in catcher.text() and "5" in catcher.text(), "error must name PushBoost: %r" % catcher.text())
solver.PushBoost = 3.0
solver.UpdatePipeline()
check(field(solver, "solved") == 1 and points(solver) == plain, "pipeline must recover after a bad PushBoost")

# Drag and DragSteps (momentum, off by default): with momentum for the first steps only the
# solve still ends with no collisions and differs from the plain one; a bad value names the
# property and the pipeline recovers.
check(solver.Drag == 0.0 and solver.DragSteps == 0, "Drag and DragSteps must default to 0")
solver.Drag = 0.8
solver.DragSteps = 5
solver.UpdatePipeline()
check(field(solver, "solved") == 1 and field(solver, "collisions") == 0, "solve with momentum left collisions")
check(points(solver) != plain, "Drag had no effect")
solver.DragSteps = -2
solver.UpdatePipeline()
check("DragSteps" in catcher.text() and "-2" in catcher.text(), "error must name DragSteps: %r" % catcher.text())
solver.Drag = 0.0
solver.DragSteps = 0
solver.UpdatePipeline()
check(field(solver, "solved") == 1 and points(solver) == plain, "pipeline must recover after a bad DragSteps")

# MaxDisplacement (default 0.125 of the smallest radius): a bad value names the property; 0.4
# solves a dense periodic cell with Gamma radii (smallest ~0.25 µm) seeded for its radii
# (docs/periodic-cells.md, "Polydisperse seeding").
check(abs(solver.MaxDisplacement - 0.125) < 1e-12, "MaxDisplacement default must be 0.125, is %g" % solver.MaxDisplacement)
solver.MaxDisplacement = 0.0
solver.UpdatePipeline()
check("MaxDisplacement" in catcher.text(), "error must name MaxDisplacement: %r" % catcher.text())
solver.MaxDisplacement = 0.125
solver.UpdatePipeline()
check(field(solver, "solved") == 1 and points(solver) == plain, "pipeline must recover after a bad MaxDisplacement")
gamma = FiberCubeSource(Populations=1, EdgeLength=20.0, FiberRadius=1.0, RadiusSpread=0.5, RadiusDistribution="Gamma",
                        Periodic=1, VolumeFraction=0.85, Seeding="Lattice", SegmentLength=2.0, Displacement=0.5, Seed=11)
dense = FiberCollisionSolver(Input=gamma, SegmentLength=2.0, MinCurvatureRadius=4.0, MaxSteps=3000, NumberOfThreads=2,
                             MaxDisplacement=0.4)
dense.UpdatePipeline()
check(field(dense, "solved") == 1 and field(dense, "collisions") == 0,
      "Gamma cell at 0.85 not solved: %d pairs left" % field(dense, "collisions"))
check(field(dense, "volume_fraction") >= 0.85, "Gamma cell fraction %g" % field(dense, "volume_fraction"))

# Iterations as time: the animation starts from the input and ends solved.
solver.IterationsAsTime = 1
solver.TimeStepInterval = 10
solver.UpdatePipelineInformation()
times = solver.TimestepValues
check(len(times) > 2 and times[0] == 0, "time steps %s" % (times[:3],))
solver.UpdatePipeline(0.0)
check(field(solver, "steps") == 0 and field(solver, "collisions") > 0, "time 0 is the input")
solver.UpdatePipeline(times[-1])
check(field(solver, "solved") == 1, "last time step solved")
solver.IterationsAsTime = 0

# The image: two crossing fibers closer than their radii, solved, as tubes.
CROSSING = """
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
pts, lines, radius = vtkPoints(), vtkCellArray(), vtkDoubleArray()
radius.SetName("radius")
for fiber in range(2):
    lines.InsertNextCell(21)
    for i in range(21):
        t = -10.0 + i
        lines.InsertCellPoint(pts.InsertNextPoint((t, 0.0, 0.0) if fiber == 0 else (0.0, t, 0.5)))
        radius.InsertNextValue(1.0)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.SetLines(lines)
out.GetPointData().AddArray(radius)
"""
crossing = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=CROSSING)
solved = FiberCollisionSolver(Input=crossing, SegmentLength=1.0, MinCurvatureRadius=0.0, MaxSteps=1000,
                              SeparationSpeed=0.025, NumberOfThreads=1)
solved.UpdatePipeline()
check(field(solved, "solved") == 1, "crossing not solved")
bounds = servermanager.Fetch(solved).GetBounds()
check(bounds[5] - bounds[4] >= 2.0, "the crossing axes must end >= r1 + r2 = 2 apart: %s" % (bounds,))
tubes = FiberTubes(Input=solved, NumberOfSides=16, Capping=1)

compare_image(tubes, "fiber_id", position=(16, -20, 10), up=(0, 0, 1))
print("test_collision_solver passed")

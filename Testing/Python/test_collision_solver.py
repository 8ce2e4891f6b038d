"""pvpython: FiberCollisionSolver on a small cube and on a crossing pair; field data, invariants,
iterations as time, and a regression image of the solved crossing as tubes."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, compare_image, load_plugin  # noqa: E402
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

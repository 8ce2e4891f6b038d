"""pvpython: an interwoven realistic periodic cell (two crossing populations, undulating, beaded,
myelinated) solved to zero overlaps, its inner_radius carried through the solver at the asked
g-ratio, and its outer and inner tubes rendered, cut open by a plane so the myelin sheaths show."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, compare_image, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

load_plugin(globals())
L = 16.0
cell = FiberCubeSource(Periodic=1, EdgeLength=L, Populations=2, Seeding="Random", Arrangement="Interwoven",
                       CrossingAngle=90.0, VolumeFraction=0.45, FiberRadius=1.0, RadiusSpread=0.5,
                       RadiusDistribution="Gamma", SegmentLength=1.0, Displacement=0.0, Tortuosity=1.15,
                       UndulationWavelength=8.0, BeadingCV=0.2, BeadingLength=6.0, GRatio=0.7, Seed=3)
solver = FiberCollisionSolver(Input=cell, SegmentLength=1.0, MaxSteps=4000, MaxDisplacement=0.4,
                              Tortuosity=1.15, NumberOfThreads=2)
solved = servermanager.Fetch(solver)
check(solved.GetFieldData().GetArray("solved").GetValue(0) == 1, "the cell is not solved")
collisions = solved.GetFieldData().GetArray("collisions").GetValue(0)
check(collisions == 0, "%d colliding pairs" % collisions)

radius = vtk_to_numpy(solved.GetPointData().GetArray("radius"))
inner = vtk_to_numpy(solved.GetPointData().GetArray("inner_radius"))
check(abs(inner / radius - 0.7).max() < 1e-6, "inner_radius / radius is not the GRatio 0.7 after the solve")
check(radius.std() > 0.0, "no radius variation")

tubes = FiberTubes(Input=solver, NumberOfSides=12, Capping=1, InnerTubes=1)
tubes.UpdatePipeline()
surfaces = tubes.CellData["tube_surface"].GetRange()
check(surfaces[0] == 0 and surfaces[1] == 1, "outer and inner tubes expected, tube_surface %s" % (surfaces,))
opened = Clip(Input=tubes, ClipType="Plane")
opened.ClipType.Origin = [0.0, 0.0, 2.0]
opened.ClipType.Normal = [0.0, 0.0, 1.0]
opened.Crinkleclip = 0
compare_image(opened, "tube_surface", position=(20, -27, 40))
print("test_realistic_cell passed")

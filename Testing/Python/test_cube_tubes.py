"""pvpython: FiberCubeSource -> FiberTubes with explicit properties, checked and rendered."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, compare_image, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
src = FiberCubeSource(Populations=2, NumberOfFibers=50, EdgeLength=40.0, FiberRadius=0.8,
                      SegmentLength=2.0, Displacement=0.5, Seed=1)
tub = FiberTubes(Input=src, NumberOfSides=8, Capping=1)
tub.UpdatePipeline()

fibers = servermanager.Fetch(src)
check(fibers.GetNumberOfLines() == 50, "50 fibers expected, got %d" % fibers.GetNumberOfLines())
points_per_fiber = round(40.0 / 2.0) + 1
check(fibers.GetNumberOfPoints() == 50 * points_per_fiber, "points per fiber")
check("radius" in src.PointData.keys(), "radius array missing")

info = tub.GetDataInformation()
expected = 50 * (2 * 8 * (points_per_fiber - 1) + 2 * 8)
check(info.GetNumberOfCells() == expected, "triangles: %d != %d" % (info.GetNumberOfCells(), expected))
check("fiber_id" in tub.CellData.keys() and "bundle_id" in tub.CellData.keys(), "ids not carried")
rng = tub.CellData["bundle_id"].GetRange()
check(rng[0] == 0 and rng[1] == 1, "bundle ids %s" % (rng,))

compare_image(tub, "bundle_id", position=(70, 50, 90))
print("test_cube_tubes passed")

"""pvpython: bad properties give a clear error and no output; the pipeline recovers."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())

src = FiberCubeSource(Populations=1, NumberOfFibers=10, EdgeLength=1.0, FiberRadius=0.8,
                      SegmentLength=2.0, Displacement=0.5, Seed=1)
catcher = ErrorCatcher(src)
tub = FiberTubes(Input=src, NumberOfSides=6, Capping=1)
tub.UpdatePipeline()
text = catcher.text()
check("EdgeLength" in text, "the error must name EdgeLength: %r" % text)
check(servermanager.Fetch(tub).GetNumberOfPoints() == 0, "no output expected")

src.EdgeLength = 20.0
tub.UpdatePipeline()
check(servermanager.Fetch(src).GetNumberOfLines() == 10, "pipeline must recover")
check(tub.GetDataInformation().GetNumberOfCells() > 0, "tubes after recovery")
print("test_bad_input passed")

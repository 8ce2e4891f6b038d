"""pvpython: bad properties give a clear error and no output; the pipeline recovers; several bad
values (as typed into the GUI's text fields, which do not enforce the XML ranges) are named in one
error."""
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
# Several bad values at once: one error naming every one of them.
many = FiberCubeSource(Populations=7, NumberOfFibers=-5, FiberRadius=-1.0, Displacement=-2.0)
catcher = ErrorCatcher(many)
many.UpdatePipeline()
own = [e for e in catcher.errors if "FiberCubeSource:" in e]  # (the executive adds its own line)
check(len(own) == 1, "%d errors: %r" % (len(own), own))
for words in ("Populations is 7", "NumberOfFibers is -5", "FiberRadius is -1", "Displacement is -2"):
    check(words in catcher.text(), "the error does not say %r: %r" % (words, catcher.text()))
many.Populations = 2
many.NumberOfFibers = 20
many.FiberRadius = 0.8
many.Displacement = 0.5
many.EdgeLength = 20.0
many.UpdatePipeline()
check(many.GetDataInformation().GetNumberOfCells() == 20, "the source does not recover")
print("test_bad_input passed")

"""pvpython: SaveData uses FiberWriter for .dat/.h5/.tck, OpenDataFile picks FiberReader for our
files (other ParaView readers claim .dat and .h5 too), and round trips keep the fibers."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
tmp = option("-T")
cube = FiberCubeSource(Populations=2, NumberOfFibers=12, EdgeLength=20.0, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.5, Seed=4)
original = servermanager.Fetch(cube)

for ext in ("dat", "h5", "tck"):
    path = os.path.join(tmp, "cube." + ext)
    if os.path.exists(path):
        os.remove(path)
    SaveData(path, proxy=cube)
    check(os.path.getsize(path) > 0, "SaveData wrote nothing for ." + ext)
    reader = OpenDataFile(path)
    check(reader is not None, "OpenDataFile found no reader for ." + ext)
    xml_name = reader.GetXMLName()
    check(xml_name == "FiberReader", "OpenDataFile chose %s for .%s" % (xml_name, ext))
    back = servermanager.Fetch(reader)
    check(back.GetNumberOfLines() == 12, ".%s: %d fibers read back" % (ext, back.GetNumberOfLines()))
    check(back.GetNumberOfPoints() == original.GetNumberOfPoints(), ".%s: points" % ext)
    radius = back.GetPointData().GetArray("radius").GetRange()
    # .tck keeps float32 radii in its .radius.tsf, the others exact doubles.
    check(abs(radius[0] - 0.8) < 1e-6 and abs(radius[1] - 0.8) < 1e-6, ".%s radii %s" % (ext, radius))
    if ext != "tck":  # .tck has no bundles
        bundles = back.GetCellData().GetArray("bundle_id").GetRange()
        check(bundles == (0.0, 1.0), ".%s bundles %s" % (ext, bundles))
    Delete(reader)

# A Tecplot .dat is not ours: FiberReader must not claim it.
tecplot = os.path.join(tmp, "tecplot.dat")
with open(tecplot, "w") as f:
    f.write('TITLE = "t"\nVARIABLES = "X", "Y"\nZONE I=2, F=POINT\n1 2\n3 4\n')
other = OpenDataFile(tecplot)
check(other is None or other.GetXMLName() != "FiberReader", "FiberReader claimed a Tecplot file")
print("test_fiber_io passed")

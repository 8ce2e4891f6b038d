"""Runs Examples/demo.py (the job scripts/demo.sh shows) and reads back what it wrote: the tubes
.vtp with VTK's vtkXMLPolyDataReader (Debian's ParaView 5.11 rejects raw appended XML data, so the
demo must write another mode), the fiber .h5 with FiberReader (periodic cell included), and the
composed picture. The demo's model is a dense periodic cell solved to zero overlaps, its printed
volume fraction FiberMetrics' measurement of the whole cell."""
import os
import runpy
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, option  # noqa: E402

plugin, out_dir = sys.argv[1], option("-T")
demo = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "demo.py")
saved_argv = sys.argv
sys.argv = [demo, plugin, out_dir]
scope = runpy.run_path(demo, run_name="__main__")
sys.argv = saved_argv

from paraview.simple import OpenDataFile, servermanager  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402

check(scope["collisions"] == 0, "the demo's model has %d collisions" % scope["collisions"])
check(scope["periodic"] == 1, "the demo's model is not measured as a periodic cell")
check(0.70 < scope["phi"] < 0.75 and scope["phi_error"] < 0.001,
      "volume fraction %g +- %g is not the dense cell's 72 %%" % (scope["phi"], scope["phi_error"]))

reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(out_dir, "demo_tubes.vtp"))
reader.Update()
tubes = reader.GetOutput()
expected = servermanager.Fetch(scope["tubes"])
check(tubes.GetNumberOfPolys() > 0 and tubes.GetNumberOfPolys() == expected.GetNumberOfPolys(),
      "the .vtp holds %d triangles, the pipeline %d" % (tubes.GetNumberOfPolys(), expected.GetNumberOfPolys()))
bundles = tubes.GetCellData().GetArray("bundle_id")
check(bundles is not None and bundles.GetRange() == (0.0, 1.0), "bundle_id missing or wrong in the .vtp")

FiberMetrics = scope["FiberMetrics"]  # the plugin's proxies live in the demo's namespace
fibers = OpenDataFile(os.path.join(out_dir, "demo_fibers.h5"))
check(fibers.GetXMLName() == "FiberReader", "the .h5 opened with %s" % fibers.GetXMLName())
summary = servermanager.Fetch(FiberMetrics(Input=fibers, ComputeVolumeFraction=0), idx=1)
check(int(summary.GetColumnByName("fibers").GetValue(0)) == scope["fibers"], "fiber count differs")
check(int(summary.GetColumnByName("periodic").GetValue(0)) == 1, "the re-read fibers lost their periodic cell")
check(int(summary.GetColumnByName("collisions").GetValue(0)) == 0, "the re-read fibers collide")

png = vtkPNGReader()
png.SetFileName(os.path.join(out_dir, "demo.png"))
png.Update()
check(png.GetOutput().GetDimensions()[:2] == (1200, 700), "demo.png is %r" % (png.GetOutput().GetDimensions(),))
print("demo: %d fibers, %.3f volume fraction, files read back" % (scope["fibers"], scope["phi"]))

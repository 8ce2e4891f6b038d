"""FiberPLI demo (pvbatch): the paper's 3-population cube -> watertight tubes -> PNG + .vtp.

    pvbatch Examples/demo.py <path to FiberPLI.so> <output folder>
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403

plugin, out_dir = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, remote=False, ns=globals())
os.makedirs(out_dir, exist_ok=True)

# A quarter of the paper's cube benchmark at the same fiber density (quick variant).
cube = FiberCubeSource(Populations=3, NumberOfFibers=250, EdgeLength=51.96 * 0.5, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.5, Seed=42)
tubes = FiberTubes(Input=cube, NumberOfSides=12, Capping=1)

vtp = os.path.join(out_dir, "cube_tubes.vtp")
SaveData(vtp, proxy=tubes)

view = CreateView("RenderView")
view.ViewSize = [1024, 768]
view.OrientationAxesVisibility = 1
display = Show(tubes, view)
ColorBy(display, ("CELLS", "bundle_id"))
display.LookupTable = GetColorTransferFunction("bundle_id")
display.LookupTable.ApplyPreset("Rainbow Uniform", True)
view.CameraPosition = [55, 40, 70]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
Render(view)
png = os.path.join(out_dir, "cube_tubes.png")
SaveScreenshot(png, view, ImageResolution=[1024, 768])

fibers = cube.GetDataInformation()
print("fibers: %d points in %d fibers; tubes: %d triangles" % (
    fibers.GetNumberOfPoints(), fibers.GetNumberOfCells(), tubes.GetDataInformation().GetNumberOfCells()))
print("wrote", png)
print("wrote", vtp)

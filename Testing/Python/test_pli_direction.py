"""pvpython: PLISimulation -> PLIAnalysis on a uniform slab (docs/pli-simulation.md §8 S-6): one straight
fiber of radius 1000 µm at in-plane direction 30° and inclination α fills the 60 µm section. The
analysed direction is 30° within 1°, the retardation falls with α as |sin(π/2 · t_rel · cos²α)|
with t_rel = 4·d·|Δn|/λ, and the tilt fit gives the signed inclination back."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

load_plugin(globals())

SLAB = """
import math
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
phi, alpha = math.radians(30.0), math.radians(%f)
u = (math.cos(alpha) * math.cos(phi), math.cos(alpha) * math.sin(phi), math.sin(alpha))
pts, lines, radius = vtkPoints(), vtkCellArray(), vtkDoubleArray()
radius.SetName("radius")
lines.InsertNextCell(2)
for s in (-2000.0, 2000.0):
    lines.InsertCellPoint(pts.InsertNextPoint(s * u[0], s * u[1], s * u[2]))
    radius.InsertNextValue(1000.0)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.SetLines(lines)
out.GetPointData().AddArray(radius)
"""

t_rel = 4.0 * 60.0 * 0.001 / 0.525
previous = 2.0
for alpha in (0.0, 20.0, 45.0, 70.0):
    slab = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=SLAB % alpha)
    sim = PLISimulation(Input=slab, VolumeOfInterest=[-10, 10, -10, 10, -30, 30], VoxelSize=1.0, PixelSize=2.0,
                        Wavelength=525.0, LightIntensity=26000.0, NumberOfRotations=18, TiltAngle=5.5,
                        Birefringence=-0.001, Absorption=0.0, Seed=1, Layers="1 -0.001 0 p", OpticalSigma=0.71,
                        NoiseGain=0.0, NumberOfThreads=1)
    ana = PLIAnalysis(Input=sim, InclinationMethod="Tilt", ReferenceRetardation=0.0, NumberOfThreads=1)
    maps = servermanager.Fetch(ana).GetPointData()
    direction = vtk_to_numpy(maps.GetArray("direction"))
    retardation = vtk_to_numpy(maps.GetArray("retardation"))
    signed = vtk_to_numpy(maps.GetArray("inclination_signed"))
    expected = abs(math.sin(0.5 * math.pi * t_rel * math.cos(math.radians(alpha)) ** 2))
    check(abs(direction - 30.0).max() < 1.0, "alpha %g: direction %s" % (alpha, direction[:3]))
    check(abs(retardation - expected).max() < 1e-4, "alpha %g: retardation %g, expected %g" % (
        alpha, retardation[0], expected))
    check(abs(signed - alpha).max() < 1.0, "alpha %g: tilt-fit inclination %g" % (alpha, signed[0]))
    check(retardation[0] < previous, "retardation must fall with the inclination")
    previous = retardation[0]
    print("alpha %4.1f: direction %.4f, retardation %.6f (closed form %.6f), tilt-fit inclination %.3f" % (
        alpha, direction[0], retardation[0], expected, signed[0]))
    for proxy in (ana, sim, slab):
        Delete(proxy)
print("test_pli_direction passed")

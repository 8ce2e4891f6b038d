"""pvpython: PLIAnalysis on a synthetic stack built from the closed form
I(ρ) = I_T·(1 + r·sin 2(ρ − φ)) (independent of the simulator): docs/api.md §3 array names, values,
properties by their pvpython names, bad input caught and recovered."""
import os
import builtins
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())

# 8 × 4 pixels: direction 22.5°·i, retardation 0.1 + 0.2·j, I_T = 1000 + i; 12 polarizer angles.
STACK = """
import math
from vtkmodules.vtkCommonCore import vtkDoubleArray
n = %d
out = self.GetOutput()
out.SetExtent(0, 7, 0, 3, 0, 0)
out.SetSpacing(1.0, 1.0, 1.0)
I = vtkDoubleArray()
I.SetName("%s")
I.SetNumberOfComponents(n)
I.SetNumberOfTuples(32)
for j in range(4):
    for i in range(8):
        for k in range(n):
            rho = math.radians(k * 180.0 / n)
            I.SetComponent(i + 8 * j, k, (1000.0 + i) * (1.0 + (0.1 + 0.2 * j) * math.sin(2.0 * (rho - math.radians(22.5 * i)))))
out.GetPointData().AddArray(I)
angles = vtkDoubleArray()
angles.SetName("polarizer_angles")
for k in range(n):
    angles.InsertNextValue(k * 180.0 / n)
out.GetFieldData().AddArray(angles)
"""
INFO = "self.GetExecutive().GetOutputInformation(0).Set(vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT(), 0, 7, 0, 3, 0, 0)"
INFO = "from paraview.vtk import vtkStreamingDemandDrivenPipeline\n" + INFO


def make_stack(n, name="intensity"):
    return ProgrammableSource(OutputDataSetType="vtkImageData", Script=STACK % (n, name),
                              ScriptRequestInformation=INFO)


src = make_stack(12)
ana = PLIAnalysis(Input=src, InclinationMethod="Retardation", ReferenceRetardation=0.7, NoiseGain=-1.0,
                  NumberOfThreads=2)
ana.UpdatePipeline()
out = servermanager.Fetch(ana)
pd = out.GetPointData()
for name in ("transmittance", "direction", "retardation", "inclination"):
    check(pd.GetArray(name) is not None, "array %s missing" % name)
for j in range(4):
    for i in range(8):
        p = i + 8 * j
        check(builtins.abs(pd.GetArray("transmittance").GetValue(p) - 2 * (1000.0 + i)) < 1e-8, "T at %d" % p)
        d = builtins.abs(pd.GetArray("direction").GetValue(p) - 22.5 * i) % 180.0
        check(builtins.min(d, 180.0 - d) < 1e-6, "direction at %d" % p)
        check(builtins.abs(pd.GetArray("retardation").GetValue(p) - (0.1 + 0.2 * j)) < 1e-9, "retardation at %d" % p)
# r = 0.7 = ReferenceRetardation → in-plane; r = 0.1 → steep (closed form of docs/pli-analysis.md §3.1).
import math  # noqa: E402
check(builtins.abs(pd.GetArray("inclination").GetValue(8 * 3)) < 1e-6, "r = r_ref must give 0°")
expect = math.degrees(math.acos(math.sqrt(math.asin(0.1) / math.asin(0.7))))
check(builtins.abs(pd.GetArray("inclination").GetValue(0) - expect) < 1e-6, "inclination of r = 0.1")

# Bad input: 2 polarizer angles → error naming the problem, then fixed → valid again.
bad = make_stack(2)
ana2 = PLIAnalysis(Input=bad, InclinationMethod="Auto", ReferenceRetardation=0.0, NumberOfThreads=1)
catcher = ErrorCatcher(ana2)
ana2.UpdatePipeline()
check("at least 3" in catcher.text(), "error text: %s" % catcher.text())
check(servermanager.Fetch(ana2).GetNumberOfPoints() == 0, "output must be empty after an error")
catcher.clear()
bad.Script = STACK % (6, "intensity")
ana2.UpdatePipeline()
check(not catcher.errors, "unexpected error %s" % catcher.text())
check(servermanager.Fetch(ana2).GetNumberOfPoints() == 32, "recovered output")
print("test_pli_analysis passed")

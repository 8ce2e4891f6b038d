"""pvpython: FiberOrientationMap's Mask blackens background pixels (low retardation or high
transmittance), adds the mask array, and needs the array it masks by."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkCommonCore import vtkDoubleArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

load_plugin(globals())

# 4 x 1 pixels: in-plane fibers at 0, 45, 90, 135 degrees; retardation and transmittance vary.
image = vtkImageData()
image.SetDimensions(4, 1, 1)
arrays = {"direction": [0, 45, 90, 135], "inclination": [0, 0, 0, 0],
          "retardation": [0.0, 0.02, 0.3, 0.9], "transmittance": [13000, 12500, 9000, 4000]}
for name, values in arrays.items():
    a = vtkDoubleArray()
    a.SetName(name)
    for v in values:
        a.InsertNextValue(v)
    image.GetPointData().AddArray(a)
source = TrivialProducer()
source.GetClientSideObject().SetOutput(image)


def fom(**props):
    f = FiberOrientationMap(Input=source, **props)
    f.UpdatePipeline()
    out = servermanager.Fetch(f)
    rgb = [out.GetPointData().GetArray("fom").GetTuple3(p) for p in range(4)]
    mask = out.GetPointData().GetArray("mask")
    return rgb, mask and [int(mask.GetValue(p)) for p in range(4)]


plain, no_mask = fom()
check(no_mask is None and all(c != (0, 0, 0) for c in plain), "unmasked FOM %s" % plain)
for props, keep in (({"Mask": "Retardation", "MaskThreshold": 0.05}, [0, 0, 1, 1]),
                    ({"Mask": "Transmittance", "MaskThreshold": 10000}, [0, 0, 1, 1]),
                    ({"Mask": "Transmittance", "MaskThreshold": 12600}, [0, 1, 1, 1])):
    rgb, mask = fom(**props)
    check(mask == keep, "%s: mask %s" % (props, mask))
    for p in range(4):
        check(rgb[p] == (plain[p] if keep[p] else (0, 0, 0)), "%s pixel %d: %s" % (props, p, rgb[p]))

# Masking by an array the input lacks is an error naming it.
lacking = vtkImageData()
lacking.DeepCopy(image)
lacking.GetPointData().RemoveArray("retardation")
source.GetClientSideObject().SetOutput(lacking)
bad = FiberOrientationMap(Input=source, Mask="Retardation")
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("needs the point array 'retardation'" in errors.text(), "error: %r" % errors.text())

# Arrays of different lengths are refused, naming them (the mask used to run past the FOM).
longer = vtkImageData()
longer.DeepCopy(image)
extra = vtkDoubleArray()
extra.SetName("transmittance")
for k in range(4000):
    extra.InsertNextValue(1.0)
longer.GetPointData().AddArray(extra)
source.GetClientSideObject().SetOutput(longer)
bad = FiberOrientationMap(Input=source, Mask="Transmittance", MaskThreshold=10)
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("'transmittance' has 4000 tuples, 'direction' has 4" in errors.text(), "error: %r" % errors.text())
shorter = vtkImageData()
shorter.DeepCopy(image)
short = vtkDoubleArray()
short.SetName("inclination")
short.InsertNextValue(0.0)
shorter.GetPointData().AddArray(short)
source.GetClientSideObject().SetOutput(shorter)
bad = FiberOrientationMap(Input=source)
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("'inclination' (1 tuples) differ" in errors.text(), "error: %r" % errors.text())
# Out-of-range codes typed in Python are errors naming the value, never clamped.
source.GetClientSideObject().SetOutput(image)
# (SetElement bypasses the XML domains, as a script calling the VTK setter would.)
def set_raw(proxy, name, value):
    proxy.SMProxy.GetProperty(name).SetElement(0, value)
    proxy.SMProxy.UpdateVTKObjects()


for prop, value, good, text in (("ColorScheme", 7, 1, "ColorScheme is 7"), ("Mask", -1, 0, "Mask is -1"),
                                ("LegendSize", 0, 64, "LegendSize 0")):
    bad = FiberOrientationMap(Input=source)
    errors = ErrorCatcher(bad)
    set_raw(bad, prop, value)
    bad.UpdatePipeline()
    check(text in errors.text(), "%s %d: %r" % (prop, value, errors.text()))
    errors.clear()
    set_raw(bad, prop, good)
    bad.UpdatePipeline()
    check(not errors.errors and servermanager.Fetch(bad).GetPointData().GetArray("fom") is not None,
          "%s: not usable after a good value: %r" % (prop, errors.text()))
print("FOM mask checks passed")

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
# MaskThreshold is a fraction of the image's largest value (0.9 and 13000 here): retardation below
# 0.05 * 0.9 = 0.045 is background; transmittance above (1 - 0.2) * 13000 = 10400, or above
# (1 - 0.03) * 13000 = 12610.
for props, keep, threshold in (({"Mask": "Retardation", "MaskThreshold": 0.05}, [0, 0, 1, 1], 0.045),
                               ({"Mask": "Transmittance", "MaskThreshold": 0.2}, [0, 0, 1, 1], 10400.0),
                               ({"Mask": "Transmittance", "MaskThreshold": 0.03}, [0, 1, 1, 1], 12610.0),
                               ({"Mask": "Transmittance", "MaskThreshold": 0.0}, [1, 1, 1, 1], 13000.0)):
    rgb, mask = fom(**props)
    check(mask == keep, "%s: mask %s" % (props, mask))
    for p in range(4):
        check(rgb[p] == (plain[p] if keep[p] else (0, 0, 0)), "%s pixel %d: %s" % (props, p, rgb[p]))
    f = FiberOrientationMap(Input=source, **props)
    f.UpdatePipeline()
    used = servermanager.Fetch(f).GetFieldData().GetArray("mask_threshold").GetValue(0)
    check(abs(used - threshold) < 1e-9 * threshold, "%s: mask_threshold %r" % (props, used))

# A fraction outside [0, 1] is an error naming the value (typed in Python, past the XML range).
bad = FiberOrientationMap(Input=source, Mask="Transmittance", MaskThreshold=1.5)
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("MaskThreshold 1.5" in errors.text() and "[0, 1]" in errors.text(), "error: %r" % errors.text())

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
bad = FiberOrientationMap(Input=source, Mask="Transmittance")
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
# The default MaskThreshold blackens a simulated background and keeps the tissue (default noise).
# Transmittance: a bundle of radius 10 um along x in a 10 um section twice as wide, the tissue
# absorbing (20 per mm); pixels with |y| <= 8 see at least 10 um of bundle, those with |y| >= 12
# none (the blur, OpticalSigma 0.71 um, does not reach 2 um). Retardation needs a signal well above
# the noise's: a bundle of radius 30 um in the 60 um section usual in 3D-PLI (|y| <= 24 tissue,
# |y| >= 34 background).
def masked(kind, radius, voi, absorption):
    SetActiveSource(None)
    bundle = FiberBundleSource(BundleRadius=radius, Length=40.0)
    sim = PLISimulation(Input=bundle, VolumeOfInterest=voi, Absorption=absorption, Seed=3)
    section = servermanager.Fetch(FiberOrientationMap(Input=PLIAnalysis(Input=sim), Mask=kind))
    shown = section.GetPointData().GetArray("mask")
    tissue, background = [], []
    for p in range(section.GetNumberOfPoints()):
        y = abs(section.GetPoint(p)[1])
        if y <= radius - 2 - (4 if radius > 10 else 0):
            tissue.append(shown.GetValue(p))
        elif y >= radius + 2 + (2 if radius > 10 else 0):
            background.append(1 - shown.GetValue(p))
    check(len(tissue) > 90 and len(background) > 90, "%s: %d tissue, %d background pixels" % (
        kind, len(tissue), len(background)))
    print("%s: %d of %d tissue pixels shown, %d of %d background pixels black" % (
        kind, sum(tissue), len(tissue), sum(background), len(background)))
    return sum(tissue) / len(tissue), sum(background) / len(background)


shown, black = masked("Transmittance", 10.0, [-16, 16, -20, 20, -5, 5], 20.0)
check(shown == 1.0 and black == 1.0, "Transmittance: tissue shown %.3f, background black %.3f" % (shown, black))
shown, black = masked("Retardation", 30.0, [-16, 16, -40, 40, -30, 30], 0.0)
check(shown == 1.0 and black >= 0.9, "Retardation: tissue shown %.3f, background black %.3f" % (shown, black))
print("FOM mask checks passed")

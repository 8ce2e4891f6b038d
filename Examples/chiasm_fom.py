"""Chiasm-like crossing (FiberBundleSource Shape='Chiasm'): FOM of the simulated and analysed
section before and after FiberCollisionSolver, the ground-truth FOM, and a map of how much the
measured fiber direction changes when the collisions are solved. Writes chiasm_fom_before.png,
chiasm_fom_after.png, chiasm_fom_truth.png and chiasm_fom_change.png into the output directory and
prints what they show.

Usage: pvpython chiasm_fom.py <path to FiberPLI plugin> [output directory]   (about 2 minutes)"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import os
import sys

import numpy as np

import paraview.simple
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

LoadPlugin(sys.argv[1], remote=False, ns=globals())
paraview.simple._DisableFirstRenderCameraReset()  # keep the explicit camera of every image
out_dir = sys.argv[2] if len(sys.argv) > 2 else "."
os.makedirs(out_dir, exist_ok=True)

chiasm = FiberBundleSource(Shape="Chiasm", BundleRadius=10.0, FiberRadius=0.8, RadiusSpread=0.0,
                           FiberSpacing=2.0, NumberOfFibers=0, SegmentLength=2.0, Displacement=0.2, Seed=42)
solved = FiberCollisionSolver(Input=chiasm, SegmentLength=2.0, MinCurvatureRadius=0.0, MaxSteps=20000,
                              SeparationSpeed=0.025, NumberOfThreads=0)
voi = [-40.0, 40.0, -40.0, 40.0, -5.0, 5.0]   # a 10 µm section through the crossing
# Tissue absorbs (Absorption 20/mm: about 0.85 of the light passes 10 µm of packed fibers), so the
# background is where the transmittance stays near its unhindered I0/2 = 13000 (noise ~1 %): the
# FOM's transmittance mask blackens it. MaskThreshold 0.1 (the default is 0.07) blackens pixels
# within 10 % of the brightest, so the bundles' thin edges count as background too and the
# statistics below compare full-thickness tissue only.
# Retardation would not do as a mask: it drops where the nerves cross, which is the point shown.
mask_threshold = 0.1


def analysed(fibers):
    sim = PLISimulation(Input=fibers, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=2.0, Wavelength=525.0,
                        LightIntensity=26000.0, NumberOfRotations=9, TiltAngle=0.0, Birefringence=-0.001,
                        Absorption=20.0, Seed=1)
    return PLIAnalysis(Input=sim, InclinationMethod="Retardation", ReferenceRetardation=0.0)


def show(source, name, array, rgb=True):
    view = CreateView("RenderView")
    view.ViewSize = [400, 400]
    view.OrientationAxesVisibility = 0
    display = Show(OutputPort(source, 0), view)
    ColorBy(display, ("POINTS", array))
    if rgb:
        display.MapScalars = 0
    else:  # degrees of direction change, background (NaN) black
        lut = GetColorTransferFunction(array)
        lut.ApplyPreset("Inferno (matplotlib)", True)
        lut.RescaleTransferFunction(0.0, 45.0)
        lut.AutomaticRescaleRangeMode = "Never"
        lut.NanColor = [0.0, 0.0, 0.0]
        display.SetScalarBarVisibility(view, True)
        bar = GetScalarBar(lut, view)
        bar.Title = "|Δ direction| [°]"
        bar.ComponentTitle = ""
        bar.WindowLocation = "Any Location"
        bar.Position = [0.82, 0.1]
        bar.ScalarBarLength = 0.8
        bar.RangeLabelFormat = "%.0f"
        bar.LabelFormat = "%.0f"
    view.CameraPosition = [0, 0, 200]
    view.CameraFocalPoint = [4 if not rgb else 0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 41
    Render(view)
    SaveScreenshot(os.path.join(out_dir, name), view, ImageResolution=[400, 400])
    Delete(view)


def arrays(source):
    source.UpdatePipeline()
    image = servermanager.Fetch(source)
    return image, {n: vtk_to_numpy(image.GetPointData().GetArray(n)).astype(float)
                   for n in ("direction", "retardation", "transmittance")}


before, after = analysed(chiasm), analysed(solved)
masks = []
for fibers, analysis, name in ((chiasm, before, "chiasm_fom_before.png"), (solved, after, "chiasm_fom_after.png")):
    fom = FiberOrientationMap(Input=analysis, ColorScheme="HSV-black", Mask="Transmittance",
                              MaskThreshold=mask_threshold)
    show(fom, name, "fom")
    fom.UpdatePipeline()
    masks.append(vtk_to_numpy(servermanager.Fetch(fom).GetPointData().GetArray("mask")) == 1)
truth = FiberOrientationGroundTruth(Input=solved, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=2.0)
show(FiberOrientationMap(Input=truth, ColorScheme="HSV-black"), "chiasm_fom_truth.png", "fom")

# The change of the measured direction (an axis: difference modulo 180°, in [0°, 90°]) on tissue.
image, b = arrays(before)
_, a = arrays(after)
change = np.abs((a["direction"] - b["direction"] + 90.0) % 180.0 - 90.0)
tissue = masks[0] | masks[1]
change[~tissue] = np.nan
changed = tissue & (change > 10.0)
diff = vtkImageData()
diff.CopyStructure(image)
column = numpy_to_vtk(change, deep=True)
column.SetName("direction_change")
diff.GetPointData().SetScalars(column)
producer = TrivialProducer()
producer.GetClientSideObject().SetOutput(diff)
show(producer, "chiasm_fom_change.png", "direction_change", rgb=False)

for fibers, label in ((chiasm, "before solving"), (solved, "after solving")):
    metrics = FiberMetrics(Input=fibers, Box=voi, ComputeVolumeFraction=1)
    metrics.UpdatePipeline()
    row = servermanager.Fetch(metrics, idx=1)
    print("%-14s collisions %6d, volume fraction in the section %.3f" % (
        label, row.GetColumnByName("collisions").GetValue(0), row.GetColumnByName("volume_fraction").GetValue(0)))
dims = image.GetDimensions()
centre = np.zeros((dims[1], dims[0]), bool)
centre[dims[1] // 4:3 * dims[1] // 4, dims[0] // 4:3 * dims[0] // 4] = True
centre = centre.ravel()
print("tissue pixels %d; direction changed by more than 10° on %d of them (%d in the central crossing "
      "half, %d outside); mean change %.1f° in the centre, %.1f° outside" % (
          tissue.sum(), changed.sum(), (changed & centre).sum(), (changed & ~centre).sum(),
          np.nanmean(change[tissue & centre]), np.nanmean(change[tissue & ~centre])))
print("transmittance: tissue %.0f ± %.0f, background %.0f ± %.0f" % (
    b["transmittance"][tissue].mean(), b["transmittance"][tissue].std(),
    b["transmittance"][~tissue].mean(), b["transmittance"][~tissue].std()))
print("retardation (before / after solving): %.3f / %.3f in the central crossing, %.3f / %.3f in the bundles "
      "outside it" % (b["retardation"][tissue & centre].mean(), a["retardation"][tissue & centre].mean(),
                       b["retardation"][tissue & ~centre].mean(), a["retardation"][tissue & ~centre].mean()))
print("wrote chiasm_fom_before.png, chiasm_fom_after.png, chiasm_fom_truth.png, chiasm_fom_change.png to", out_dir)

"""Chiasm-like crossing (FiberBundleSource Shape='Chiasm'): FOM of the simulated and analysed
section before and after FiberCollisionSolver, next to the ground-truth FOM. Writes
chiasm_fom_before.png, chiasm_fom_after.png and chiasm_fom_truth.png into the output directory.

Usage: pvpython chiasm_fom.py <path to FiberPLI plugin> [output directory]"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import os
import sys

import paraview.simple
from paraview.simple import *  # noqa: F401,F403

LoadPlugin(sys.argv[1], remote=False, ns=globals())
paraview.simple._DisableFirstRenderCameraReset()  # keep the explicit camera of every image
out_dir = sys.argv[2] if len(sys.argv) > 2 else "."
os.makedirs(out_dir, exist_ok=True)

chiasm = FiberBundleSource(Shape="Chiasm", BundleRadius=10.0, FiberRadius=0.8, RadiusSpread=0.0,
                           FiberSpacing=2.0, NumberOfFibers=0, SegmentLength=2.0, Displacement=0.2, Seed=42)
solved = FiberCollisionSolver(Input=chiasm, SegmentLength=2.0, MinCurvatureRadius=0.0, MaxSteps=20000,
                              SeparationSpeed=0.025, NumberOfThreads=0)
voi = [-40.0, 40.0, -40.0, 40.0, -5.0, 5.0]   # a 10 µm section through the crossing


def fom_of(fibers):
    sim = PLISimulation(Input=fibers, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=2.0, Wavelength=525.0,
                        LightIntensity=26000.0, NumberOfRotations=9, TiltAngle=0.0, Birefringence=-0.001,
                        Absorption=0.0, Seed=1)
    analysis = PLIAnalysis(Input=sim, InclinationMethod="Retardation", ReferenceRetardation=0.0)
    return FiberOrientationMap(Input=analysis, ColorScheme="HSV-black")


def save(source, name):
    view = CreateView("RenderView")
    view.ViewSize = [400, 400]
    view.OrientationAxesVisibility = 0
    display = Show(OutputPort(source, 0), view)
    ColorBy(display, ("POINTS", "fom"))
    display.MapScalars = 0
    view.CameraPosition = [0, 0, 200]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 41
    Render(view)
    SaveScreenshot(os.path.join(out_dir, name), view, ImageResolution=[400, 400])
    Delete(view)


save(fom_of(chiasm), "chiasm_fom_before.png")
save(fom_of(solved), "chiasm_fom_after.png")
truth = FiberOrientationGroundTruth(Input=solved, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=2.0)
save(FiberOrientationMap(Input=truth, ColorScheme="HSV-black"), "chiasm_fom_truth.png")
print("wrote chiasm_fom_before.png, chiasm_fom_after.png, chiasm_fom_truth.png to", out_dir)

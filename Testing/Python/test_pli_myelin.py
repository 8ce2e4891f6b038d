"""pvpython: PLISimulation with the point array inner_radius (docs/pli-simulation.md §3.2). A straight
myelinated fiber along the beam: the tissue labels are the voxel centres inside the inner radius
(axon) and between it and the radius (sheath), counted independently; a pixel in the axon shows no
birefringence, a pixel in the sheath the closed-form amplitude of a uniform in-plane retarder of
the section's thickness. Without inner_radius, or with a Layers text, the images are unchanged."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData  # noqa: E402

load_plugin(globals())

X0, Y0, R, G = 0.15, -0.2, 4.0, 0.6


def fiber(inner):
    """One straight fiber along z through (X0, Y0), radius R, with inner_radius `inner` (None: none)."""
    points, lines, radius, inner_array = vtkPoints(), vtkCellArray(), vtkDoubleArray(), vtkDoubleArray()
    points.SetDataTypeToDouble()
    radius.SetName("radius")
    inner_array.SetName("inner_radius")
    lines.InsertNextCell(5)
    for k in range(5):
        lines.InsertCellPoint(points.InsertNextPoint(X0, Y0, -10 + 5 * k))
        radius.InsertNextValue(R)
        inner_array.InsertNextValue(inner if inner is not None else 0.0)
    pd = vtkPolyData()
    pd.SetPoints(points)
    pd.SetLines(lines)
    pd.GetPointData().AddArray(radius)
    if inner is not None:
        pd.GetPointData().AddArray(inner_array)
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(pd)
    return producer


def simulate(source, layers="", update=True):
    sim = PLISimulation(Input=source, VolumeOfInterest=[-6, 6, -6, 6, -2, 2], VoxelSize=0.5, PixelSize=0.5,
                        NumberOfRotations=9, Birefringence=-0.001, Absorption=0.0, Layers=layers,
                        Interpolation="NN", OpticalSigma=0.0, NoiseGain=0.0, ExportTissue=1, NumberOfThreads=2)
    if update:
        sim.UpdatePipeline()
    return sim


myelinated = simulate(fiber(G * R))
tissue = servermanager.Fetch(myelinated, idx=1)
labels = vtk_to_numpy(tissue.GetPointData().GetArray("label"))
centres = np.array([tissue.GetPoint(i) for i in range(tissue.GetNumberOfPoints())])
rho2 = (centres[:, 0] - X0) ** 2 + (centres[:, 1] - Y0) ** 2
check(tissue.GetFieldData().GetArray("layers_per_bundle").GetValue(0) == 2, "two layers: axon and sheath")
axon, sheath = np.count_nonzero(labels == 1), np.count_nonzero(labels == 2)
slices = 8  # 4 um of 0.5 um voxels
print("labels: axon %d sheath %d per slice; areas %.1f %.1f voxels" % (
    axon / slices, sheath / slices, math.pi * (G * R) ** 2 / 0.25, math.pi * (1 - G * G) * R * R / 0.25))
check(axon == np.count_nonzero(rho2 <= (G * R) ** 2), "axon voxels")
check(sheath == np.count_nonzero((rho2 > (G * R) ** 2) & (rho2 <= R * R)), "sheath voxels")

image = servermanager.Fetch(myelinated)
stack = vtk_to_numpy(image.GetPointData().GetArray("intensity"))
rho = np.radians(vtk_to_numpy(image.GetFieldData().GetArray("polarizer_angles")))


def pixel(x, y):
    i = int(round((x - image.GetOrigin()[0]) / image.GetSpacing()[0]))
    j = int(round((y - image.GetOrigin()[1]) / image.GetSpacing()[1]))
    return stack[j * (image.GetExtent()[1] + 1) + i]


def amplitude(values):
    """Relative amplitude of the 2-rho harmonic (the retardation sin(pi/2 t_rel) of a uniform layer)."""
    c, s = (values * np.cos(2 * rho)).mean() * 2, (values * np.sin(2 * rho)).mean() * 2
    return math.hypot(c, s) / values.mean()


t_rel = 4 * 4.0 * 0.001 / 0.525  # d = 4 um, |dn| = 0.001, 525 nm
print("axon pixel amplitude %.3g; sheath pixel %.6f, closed form %.6f" % (
    amplitude(pixel(0.25, -0.25)), amplitude(pixel(3.25, -0.25)), math.sin(math.pi / 2 * t_rel)))
check(amplitude(pixel(0.25, -0.25)) < 1e-12, "the axon is not birefringent")
check(abs(amplitude(pixel(3.25, -0.25)) - math.sin(math.pi / 2 * t_rel)) < 1e-9, "sheath retardation")

# Without inner_radius: today's single parallel layer (a fiber along the beam shows nothing), the
# same image as that layer written out; with a Layers text the inner radii are not used.
plain = servermanager.Fetch(simulate(fiber(None)))
plain_stack = vtk_to_numpy(plain.GetPointData().GetArray("intensity"))
check(np.ptp(plain_stack, axis=1).max() < 1e-9, "a parallel fiber along the beam is dark")
written = vtk_to_numpy(servermanager.Fetch(simulate(fiber(G * R), "1 -0.001 0 p")).GetPointData().GetArray("intensity"))
check(np.array_equal(plain_stack, written), "Layers text: inner_radius must change nothing")

# A bad inner_radius (above the radius) is an error naming it; the pipeline recovers.
bad = simulate(fiber(2 * R), update=False)
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("inner_radius" in errors.text() and "8" in errors.text(), "no inner_radius error: %r" % errors.text())
errors.clear()
bad.Input = fiber(G * R)
bad.UpdatePipeline()
check(not errors.errors and bad.GetDataInformation().GetNumberOfPoints() == 24 * 24, "no recovery")
print("OK")

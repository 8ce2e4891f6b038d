"""Direction and inclination maps (PLIAnalysis or FiberOrientationGroundTruth) → a 3-D orientation
field for FiberFieldSource, and a dense model that follows it.

orientation_field(image, thickness, slices) turns the one-slice maps into a vtkImageData of
`slices` planes spread over `thickness` µm (the section's thickness; each plane repeats the
maps) with the point array "orientation": (cos i · cos d, cos i · sin d, sin i) for direction d and
inclination i in degrees. PLI does not measure the sign of the inclination, so the field takes it
positive; NaN pixels (and, with min_retardation, pixels of weak retardation: no fibers) become
empty. The example below measures the ground truth of a chiasm-like crossing, rebuilds a model from
it and prints how well the new model follows the map.

Usage: pvpython field_from_pli_maps.py <path to FiberPLI plugin>   (about a minute)"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import sys

import numpy as np

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData


def orientation_field(image, thickness, slices, direction="direction", inclination="inclination",
                      min_retardation=None):
    """A 3-D orientation field (vtkImageData, point array "orientation") from a one-slice image
    with direction and inclination point arrays in degrees, repeated over `slices` >= 2 planes
    that span `thickness` µm centred on the image's plane."""
    if slices < 2 or thickness <= 0:
        raise ValueError("slices must be >= 2 and thickness > 0 (got %r, %r)" % (slices, thickness))
    nx, ny, nz = image.GetDimensions()
    if nz != 1:
        raise ValueError("expected a one-slice image, got %d slices" % nz)
    d = np.radians(vtk_to_numpy(image.GetPointData().GetArray(direction)).astype(np.float64))
    i = np.radians(vtk_to_numpy(image.GetPointData().GetArray(inclination)).astype(np.float64))
    v = np.c_[np.cos(i) * np.cos(d), np.cos(i) * np.sin(d), np.sin(i)]
    v[~np.all(np.isfinite(v), axis=1)] = 0.0  # pixels without an orientation: empty, no fibers
    if min_retardation is not None:
        r = vtk_to_numpy(image.GetPointData().GetArray("retardation"))
        v[r < min_retardation] = 0.0
    out = vtkImageData()
    out.SetDimensions(nx, ny, slices)
    sx, sy, _ = image.GetSpacing()
    ox, oy, oz = image.GetOrigin()
    out.SetSpacing(sx, sy, thickness / (slices - 1))
    out.SetOrigin(ox, oy, oz - 0.5 * thickness)
    a = numpy_to_vtk(np.ascontiguousarray(np.tile(v, (slices, 1))), deep=1)  # x fastest, then y, then z
    a.SetName("orientation")
    out.GetPointData().AddArray(a)
    return out


if __name__ == "__main__":
    LoadPlugin(sys.argv[1], remote=False, ns=globals())
    chiasm = FiberBundleSource(Shape="Chiasm", BundleRadius=10.0, FiberRadius=0.8, FiberSpacing=2.0,
                               NumberOfFibers=0, SegmentLength=2.0, Displacement=0.2, Seed=42)
    voi = [-40.0, 40.0, -40.0, 40.0, -5.0, 5.0]
    truth = FiberOrientationGroundTruth(Input=chiasm, VolumeOfInterest=voi, VoxelSize=0.5, PixelSize=2.0)
    maps = servermanager.Fetch(truth)
    field = orientation_field(maps, thickness=10.0, slices=6)
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(field)
    model = FiberFieldSource(Input=producer, VolumeFraction=0.3, FiberRadius=0.8, SegmentLength=2.0, Seed=1)
    model.OrientationArray = ["POINTS", "orientation"]
    solved = FiberCollisionSolver(Input=model, SegmentLength=2.0, MaxSteps=5000)
    solved.UpdatePipeline()
    data = servermanager.Fetch(solved)
    print("%d fibers traced through the measured map (traced volume fraction %.3f), %d collisions left"
          % (data.GetNumberOfCells(),
             servermanager.Fetch(model).GetFieldData().GetArray("traced_volume_fraction").GetValue(0),
             data.GetFieldData().GetArray("collisions").GetValue(0)))

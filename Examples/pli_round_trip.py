"""Measurement → model → measurement: how well can a dense model built from a 3D-PLI orientation
map reproduce that map, and how far is either from the true orientation?

1. a known model: the chiasm-like crossing of FiberBundleSource, solved by FiberCollisionSolver;
2. PLISimulation with four tilted views, PLIAnalysis (tilt fit): direction, inclination,
   retardation, transmittance — measurement 1;
3. the measured direction and inclination become a 3-D orientation field repeated through the
   section's thickness (Examples/field_from_pli_maps.py), empty where the retardation is weak (no
   fibers); FiberFieldSource fills it at the first model's volume fraction, the solver solves it;
4. the new model is simulated and analysed the same way — measurement 2;
5. per-pixel errors of measurement 1 and 2 against the true orientation
   (FiberOrientationGroundTruth of the first model on the same pixel grid) and of measurement 2
   against measurement 1: direction as an axis (0° ≡ 180°: min(|a − b|, 180° − |a − b|)) and
   unsigned inclination (| |a| − |b| |). Written to pli_round_trip.vti (binary), summarised on
   stdout (mean, median, 90th percentile over the pixels with fibers) and drawn into
   pli_round_trip.png (FOMs of the truth and both measurements, and the error of measurement 2).

Usage: pvbatch pli_round_trip.py <path to FiberPLI plugin> <output folder>
           [--bundle-radius R] [--half-width W] [--seed S] [--mask retardation|transmittance]
           [--rotate-field DEG]
(about 15 s on two cores). --rotate-field turns the measured directions by DEG before the
model is built: a deliberately wrong field, whose measurement 2 must then disagree."""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import argparse
import os
import sys

import numpy as np

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from field_from_pli_maps import orientation_field  # noqa: E402

FIBER_RADIUS = 0.8
SEGMENT = 2.0
# The simulation's voxel: at most half the smallest radius (docs/pli-simulation.md §2.1); the
# chiasm's nodes of Ranvier narrow the 0.8 µm fibers to 0.56 µm.
VOXEL = 0.25
PIXEL = 2.0
THICKNESS = 8.0      # the section, centred on the chiasm's plane z = 0
# Δn = −0.004 over 8 µm of tissue would give t_rel = 4·8·0.004/0.525 = 0.24; the bundles fill
# about half of each column, so in-plane fibers give a retardation near 0.17, well above the
# noise's few hundredths and in the monotonic range of the inversion (docs/pli-analysis.md §3.1).
# 3D-PLI sections are thicker with a weaker Δn; t_rel is what counts.
BIREFRINGENCE = -0.004
TILT = 5.5
# Which pixels carry fibers, by the measurement alone (--mask):
# - retardation: at least MASK_SHARE of the image's 99th percentile; the noise's retardation is a
#   few hundredths, the bundles' about 0.17. A crossing of two perpendicular populations cancels
#   its own retardation (about 0.06 here) and is left empty.
# - transmittance: at most (1 − ABSORPTION_SHARE) of the image's 99th percentile; the fibers absorb
#   (Absorption 20/mm: 4–8 % over the section) while the background's noise is about 1 %. A
#   crossing then keeps its measured direction, the mean of its two populations.
MASK_SHARE = 0.3
ABSORPTION_SHARE = 0.03


def parse(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("plugin")
    p.add_argument("out")
    p.add_argument("--bundle-radius", type=float, default=10.0, help="µm, of each nerve of the chiasm")
    p.add_argument("--half-width", type=float, default=30.0, help="µm, half the section's edge")
    p.add_argument("--seed", type=int, default=42)
    p.add_argument("--mask", choices=("retardation", "transmittance"), default="retardation",
                   help="which measured map says where the fibers are")
    p.add_argument("--rotate-field", type=float, default=0.0,
                   help="degrees added to the measured direction before the model is built")
    return p.parse_args(argv)


def section(half_width):
    """The volume of interest: a square section of THICKNESS µm through the model's plane."""
    return [-half_width, half_width, -half_width, half_width, -0.5 * THICKNESS, 0.5 * THICKNESS]


def known_model(bundle_radius, seed):
    """The chiasm-like crossing, solved: the model whose orientation is known."""
    chiasm = FiberBundleSource(Shape="Chiasm", BundleRadius=bundle_radius, FiberRadius=FIBER_RADIUS,
                               FiberSpacing=2.0, NumberOfFibers=0, SegmentLength=SEGMENT,
                               Displacement=0.2, Seed=seed)
    return FiberCollisionSolver(Input=chiasm, SegmentLength=SEGMENT, MaxSteps=20000)


def measure(fibers, voi, seed):
    """3D-PLI of the section: untilted and four views tilted by TILT, 9 polarizer angles, camera
    noise; analysed with the tilt fit (direction, signed inclination, retardation)."""
    sim = PLISimulation(Input=fibers, VolumeOfInterest=voi, VoxelSize=VOXEL, PixelSize=PIXEL,
                        NumberOfRotations=9, TiltAngle=TILT, Birefringence=BIREFRINGENCE,
                        Absorption=20.0, Seed=seed)
    return PLIAnalysis(Input=sim, InclinationMethod="Tilt")


def truth(fibers, voi):
    """The true mean fiber axis per pixel, on the simulation's pixel grid."""
    return FiberOrientationGroundTruth(Input=fibers, VolumeOfInterest=voi, VoxelSize=VOXEL, PixelSize=PIXEL)


def fetch(proxy):
    proxy.UpdatePipeline()
    image = vtkImageData()
    image.DeepCopy(servermanager.Fetch(proxy))
    return image


def array(image, name):
    return vtk_to_numpy(image.GetPointData().GetArray(name)).astype(np.float64)


def fibre_mask(maps, by="retardation"):
    """Pixels with fibers by the measurement alone (see MASK_SHARE); the 99th percentile, so that
    one noisy pixel does not set the scale."""
    if by == "retardation":
        r = array(maps, "retardation")
        return np.isfinite(r) & (r >= MASK_SHARE * np.nanpercentile(r, 99))
    t = array(maps, "transmittance")
    return np.isfinite(t) & (t <= (1.0 - ABSORPTION_SHARE) * np.nanpercentile(t, 99))


def measured_field(maps, rotate=0.0, by="retardation"):
    """The 3-D orientation field of a measured map: direction (turned by `rotate` degrees) and the
    tilt fit's signed inclination, repeated over the section's thickness, empty where fibre_mask
    says there are no fibers."""
    m = vtkImageData()
    m.DeepCopy(maps)
    d = (array(maps, "direction") + rotate) % 180.0
    d[~fibre_mask(maps, by)] = np.nan   # empty: no fiber enters there
    column = numpy_to_vtk(d, deep=1)
    column.SetName("direction")
    m.GetPointData().AddArray(column)
    return orientation_field(m, thickness=THICKNESS, slices=5, inclination="inclination_signed")


def model_from_field(field, volume_fraction, seed):
    """A dense model following the field at the given volume fraction, solved."""
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(field)
    traced = FiberFieldSource(Input=producer, VolumeFraction=volume_fraction, FiberRadius=FIBER_RADIUS,
                              SegmentLength=SEGMENT, Seed=seed)
    traced.OrientationArray = ["POINTS", "orientation"]
    return traced, FiberCollisionSolver(Input=traced, SegmentLength=SEGMENT, MaxSteps=20000)


def axial_error(a, b):
    """Angle between two axes given as directions in degrees (0° ≡ 180°), in [0°, 90°]."""
    d = np.abs(a - b) % 180.0
    return np.minimum(d, 180.0 - d)


def statistics(values):
    v = values[np.isfinite(values)]
    return float(np.mean(v)), float(np.median(v)), float(np.percentile(v, 90)), v.size


def error_image(geometry, arrays):
    out = vtkImageData()
    out.CopyStructure(geometry)
    for name, values in arrays.items():
        column = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float64), deep=1)
        column.SetName(name)
        out.GetPointData().AddArray(column)
    return out


def write_vti(image, path):
    writer = vtkXMLImageDataWriter()
    writer.SetInputData(image)
    writer.SetDataModeToBinary()
    writer.SetFileName(path)
    if not writer.Write():
        raise RuntimeError("could not write " + path)


def picture(panels, path):
    """One row of views: (proxy, array, title, rgb) each; FOMs in true colour, errors in degrees."""
    layout = CreateLayout("round trip")
    views = []
    for k, (proxy, name, title, rgb) in enumerate(panels):
        view = CreateView("RenderView")
        view.OrientationAxesVisibility = 0
        view.Background = [1.0, 1.0, 1.0]
        try:
            view.UseColorPaletteForBackground = 0
        except AttributeError:
            pass
        display = Show(proxy, view)
        ColorBy(display, ("POINTS", name))
        if rgb:
            display.MapScalars = 0
        else:
            lut = GetColorTransferFunction(name)
            lut.ApplyPreset("Inferno (matplotlib)", True)
            lut.RescaleTransferFunction(0.0, 30.0)
            lut.AutomaticRescaleRangeMode = "Never"
            lut.NanColor = [0.5, 0.5, 0.5]
            display.SetScalarBarVisibility(view, True)
            bar = GetScalarBar(lut, view)
            bar.Title = "°"
            bar.ComponentTitle = ""
            bar.RangeLabelFormat = "%.0f"
            bar.LabelFormat = "%.0f"
            bar.TitleColor = bar.LabelColor = [0, 0, 0]
            bar.WindowLocation = "Any Location"
            bar.Position = [0.84, 0.1]
            bar.ScalarBarLength = 0.75
        text = Text(Text=title)
        label = Show(text, view)
        label.FontSize = 14
        label.Color = [0, 0, 0]
        label.WindowLocation = "Upper Center"
        view.CameraPosition = [0, 0, 200]
        half = max(proxy.GetDataInformation().GetBounds()[1], 1.0)
        # The error panel leaves room on the right for its colour bar.
        view.CameraFocalPoint = [0.0 if rgb else 0.25 * half, 0.0, 0.0]
        view.CameraViewUp = [0, 1, 0]
        view.CameraParallelProjection = 1
        view.CameraParallelScale = (1.2 if rgb else 1.35) * half
        views.append(view)
    # Split the layout into len(views) equal columns: cell 0 holds the first view, the right part
    # of each split holds the rest.
    cell = 0
    for k, view in enumerate(views):
        if k < len(views) - 1:
            left = layout.SplitHorizontal(cell, 1.0 / (len(views) - k))
            AssignViewToLayout(view=view, layout=layout, hint=left)
            cell = left + 1
        else:
            AssignViewToLayout(view=view, layout=layout, hint=cell)
    layout.SetSize(300 * len(views), 320)
    SaveScreenshot(path, layout, ImageResolution=[300 * len(views), 320])


def main(argv):
    args = parse(argv)
    LoadPlugin(args.plugin, remote=False, ns=globals())
    os.makedirs(args.out, exist_ok=True)
    voi = section(args.half_width)

    model1 = known_model(args.bundle_radius, args.seed)
    true_orientation = truth(model1, voi)
    true_maps = fetch(true_orientation)
    analysis1 = measure(model1, voi, seed=1)
    maps1 = fetch(analysis1)

    # The first model's volume fraction where it has fibers: the truth's tissue share per pixel
    # (n_t / n_all over the column), averaged over the pixels the measurement finds fibers in.
    fraction = array(true_maps, "fraction")
    fibres1 = fibre_mask(maps1, args.mask)
    volume_fraction = float(np.mean(fraction[fibres1]))
    traced, model2 = model_from_field(measured_field(maps1, args.rotate_field, args.mask), volume_fraction, args.seed)
    model2.UpdatePipeline()
    analysis2 = measure(model2, voi, seed=2)
    maps2 = fetch(analysis2)

    d_t, i_t = array(true_maps, "direction"), np.abs(array(true_maps, "inclination"))
    d_1, i_1 = array(maps1, "direction"), np.abs(array(maps1, "inclination"))
    d_2, i_2 = array(maps2, "direction"), np.abs(array(maps2, "inclination"))
    # Pixels with fibers: the truth has tissue in at least a quarter of the column (so a pixel at
    # a bundle's rim with a few voxels of fiber does not count) and the first measurement sees it.
    fibres = np.nan_to_num(fraction) >= 0.25
    nan = np.where(fibres, 0.0, np.nan)
    errors = {
        "direction_error_1_truth": axial_error(d_1, d_t) + nan,
        "direction_error_2_truth": axial_error(d_2, d_t) + nan,
        "direction_error_2_1": axial_error(d_2, d_1) + nan,
        "inclination_error_1_truth": np.abs(i_1 - i_t) + nan,
        "inclination_error_2_truth": np.abs(i_2 - i_t) + nan,
        "inclination_error_2_1": np.abs(i_2 - i_1) + nan,
        "direction_truth": d_t, "inclination_truth": i_t,
        "direction_1": d_1, "inclination_1": i_1, "retardation_1": array(maps1, "retardation"),
        "direction_2": d_2, "inclination_2": i_2, "retardation_2": array(maps2, "retardation"),
        "fibres": fibres.astype(np.float64),
    }
    image = error_image(maps1, errors)
    write_vti(image, os.path.join(args.out, "pli_round_trip.vti"))

    n1 = servermanager.Fetch(model1).GetNumberOfCells()
    n2 = servermanager.Fetch(model2).GetNumberOfCells()
    c2 = servermanager.Fetch(model2).GetFieldData().GetArray("collisions").GetValue(0)
    print("model 1: %d fibers (chiasm, bundle radius %g um); model 2: %d fibers traced at volume fraction "
          "%.3f (reached %.3f), %d collisions left after solving"
          % (n1, args.bundle_radius, n2, volume_fraction,
             servermanager.Fetch(traced).GetFieldData().GetArray("traced_volume_fraction").GetValue(0), c2))
    print("pixels with fibers: %d of %d (the measurement's %s mask: %d)"
          % (fibres.sum(), fibres.size, args.mask, fibres1.sum()))
    print("%-36s %8s %8s %8s" % ("error (degrees)", "mean", "median", "90 %"))
    for key, label in (("direction_error_1_truth", "direction, measurement 1 vs truth"),
                       ("direction_error_2_truth", "direction, measurement 2 vs truth"),
                       ("direction_error_2_1", "direction, measurement 2 vs 1"),
                       ("inclination_error_1_truth", "inclination, measurement 1 vs truth"),
                       ("inclination_error_2_truth", "inclination, measurement 2 vs truth"),
                       ("inclination_error_2_1", "inclination, measurement 2 vs 1")):
        mean, median, p90, _ = statistics(errors[key])
        print("%-36s %8.2f %8.2f %8.2f" % (label, mean, median, p90))

    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(image)
    panels = [(FiberOrientationMap(Input=true_orientation), "fom", "truth", True),
              (FiberOrientationMap(Input=analysis1, Mask="Retardation", MaskThreshold=0.15), "fom",
               "measurement 1", True),
              (FiberOrientationMap(Input=analysis2, Mask="Retardation", MaskThreshold=0.15), "fom",
               "measurement 2 (model from 1)", True),
              (producer, "direction_error_2_1", "direction error 2 vs 1", False)]
    picture(panels, os.path.join(args.out, "pli_round_trip.png"))
    print("wrote pli_round_trip.vti and pli_round_trip.png to", args.out)
    return {"truth": true_maps, "measurement_1": maps1, "measurement_2": maps2, "errors": errors,
            "volume_fraction": volume_fraction, "model_1": model1, "model_2": model2}


if __name__ == "__main__":
    main(sys.argv[1:])

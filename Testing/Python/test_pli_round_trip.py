"""pvpython: Examples/pli_round_trip.py on a small chiasm. Measurement 1 (simulated 3D-PLI of the
solved chiasm, tilt-fit analysis) matches the known geometry and the true orientation within the
camera noise; the model rebuilt from the measured maps by FiberFieldSource is collision-free and
its measurement reproduces measurement 1; a field turned by 90° gives a measurement 90° off; the
error maps the example writes (binary .vti) are the ones this test computes itself."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples"))
from fiberpli_test import check, load_plugin, option  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader  # noqa: E402

import pli_round_trip  # noqa: E402

out = option("-T", ".")
R = 8.0  # µm, each nerve's radius: about 90 fibers
run = pli_round_trip.main([sys.argv[1], out, "--bundle-radius", str(R), "--half-width", "26"])


def values(image, name):
    return vtk_to_numpy(image.GetPointData().GetArray(name)).astype(np.float64)


def axis_error(a, b):
    """Angle between axes given by in-plane directions in degrees: 0° and 180° are one axis."""
    d = np.mod(np.abs(a - b), 180.0)
    return np.where(d > 90.0, 180.0 - d, d)


def has_fibers(maps):
    """The measurement's own evidence of fibers: retardation above 0.3 of its 99th percentile (the
    camera noise alone gives a few hundredths, the bundles' in-plane fibers about 0.17)."""
    r = values(maps, "retardation")
    return np.isfinite(r) & (r >= 0.3 * np.nanpercentile(r, 99))


truth, m1, m2 = run["truth"], run["measurement_1"], run["measurement_2"]
d_t, i_t = values(truth, "direction"), np.abs(values(truth, "inclination"))
d_1, i_1 = values(m1, "direction"), np.abs(values(m1, "inclination"))
d_2, i_2 = values(m2, "direction"), np.abs(values(m2, "inclination"))
fraction = np.nan_to_num(values(truth, "fraction"))
anisotropy = np.nan_to_num(values(truth, "anisotropy"))
nx, ny, _ = m1.GetDimensions()
ox, oy, _ = m1.GetOrigin()
sx, sy, _ = m1.GetSpacing()
x = np.tile(ox + sx * np.arange(nx), ny)
y = np.repeat(oy + sy * np.arange(ny), nx)

# Pixels of one in-plane population: tissue over at least a quarter of the column, a single
# dominant axis (anisotropy λ1 − λ2 ≥ 0.9, so not the crossing) within 10° of the section's plane.
single = (fraction >= 0.25) & (anisotropy >= 0.9) & (np.nan_to_num(i_t, nan=90.0) <= 10.0)
check(single.sum() >= 100, "only %d in-plane single-population pixels" % single.sum())

# 1. Geometry known without the code: the chiasm's nerves cross at 90° along the diagonals, so far
# from the centre (beyond 2.2 R, where the uncrossed fibers have turned back) the fibers run at 45°
# in the quadrants x·y > 0 and at 135° in the others.
arms = single & (np.hypot(x, y) > 2.2 * R)
expected = np.where(x * y > 0, 45.0, 135.0)
check(arms.sum() >= 30, "only %d arm pixels" % arms.sum())
for name, d in (("truth", d_t), ("measurement 1", d_1)):
    e = np.median(axis_error(d, expected)[arms])
    check(e < 5.0, "%s: median direction %.2f deg off the nerves' axes" % (name, e))

# 2. Measurement 1 vs the truth. Camera noise (gain 3, a0 ≈ 5000 counts, retardation ≈ 0.17, 9
# angles) scatters the direction by σ ≈ √(3·a0)·√(2/9) / (2·a0·0.17) ≈ 1.8°: a median |error| near
# 0.67 σ ≈ 1.2°; 3° allows blur and partly filled pixels and fails for any systematic turn.
e1 = axis_error(d_1, d_t)[single]
check(np.median(e1) < 3.0, "measurement 1 vs truth: median direction error %.2f deg" % np.median(e1))
# The tilt fit's inclination of in-plane fibers: noise only biases |α| upwards; a fit that mixed up
# direction and inclination would put these fibers tens of degrees out of the plane.
ei1 = np.abs(i_1 - i_t)[single]
check(np.median(ei1) < 12.0, "measurement 1 vs truth: median inclination error %.2f deg" % np.median(ei1))

# 3. The model rebuilt from measurement 1 is collision-free (FiberMetrics' own count), fills the
# measured bundles and its measurement reproduces measurement 1: two noise realisations differ by
# √2 σ ≈ 2.5°, a median near 1.7°; 4° leaves room for the rebuilt fibers' own arrangement.
metrics = FiberMetrics(Input=run["model_2"], ComputeVolumeFraction=0)
metrics.UpdatePipeline()
collisions = servermanager.Fetch(metrics, idx=1).GetColumnByName("collisions").GetValue(0)
check(collisions == 0, "%d colliding pairs in the rebuilt model" % collisions)
seen = single & has_fibers(m2)
check(seen.sum() >= 0.8 * single.sum(), "measurement 2 finds fibers on %d of %d pixels" % (seen.sum(), single.sum()))
e21 = axis_error(d_2, d_1)[seen]
check(np.median(e21) < 4.0, "measurement 2 vs 1: median direction error %.2f deg" % np.median(e21))

# 4. A deliberately wrong field: the measured directions turned by 90°. Its model runs across the
# nerves, so measurement 2 must be about 90° off measurement 1 — the comparison can fail.
_, wrong = pli_round_trip.model_from_field(pli_round_trip.measured_field(m1, rotate=90.0),
                                           run["volume_fraction"], 42)
wrong_maps = pli_round_trip.fetch(pli_round_trip.measure(wrong, pli_round_trip.section(26.0), seed=2))
crossed = single & has_fibers(wrong_maps)
ew = axis_error(values(wrong_maps, "direction"), d_1)[crossed]
check(crossed.sum() >= 0.5 * single.sum(), "the turned model covers only %d pixels" % crossed.sum())
check(np.median(ew) > 60.0, "turned field: median direction error only %.2f deg" % np.median(ew))

# 5. The example's error maps, as written (binary), are these.
path = os.path.join(out, "pli_round_trip.vti")
with open(path, "rb") as f:
    head = f.read(4096)
check(b'format="binary"' in head, "%s is not written in binary mode" % path)
reader = vtkXMLImageDataReader()
reader.SetFileName(path)
reader.Update()
written = reader.GetOutput()
check(written.GetDimensions() == m1.GetDimensions(), "error map dimensions %s" % (written.GetDimensions(),))
mask = fraction >= 0.25
for name, ours in (("direction_error_1_truth", axis_error(d_1, d_t)),
                   ("direction_error_2_truth", axis_error(d_2, d_t)),
                   ("direction_error_2_1", axis_error(d_2, d_1)),
                   ("inclination_error_1_truth", np.abs(i_1 - i_t)),
                   ("inclination_error_2_1", np.abs(i_2 - i_1))):
    theirs = values(written, name)
    check(np.array_equal(np.isnan(theirs), ~mask | np.isnan(ours)), "%s: NaN outside the fiber pixels differ" % name)
    ok = ~np.isnan(theirs)
    check(np.allclose(theirs[ok], ours[ok], atol=1e-9), "%s differs from the test's own computation" % name)
check(os.path.getsize(os.path.join(out, "pli_round_trip.png")) > 10000, "no picture")

print("in-plane pixels %d: median direction error 1 vs truth %.2f, 2 vs 1 %.2f (on %d), turned field %.1f deg; "
      "median inclination error 1 vs truth %.2f deg" % (single.sum(), np.median(e1), np.median(e21), seen.sum(),
                                                       np.median(ew), np.median(ei1)))

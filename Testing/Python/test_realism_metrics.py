"""pvpython: FiberMetrics' realism outputs against closed forms — closed helices of known tortuosity
per population, myelin and axon volume of straight myelinated fibers through a periodic cell, the
mixing figure of populations in halves or interleaved, the histogram tables (as a Bar Chart View shows them) — a realistic cube from
the source (its inner_radius also through .h5 and back), and a bad inner_radius (an error naming it; the pipeline usable again)."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData  # noqa: E402

load_plugin(globals())


def polydata(fibers, cell):
    """Fibers as (bundle, [(x, y, z, r, inner or None)]) in a periodic cell [0, cell]^3."""
    points, lines, radius, inner, bundle = vtkPoints(), vtkCellArray(), vtkDoubleArray(), vtkDoubleArray(), vtkIntArray()
    points.SetDataTypeToDouble()
    radius.SetName("radius")
    inner.SetName("inner_radius")
    bundle.SetName("bundle_id")
    with_inner = all(p[4] is not None for _, f in fibers for p in f)
    for b, fiber in fibers:
        lines.InsertNextCell(len(fiber))
        bundle.InsertNextValue(b)
        for x, y, z, r, ri in fiber:
            lines.InsertCellPoint(points.InsertNextPoint(x, y, z))
            radius.InsertNextValue(r)
            inner.InsertNextValue(ri if with_inner else 0.0)
    pd = vtkPolyData()
    pd.SetPoints(points)
    pd.SetLines(lines)
    pd.GetPointData().AddArray(radius)
    if with_inner:
        pd.GetPointData().AddArray(inner)
    pd.GetCellData().AddArray(bundle)
    field = vtkDoubleArray()
    field.SetName("periodic_cell")
    for v in (0, cell, 0, cell, 0, cell):
        field.InsertNextValue(v)
    pd.GetFieldData().AddArray(field)
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(pd)
    return producer


def table(proxy, port):
    proxy.UpdatePipeline()
    return servermanager.Fetch(proxy, idx=port)


def column(t, name, row=0):
    return t.GetColumnByName(name).GetTuple(row)[0] if t.GetColumnByName(name).GetNumberOfComponents() == 1 \
        else t.GetColumnByName(name).GetTuple(row)


def helix(cx, cy, R, turns, n, L, r, g=None):
    pts = []
    for k in range(turns * n + 1):
        t = 2 * math.pi * k / n
        pts.append((cx + R * math.cos(t), cy + R * math.sin(t), L * k / (turns * n), r, None if g is None else g * r))
    return pts


# --- tortuosity and c2 per population: closed helices (tau of the sampled helix in closed form) ---
L, n = 20.0, 360
fibers = [(0, helix(5, 5, 0.5, 4, n, L, 0.2)), (0, helix(15, 5, 1.0, 4, n, L, 0.2)), (3, helix(5, 15, 0.8, 2, n, L, 0.2))]
metrics = FiberMetrics(Input=polydata(fibers, L), ComputeVolumeFraction=0, ComputeCollisions=0)
populations = table(metrics, 3)


def polyline_tau(R, pitch):
    return n * math.sqrt((2 * R * math.sin(math.pi / n)) ** 2 + (pitch / n) ** 2) / pitch


print("helices: tortuosity", [column(populations, "tortuosity_mean", i) for i in range(2)])
check(populations.GetNumberOfRows() == 2 and column(populations, "bundle_id", 1) == 3, "Populations rows")
check(abs(column(populations, "tortuosity_min", 0) - polyline_tau(0.5, 5)) < 1e-9, "tortuosity_min")
check(abs(column(populations, "tortuosity_max", 0) - polyline_tau(1.0, 5)) < 1e-9, "tortuosity_max")
check(abs(column(populations, "tortuosity_mean", 1) - math.sqrt(1 + (2 * math.pi * 0.8 / 10) ** 2)) < 1e-3, "helix tau")
check(abs(column(populations, "c2_end_to_end", 1) - 1) < 1e-12 and abs(abs(column(populations, "axis", 1)[2]) - 1) < 1e-12,
      "closed fibers run along their lattice vector")
hist = table(metrics, 5)  # tortuosity histogram: one count per fiber
check(sum(hist.GetColumnByName("count").GetValue(k) for k in range(hist.GetNumberOfRows())) == 3, "tortuosity histogram")
check(hist.GetNumberOfRows() == 20 and hist.GetColumnByName("bin_extents") is not None, "20 bins, bin_extents")
angles = table(metrics, 7)
check(abs(angles.GetFieldData().GetArray("histogram_range").GetValue(1) - 90) < 1e-12 and
      abs(angles.GetFieldData().GetArray("bin_width").GetValue(0) - 4.5) < 1e-12 and
      abs(angles.GetColumnByName("bin_extents").GetValue(0) - 2.25) < 1e-12, "angles in 4.5-degree bins up to 90")
check(angles.GetNumberOfColumns() == 2 and hist.GetNumberOfColumns() == 2, "only the bar chart's columns")
check(sum(angles.GetColumnByName("count").GetValue(k) for k in range(20)) == 3 * 4 * n - 2 * n, "one count per link")

# --- myelin: straight fibers through the cell, inner radius g r: closed-form fractions ---
L, R, g = 12.0, 1.5, 0.6
straight = [(b, [(x, y, L * k / 6, R, g * R) for k in range(7)]) for b, (x, y) in enumerate(((3, 3), (9, 9)))]
metrics = FiberMetrics(Input=polydata(straight, L), VoxelSize=0.04, VolumeFractionMethod="Voxels", ComputeCollisions=0)
s = table(metrics, 1)
fiber, axon = 2 * math.pi * R * R / (L * L), 2 * math.pi * (g * R) ** 2 / (L * L)
err, axon_err = column(s, "volume_fraction_error"), column(s, "axon_fraction_error")
print("myelin: fiber %.5f axon %.5f myelin %.5f (exact %.5f %.5f %.5f)" % (
    column(s, "volume_fraction"), column(s, "axon_fraction"), column(s, "myelin_fraction"), fiber, axon, fiber - axon))
check(abs(column(s, "axon_fraction") - axon) <= axon_err and axon_err < 0.01, "axon fraction")
check(abs(column(s, "myelin_fraction") - (fiber - axon)) <= err + axon_err, "myelin fraction")
check(abs(column(s, "extra_axonal_fraction") - (1 - fiber)) <= err, "extra-axonal fraction")
check(abs(column(s, "g_ratio_mean") - g) < 1e-12 and abs(column(s, "radius_cv")) < 1e-7, "g-ratio, radius CV")
out = servermanager.Fetch(metrics)
check(abs(out.GetCellData().GetArray("g_ratio").GetValue(1) - g) < 1e-12, "g_ratio cell array")
check(abs(out.GetFieldData().GetArray("myelin_fraction").GetValue(0) - column(s, "myelin_fraction")) == 0, "field data")
check(column(s, "mixing_min_share") == 0, "two populations in separate columns are not mixed")

# --- mixing: 6 x 6 fibers along z in a (12 um)^3 cell, halves vs checkerboard ---
def grid(population):
    return [(population(i, j), [(1 + 2 * i, 1 + 2 * j, 2 * k, 0.8, None) for k in range(7)]) for i in range(6) for j in range(6)]


halves = column(table(FiberMetrics(Input=polydata(grid(lambda i, j: int(i >= 3)), 12), ComputeVolumeFraction=0,
                                   ComputeCollisions=0, Samples=200000), 1), "mixing_min_share")
mixed_metrics = FiberMetrics(Input=polydata(grid(lambda i, j: (i + j) % 2), 12), ComputeVolumeFraction=0,
                             ComputeCollisions=0, Samples=200000)
mixed = column(table(mixed_metrics, 1), "mixing_min_share")
print("mixing: halves %.3f, checkerboard %.3f" % (halves, mixed))
check(halves == 0 and 0.44 < mixed <= 0.5, "mixing figure")
check(math.isnan(column(table(FiberMetrics(Input=polydata(grid(lambda i, j: (i + j) % 2), 12), ComputeVolumeFraction=0,
                                           ComputeCollisions=0, ComputeMixing=0), 1), "mixing_min_share")), "mixing off")

# --- a realistic periodic cube from the source: g-ratio exact, tortuosity and CV present ---
cube = FiberCubeSource(Populations=2, NumberOfFibers=40, EdgeLength=30, Periodic=1, Seed=2, GRatio=0.7,
                       Tortuosity=1.1, UndulationWavelength=15, BeadingCV=0.2, BeadingLength=5)
s = table(FiberMetrics(Input=cube, VolumeFractionMethod="MonteCarlo", Samples=200000, ComputeCollisions=0), 1)
print("cube: tortuosity_mean %.3f radius_cv %.3f g %.3f myelin %.4f axon %.4f" % (
    column(s, "tortuosity_mean"), column(s, "radius_cv"), column(s, "g_ratio_mean"), column(s, "myelin_fraction"),
    column(s, "axon_fraction")))
check(abs(column(s, "g_ratio_mean") - 0.7) < 1e-9, "constant g-ratio")
check(column(s, "radius_cv") > 0.05 and column(s, "tortuosity_mean") > 1.02, "beading and undulation measured")
check(column(s, "myelin_fraction") > 0 and column(s, "axon_fraction") > 0, "myelin and axon volume")

# --- inner_radius through .h5 (attributes beside fastPLI's (n, 4) datasets) and back ---
h5 = os.path.join(option("-T"), "realism_cube.h5")
SaveData(h5, proxy=cube)
original = servermanager.Fetch(cube)
back = servermanager.Fetch(FiberReader(FileName=h5))
a, b = original.GetPointData().GetArray("inner_radius"), back.GetPointData().GetArray("inner_radius")
check(b is not None and b.GetNumberOfTuples() == a.GetNumberOfTuples() and
      all(a.GetValue(i) == b.GetValue(i) for i in range(a.GetNumberOfTuples())), ".h5 round trip of inner_radius")

# --- a bad inner_radius: an error naming it and the value; usable once fixed ---
bad_fibers = [(0, [(0, 0, 0, 1.0, 0.5), (0, 0, 4, 1.0, 1.5), (0, 0, 8, 1.0, 0.5)])]
bad = FiberMetrics(Input=polydata(bad_fibers, 12), ComputeVolumeFraction=0)
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("inner_radius" in errors.text() and "1.5" in errors.text() and "line cell 0" in errors.text(),
      "no inner_radius error: %r" % errors.text())
bad.Input = polydata([(0, [(0, 0, 0, 1.0, 0.5), (0, 0, 4, 1.0, 0.5), (0, 0, 8, 1.0, 0.5)])], 12)
check(abs(column(table(bad, 1), "g_ratio_mean") - 0.5) < 1e-12, "pipeline not usable after the error")
# --- the histograms as ParaView shows them: a Bar Chart View takes bin_extents as x, bars of count ---
view = CreateView("XYBarChartView")
bars = Show(OutputPort(metrics, 7), view)
print("bar chart: x", bars.XArrayName, "series", bars.SeriesVisibility)
check(bars.XArrayName == "bin_extents" and not bars.UseIndexForXAxis and list(bars.SeriesVisibility) == ["count"],
      "bar chart defaults: x %s, series %s" % (bars.XArrayName, list(bars.SeriesVisibility)))
Render(view)
print("OK")

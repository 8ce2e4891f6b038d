"""pvbatch: FiberCollisionSolver distributed over the MPI ranks (docs/solver.md §13) gives the
one-process result bit for bit, for 1, 2, 3 and 4 ranks x 1 and 2 threads; so does a solve that
holds the tortuosity (HoldTortuosity, several solves, docs/solver.md §5.5).

Usage: pvbatch mpi_solver.py <plugin> <tmp dir> serial          (one process: writes the reference)
       mpiexec -n R pvbatch mpi_solver.py <plugin> <tmp dir> R  (compares with the reference)
The sources make their pieces; every rank's output piece is fetched on its own, and the pieces in
rank order must be the serial output: a hash over every fiber's points, radii, point and cell
arrays, and the field data, which must be the same on every piece."""
import hashlib
import json
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

signal.alarm(250)  # a rank stuck in a collective dies instead of hanging
load_plugin(globals())
tmp = sys.argv[2]
serial = sys.argv[3] == "serial"
reference = os.path.join(tmp, "..", "mpi.solver_reference.json")
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == (1 if serial else int(sys.argv[3])), "expected %s ranks, got %d" % (sys.argv[3], ranks))

FIELDS = ["steps", "collisions", "solved", "max_overlap", "shape_ok", "segment_length", "volume_fraction",
          "min_gap", "radius_scale", "tortuosity_solves"]


def digest(pieces):
    """Hash of the pieces joined in order (points, fiber lengths, every point and cell array; the
    connectivity is the points in order) and their field data."""
    import numpy
    parts = {}
    fields = None
    for data in pieces:
        if data.GetNumberOfPoints() > 0:
            offsets = vtk_to_numpy(data.GetLines().GetOffsetsArray())
            check((vtk_to_numpy(data.GetLines().GetConnectivityArray()) == numpy.arange(offsets[-1])).all(),
                  "the lines are the points in order")
            parts.setdefault("points", []).append(vtk_to_numpy(data.GetPoints().GetData()))
            parts.setdefault("lengths", []).append(numpy.diff(offsets))
            for kind, attributes in (("point", data.GetPointData()), ("cell", data.GetCellData())):
                for i in range(attributes.GetNumberOfArrays()):
                    name = kind + ":" + attributes.GetArrayName(i)
                    parts.setdefault(name, []).append(vtk_to_numpy(attributes.GetArray(i)))
        fd = data.GetFieldData()
        mine = {name: fd.GetArray(name).GetTuple1(0) for name in FIELDS if fd.GetArray(name)}
        check(fields is None or mine == fields, "field data differ between pieces: %s vs %s" % (mine, fields))
        fields = mine
    h = hashlib.sha256()
    for name in sorted(parts):
        h.update(name.encode())
        h.update(numpy.concatenate(parts[name]).tobytes())
    return {"hash": h.hexdigest(), "fibers": int(sum(len(x) for x in parts.get("lengths", []))),
            "arrays": sorted(parts), "fields": fields}


def solve(source, threads, **properties):
    solver = FiberCollisionSolver(Input=source, NumberOfThreads=threads, **properties)
    solver.UpdatePipeline()
    pieces = [servermanager.Fetch(solver, r) for r in range(ranks)]
    for r, data in enumerate(pieces):
        fd = data.GetFieldData()
        if fd.GetArray("rank_points"):
            print("mpi_solver: rank %d: %d fibers, peak %d points + halo links, %d halo links, %.0f halo bytes/step, "
                  "%d migrations" % (r, data.GetNumberOfLines(), fd.GetArray("rank_points").GetTuple1(0),
                                     fd.GetArray("halo_links").GetTuple1(0),
                                     fd.GetArray("halo_bytes_per_step").GetTuple1(0),
                                     fd.GetArray("migrations").GetTuple1(0)))
    if ranks > 1:
        check(all(p.GetNumberOfLines() > 0 for p in pieces), "every rank holds fibers of the output")
        check(all(p.GetFieldData().GetArray("halo_links").GetTuple1(0) > 0 for p in pieces), "halos exchanged")
        check(all(p.GetFieldData().GetArray("held_links").GetTuple1(0) >= p.GetFieldData().GetArray("halo_links").GetTuple1(0)
                  for p in pieces), "a rank's held links include its halo links")
        # Plumbing only (the values are global reductions; TestDistributedSolver asserts them).
        recuts = [(p.GetFieldData().GetArray("tester_recuts").GetTuple1(0),
                   p.GetFieldData().GetArray("tester_cut_move").GetTuple1(0)) for p in pieces]
        check(all(r == recuts[0] for r in recuts) and 0.0 <= recuts[0][1] < 1.0,
              "tester re-cuts agreed over the ranks, a cut moved by less than the axis: %s" % recuts)
    Delete(solver)
    return digest(pieces)


cube = FiberCubeSource(Populations=2, NumberOfFibers=120, EdgeLength=18.0, Seed=5)
cell = FiberCubeSource(Populations=2, Periodic=1, VolumeFraction=0.45, EdgeLength=14.0, Displacement=0.3, Seed=8)
crossing = FiberCubeSource(Populations=2, Periodic=1, VolumeFraction=0.55, EdgeLength=16.0, FiberRadius=0.8,
                           SegmentLength=1.0, Displacement=0.0, Seed=5, Seeding="Random", Arrangement="Interwoven",
                           Tortuosity=1.25, UndulationWavelength=8.0)
results = {}
for threads in (1, 2):
    results["cube"] = solve(cube, threads, MaxSteps=60, MinCurvatureRadius=4.0, SegmentLength=0.0)
    results["cell"] = solve(cell, threads, MaxSteps=60, MinCurvatureRadius=4.0)
    if threads == 1:  # four solves of up to 120 steps each: once is enough
        results["held"] = solve(crossing, threads, MaxSteps=120, SegmentLength=1.0, MaxDisplacement=0.4,
                                Tortuosity=1.25, HoldTortuosity=1)
        check(results["held"]["fields"]["tortuosity_solves"] >= 2,
              "the held crossing solved once: %s" % results["held"]["fields"])
    for name, r in results.items():
        print("mpi_solver: %d ranks x %d threads, %s: %s" % (ranks, threads, name, r))
    if serial and threads == 1:
        with open(reference, "w") as f:
            json.dump(results, f)
    else:
        with open(reference) as f:
            expected = json.load(f)
        for name in results:
            check(results[name] == expected[name], "%s, %d ranks x %d threads: %s, serial %s" % (
                name, ranks, threads, results[name], expected[name]))
print("mpi_solver passed")

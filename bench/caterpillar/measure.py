"""Measures a CATERPillar substrate (its voxel .csv: one sphere per line, `cell_type cell_id component
component_id X Y Z inner_radius outer_radius`) with the figures of realistic_bench.py, in numpy,
sharing no code with FiberPLI or CATERPillar:
    /usr/bin/python3 bench/caterpillar/measure.py out/run.csv --edge 40
φ = the union of the axons' outer spheres over the voxel [0, L]³ (Monte Carlo, 4·10⁵ points, ± one
standard error); per population (an axon's population is the coordinate axis its end-to-end vector
is closest to): tortuosity (path through the sphere centres over the end-to-end distance), c2 of
segments (length-weighted ⟨cos²⟩ about the axis), along-axon radius CV; and the smallest population
share of the axon volume over the 27 sub-cubes of edge L/3 (populations > 1)."""
import argparse

import numpy as np
from scipy.spatial import cKDTree

parser = argparse.ArgumentParser()
parser.add_argument("csv")
parser.add_argument("--edge", type=float, required=True)
parser.add_argument("--samples", type=int, default=400000)
args = parser.parse_args()
L = args.edge

rows = [line.split() for line in open(args.csv) if line.startswith("axon")]
cell = np.array([int(r[1]) for r in rows])
xyz = np.array([[float(v) for v in r[4:7]] for r in rows])
outer = np.array([float(r[8]) for r in rows])

axons = []
for c in np.unique(cell):
    sel = cell == c
    p, r = xyz[sel], outer[sel]
    if len(p) < 2:
        continue
    span = p[-1] - p[0]
    axis = int(np.argmax(np.abs(span)))
    axons.append((p, r, axis))
pop_of_sphere = np.concatenate([np.full(len(a[0]), a[2]) for a in axons])
centres = np.concatenate([a[0] for a in axons])
radii = np.concatenate([a[1] for a in axons])

# Union of spheres over the voxel, and per sub-cube the population of the covering sphere.
rng = np.random.default_rng(0)
x = rng.uniform(0.0, L, size=(args.samples, 3))
tree = cKDTree(centres)
rmax = radii.max()
inside = np.zeros(len(x), bool)
owner = np.full(len(x), -1)
for i, near in enumerate(tree.query_ball_point(x, rmax)):
    if near:
        near = np.array(near)
        d = np.linalg.norm(centres[near] - x[i], axis=1) - radii[near]
        k = np.argmin(d)
        if d[k] <= 0.0:
            inside[i] = True
            owner[i] = pop_of_sphere[near[k]]
phi = inside.mean()
err = np.sqrt(phi * (1 - phi) / len(x))
pops = sorted(set(a[2] for a in axons))
print("axons %d, spheres %d, φ %.1f ± %.1f %%" % (len(axons), len(centres), 100 * phi, 100 * err))
for k in pops:
    group = [a for a in axons if a[2] == k]
    tau, c2num, c2den, cv = [], 0.0, 0.0, []
    for p, r, _ in group:
        seg = np.diff(p, axis=0)
        length = np.linalg.norm(seg, axis=1)
        tau.append(length.sum() / np.linalg.norm(p[-1] - p[0]))
        ok = length > 0
        c2num += np.sum(seg[ok, k] ** 2 / length[ok])
        c2den += np.sum(length[ok])
        cv.append(r.std() / r.mean())
    print("population %d (axis %s): %d axons, tortuosity %.3f [%.3f, %.3f], c2 segments %.3f, radius CV %.3f" % (
        k, "xyz"[k], len(group), np.mean(tau), np.min(tau), np.max(tau), c2num / c2den, np.mean(cv)))
if len(pops) > 1:
    sub = np.minimum((x[inside] / (L / 3)).astype(int), 2)
    cube = sub[:, 0] * 9 + sub[:, 1] * 3 + sub[:, 2]
    share = np.zeros((27, len(pops)))
    for j, k in enumerate(pops):
        share[:, j] = np.bincount(cube[owner[inside] == k], minlength=27)
    print("mixing (smallest population share over 27 sub-cubes): %.2f" % (share / share.sum(1, keepdims=True)).min())

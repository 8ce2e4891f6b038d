"""Signals of the MC/DC run per gradient direction and strength, and where the walkers ended:
inside a fiber (distance to its polyline, minimum image in the 20 µm cell, below the capsule radius)."""
import sys
import numpy as np

prefix, dat = sys.argv[1], sys.argv[2]
scheme = np.loadtxt("pgse.scheme", skiprows=1)
dwi = np.loadtxt(prefix + "_DWI.txt")
gamma = 2.6751525e8
for row, s in zip(scheme, dwi):
    g, G, Delta, delta = row[:3], row[3], row[4], row[5]
    b = (gamma * G * delta) ** 2 * (Delta - delta / 3.0)
    print("dir %-10s G %.2f T/m  b %6.0f s/mm2  S/S0 %.4f" % (tuple(int(x) for x in g), G, b * 1e-6, s / dwi[0]))

fibers, cur = [], []
for line in open(dat):
    t = line.split()
    if len(t) == 4:
        cur.append([float(x) for x in t])
    elif cur:
        fibers.append(np.array(cur)); cur = []
if cur:
    fibers.append(np.array(cur))
traj = np.loadtxt(prefix + "_0.traj.txt") if len(sys.argv) < 4 else None
N = int(sys.argv[3]) if len(sys.argv) > 3 else 200
pos = traj.reshape(N, -1, 3) * 1e3  # mm -> µm
L = 20.0
def inside(p):
    for f in fibers:
        a, b = f[:-1, :3], f[1:, :3]
        r = np.maximum(f[:-1, 3], f[1:, 3])
        for shift in np.array(np.meshgrid([-1, 0, 1], [-1, 0, 1], [-1, 0, 1])).reshape(3, -1).T * L:
            q = p + shift
            ab = b - a
            t = np.clip(np.einsum("ij,ij->i", q - a, ab) / np.einsum("ij,ij->i", ab, ab), 0, 1)
            d = np.linalg.norm(q - (a + ab * t[:, None]), axis=1)
            if np.any(d < r):
                return True
    return False
start_in = sum(inside(((p + 10.0) % L) - 10.0) for p in pos[:, 0])
end_in = sum(inside(((p + 10.0) % L) - 10.0) for p in pos[:, -1])
print("walkers %d, started inside a fiber %d, ended inside a fiber %d" % (N, start_in, end_in))
disp = pos[:, -1] - pos[:, 0]
print("mean squared displacement (µm²): x %.1f  y %.2f  z %.2f" % tuple(np.mean(disp ** 2, axis=0)))

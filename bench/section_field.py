"""The orientation field of the millimetre-section benchmarks (bench/README.md "A millimetre
section"), shared by section_bench.py and mpi_solver_bench.py: on a 10 µm grid over an L × L × T µm
section, array "a" follows sinusoidal paths y = y0 + a·sin(2πx/λ) along x (a 25 µm, λ 400 µm: the
steepest part 21° off x, the tightest bend of radius λ²/(4π²a) = 162 µm) and array "b" runs along y
in the band |x − L/2| < band·L/2 (zero elsewhere: no fibers of that population there)."""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData


def section_field(L, T, band):
    h = 10.0
    n = int(round(L / h)) + 1
    nz = max(2, int(round(T / h)) + 1)
    x = np.linspace(0.0, L, n)
    z = np.linspace(0.0, T, nz)
    X, Y, _ = np.meshgrid(x, x, z, indexing="ij")
    a, wavelength = 25.0, 400.0
    k = 2.0 * np.pi / wavelength
    va = np.stack([np.ones_like(X), a * k * np.cos(k * X), np.zeros_like(X)], -1)
    vb = np.zeros_like(va)
    vb[np.abs(X - 0.5 * L) < 0.5 * band * L] = (0.0, 1.0, 0.0)
    image = vtkImageData()
    image.SetDimensions(n, n, nz)
    image.SetSpacing(h, h, T / (nz - 1))
    for name, v in (("a", va), ("b", vb)):
        array = numpy_to_vtk(np.ascontiguousarray(v.transpose(2, 1, 0, 3).reshape(-1, 3)), deep=1)
        array.SetName(name)
        image.GetPointData().AddArray(array)
    return image

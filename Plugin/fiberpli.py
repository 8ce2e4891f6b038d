"""fiberpli: fibers as NumPy arrays and back, for pvpython users (shipped inside FiberPLI.so).

After ``LoadPlugin(".../FiberPLI.so", remote=False, ns=globals())``, ``import fiberpli`` gives:

- ``to_arrays(data)``: fibers of a vtkPolyData (or a pipeline proxy, fetched) as a list of
  (n, 4) float64 arrays ``x y z r`` plus NumPy arrays of their ``fiber_id`` and ``bundle_id``;
- ``to_bundles(data)``: the same grouped as fastPLI's ``fiber_bundles`` (a list of bundles, each a
  list of (n, 4) arrays, in increasing ``bundle_id``);
- ``from_arrays(fibers, fiber_ids=None, bundle_ids=None)`` and ``from_bundles(bundles)``: back to
  fiber vtkPolyData (point array ``radius``, cell arrays ``fiber_id`` and ``bundle_id``);
- ``producer(polydata)``: a pipeline source proxy holding that polydata (pvpython's built-in
  session), so that ``FiberCollisionSolver(Input=fiberpli.producer(...))`` works.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdTypeArray, vtkIntArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

__all__ = ["to_arrays", "to_bundles", "from_arrays", "from_bundles", "producer"]


def _polydata(data):
    """A vtkPolyData from a vtkPolyData or a paraview.simple proxy (fetched to the client)."""
    if isinstance(data, vtkPolyData):
        return data
    if hasattr(data, "GetXMLName") or hasattr(data, "SMProxy"):
        from paraview import servermanager
        data = servermanager.Fetch(data)
    if not isinstance(data, vtkPolyData):
        raise TypeError("fiberpli: expected fiber vtkPolyData or a proxy producing it, got %s" % type(data).__name__)
    return data


def to_arrays(data):
    """(fibers, fiber_ids, bundle_ids): one (n, 4) float64 array x y z r per line cell, in cell order.

    Without a fiber_id / bundle_id cell array the ids are the cell index / 0, as in the filters.
    """
    pd = _polydata(data)
    if pd.GetNumberOfPoints() == 0 or pd.GetLines().GetNumberOfCells() == 0:
        return [], np.zeros(0, np.int64), np.zeros(0, np.int32)
    radius = pd.GetPointData().GetArray("radius")
    if radius is None or radius.GetNumberOfComponents() != 1:
        raise ValueError("fiberpli: the polydata has no one-component point array 'radius'")
    xyzr = np.empty((pd.GetNumberOfPoints(), 4))
    xyzr[:, :3] = vtk_to_numpy(pd.GetPoints().GetData())
    xyzr[:, 3] = vtk_to_numpy(radius)
    lines = pd.GetLines()
    offsets = vtk_to_numpy(lines.GetOffsetsArray()).astype(np.int64)
    connectivity = vtk_to_numpy(lines.GetConnectivityArray()).astype(np.int64)
    fibers = [xyzr[connectivity[offsets[k]:offsets[k + 1]]] for k in range(len(offsets) - 1)]
    # Line cells come after vertices in VTK's cell numbering: cell arrays are indexed from there.
    first = pd.GetVerts().GetNumberOfCells()
    count = len(fibers)

    def cell_ids(name, default, dtype):
        array = pd.GetCellData().GetArray(name)
        if array is None:
            return default.astype(dtype)
        return vtk_to_numpy(array)[first:first + count].astype(dtype)

    fiber_ids = cell_ids("fiber_id", np.arange(first, first + count), np.int64)
    bundle_ids = cell_ids("bundle_id", np.zeros(count), np.int32)
    return fibers, fiber_ids, bundle_ids


def to_bundles(data):
    """fastPLI's fiber_bundles: a list of bundles (increasing bundle_id), each a list of (n, 4) arrays."""
    fibers, _, bundle_ids = to_arrays(data)
    return [[f for f, b in zip(fibers, bundle_ids) if b == bundle] for bundle in np.unique(bundle_ids)]


def from_arrays(fibers, fiber_ids=None, bundle_ids=None):
    """Fiber vtkPolyData from a sequence of (n, 4) arrays x y z r (n >= 2, finite, r > 0).

    fiber_ids default to 0, 1, ...; bundle_ids to 0. Bad input raises ValueError naming the fiber.
    """
    fibers = [np.asarray(f, dtype=np.float64) for f in fibers]
    for k, f in enumerate(fibers):
        if f.ndim != 2 or f.shape[1] != 4 or f.shape[0] < 2:
            raise ValueError("fiberpli: fiber %d has shape %s, (n >= 2, 4) expected" % (k, f.shape))
        # Same rule and wording as the C++ conversion (FiberPolyData / validateModel), which
        # test_numpy_fibers.py checks on the same bad arrays.
        for i, row in enumerate(f):
            if not np.all(np.isfinite(row[:3])):
                raise ValueError("fiberpli: fiber %d point %d has a non-finite coordinate" % (k, i))
            if not (np.isfinite(row[3]) and row[3] > 0):
                raise ValueError("fiberpli: fiber %d point %d has radius %g (must be finite and > 0)" % (k, i, row[3]))
    count = len(fibers)
    fiber_ids = np.arange(count) if fiber_ids is None else np.asarray(fiber_ids)
    bundle_ids = np.zeros(count, np.int32) if bundle_ids is None else np.asarray(bundle_ids)
    if fiber_ids.shape != (count,) or bundle_ids.shape != (count,):
        raise ValueError("fiberpli: %d fibers but %d fiber ids and %d bundle ids" % (count, fiber_ids.size, bundle_ids.size))
    if len(np.unique(fiber_ids)) != count:
        raise ValueError("fiberpli: fiber ids are not unique")

    return _unchecked_polydata(fibers, fiber_ids, bundle_ids)


def _unchecked_polydata(fibers, fiber_ids, bundle_ids):
    """The polydata of from_arrays without its checks (the tests feed bad arrays to the C++ side)."""
    count = len(fibers)
    pd = vtkPolyData()
    if count == 0:
        return pd
    xyzr = np.concatenate(fibers)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyzr[:, :3]), deep=True))
    radius = numpy_to_vtk(np.ascontiguousarray(xyzr[:, 3]), deep=True)
    radius.SetName("radius")
    offsets = np.concatenate([[0], np.cumsum([len(f) for f in fibers])])
    cells = vtkCellArray()
    cells.SetData(_id_array(offsets), _id_array(np.arange(len(xyzr))))
    pd.SetPoints(points)
    pd.SetLines(cells)
    pd.GetPointData().AddArray(radius)
    ids = _id_array(fiber_ids)
    ids.SetName("fiber_id")
    bundles = vtkIntArray()
    bundles.SetName("bundle_id")
    for b in bundle_ids:
        bundles.InsertNextValue(int(b))
    pd.GetCellData().AddArray(ids)
    pd.GetCellData().AddArray(bundles)
    return pd


def from_bundles(bundles):
    """Fiber vtkPolyData from fastPLI's fiber_bundles: bundle_id = the bundle's index, fiber ids 0, 1, ..."""
    fibers, bundle_ids = [], []
    for b, bundle in enumerate(bundles):
        fibers.extend(bundle)
        bundle_ids.extend([b] * len(bundle))
    return from_arrays(fibers, bundle_ids=np.asarray(bundle_ids, np.int32))


def producer(polydata):
    """A TrivialProducer proxy holding the polydata, as pipeline input (built-in session only)."""
    from paraview.simple import TrivialProducer
    proxy = TrivialProducer()
    proxy.GetClientSideObject().SetOutput(polydata)
    return proxy


def _id_array(values):
    array = vtkIdTypeArray()
    array.SetNumberOfTuples(len(values))
    vtk_to_numpy(array)[:] = values
    return array

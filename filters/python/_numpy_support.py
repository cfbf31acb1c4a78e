"""What the numpy-level functions of ``pointsetsurfaces`` share: their errors and result type, the
conversion of their inputs (arrays, paths, datasets) and outputs, files read by extension, and a
filter run with its errors, warnings, threads and progress captured. Private: ``_numpy_api``
holds the functions."""
import math
import os
import re
import threading
import warnings

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand, vtkPoints, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkDataSet, vtkImageData, vtkPointSet, vtkPolyData

from . import PointSetSurfacesFilters as _filters



class Error(RuntimeError):
    """A PointSetSurfaces computation failed; the message is the one the C++ filter reported."""


class InputError(Error, ValueError):
    """An argument was refused before anything ran: wrong shape, NaN coordinates, an unknown name, a
    parameter outside its range. Also a ValueError."""


class SurfaceWarning(UserWarning):
    """A warning of a C++ filter (e.g. cloud points with NaN coordinates left out)."""


#: The surface definitions, by the names the ``pss`` tool takes (``--variant``), in the order of
#: vtkPointSetSurface's enum. Case, ``-``, ``_`` and spaces do not count, and the VTK spellings
#: ("LevinMLS", "CenterOfMass", ...) and "mls" (Levin's) are accepted too.
VARIANTS = ("levin", "normalized", "com", "integral", "delta", "apss", "rimls")
_VARIANT_ALIASES = {"levinmls": 0, "mls": 0, "normalizedmls": 1, "centerofmass": 2}
_PROCEDURES = ("extremal", "plane")
_ORIENTATIONS = ("away-from-centroid", "away-from-point", "along-direction", "propagate")
_NONFINITE = ("raise", "allow")


class Result(dict):
    """Named numpy arrays, readable as items or attributes (``r["Normal"]`` or ``r.Normal``).

    ``info`` holds the scalars of the run: ``h`` (the scale used), ``dimension`` (2 or 3) and the
    output's field data (for a mesh, e.g. ``EulerCharacteristic``, ``Components``,
    ``BoundaryEdges``).
    """

    def __init__(self, arrays, info):
        super().__init__(arrays)
        self.info = info

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError("no array named %r (arrays: %s)" % (name, ", ".join(self))) from None

    def __dir__(self):
        return list(super().__dir__()) + [k for k in self if k.isidentifier()]

    def __repr__(self):
        parts = ["%s=%s %s" % (k, "x".join(str(d) for d in v.shape) or "scalar", v.dtype) for k, v in self.items()]
        return "Result(%s; h=%s)" % (", ".join(parts), self.info.get("h"))


# ---------------------------------------------------------------------------------------------
# Inputs


def _key(text):
    return re.sub(r"[-_ ]", "", str(text)).lower()


def _choice(what, value, names, aliases=None):
    """The index of value among names (case, '-', '_' and ' ' ignored; an int is taken as is)."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool) and 0 <= value < len(names):
        return int(value)
    if isinstance(value, str):
        wanted = _key(value)
        for i, name in enumerate(names):
            if wanted == _key(name):
                return i
        if aliases and wanted in aliases:
            return aliases[wanted]
    raise InputError("%s must be one of %s, got %r" % (what, ", ".join(names), value))


def _number(what, value, integer=False):
    """value as a float (or an int), or InputError. NaN passes: the C++ checks say what it means."""
    try:
        if isinstance(value, (bool, np.bool_)) or isinstance(value, str):
            raise TypeError
        if integer:
            if isinstance(value, (float, np.floating)) and not float(value).is_integer():
                raise TypeError
            return int(value)
        return float(value)
    except (TypeError, ValueError, OverflowError):
        raise InputError("%s must be %s, got %r" % (what, "an integer" if integer else "a number", value)) from None


def _set(obj, prop, value, keyword):
    """obj.Set<prop>(value); the VTK setters clamp silently, so a value they would change is refused."""
    if isinstance(value, float) and math.isnan(value):
        # A clamp lets NaN through, and no filter checks its numerical settings for it.
        raise InputError("%s must be a number, got nan" % keyword)
    getattr(obj, "Set" + prop)(value)
    got = getattr(obj, "Get" + prop)()
    if got != value:
        low = getattr(obj, "Get%sMinValue" % prop, None)
        high = getattr(obj, "Get%sMaxValue" % prop, None)
        bounds = " within [%s, %s]" % (low(), high()) if low and high else ""
        raise InputError("%s must be%s, got %r" % (keyword, bounds, value))


def _finite_rows(points):
    return np.isfinite(points).all(axis=1)


class _Cloud:
    """Points given as an (N, 3) or (N, 2) array, a file path or a VTK point set, as a vtkPolyData
    of points only (what the filters read); two_d when they came as (N, 2)."""

    def __init__(self, what, data, nonfinite):
        self.two_d = False
        if isinstance(data, (str, os.PathLike)):
            dataset = _read_dataset(os.fspath(data))
            points = _points_of_dataset(dataset)
            self.polydata = _points_only(dataset)
        elif isinstance(data, vtkDataSet):
            points = _points_of_dataset(data)
            self.polydata = data if isinstance(data, vtkPointSet) else _points_only(data)
        else:
            try:
                array = np.asarray(data, dtype=np.float64)
            except (TypeError, ValueError):
                raise InputError("%s must be an (N, 3) or (N, 2) array of numbers, a file path or a VTK dataset"
                                 % what) from None
            if array.ndim != 2 or array.shape[1] not in (2, 3):
                raise InputError("%s must have the shape (N, 3) or (N, 2), not %s" % (what, array.shape))
            self.two_d = array.shape[1] == 2
            if self.two_d:
                # The filters take 2D clouds in the xy-plane (Dimension 2, or auto: all z equal).
                array = np.column_stack([array, np.zeros(len(array))])
            points = np.ascontiguousarray(array)
            vtk_points = vtkPoints()
            # numpy_to_vtk shares the buffer and keeps `points` alive through the VTK array.
            vtk_points.SetData(numpy_to_vtk(points, deep=False))
            self.polydata = vtkPolyData()
            self.polydata.SetPoints(vtk_points)
        if nonfinite == "raise" and len(points):
            bad = np.flatnonzero(~_finite_rows(points))
            if len(bad):
                raise InputError("%s: %d of %d points %s a NaN or infinite coordinate (the first: index %d); "
                                 "nonfinite='allow' lets the filters handle them"
                                 % (what, len(bad), len(points), "has" if len(bad) == 1 else "have", bad[0]))


def _points_of(dataset):
    if dataset.GetNumberOfPoints() == 0:
        return np.zeros((0, 3))
    return vtk_to_numpy(dataset.GetPoints().GetData()).reshape(-1, 3)


def _points_only(dataset):
    """The points, point data and field data of dataset as a vtkPolyData without cells (the field
    data say whether it is a sensor frame, and where the sensor was: a PCD file's Viewpoint)."""
    poly = vtkPolyData()
    points = vtkPoints()
    if dataset.GetNumberOfPoints():
        if isinstance(dataset, vtkPointSet):
            points = dataset.GetPoints()
        else:
            points.SetData(numpy_to_vtk(np.array([dataset.GetPoint(i) for i in range(dataset.GetNumberOfPoints())])))
    poly.SetPoints(points)
    poly.GetPointData().ShallowCopy(dataset.GetPointData())
    poly.GetFieldData().ShallowCopy(dataset.GetFieldData())
    return poly


# ---------------------------------------------------------------------------------------------
# Running a filter


def _message(text):
    """A VTK error or warning without its "ERROR: In file, line N" header and object address."""
    lines = [line.rstrip() for line in str(text).splitlines() if line.strip()]
    if lines and re.match(r"^(ERROR|Warning|Generic Warning): In ", lines[0]):
        lines = lines[1:]
    return re.sub(r"^(vtk\w+) \(0x[0-9a-fA-F]+\): ", r"\1: ", "\n".join(lines))


class _Watch:
    """Observers on an algorithm and its executive for one update: errors and warnings are kept
    (so that VTK does not print them), progress goes to the user's callback."""

    def __init__(self, algorithm, progress):
        self.algorithm = algorithm
        self.errors = []
        self.pipeline_errors = []
        self.warnings = []
        self.progress = progress
        self.last = -1.0
        self.raised = None
        # Progress may come from a worker thread of vtkSMPTools (the one that reports).
        self.lock = threading.Lock()
        self.tags = []
        executive = algorithm.GetExecutive()
        self.tags.append((algorithm, algorithm.AddObserver(vtkCommand.ErrorEvent, self._on_error)))
        self.tags.append((algorithm, algorithm.AddObserver(vtkCommand.WarningEvent, self._on_warning)))
        self.tags.append((executive, executive.AddObserver(vtkCommand.ErrorEvent, self._on_pipeline_error)))
        if progress is not None:
            self.tags.append((algorithm, algorithm.AddObserver(vtkCommand.ProgressEvent, self._on_progress)))

    @calldata_type(VTK_STRING)
    def _on_error(self, _caller, _event, text):
        self.errors.append(_message(text))

    @calldata_type(VTK_STRING)
    def _on_warning(self, _caller, _event, text):
        self.warnings.append(_message(text))

    @calldata_type(VTK_STRING)
    def _on_pipeline_error(self, _caller, _event, text):
        self.pipeline_errors.append(_message(text).splitlines()[0])

    def _report(self, fraction):
        with self.lock:
            if self.raised is not None or not fraction > self.last:
                return
            self.last = fraction
            try:
                self.progress(fraction)
            except BaseException as e:  # noqa: B902 -- re-raised by run() once the filter stopped
                self.raised = e
                self.algorithm.AbortExecuteOn()

    def _on_progress(self, caller, _event):
        self._report(min(1.0, max(0.0, caller.GetProgress())))

    def run(self):
        try:
            ok = self.algorithm.GetExecutive().Update()
        finally:
            for obj, tag in self.tags:
                obj.RemoveObserver(tag)
        for text in self.warnings:
            warnings.warn(text, SurfaceWarning, stacklevel=4)
        if self.raised is not None:
            raise self.raised
        if self.errors:
            raise Error("\n".join(self.errors))
        if not ok or self.pipeline_errors:
            raise Error(self.pipeline_errors[0] if self.pipeline_errors else
                        "%s failed without a message" % self.algorithm.GetClassName())
        if self.progress is not None and self.last < 1.0:
            self._report(1.0)
            if self.raised is not None:
                raise self.raised


class _Threads:
    """vtkSMPTools' thread count for one call (0: every core), restored afterwards: the count is a
    setting of the whole process, and one call's choice must not become the next one's."""

    def __init__(self, threads):
        self.threads = _number("threads", threads, integer=True)
        if self.threads < 0:
            raise InputError("threads must be >= 0 (0: every core), got %r" % threads)

    def __enter__(self):
        self.previous = vtkSMPTools.GetEstimatedNumberOfThreads()
        vtkSMPTools.Initialize(self.threads)

    def __exit__(self, *exc):
        vtkSMPTools.Initialize(self.previous)


def _run(algorithm, threads, progress):
    if progress is not None and not callable(progress):
        raise InputError("progress must be a callable taking a fraction in [0, 1], got %r" % (progress,))
    with _Threads(threads):
        _Watch(algorithm, progress).run()


_POINT_SCALES = ("automatic", "off", "estimated")


def _attach_point_array(cloud, values, name):
    """values as the point array name of a shallow copy of cloud's polydata, never of the
    caller's dataset."""
    copy = cloud.polydata.NewInstance()
    copy.ShallowCopy(cloud.polydata)
    array = numpy_to_vtk(values, deep=True)
    array.SetName(name)
    copy.GetPointData().AddArray(array)
    cloud.polydata = copy


def _configure_point_scales(surface, cloud, point_scales, point_scale_multiplier, scale_spread):
    """point_scales: one of _POINT_SCALES, the name of a point array of the cloud, or h_i values;
    values are attached to a shallow copy of the cloud, never to the caller's dataset."""
    _set(surface, "ScaleSpreadThreshold", _number("scale_spread", scale_spread), "scale_spread")
    _set(surface, "PointScaleMultiplier", _number("point_scale_multiplier", point_scale_multiplier),
         "point_scale_multiplier")
    if isinstance(point_scales, str):
        if _key(point_scales) in [_key(name) for name in _POINT_SCALES]:
            surface.SetPointScales(_choice("point_scales", point_scales, _POINT_SCALES))
            return
        if not cloud.polydata.GetPointData().GetArray(point_scales):
            raise InputError("point_scales must be one of %s, the name of a point array of the cloud or one "
                             "value per cloud point, got %r" % (", ".join(_POINT_SCALES), point_scales))
        surface.SetPointScalesToFromArray()
        surface.SetScaleArrayName(point_scales)
        return
    try:
        values = np.ascontiguousarray(np.asarray(point_scales, dtype=np.float64))
    except (TypeError, ValueError):
        raise InputError("point_scales must be a name or one number per cloud point, got %r"
                         % (point_scales,)) from None
    count = cloud.polydata.GetNumberOfPoints()
    if values.shape != (count,):
        raise InputError("point_scales must hold one value per cloud point (%d), got the shape %s"
                         % (count, values.shape))
    # Zeros, negatives and NaN are the C++ side's to refuse, naming the point.
    _attach_point_array(cloud, values, "Scale")
    surface.SetPointScalesToFromArray()
    surface.SetScaleArrayName("Scale")


def _configure_normals(surface, cloud, normals):
    """normals (APSS, RIMLS): None (the cloud's "Normals" array, else estimated), the name of a
    3-component point array of the cloud, or (N, 3) values, attached to a shallow copy of the cloud."""
    if normals is None:
        return
    if isinstance(normals, str):
        array = cloud.polydata.GetPointData().GetArray(normals)
        if array is None or array.GetNumberOfComponents() != 3:
            raise InputError("normals must be None, the name of a 3-component point array of the cloud or "
                             "(N, 3) values, got %r" % (normals,))
        surface.SetNormalsArrayName(normals)
        return
    try:
        values = np.ascontiguousarray(np.asarray(normals, dtype=np.float64))
    except (TypeError, ValueError):
        raise InputError("normals must be a name or (N, 3) values, got %r" % (normals,)) from None
    count = cloud.polydata.GetNumberOfPoints()
    if values.ndim == 2 and values.shape[1] == 2 and cloud.two_d:
        values = np.column_stack([values, np.zeros(len(values))])
    if values.shape != (count, 3):
        raise InputError("normals must hold one 3-vector per cloud point (%d, 3), got the shape %s"
                         % (count, values.shape))
    # Zero and NaN normals are the C++ side's to refuse, naming the point.
    _attach_point_array(cloud, values, "Normals")
    surface.SetNormalsArrayName("Normals")


def _configure_surface(surface, cloud, variant, h, scale_neighbors, scale_multiplier, point_scales,
                       point_scale_multiplier, scale_spread, dimension, cutoff, quadrature, delta_lattice,
                       min_stability, normals=None):
    surface.SetVariant(_choice("variant", variant, VARIANTS, _VARIANT_ALIASES))
    if h is None:
        surface.AutomaticScaleOn()
    else:
        # h <= 0 or NaN is the C++ side's to refuse, with its own message.
        surface.AutomaticScaleOff()
        surface.SetScaleFactor(_number("h", h))
    _set(surface, "ScaleNeighbors", _number("scale_neighbors", scale_neighbors, integer=True), "scale_neighbors")
    _set(surface, "ScaleMultiplier", _number("scale_multiplier", scale_multiplier), "scale_multiplier")
    _configure_point_scales(surface, cloud, point_scales, point_scale_multiplier, scale_spread)
    if isinstance(dimension, str) and _key(dimension) == "auto":
        surface.SetDimension(surface.DIMENSION_AUTO)
    else:
        _set(surface, "Dimension", _number("dimension", dimension, integer=True), "dimension ('auto', 2 or 3)")
    _set(surface, "KernelCutoff", _number("cutoff", cutoff), "cutoff")
    _set(surface, "QuadratureOrder", _number("quadrature", quadrature, integer=True), "quadrature")
    _set(surface, "DeltaLatticeSpacing", _number("delta_lattice", delta_lattice), "delta_lattice")
    _set(surface, "MinimumStability", _number("min_stability", min_stability), "min_stability")
    _configure_normals(surface, cloud, normals)


def _nonfinite(value):
    return _NONFINITE[_choice("nonfinite", value, _NONFINITE)]


# ---------------------------------------------------------------------------------------------
# Outputs


def _field_info(dataset, surface):
    info = {}
    fd = dataset.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        array = fd.GetArray(i)
        if array is None or not array.GetName():
            continue
        values = vtk_to_numpy(array)
        info[array.GetName()] = values.item() if values.size == 1 else values.copy()
    info["h"] = surface.GetEffectiveScale()
    info["dimension"] = surface.GetEffectiveDimension()
    info["point_scales"] = bool(surface.GetUsesPointScales())
    info["scale_spread"] = surface.GetScaleSpread()
    return info


def _point_arrays(dataset, two_d, shape=None):
    """The point data of dataset as numpy arrays; 3-component arrays lose z for a 2D caller;
    reshaped to shape (an image's [i, j, k]) when given."""
    arrays = {}
    pd = dataset.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        array = pd.GetArray(i)
        if array is None or not array.GetName():
            continue
        arrays[array.GetName()] = _shaped(vtk_to_numpy(array), two_d, shape)
    return arrays


def _shaped(values, two_d, shape):
    if two_d and values.ndim == 2 and values.shape[1] == 3:
        values = values[:, :2]
    if shape is not None:
        # VTK orders an image's points x fastest: (nz, ny, nx) in C order, read as [i, j, k].
        nx, ny, nz = shape
        values = values.reshape((nz, ny, nx) + values.shape[1:])
        values = np.moveaxis(values, (0, 1, 2), (2, 1, 0))
    return values


def _copy(dataset):
    out = dataset.NewInstance()
    out.ShallowCopy(dataset)
    return out


def _cells(cells, size):
    """The cells of a vtkCellArray as an (M, size) array; polylines become their segments."""
    if cells is None or cells.GetNumberOfCells() == 0:
        return np.zeros((0, size), dtype=np.int64)
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
    connectivity = vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)
    counts = np.diff(offsets)
    if np.all(counts == size):
        return connectivity.reshape(-1, size)
    if size == 2:
        pairs = [np.column_stack([connectivity[b:e - 1], connectivity[b + 1:e]]) for b, e in zip(offsets[:-1], offsets[1:])]
        return np.concatenate(pairs) if pairs else np.zeros((0, 2), dtype=np.int64)
    raise Error("the mesh has cells of %s points where %d were expected" % (sorted(set(counts.tolist())), size))


# ---------------------------------------------------------------------------------------------
# Reading


def _reader_for(path):
    ext = os.path.splitext(path)[1].lower()
    if ext == ".vtp":
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        return vtkXMLPolyDataReader()
    if ext == ".vtu":
        from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
        return vtkXMLUnstructuredGridReader()
    if ext == ".vti":
        from vtkmodules.vtkIOXML import vtkXMLImageDataReader
        return vtkXMLImageDataReader()
    if ext == ".vtk":
        from vtkmodules.vtkIOLegacy import vtkDataSetReader
        return vtkDataSetReader()
    if ext == ".ply":
        from vtkmodules.vtkIOPLY import vtkPLYReader
        return vtkPLYReader()
    if ext == ".stl":
        from vtkmodules.vtkIOGeometry import vtkSTLReader
        return vtkSTLReader()
    if ext == ".obj":
        from vtkmodules.vtkIOGeometry import vtkOBJReader
        return vtkOBJReader()
    if ext == ".pcd":
        # vtkPCDReader is part of the VTK module from its introduction on; older builds lack it.
        reader_class = getattr(_filters, "vtkPCDReader", None)
        if reader_class is None:
            raise InputError("%s: this build of pointsetsurfaces has no vtkPCDReader to read .pcd files" % path)
        return reader_class()
    if ext in (".csv", ".xyz", ".txt"):
        return None
    raise InputError("unknown file format '%s' of %s (use .vtp .vtu .vti .vtk .ply .stl .obj .pcd .csv .xyz)"
                     % (ext, path))


def _read_table(path):
    """A .csv (commas, optional header naming x, y, z and more columns) or .xyz/.txt (whitespace)
    table, as the pss tool reads it: the coordinates are the columns x, y, z (first two or three
    without a header); a header's other columns become point arrays. Lines starting with # are skipped."""
    csv = path.lower().endswith(".csv")
    names = []
    rows = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            text = line.strip()
            if not text or text.startswith("#"):
                continue
            tokens = [t.strip() for t in text.split(",")] if csv else text.split()
            try:
                values = [float(t) for t in tokens]
            except ValueError:
                if csv and not names and not rows:
                    names = [t.lower() for t in tokens]
                    continue
                raise Error("%s:%d: not a row of numbers: %s" % (path, number, text)) from None
            if rows and len(values) != len(rows[0]):
                raise Error("%s:%d: expected %d columns, found %d" % (path, number, len(rows[0]), len(values)))
            if not rows and len(values) < 2:
                raise Error("%s:%d: need at least two columns (x y)" % (path, number))
            if not rows and names and len(names) != len(values):
                raise Error("%s:%d: the header names %d columns, this row has %d" % (path, number, len(names), len(values)))
            rows.append(values)
    table = np.array(rows, dtype=np.float64).reshape(len(rows), -1)
    width = table.shape[1]

    def column(name, fallback):
        if names:
            return names.index(name) if name in names else -1
        return fallback if fallback < width else -1

    cx, cy, cz = column("x", 0), column("y", 1), column("z", 2)
    if rows and (cx < 0 or cy < 0):
        raise Error("%s: the header has no x and y columns" % path)
    points = np.zeros((len(rows), 3))
    if rows:
        points[:, 0] = table[:, cx]
        points[:, 1] = table[:, cy]
        if cz >= 0:
            points[:, 2] = table[:, cz]
    poly = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points, deep=True))
    poly.SetPoints(vtk_points)
    for c, name in enumerate(names):
        if c not in (cx, cy, cz):
            array = numpy_to_vtk(np.ascontiguousarray(table[:, c]), deep=True)
            array.SetName(name)
            poly.GetPointData().AddArray(array)
    return poly


def _read_dataset(path):
    if not os.path.isfile(path):
        raise FileNotFoundError("cannot open %s" % path)
    reader = _reader_for(path)
    if reader is None:
        return _read_table(path)
    reader.SetFileName(path)
    _Watch(reader, None).run()
    output = reader.GetOutputDataObject(0)
    if not isinstance(output, vtkDataSet):
        raise Error("%s holds a %s, not a dataset with points" % (path, output.GetClassName()))
    return output

def _points_of_dataset(dataset):
    if isinstance(dataset, vtkPointSet):
        return _points_of(dataset)
    if isinstance(dataset, vtkImageData):
        nx, ny, nz = dataset.GetDimensions()
        ox, oy, oz = dataset.GetOrigin()
        sx, sy, sz = dataset.GetSpacing()
        z, y, x = np.meshgrid(oz + sz * np.arange(nz), oy + sy * np.arange(ny), ox + sx * np.arange(nx), indexing="ij")
        return np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    return np.array([dataset.GetPoint(i) for i in range(dataset.GetNumberOfPoints())]).reshape(-1, 3)

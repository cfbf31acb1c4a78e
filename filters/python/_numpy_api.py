"""The numpy-level functions of ``pointsetsurfaces``: project, classify, sample, mesh and read.

Each function builds the VTK filter of the same job (vtkPointSetSurfaceProjection,
vtkPointSetSurfaceDomainClassifier, vtkPointSetSurfaceFieldSampler, vtkPointSetSurfaceMesher),
sets every keyword on it, runs it, and hands back its output as numpy arrays in a Result. The
keywords are the ``pss`` tool's flags with ``_`` for ``-`` (``--max-iterations`` is
``max_iterations=``), and their defaults are the filters' own (a test compares them).

What the filters report with vtkErrorMacro is raised as ``Error`` with the filter's message,
instead of being printed; their warnings become Python warnings (``SurfaceWarning``).
"""
import os

from vtkmodules.vtkCommonDataModel import vtkDataSet, vtkImageData
from vtkmodules.util.numpy_support import vtk_to_numpy

from . import PointSetSurfacesFilters as _filters
# The public names are re-exported by the package; the private ones are the shared helpers.
from ._numpy_support import VARIANTS, Error, InputError, Result, SurfaceWarning  # noqa: F401
from ._numpy_support import (_ORIENTATIONS, _PROCEDURES, _Cloud, _cells, _choice, _configure_surface, _copy,
                             _field_info, _nonfinite, _number, _point_arrays, _points_of, _points_only,
                             _points_of_dataset, _read_dataset, _run, _set, _shaped)

__all__ = ["Error", "InputError", "SurfaceWarning", "Result", "VARIANTS", "project", "classify", "sample", "mesh",
           "read"]


# ---------------------------------------------------------------------------------------------
# The functions


def project(cloud, start=None, *, variant="com", h=None, scale_neighbors=10, scale_multiplier=1.0,
            point_scales="automatic", point_scale_multiplier=3.0, scale_spread=3.0, dimension="auto", cutoff=3.0,
            quadrature=6, delta_lattice=0.5, min_stability=1e-5, normals=None, procedure="extremal", max_iterations=100,
            tolerance=1e-6, max_travel=1000.0, seek_maxima=False, propagate_normals=False, normal_neighbors=10, threads=0,
            progress=None, nonfinite="raise", as_polydata=False):
    """Move points onto the point-set surface of a cloud (vtkPointSetSurfaceProjection, ``pss project``).

    Parameters
    ----------
    cloud : (N, 3) or (N, 2) array, file path or vtkPointSet
        The points that define the surface. An (N, 2) array is a cloud in the plane (its results
        come back with two coordinates); a path is read as ``read()`` does.
    start : like cloud, optional
        The points to project; by default the cloud's own points.
    variant : str
        The surface definition: "levin", "normalized", "com" (centre of mass, the default),
        "integral", "delta", "apss" or "rimls" (see ``VARIANTS``). APSS and RIMLS read oriented
        normals from a vtkPointSet cloud's ``Normals`` array, or estimate and orient them.
    h : float, optional
        The Gaussian scale. None (default): automatic, ``scale_multiplier`` times the median
        distance to the ``scale_neighbors``-th nearest neighbour. h <= 0 raises Error.
    scale_neighbors, scale_multiplier : int, float
        The automatic scale's k (1 to 1000) and multiplier (1e-3 to 1e3).
    point_scales : str or (N,) array
        With the automatic scale: "automatic" (default: a scale h_i per point for a sensor frame,
        i.e. a cloud with an organized grid or a Viewpoint, as PCD files carry, or where the
        estimated scales spread more than ``scale_spread``; else one h), "off" (one h),
        "estimated" (h_i from each point's k-th neighbour distance, see below),
        the name of a point array of the cloud holding h_i, or one h_i per cloud point.
        ``info["h"]`` is then the median h_i. Not with ``h`` given.
    point_scale_multiplier : float
        Estimated scales: h_i = scale_multiplier x point_scale_multiplier x each point's smoothed
        k-th neighbour distance (0.01 to 100, default 3).
    scale_spread : float
        "automatic": the 90th over 10th percentile ratio of the estimated scales above which they
        are used (>= 1, default 3).
    dimension : "auto", 2 or 3
        "auto": 2 when all z are equal (every (N, 2) cloud), else 3.
    cutoff : float
        Kernel truncation, in h beyond the nearest point (0.5 to 20).
    quadrature : int
        Gauss-Hermite nodes per axis for the integral energy (1 to 32).
    delta_lattice : float
        "integral" and "delta": spacing, in h, of the lattice delta is interpolated from; 0
        evaluates it exactly at every node (values in (0, 0.05) raise Error).
    min_stability : float
        n counts as undefined below this stability (0 to 0.999).
    normals : None, str or (N, 3) array
        APSS and RIMLS: the cloud's oriented normals. None (default): the cloud's ``Normals``
        point array when it has one (a PLY's nx ny nz, a PCD's normal_x/y/z), else estimated and
        oriented; a name: that 3-component point array; values: one normal per cloud point
        (zero or NaN ones raise Error, naming the point). The other definitions ignore it.
    procedure : "extremal" or "plane"
        "extremal": the paper's projection to the nearest minimum of the energy along n;
        "plane": the centre-of-mass procedure x <- x - <n, x - c(x)> n.
    max_iterations, tolerance, max_travel : int, float, float
        Iteration limit per point; convergence when a step is below tolerance * h; longest line
        search, in h.
    seek_maxima : bool
        Converge to maxima of the energy along n instead of minima.
    propagate_normals : bool
        Orient ``Normal`` consistently over the end points (a maximum spanning tree of
        |n_i . n_j| over their ``normal_neighbors`` nearest neighbours, each piece from its
        highest point with its normal up; toward the viewpoint when there is one) instead of away
        from the cloud's centroid. ``project(cloud, propagate_normals=True).Normal`` are the
        cloud's oriented normals.
    normal_neighbors : int
        k of that graph (1 to 100).
    threads : int
        Worker threads for this call; 0 (default): every core.
    progress : callable, optional
        Called as ``progress(fraction)`` with increasing fractions in [0, 1], the last 1.0 on
        success. It may run on a worker thread while the call waits, so keep it short. An
        exception it raises stops the computation and is raised by this function.
    nonfinite : "raise" or "allow"
        "raise" (default): a point with a NaN or infinite coordinate raises InputError. "allow":
        such cloud points are left out (a SurfaceWarning says how many) and such start points
        stay where they are with StopReason 4.
    as_polydata : bool
        Return the filter's vtkPolyData (vertices at the end points, with the arrays) instead.

    Returns
    -------
    Result
        ``points`` (the end points, (M, 3) or (M, 2)), ``Normal``, ``Energy``, ``Displacement``,
        ``Iterations``, ``Converged`` (0/1), ``Stability``, ``ExtremumType`` (0 none, 1 minimum,
        2 maximum), ``StopReason`` (0 converged, 1 iteration limit, 2 n undefined, 3 no extremum
        along the line, 4 NaN/infinite start point); ``info["h"]`` is the scale used, ``info["point_scales"]``
        True when every point had its own h_i, ``info["scale_spread"]`` their measured spread.

    Raises
    ------
    InputError
        Bad arguments (shape, names, ranges, NaN coordinates).
    Error
        The filter failed (empty cloud, h <= 0, ...), with the filter's message.
    """
    filter_ = _filters.vtkPointSetSurfaceProjection()
    return _project(filter_, locals(), {})


def classify(cloud, start=None, *, variant="com", h=None, scale_neighbors=10, scale_multiplier=1.0,
             point_scales="automatic", point_scale_multiplier=3.0, scale_spread=3.0, dimension="auto", cutoff=3.0,
             quadrature=6, delta_lattice=0.5, min_stability=1e-5, normals=None, procedure="extremal", max_iterations=100,
             tolerance=1e-6, max_travel=1000.0, seek_maxima=False, propagate_normals=False, normal_neighbors=10,
             max_distance=1.0, max_normal_angle=30.0, threads=0, progress=None, nonfinite="raise", as_polydata=False):
    """Is each start point inside the domain of the surface? (vtkPointSetSurfaceDomainClassifier,
    ``pss classify``).

    Takes every parameter of ``project()`` (each start point is projected once) and:

    max_distance : float
        A fixed point farther than max_distance * h from every cloud point is Spurious.
    max_normal_angle : float
        A fixed point whose n is more than this many degrees (0 to 90) off the cloud's own normal
        there is Spurious.

    Returns
    -------
    Result
        What ``project()`` returns plus ``DomainLabel`` (0 InDomain, 1 Spurious, 2 Undefined,
        3 NotConverged; one per start point) and its evidence: ``DistanceToCloud``,
        ``NormalAngle``, ``StartAngle`` (NaN where there is no fixed point), ``StartStability``.
    """
    filter_ = _filters.vtkPointSetSurfaceDomainClassifier()
    params = locals()
    return _project(filter_, params, {"MaxDistance": ("max_distance", False),
                                      "MaxNormalAngle": ("max_normal_angle", False)})


def _project(filter_, p, extra):
    nonfinite = _nonfinite(p["nonfinite"])
    cloud = _Cloud("cloud", p["cloud"], nonfinite)
    _configure_surface(filter_.GetSurface(), cloud, p["variant"], p["h"], p["scale_neighbors"], p["scale_multiplier"],
                       p["point_scales"], p["point_scale_multiplier"], p["scale_spread"], p["dimension"], p["cutoff"],
                       p["quadrature"], p["delta_lattice"], p["min_stability"], p["normals"])
    filter_.SetProcedure(_choice("procedure", p["procedure"], _PROCEDURES))
    _set(filter_, "MaxIterations", _number("max_iterations", p["max_iterations"], integer=True), "max_iterations")
    _set(filter_, "Tolerance", _number("tolerance", p["tolerance"]), "tolerance")
    _set(filter_, "MaxTravel", _number("max_travel", p["max_travel"]), "max_travel")
    filter_.SetSeekMaxima(bool(p["seek_maxima"]))
    filter_.SetPropagateNormals(bool(p["propagate_normals"]))
    _set(filter_, "NormalNeighbors", _number("normal_neighbors", p["normal_neighbors"], integer=True), "normal_neighbors")
    for prop, (keyword, integer) in extra.items():
        _set(filter_, prop, _number(keyword, p[keyword], integer=integer), keyword)
    filter_.SetInputData(0, cloud.polydata)
    two_d = cloud.two_d
    if p["start"] is not None:
        start = _Cloud("start", p["start"], nonfinite)
        filter_.SetStartPointsData(start.polydata)
        two_d = start.two_d
    _run(filter_, p["threads"], p["progress"])
    output = filter_.GetOutput(0)
    if p["as_polydata"]:
        return _copy(output)
    arrays = {"points": _shaped(_points_of(output), two_d, None)}
    arrays.update(_point_arrays(output, two_d))
    return Result(arrays, _field_info(output, filter_.GetSurface()))


def sample(cloud, probe=None, *, grid=None, margin=3.0, variant="com", h=None, scale_neighbors=10,
           scale_multiplier=1.0, point_scales="automatic", point_scale_multiplier=3.0, scale_spread=3.0,
           dimension="auto", cutoff=3.0, quadrature=6, delta_lattice=0.5, min_stability=1e-5, normals=None,
           orientation="away-from-centroid", reference_point=(0.0, 0.0, 0.0), reference_direction=(0.0, 0.0, 1.0),
           domain_labels=False, max_distance=1.0, max_normal_angle=30.0, max_iterations=100, tolerance=1e-6,
           threads=0, progress=None, nonfinite="raise", as_polydata=False):
    """Sample n, the energy, delta and g of the surface (vtkPointSetSurfaceFieldSampler, ``pss sample``).

    Parameters
    ----------
    cloud : (N, 3) or (N, 2) array, file path or vtkPointSet
        The points that define the surface.
    probe : like cloud, or a vtkDataSet, optional
        Sample at these points. Without it, sample on a grid.
    grid : (nx, ny) or (nx, ny, nz), optional
        Points of the grid along x, y, z (default (101, 101, 1); a 1 samples the mid-plane of that
        axis), spanning the cloud's bounds plus ``margin`` * h on every side.
    variant, h, scale_neighbors, scale_multiplier, point_scales, point_scale_multiplier, scale_spread,
    dimension, cutoff, quadrature, delta_lattice, min_stability : as in ``project()``.
    orientation : str
        How n is oriented: "away-from-centroid" (default), "away-from-point" (from
        ``reference_point``), "along-direction" (n . ``reference_direction`` >= 0) or "propagate"
        (neighbouring samples agree; see the filter's documentation).
    domain_labels : bool
        Also compute ``DomainLabel`` at every sample (projects every sample: slow), with
        ``max_distance``, ``max_normal_angle``, ``max_iterations`` and ``tolerance`` as in
        ``classify()``.
    threads, progress, nonfinite, as_polydata : as in ``project()``; as_polydata returns the
        filter's output dataset (a vtkImageData on a grid, else the probe's type).

    Returns
    -------
    Result
        ``points`` and the arrays ``Normal``, ``Energy``, ``Delta``, ``ImplicitG``, ``Stability``,
        ``ExtremumType``, ``Valid`` (and ``DomainLabel``). On a grid every array is indexed
        [i, j, k] (x, y, z), shaped (nx, ny, nz) or (nx, ny, nz, 3), and ``info`` holds
        ``origin``, ``spacing`` and ``dimensions``; at probe points the first axis is the point.
    """
    nonfinite = _nonfinite(nonfinite)
    source = _Cloud("cloud", cloud, nonfinite)
    sampler = _filters.vtkPointSetSurfaceFieldSampler()
    _configure_surface(sampler.GetSurface(), source, variant, h, scale_neighbors, scale_multiplier, point_scales,
                       point_scale_multiplier, scale_spread, dimension, cutoff, quadrature, delta_lattice,
                       min_stability, normals)
    sampler.SetOrientationMode(_choice("orientation", orientation, _ORIENTATIONS))
    sampler.SetReferencePoint(*_vector("reference_point", reference_point))
    sampler.SetReferenceDirection(*_vector("reference_direction", reference_direction))
    _set(sampler, "SamplingMargin", _number("margin", margin), "margin")
    sampler.SetComputeDomainLabels(bool(domain_labels))
    _set(sampler, "MaxDistance", _number("max_distance", max_distance), "max_distance")
    _set(sampler, "MaxNormalAngle", _number("max_normal_angle", max_normal_angle), "max_normal_angle")
    _set(sampler, "MaxIterations", _number("max_iterations", max_iterations, integer=True), "max_iterations")
    _set(sampler, "Tolerance", _number("tolerance", tolerance), "tolerance")
    sampler.SetSourceData(source.polydata)
    two_d = source.two_d
    shape = None
    if probe is not None:
        if grid is not None:
            raise InputError("give probe or grid, not both")
        probe_cloud = _Cloud("probe", probe, nonfinite)
        two_d = probe_cloud.two_d
        sampler.SetInputData(probe if isinstance(probe, vtkDataSet) else probe_cloud.polydata)
        sampler.GenerateSamplingGridOff()
    else:
        dims = (101, 101, 1) if grid is None else tuple(grid)
        if len(dims) == 2:
            dims = dims + (1,)
        if len(dims) != 3:
            raise InputError("grid must be (nx, ny) or (nx, ny, nz), got %r" % (grid,))
        dims = tuple(_number("grid", d, integer=True) for d in dims)
        if min(dims) < 1:
            raise InputError("grid must have at least one point along each axis, got %r" % (grid,))
        sampler.SetSampleDimensions(*dims)
        sampler.GenerateSamplingGridOn()
        shape = dims
    _run(sampler, threads, progress)
    output = sampler.GetOutputDataObject(0)
    if as_polydata:
        return _copy(output)
    arrays = {"points": _shaped(_points_of_dataset(output), two_d, shape)}
    arrays.update(_point_arrays(output, two_d, shape))
    info = _field_info(output, sampler.GetSurface())
    if isinstance(output, vtkImageData):
        info.update(origin=output.GetOrigin(), spacing=output.GetSpacing(), dimensions=output.GetDimensions())
    return Result(arrays, info)


def _vector(what, value):
    try:
        v = [float(x) for x in value]
    except (TypeError, ValueError):
        raise InputError("%s must be three numbers, got %r" % (what, value)) from None
    if len(v) == 2:
        v.append(0.0)
    if len(v) != 3:
        raise InputError("%s must be three numbers, got %r" % (what, value))
    return v



def mesh(cloud, *, variant="com", h=None, scale_neighbors=10, scale_multiplier=1.0, point_scales="automatic",
         point_scale_multiplier=3.0, scale_spread=3.0, dimension="auto", cutoff=3.0, quadrature=6, delta_lattice=0.5,
         min_stability=1e-5, normals=None, cell=1.0, band=1.0, adaptive_cells=True, project_vertices=True, procedure="automatic",
         max_distance=-1.0,
         max_normal_angle=30.0, max_border_offset=-1.0, trim_distance=-1.0, max_vertex_travel=2.0, max_seam_angle=80.0, max_fold_angle=60.0,
         max_hole_edges=100, min_piece_area=10.0, covered_piece_area=10.0, max_band_cells=1 << 24, threads=0, progress=None,
         nonfinite="raise", as_polydata=False):
    """The surface as a triangle mesh (segments in 2D), only where it is defined
    (vtkPointSetSurfaceMesher, ``pss mesh``).

    Parameters
    ----------
    cloud : (N, 3) or (N, 2) array, file path or vtkPointSet
        The points that define the surface.
    variant, h, scale_neighbors, scale_multiplier, point_scales, point_scale_multiplier, scale_spread,
    dimension, cutoff, quadrature, delta_lattice, min_stability, max_distance, max_normal_angle :
    as in ``classify()``.
    procedure : "extremal", "plane" or "automatic"
        How the vertices are projected; "automatic" (the default) takes "plane" for the centre of
        mass with a scale per point (a sensor frame) and "extremal" otherwise.
    cell : float
        Grid cell size, in h (0.05 to 100).
    band : float
        Visit the cells within band * h of the cloud (0.1 to 100).
    adaptive_cells : bool
        With a scale per point, cells that grow with h_i (a balanced octree; the default); False
        keeps one grid of cell * h (``pss mesh --regular-cells``). ``info["CellLevels"]`` says how
        many cell sizes ran.
    project_vertices : bool
        Move the vertices onto the surface (default); False leaves them at the grid's crossings
        (``pss mesh --no-projection``).
    max_border_offset : float
        Outside the domain past the cloud's border: the neighbours' weighted centroid farther than
        this many local h from the vertex along the surface (0.56 at a straight border; 0 off;
        -1, the default: 0.6 with a scale per point, off with one h).
    trim_distance : float
        3D: cut the mesh back where it runs farther than this many local point spacings from
        every cloud point (0 off; -1, the default: 2.5 with a scale per point, off with one h;
        docs/mesh.md).
    max_vertex_travel : float
        Drop crossings whose projection moves farther, in cells (0.1 to 100).
    max_seam_angle, max_fold_angle : float
        Degrees: skip cells across which the oriented n turns more; drop triangles whose normal
        is farther off their vertices' n.
    max_hole_edges : int
        3D: close holes of at most this many edges (0 to 1000).
    min_piece_area, covered_piece_area : float
        3D, in h^2: remove pieces smaller than min_piece_area; remove pieces smaller than
        covered_piece_area that lie over the largest piece (0 keeps them).
    max_band_cells : int
        Refuse (Error) a band of more cells than this (about 60 bytes each).
    threads, progress, nonfinite, as_polydata : as in ``project()``.

    Returns
    -------
    Result
        ``vertices`` ((V, 3), or (V, 2) for a 2D cloud given as (N, 2)), ``triangles`` ((T, 3)
        indices into vertices, counter-clockwise about ``Normals``) in 3D or ``segments``
        ((S, 2)) in 2D, and per vertex ``Normals``, ``Stability``, ``Energy``, ``DomainLabel``,
        ``DistanceToCloud``, ``NormalAngle``, ``StartAngle``, ``StartStability``,
        ``Displacement``, ``Iterations``, ``StopReason``. ``info`` holds the counts
        (``Components``, ``BoundaryEdges``, ``NonManifoldEdges``, ``EulerCharacteristic``,
        ``BandCells``, ...) and ``h``.
    """
    nonfinite = _nonfinite(nonfinite)
    source = _Cloud("cloud", cloud, nonfinite)
    mesher = _filters.vtkPointSetSurfaceMesher()
    _configure_surface(mesher.GetSurface(), source, variant, h, scale_neighbors, scale_multiplier, point_scales,
                       point_scale_multiplier, scale_spread, dimension, cutoff, quadrature, delta_lattice,
                       min_stability, normals)
    _set(mesher, "CellSize", _number("cell", cell), "cell")
    _set(mesher, "Band", _number("band", band), "band")
    mesher.SetAdaptiveCells(bool(adaptive_cells))
    mesher.SetProjectVertices(bool(project_vertices))
    mesher.SetProcedure(_choice("procedure", procedure, _PROCEDURES + ("automatic",)))
    for prop, keyword, value, integer in (("MaxDistance", "max_distance", max_distance, False),
                                          ("MaxNormalAngle", "max_normal_angle", max_normal_angle, False),
                                          ("MaxBorderOffset", "max_border_offset", max_border_offset, False),
                                          ("TrimDistance", "trim_distance", trim_distance, False),
                                          ("MaxVertexTravel", "max_vertex_travel", max_vertex_travel, False),
                                          ("MaxSeamAngle", "max_seam_angle", max_seam_angle, False),
                                          ("MaxFoldAngle", "max_fold_angle", max_fold_angle, False),
                                          ("MaxHoleEdges", "max_hole_edges", max_hole_edges, True),
                                          ("MinPieceArea", "min_piece_area", min_piece_area, False),
                                          ("CoveredPieceArea", "covered_piece_area", covered_piece_area, False),
                                          ("MaximumNumberOfBandCells", "max_band_cells", max_band_cells, True)):
        _set(mesher, prop, _number(keyword, value, integer=integer), keyword)
    mesher.SetInputData(source.polydata)
    _run(mesher, threads, progress)
    output = mesher.GetOutput()
    if as_polydata:
        return _copy(output)
    arrays = {"vertices": _shaped(_points_of(output), source.two_d, None)}
    if output.GetNumberOfLines() > 0 and output.GetNumberOfPolys() == 0:
        arrays["segments"] = _cells(output.GetLines(), 2)
    else:
        arrays["triangles"] = _cells(output.GetPolys(), 3)
    arrays.update(_point_arrays(output, source.two_d))
    return Result(arrays, _field_info(output, mesher.GetSurface()))


def read(path, *, as_polydata=False):
    """Read the points of a file, by its extension.

    .vtp .vtu .vti (VTK XML), .vtk (legacy), .ply, .stl, .obj, .pcd (when the module has
    vtkPCDReader), .csv (commas; an optional header names the x, y, z columns and the arrays) and
    .xyz / .txt (whitespace-separated x y [z] columns).

    Returns
    -------
    Result
        ``points`` ((N, 3)) and every named point array of the file; ``info`` holds its field
        data. With ``as_polydata=True``, a vtkPolyData of the points (no cells) and point data.

    Raises
    ------
    FileNotFoundError
        No such file.
    InputError
        An extension this function does not read.
    Error
        The reader failed, with its message.
    """
    dataset = _read_dataset(os.fspath(path))
    if as_polydata:
        return _points_only(dataset)
    arrays = {"points": _points_of_dataset(dataset)}
    arrays.update(_point_arrays(dataset, False))
    info = {}
    fd = dataset.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        array = fd.GetArray(i)
        if array is not None and array.GetName():
            values = vtk_to_numpy(array)
            info[array.GetName()] = values.item() if values.size == 1 else values
    return Result(arrays, info)

"""Every proxy of the PointSetSurfaces plugin against the C++ filters, run by pvpython.

    pvpython test_plugin_proxies.py --plugin PointSetSurfaces.so --pss build/bin/pss --workdir DIR
                                    [--load loadplugin | --load env]

--load loadplugin (default): the plugin must not be loaded yet; LoadPlugin(path, remote=False)
loads it. --load env: the plugin must already be loaded by PV_PLUGIN_PATH when paraview.simple is
imported (no LoadPlugin call).

Each case writes the same synthetic input files with `pss generate`, runs a `pss` subcommand (the
C++ filter, with the parameters given as flags) and the plugin's proxy with the same parameters on
the same files, fetches the proxy's output to the client (servermanager.Fetch) and compares it with
the file pss wrote: dataset type, points, cells, image geometry, the names, types and component
counts of every point, cell and field array (also against the list the headers document), and
every value (NaN where NaN). Cases with default properties check that the XML defaults behave as
the C++ defaults. Properties pss has no flag for (OrientationMode, ReferencePoint,
ReferenceDirection, ScaleMode, MaximumNumberOfBandCells) are checked by what they must do to the
output. The mesher's output is also compared field array by field array (its counts).
Exit status 0 when everything matches; 1 with a message per mismatch otherwise.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

import numpy as np

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", required=True, help="path of PointSetSurfaces.so")
parser.add_argument("--pss", required=True, help="path of the pss tool")
parser.add_argument("--workdir", required=True)
parser.add_argument("--load", choices=["loadplugin", "env"], default="loadplugin")
args = parser.parse_args()

import paraview.simple as pvs  # noqa: E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkSMPTools  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader  # noqa: E402

PROXIES = [
    "PointSetSurfaceCloudSource",
    "PointSetSurfaceProjection",
    "PointSetSurfaceDomainClassifier",
    "PointSetSurfaceFieldSampler",
    "PointSetSurfaceEnergyGlyphs",
    "PointSetSurfaceMesh",
]
failures = []
counts = {"cases": 0, "arrays": 0, "values": 0}


def fail(message):
    print("FAIL:", message, flush=True)
    failures.append(message)


def check(condition, message):
    if not condition:
        fail(message)
    return condition


# ---------------------------------------------------------------------------------------------
# Loading
if args.load == "loadplugin":
    if hasattr(pvs, "PointSetSurfaceProjection"):
        fail("the plugin is loaded before LoadPlugin: unset PV_PLUGIN_PATH for this test")
    pvs.LoadPlugin(args.plugin, remote=False, ns=globals())
    namespace = globals()
else:
    check("PV_PLUGIN_PATH" in os.environ, "--load env needs PV_PLUGIN_PATH")
    namespace = vars(pvs)
# Loading the plugin is where ParaView's Sequential vtkSMPTools becomes threaded (the filters never
# change the process-wide backend themselves).
if "VTK_SMP_BACKEND_IN_USE" not in os.environ:
    backend = vtkSMPTools.GetBackend()
    check(backend == "STDThread", "after loading the plugin vtkSMPTools runs on %s, not STDThread" % backend)
for name in PROXIES:
    if not check(name in namespace, "proxy %s not available after loading the plugin (%s)" % (name, args.load)):
        sys.exit(1)
P = {name: namespace[name] for name in PROXIES}

# ---------------------------------------------------------------------------------------------
# Inputs and C++ references, written by the pss tool.
work = os.path.abspath(args.workdir)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)


def path(name):
    return os.path.join(work, name)


def pss(*argv):
    command = [args.pss] + [str(a) for a in argv] + ["--no-progress"]
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        fail("%s exited with %d:\n%s" % (" ".join(command), result.returncode, result.stdout))
        sys.exit(1)


def read(filename):
    reader = vtkXMLGenericDataObjectReader()
    reader.SetFileName(path(filename))
    reader.Update()
    data = reader.GetOutputDataObject(0)
    if not check(data is not None and data.GetNumberOfPoints() > 0, "cannot read %s (or it is empty)" % filename):
        sys.exit(1)
    return data


readers = {}


def reader(filename):
    if filename not in readers:
        readers[filename] = pvs.XMLPolyDataReader(FileName=[path(filename)])
    return readers[filename]


def fetch(proxy, port=0):
    proxy.UpdatePipeline()
    data = servermanager.Fetch(proxy, 0, idx=port)  # 0: pass the data through, keep its type
    if not check(data is not None, "no output on port %d of %s" % (port, proxy.GetXMLName())):
        sys.exit(1)
    return data


# ---------------------------------------------------------------------------------------------
# Comparison of a fetched output with the C++ reference.
def values(array):
    return vtk_to_numpy(array).astype(np.float64).reshape(array.GetNumberOfTuples(), -1)


def same(a, b):
    return a.shape == b.shape and np.allclose(a, b, rtol=1e-10, atol=1e-12, equal_nan=True)


def compare_attributes(case, kind, got, ref, expected):
    got_names = {got.GetArrayName(i) for i in range(got.GetNumberOfArrays())}
    ref_names = {ref.GetArrayName(i) for i in range(ref.GetNumberOfArrays())}
    check(got_names == ref_names, "%s: %s arrays %s, C++ %s" % (case, kind, sorted(got_names), sorted(ref_names)))
    if expected is not None:
        check(got_names == set(expected), "%s: %s arrays %s, documented %s" % (case, kind, sorted(got_names), sorted(expected)))
    for name in sorted(got_names & ref_names):
        a, b = got.GetArray(name), ref.GetArray(name)
        if a is None or b is None:  # non-numeric arrays are not expected here
            check(a is None and b is None, "%s: %s array %s is numeric on one side only" % (case, kind, name))
            continue
        counts["arrays"] += 1
        check(a.GetDataType() == b.GetDataType(), "%s: %s array %s has type %s, C++ %s" % (case, kind, name, a.GetDataTypeAsString(), b.GetDataTypeAsString()))
        check(a.GetNumberOfComponents() == b.GetNumberOfComponents(), "%s: %s array %s components differ" % (case, kind, name))
        va, vb = values(a), values(b)
        counts["values"] += va.size
        if not same(va, vb):
            bad = np.argwhere(~np.isclose(va, vb, rtol=1e-10, atol=1e-12, equal_nan=True)) if va.shape == vb.shape else []
            fail("%s: %s array %s differs from C++ (%d of %d values; first at %s: %s vs %s)" % (
                case, kind, name, len(bad), va.size, bad[0] if len(bad) else "shape",
                va[tuple(bad[0])] if len(bad) else va.shape, vb[tuple(bad[0])] if len(bad) else vb.shape))


def compare(case, got, ref, point_arrays=None, cell_arrays=None, field_arrays=None):
    """got: the fetched proxy output; ref: the file pss wrote. With field_arrays, every field array
    is compared too (else only ScaleFactor)."""
    counts["cases"] += 1
    check(got.GetClassName() == ref.GetClassName(), "%s: output is a %s, C++ a %s" % (case, got.GetClassName(), ref.GetClassName()))
    check(got.GetNumberOfPoints() == ref.GetNumberOfPoints() and got.GetNumberOfPoints() > 0,
          "%s: %d points, C++ %d" % (case, got.GetNumberOfPoints(), ref.GetNumberOfPoints()))
    if got.GetNumberOfPoints() != ref.GetNumberOfPoints():
        return
    if got.IsA("vtkImageData"):
        check(got.GetDimensions() == ref.GetDimensions(), "%s: dimensions %s, C++ %s" % (case, got.GetDimensions(), ref.GetDimensions()))
        check(np.allclose(got.GetOrigin(), ref.GetOrigin(), rtol=1e-12) and np.allclose(got.GetSpacing(), ref.GetSpacing(), rtol=1e-12),
              "%s: origin/spacing %s %s, C++ %s %s" % (case, got.GetOrigin(), got.GetSpacing(), ref.GetOrigin(), ref.GetSpacing()))
    else:
        check(same(values(got.GetPoints().GetData()), values(ref.GetPoints().GetData())), "%s: point coordinates differ from C++" % case)
        counts["values"] += 3 * got.GetNumberOfPoints()
    if got.IsA("vtkPolyData"):
        for kind in ("Verts", "Lines", "Polys", "Strips"):
            a, b = getattr(got, "Get" + kind)(), getattr(ref, "Get" + kind)()
            same_cells = (a.GetNumberOfCells() == b.GetNumberOfCells()
                          and np.array_equal(vtk_to_numpy(a.GetConnectivityArray()), vtk_to_numpy(b.GetConnectivityArray()))
                          and np.array_equal(vtk_to_numpy(a.GetOffsetsArray()), vtk_to_numpy(b.GetOffsetsArray())))
            check(same_cells, "%s: %s cells differ from C++ (%d vs %d)" % (case, kind, a.GetNumberOfCells(), b.GetNumberOfCells()))
    compare_attributes(case, "point", got.GetPointData(), ref.GetPointData(), point_arrays)
    compare_attributes(case, "cell", got.GetCellData(), ref.GetCellData(), cell_arrays)
    if field_arrays is not None:
        compare_attributes(case, "field", got.GetFieldData(), ref.GetFieldData(), field_arrays)
    rf = ref.GetFieldData().GetArray("ScaleFactor")
    if rf is not None:
        gf = got.GetFieldData().GetArray("ScaleFactor")
        check(gf is not None and gf.GetValue(0) == rf.GetValue(0), "%s: field data ScaleFactor %s, C++ %s" % (
            case, gf.GetValue(0) if gf is not None else None, rf.GetValue(0)))
    print("ok   %-44s %6d points %5d cells %6.1f s" % (case, got.GetNumberOfPoints(), got.GetNumberOfCells(), time.time() - started), flush=True)


def array(data, name):
    a = data.GetPointData().GetArray(name)
    if not check(a is not None, "no point array %s" % name):
        sys.exit(1)
    return values(a)


PROJECTION_ARRAYS = ["Normal", "Energy", "Displacement", "Iterations", "Converged", "Stability", "ExtremumType", "StopReason"]
CLASSIFIER_ARRAYS = PROJECTION_ARRAYS + ["DomainLabel", "DistanceToCloud", "NormalAngle", "StartAngle", "StartStability"]
SAMPLER_ARRAYS = ["Normal", "Energy", "Delta", "ImplicitG", "Stability", "ExtremumType", "Valid"]
LINE_ARRAYS = ["Converged", "StopReason", "StartPointId"]
MESH_ARRAYS = ["Normals", "Stability", "Energy", "DomainLabel", "DistanceToCloud", "NormalAngle", "StartAngle",
               "StartStability", "Displacement", "Iterations", "StopReason"]
MESH_FIELDS = ["ScaleFactor", "Dimension", "PointScales", "CellSize", "Band", "MaxDistance", "MaxBorderOffset",
               "TrimDistance", "Procedure", "BandCells", "CellLevels", "HangingVertices",
               "GridVertices", "Crossings",
               "DroppedVertices", "MaximumCrossings", "SeamSimplices", "FoldedTriangles", "RemovedPieces", "CoveredPieces", "ClosedHoles",
               "DanglingTriangles", "TrimmedTriangles",
               "UndefinedGridVertices", "Components", "BoundaryEdges", "NonManifoldEdges", "EulerCharacteristic"]
PASSED = ["DistanceToShape"]  # the start / probe points' own array, passed through
started = time.time()

# ---------------------------------------------------------------------------------------------
# Cloud source: the same cloud as `pss generate`, with explicit and with default parameters.
pss("generate", "--scene", "noisy-curve", "--count", 400, "--size", 100, "--noise", 3, "--seed", 7, "-o", path("cloud.vtp"))
pss("generate", "--scene", "line", "--count", 60, "--size", 140, "--noise", 12, "--seed", 3, "-o", path("starts.vtp"))
pss("generate", "--scene", "circle", "--count", 9, "--size", 70, "--seed", 2, "-o", path("samples.vtp"))
pss("generate", "--scene", "sphere", "--dimension", 3, "--count", 300, "--size", 20, "--noise", 0.3, "--seed", 5, "-o", path("sphere.vtp"))
pss("generate", "--scene", "corner", "--count", 120, "--corner-angle", 75, "--size", 50, "--noise", 0.5, "-o", path("corner.vtp"))
pss("generate", "--scene", "two-sheets", "--dimension", 3, "--count", 200, "--gap", 4, "--size", 30, "-o", path("sheets.vtp"))
pss("generate", "-o", path("cloud_default.vtp"))
pss("generate", "--scene", "depth-camera", "--image", "160x120", "--depth-noise", 0.002, "--seed", 4, "-o", path("depth.vtp"))

source = P["PointSetSurfaceCloudSource"](Scene="Noisy Curve", NumberOfPoints=400, Size=100, Noise=3, Seed=7)
compare("CloudSource noisy-curve", fetch(source), read("cloud.vtp"), PASSED, [])
source = P["PointSetSurfaceCloudSource"](Scene="Sphere", Dimension="3D", NumberOfPoints=300, Size=20, Noise=0.3, Seed=5)
compare("CloudSource sphere 3D", fetch(source), read("sphere.vtp"), PASSED, [])
source = P["PointSetSurfaceCloudSource"](Scene="Corner", NumberOfPoints=120, CornerAngle=75, Size=50, Noise=0.5)
compare("CloudSource corner", fetch(source), read("corner.vtp"), PASSED, [])
source = P["PointSetSurfaceCloudSource"](Scene="Two Sheets", Dimension="3D", NumberOfPoints=200, SheetGap=4, Size=30)
compare("CloudSource two-sheets", fetch(source), read("sheets.vtp"), PASSED, [])
compare("CloudSource defaults", fetch(P["PointSetSurfaceCloudSource"]()), read("cloud_default.vtp"), PASSED, [])
source = P["PointSetSurfaceCloudSource"](Scene="Depth Camera", ImageWidth=160, ImageHeight=120, DepthNoise=0.002, Seed=4)
compare("CloudSource depth-camera", fetch(source), read("depth.vtp"), PASSED + ["Pixel", "SurfaceId", "NoiseSigma"], [],
        ["GridDimensions", "Viewpoint"])

cloud = reader("cloud.vtp")
starts = reader("starts.vtp")

# ---------------------------------------------------------------------------------------------
# Projection.
pss("project", path("cloud.vtp"), "--variant", "levin", "--h", 5, "--start", path("starts.vtp"),
    "--lines", path("lines_levin.vtp"), "-o", path("proj_levin.vtp"))
proj = P["PointSetSurfaceProjection"](Input=cloud, StartPoints=starts, Variant="Levin MLS", AutomaticScale=0,
                                      ScaleFactor=5, GenerateProjectionLines=1)
got = fetch(proj)
compare("Projection levin h=5", got, read("proj_levin.vtp"), PROJECTION_ARRAYS + PASSED, [])
compare("Projection levin h=5, lines", fetch(proj, 1), read("lines_levin.vtp"), [], LINE_ARRAYS)
check(np.count_nonzero(array(got, "Converged")) >= 10, "Projection levin: fewer than 10 start points converged")

pss("project", path("cloud.vtp"), "--variant", "levin", "--h", 6, "--seek-maxima", "--max-iterations", 20,
    "--tolerance", 1e-5, "--max-travel", 40, "--cutoff", 2.5, "--min-stability", 1e-4,
    "--start", path("starts.vtp"), "-o", path("proj_levin_max.vtp"))
proj = P["PointSetSurfaceProjection"](Input=cloud, StartPoints=starts, Variant="Levin MLS", AutomaticScale=0,
                                      ScaleFactor=6, SeekMaxima=1, MaxIterations=20, Tolerance=1e-5, MaxTravel=40,
                                      KernelCutoff=2.5, MinimumStability=1e-4)
got = fetch(proj)
compare("Projection levin maxima, limits", got, read("proj_levin_max.vtp"), PROJECTION_ARRAYS + PASSED, [])
check(np.any(array(got, "ExtremumType") == 2), "Projection with SeekMaxima found no maximum")
check(np.any(array(got, "StopReason") == 1), "Projection with MaxIterations 20: no point hit the limit")

pss("project", path("cloud.vtp"), "--variant", "integral", "--h", 6, "--quadrature", 4, "--start", path("starts.vtp"),
    "-o", path("proj_integral.vtp"))
proj = P["PointSetSurfaceProjection"](Input=cloud, StartPoints=starts, Variant="Integral Energy", AutomaticScale=0,
                                      ScaleFactor=6, QuadratureOrder=4)
compare("Projection integral, quadrature 4", fetch(proj), read("proj_integral.vtp"), PROJECTION_ARRAYS + PASSED, [])

pss("project", path("cloud.vtp"), "--variant", "normalized", "--procedure", "plane", "--scale-neighbors", 6,
    "--scale-multiplier", 1.7, "--dimension", 2, "-o", path("proj_plane.vtp"))
proj = P["PointSetSurfaceProjection"](Input=cloud, Variant="Normalized MLS", Procedure="Plane", ScaleNeighbors=6,
                                      ScaleMultiplier=1.7, Dimension="2D (xy-plane)")
compare("Projection plane, automatic h", fetch(proj), read("proj_plane.vtp"), PROJECTION_ARRAYS + PASSED, [])

pss("project", path("cloud.vtp"), "--point-scales", "estimated", "--point-scale-multiplier", 2, "--start",
    path("starts.vtp"), "-o", path("proj_point_scales.vtp"))
proj = P["PointSetSurfaceProjection"](Input=cloud, StartPoints=starts, PointScales="Estimated from the data",
                                      PointScaleMultiplier=2)
got = fetch(proj)
compare("Projection, a scale per point", got, read("proj_point_scales.vtp"), PROJECTION_ARRAYS + PASSED, [])
check(got.GetFieldData().GetArray("PointScales").GetValue(0) == 1, "PointScales Estimated: no scale per point")

pss("project", path("cloud.vtp"), "-o", path("proj_default.vtp"))
compare("Projection defaults", fetch(P["PointSetSurfaceProjection"](Input=cloud)), read("proj_default.vtp"),
        PROJECTION_ARRAYS + PASSED, [])

pss("project", path("sphere.vtp"), "--h", 3, "--dimension", 3, "-o", path("proj_sphere.vtp"))
proj = P["PointSetSurfaceProjection"](Input=reader("sphere.vtp"), AutomaticScale=0, ScaleFactor=3, Dimension="3D")
compare("Projection com, 3D sphere", fetch(proj), read("proj_sphere.vtp"), PROJECTION_ARRAYS + PASSED, [])

pss("project", path("sphere.vtp"), "--h", 3, "--dimension", 3, "--propagate-normals", "--normal-neighbors", 8,
    "-o", path("proj_sphere_oriented.vtp"))
proj = P["PointSetSurfaceProjection"](Input=reader("sphere.vtp"), AutomaticScale=0, ScaleFactor=3, Dimension="3D",
                                      PropagateNormals=1, NormalNeighbors=8)
got = fetch(proj)
compare("Projection com, 3D sphere, propagated normals", got, read("proj_sphere_oriented.vtp"), PROJECTION_ARRAYS + PASSED, [])
outward = np.einsum("ij,ij->i", array(got, "Normal"), vtk_to_numpy(got.GetPoints().GetData()))
check(np.all(outward > 0), "Projection with PropagateNormals: %d of %d normals point into the sphere" % (
    np.count_nonzero(outward <= 0), outward.size))

pss("project", path("cloud.vtp"), "--variant", "delta", "--h", 4, "--start", path("starts.vtp"), "-o", path("proj_delta.vtp"))
proj = P["PointSetSurfaceProjection"](Input=cloud, StartPoints=starts, Variant="Delta Energy", AutomaticScale=0, ScaleFactor=4)
compare("Projection delta", fetch(proj), read("proj_delta.vtp"), PROJECTION_ARRAYS + PASSED, [])

# ---------------------------------------------------------------------------------------------
# Domain classifier.
pss("classify", path("cloud.vtp"), "--variant", "levin", "--h", 5, "--start", path("starts.vtp"), "--max-distance", 0.5,
    "--max-normal-angle", 20, "--max-travel", 50, "--lines", path("cls_lines.vtp"), "-o", path("cls_levin.vtp"))
cls = P["PointSetSurfaceDomainClassifier"](Input=cloud, StartPoints=starts, Variant="Levin MLS", AutomaticScale=0,
                                           ScaleFactor=5, MaxDistance=0.5, MaxNormalAngle=20, MaxTravel=50,
                                           GenerateProjectionLines=1)
got = fetch(cls)
compare("DomainClassifier levin", got, read("cls_levin.vtp"), CLASSIFIER_ARRAYS + PASSED, [])
compare("DomainClassifier levin, lines", fetch(cls, 1), read("cls_lines.vtp"), [], LINE_ARRAYS)
check(len(np.unique(array(got, "DomainLabel"))) >= 2, "DomainClassifier: all start points got the same label")

pss("classify", path("cloud.vtp"), "-o", path("cls_default.vtp"))
compare("DomainClassifier defaults", fetch(P["PointSetSurfaceDomainClassifier"](Input=cloud)), read("cls_default.vtp"),
        CLASSIFIER_ARRAYS + PASSED, [])

# ---------------------------------------------------------------------------------------------
# Field sampler: on its own grid, at the points of a probe dataset, defaults.
pss("sample", path("cloud.vtp"), "--variant", "levin", "--h", 5, "--grid", "41,31", "--margin", 2, "-o", path("field_levin.vti"))
sampler = P["PointSetSurfaceFieldSampler"](Input=cloud, GenerateSamplingGrid=1, SampleDimensions=[41, 31, 1],
                                           SamplingMargin=2, Variant="Levin MLS", AutomaticScale=0, ScaleFactor=5)
got = fetch(sampler)
compare("FieldSampler grid levin", got, read("field_levin.vti"), SAMPLER_ARRAYS, [])
check(np.any(array(got, "ImplicitG") > 0) and np.any(array(got, "ImplicitG") < 0), "FieldSampler: g does not change sign on the grid")

# Domain labels with the centre-of-mass definition (Levin's far samples make labelling slow).
pss("sample", path("cloud.vtp"), "--variant", "com", "--h", 5, "--grid", "25,19", "--margin", 2, "--domain-labels",
    "-o", path("field_labels.vti"))
sampler = P["PointSetSurfaceFieldSampler"](Input=cloud, GenerateSamplingGrid=1, SampleDimensions=[25, 19, 1],
                                           SamplingMargin=2, ComputeDomainLabels=1, AutomaticScale=0, ScaleFactor=5)
got = fetch(sampler)
compare("FieldSampler grid com + domain labels", got, read("field_labels.vti"), SAMPLER_ARRAYS + ["DomainLabel"], [])
check(len(np.unique(array(got, "DomainLabel"))) >= 2, "FieldSampler: every sample got the same DomainLabel")

pss("sample", path("cloud.vtp"), "--variant", "delta", "--scale-neighbors", 8, "--scale-multiplier", 1.5,
    "--probe", path("starts.vtp"), "-o", path("field_probe.vtp"))
sampler = P["PointSetSurfaceFieldSampler"](Input=cloud, Probe=starts, Variant="Delta Energy", ScaleNeighbors=8,
                                           ScaleMultiplier=1.5)
# The probe's own arrays (DistanceToShape) are passed through beside the sampled ones.
compare("FieldSampler probe delta", fetch(sampler), read("field_probe.vtp"), SAMPLER_ARRAYS + PASSED, [])

pss("sample", path("sphere.vtp"), "--variant", "com", "--grid", "9,8,7", "-o", path("field_sphere.vti"))
sampler = P["PointSetSurfaceFieldSampler"](Input=reader("sphere.vtp"), GenerateSamplingGrid=1, SampleDimensions=[9, 8, 7])
compare("FieldSampler grid 3D sphere", fetch(sampler), read("field_sphere.vti"), SAMPLER_ARRAYS, [])

pss("sample", path("cloud.vtp"), "-o", path("field_default.vti"))
default_sampler = P["PointSetSurfaceFieldSampler"](Input=cloud, GenerateSamplingGrid=1)
default_field = fetch(default_sampler)
compare("FieldSampler defaults (grid on)", default_field, read("field_default.vti"), SAMPLER_ARRAYS, [])

# Orientation rules (no pss flag): same lines, sign chosen as documented, g flips with n.
n0, g0 = array(default_field, "Normal"), array(default_field, "ImplicitG")
xyz = np.array([default_field.GetPoint(i) for i in range(default_field.GetNumberOfPoints())])
for mode, extra, sign_of in [
    ("Along Direction", {"ReferenceDirection": [0, 1, 0]}, lambda n: n[:, 1]),
    ("Away From Point", {"ReferencePoint": [50, -200, 0]}, lambda n: np.einsum("ij,ij->i", n, xyz - [50, -200, 0])),
    ("Propagate", {}, None),
]:
    sampler = P["PointSetSurfaceFieldSampler"](Input=cloud, GenerateSamplingGrid=1, OrientationMode=mode, **extra)
    got = fetch(sampler)
    n, g = array(got, "Normal"), array(got, "ImplicitG")
    flip = np.where(np.einsum("ij,ij->i", n, n0) < 0, -1.0, 1.0)[:, None]
    case = "FieldSampler OrientationMode %s" % mode
    check(np.allclose(n, flip * n0, atol=1e-12), "%s: Normal is not +-Normal of the default orientation" % case)
    check(np.allclose(g, flip * g0, rtol=1e-9, atol=1e-12 * np.abs(g0).max()), "%s: ImplicitG does not flip with Normal" % case)
    check(np.array_equal(array(got, "Energy"), array(default_field, "Energy")), "%s: Energy changed with the orientation" % case)
    if sign_of is not None:
        check(np.all(sign_of(n) >= -1e-12), "%s: some Normal violates the rule" % case)
        check(np.any(flip < 0), "%s: no sample was flipped relative to Away From Centroid (the property had no effect)" % case)
    print("ok   %-44s %6d flipped" % (case, int(np.count_nonzero(flip < 0))), flush=True)

# ---------------------------------------------------------------------------------------------
# Energy glyphs: both outputs, 2D and 3D.
pss("glyphs", path("cloud.vtp"), "--variant", "com", "--h", 5, "--samples", path("samples.vtp"), "--resolution", 36,
    "--glyph-size", 0.8, "--segment-length", 1.5, "--segments", path("segments.vtp"), "-o", path("glyphs.vtp"))
glyphs = P["PointSetSurfaceEnergyGlyphs"](Input=cloud, SamplePoints=reader("samples.vtp"), Variant="Center of Mass",
                                          AutomaticScale=0, ScaleFactor=5, Resolution=36, GlyphSize=0.8, SegmentLength=1.5)
compare("EnergyGlyphs com, glyphs", fetch(glyphs), read("glyphs.vtp"), ["Energy"], ["SampleId", "Stability"])
compare("EnergyGlyphs com, best fit", fetch(glyphs, 1), read("segments.vtp"), [], ["SampleId", "Stability", "Normal"])

pss("glyphs", path("sphere.vtp"), "--variant", "normalized", "--samples", path("samples.vtp"), "--resolution", 12,
    "--segments", path("segments3d.vtp"), "-o", path("glyphs3d.vtp"))
glyphs = P["PointSetSurfaceEnergyGlyphs"](Input=reader("sphere.vtp"), SamplePoints=reader("samples.vtp"),
                                          Variant="Normalized MLS", Resolution=12)
compare("EnergyGlyphs 3D, glyphs", fetch(glyphs), read("glyphs3d.vtp"), ["Energy"], ["SampleId", "Stability"])
compare("EnergyGlyphs 3D, best fit", fetch(glyphs, 1), read("segments3d.vtp"), [], ["SampleId", "Stability", "Normal"])

# Scale mode Per Glyph (no pss flag): every glyph's widest radius is GlyphSize * h.
glyphs = P["PointSetSurfaceEnergyGlyphs"](Input=cloud, SamplePoints=reader("samples.vtp"), AutomaticScale=0,
                                          ScaleFactor=5, Resolution=36, GlyphSize=0.8, ScaleMode="Per Glyph")
got = fetch(glyphs)
samples = read("samples.vtp")
lines = got.GetLines()
check(lines.GetNumberOfCells() == samples.GetNumberOfPoints(), "EnergyGlyphs Per Glyph: %d glyphs for %d samples" % (
    lines.GetNumberOfCells(), samples.GetNumberOfPoints()))
offsets, conn = vtk_to_numpy(lines.GetOffsetsArray()), vtk_to_numpy(lines.GetConnectivityArray())
pts = values(got.GetPoints().GetData())
sample_ids = vtk_to_numpy(got.GetCellData().GetArray("SampleId"))
radii = []
for c in range(lines.GetNumberOfCells()):
    centre = np.array(samples.GetPoint(int(sample_ids[c])))
    radii.append(np.linalg.norm(pts[conn[offsets[c]:offsets[c + 1]]] - centre, axis=1).max())
check(np.allclose(radii, 0.8 * 5, rtol=1e-9), "EnergyGlyphs Per Glyph: widest radii %s, expected 4" % np.round(radii, 6))
print("ok   %-44s radii %.9g..%.9g" % ("EnergyGlyphs ScaleMode Per Glyph", min(radii), max(radii)), flush=True)

# ---------------------------------------------------------------------------------------------
# Mesher: triangles on a 3D sphere (the cloud source's sphere as input, default and explicit
# parameters), line segments on the 2D noisy curve, vertices left on the grid.
def field(data, name):
    a = data.GetFieldData().GetArray(name)
    return a.GetValue(0) if a is not None else None


sphere_source = P["PointSetSurfaceCloudSource"](Scene="Sphere", Dimension="3D", NumberOfPoints=300, Size=20, Noise=0.3, Seed=5)
pss("mesh", path("sphere.vtp"), "-o", path("mesh_default.vtp"))
got = fetch(P["PointSetSurfaceMesh"](Input=sphere_source))
compare("Mesher defaults, 3D sphere (cloud source)", got, read("mesh_default.vtp"), MESH_ARRAYS, [], MESH_FIELDS)
check(got.GetNumberOfPolys() == got.GetNumberOfCells() and got.GetNumberOfPolys() > 100,
      "Mesher sphere: %d triangles of %d cells" % (got.GetNumberOfPolys(), got.GetNumberOfCells()))
check(got.GetPointData().GetNormals() is not None and got.GetPointData().GetNormals().GetName() == "Normals",
      "Mesher sphere: Normals are not the active normals")
check(np.all(array(got, "DomainLabel") == 0), "Mesher sphere: a vertex outside the domain")
topology = [field(got, name) for name in ("Components", "BoundaryEdges", "NonManifoldEdges", "EulerCharacteristic")]
check(topology == [1, 0, 0, 2], "Mesher sphere: components, boundary edges, non-manifold edges, Euler characteristic %s, "
      "expected a closed sphere [1, 0, 0, 2]" % topology)

pss("mesh", path("sphere.vtp"), "--variant", "normalized", "--h", 3.5, "--cell", 0.7, "--band", 1.5, "--procedure", "plane",
    "--max-distance", 0.8, "--max-normal-angle", 25, "--max-vertex-travel", 1.5, "--max-seam-angle", 50,
    "--max-fold-angle", 45, "--max-hole-edges", 8, "--min-piece-area", 5, "-o", path("mesh_params.vtp"))
mesher = P["PointSetSurfaceMesh"](Input=reader("sphere.vtp"), Variant="Normalized MLS", AutomaticScale=0, ScaleFactor=3.5,
                                    CellSize=0.7, Band=1.5, Procedure="Plane", MaxDistance=0.8, MaxNormalAngle=25,
                                    MaxVertexTravel=1.5, MaxSeamAngle=50, MaxFoldAngle=45, MaxHoleEdges=8,
                                    MinPieceArea=5)
got = fetch(mesher)
compare("Mesher normalized, plane, explicit knobs", got, read("mesh_params.vtp"), MESH_ARRAYS, [], MESH_FIELDS)
check(field(got, "CellSize") == 0.7 and field(got, "Band") == 1.5, "Mesher: field data CellSize %s, Band %s" % (
    field(got, "CellSize"), field(got, "Band")))

pss("mesh", path("sphere.vtp"), "--h", 3, "--no-projection", "-o", path("mesh_grid.vtp"))
got = fetch(P["PointSetSurfaceMesh"](Input=reader("sphere.vtp"), AutomaticScale=0, ScaleFactor=3, ProjectVertices=0))
compare("Mesher vertices on the grid", got, read("mesh_grid.vtp"), MESH_ARRAYS, [], MESH_FIELDS)

# A depth frame (a scale per point, taken automatically): cells that follow it by default, one grid
# with AdaptiveCells off.
pss("mesh", path("depth.vtp"), "-o", path("mesh_depth.vtp"))
got = fetch(P["PointSetSurfaceMesh"](Input=reader("depth.vtp")))
compare("Mesher depth frame, adaptive cells", got, read("mesh_depth.vtp"), MESH_ARRAYS, [],
        MESH_FIELDS + ["GridDimensions", "Viewpoint"])
check(field(got, "CellLevels") > 1 and field(got, "HangingVertices") > 0, "Mesher depth frame: %s cell levels, %s hanging "
      "corners, expected several levels" % (field(got, "CellLevels"), field(got, "HangingVertices")))
pss("mesh", path("depth.vtp"), "--regular-cells", "-o", path("mesh_depth_grid.vtp"))
got = fetch(P["PointSetSurfaceMesh"](Input=reader("depth.vtp"), AdaptiveCells=0))
compare("Mesher depth frame, one grid", got, read("mesh_depth_grid.vtp"), MESH_ARRAYS, [],
        MESH_FIELDS + ["GridDimensions", "Viewpoint"])
check(field(got, "CellLevels") == 1, "Mesher depth frame with AdaptiveCells off: %s cell levels" % field(got, "CellLevels"))

pss("mesh", path("cloud.vtp"), "--variant", "com", "--h", 5, "-o", path("mesh_2d.vtp"))
got = fetch(P["PointSetSurfaceMesh"](Input=cloud, Variant="Center of Mass", AutomaticScale=0, ScaleFactor=5))
compare("Mesher 2D noisy curve, polylines", got, read("mesh_2d.vtp"), MESH_ARRAYS, [], MESH_FIELDS)
check(got.GetNumberOfLines() == got.GetNumberOfCells() and got.GetNumberOfLines() > 10,
      "Mesher 2D: %d segments of %d cells" % (got.GetNumberOfLines(), got.GetNumberOfCells()))

# MaximumNumberOfBandCells (no pss flag): a band larger than the limit is refused, empty output
# (the filter reports the error with the count; VTK prints it on stderr).
print("(an error about the band's cell count is expected next)", flush=True)
mesher = P["PointSetSurfaceMesh"](Input=reader("sphere.vtp"), MaximumNumberOfBandCells=10)
mesher.UpdatePipeline()
got = servermanager.Fetch(mesher, 0)
check(got is not None and got.GetNumberOfPoints() == 0 and got.GetNumberOfCells() == 0,
      "Mesher MaximumNumberOfBandCells 10: %s points, expected an empty output" % (got.GetNumberOfPoints() if got else None))
mesher.MaximumNumberOfBandCells = 16777216
got = fetch(mesher)
check(got.GetNumberOfPolys() > 100, "Mesher: no mesh after raising MaximumNumberOfBandCells again")
print("ok   %-44s refused, then %d triangles" % ("Mesher MaximumNumberOfBandCells", got.GetNumberOfPolys()), flush=True)

print("%d comparisons with the C++ filters, %d arrays, %d values, %.1f s; %d failures" % (
    counts["cases"], counts["arrays"], counts["values"], time.time() - started, len(failures)))
sys.exit(1 if failures else 0)

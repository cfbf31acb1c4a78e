"""Distributed projection, domain classification and field sampling against the one-process run (ctest
ParaView.Mpi.Distributed.<case>).

    pvpython test_mpi_distributed.py --case NAME --np N --plugin PointSetSurfaces.so
        --pvbatch pvbatch --mpiexec mpiexec --workdir DIR

Writes a small noisy sphere (a few thousand points, seeded) as a .pvtp of pieces, runs
mpi_distributed_worker.py once in one process (pvbatch) and once with `mpiexec --oversubscribe
-np N pvbatch --symmetric`, then checks for the projection, the classifier and the field sampler
(probing the start points or the cloud): no point lost or duplicated (count and GlobalPointIds =
0..n-1), every point array of the one-process output equal at each global id (integers identical,
doubles bitwise, NaN = NaN), positions bitwise (else within max(1e-9 h, 4 ulp), reported), and
ScaleFactor (the automatic h) identical on every rank; for the sampler's own grid: the ranks'
parts cover the one-process image's extent, with its origin and spacing and every array bitwise
equal there; for the energy glyphs and their best fits: the ranks' outputs, concatenated in rank
order, are the one-process output (points, point and cell arrays bitwise); for the mesh: the
ranks' triangles, in rank order and mapped through GlobalPointIds, are the one-process triangles,
and every vertex and its arrays are bitwise those of the one-process mesh. Cases:
  rank0     the whole cloud in one piece: read by rank 0 only
  normals   APSS on the pieces' own Normals array (gathered with the points; the mesher orients by it)
  frame     every piece with the field data Viewpoint: a sensor frame, so the automatic scale takes
            one per point (asserted on every rank) as one process does
  tiled     the cloud in N slabs along x, separate start points in N-1 pieces (one rank has none)
            with NaN and Inf start points and NaN/Inf cloud points
  emptyrank the cloud in N-1 slabs: one rank has no cloud point and no start point
  offset    coordinates offset by 5e6 (where float coordinates or float cut boxes would fail)
  nonfinite NaN and Inf cloud points of every kind in every piece, separate start points in N
            pieces with NaN/Inf start points in every piece, the last piece nothing but them
  badpiece  the cloud in N pieces, piece 1's file garbage and (N > 2) piece 2's missing: every rank
            must stop in every filter, see check_unreadable
  empty     bad input: no cloud point on any rank; every rank must fail with the same error
  zeroh     bad input: AutomaticScale off and h = 0; every rank must fail with the same error
  ghost-*   GhostMargin > 0 (ghost points instead of the gathered cloud; projection, classifier,
            field sampler (probe and grid) and energy glyphs; h = 0.13 given but in ghost-autoh): ghost-tiled as tiled with margin 4;
            ghost-narrow margin 0.25, so that projections and grid samples leave the first box and later rounds
            must finish them (asserted: a rank takes more than one round); ghost-rank0 the cloud on rank 0 only and start points
            on every rank; ghost-offset and ghost-emptyrank as offset and emptyrank; ghost-autoh the
            automatic h (estimated on rank 0: identical); ghost-empty and ghost-zeroh as empty and zeroh
            (ghost-zeroh with a rank that holds no point, so asks for no ghost point, and must fail too);
            center of mass but ghost-narrow (normalized MLS), ghost-offset (Levin's MLS) and
            ghost-emptyrank (delta). Compared as the other cases: bitwise, since with GhostMargin > 0
            every neighbourhood is summed in the order of its points' coordinates, on every rank and
            in the one-process run alike
For every case that runs, the skipped points are reported the same way: each rank warns of the
same number of NaN/Inf cloud points as one process (they are counted in the gathered cloud), and
the ranks' warnings about their own NaN/Inf start or sample points add up to one process's.
Exits 0 with "ok" lines, 1 with the reasons.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader, vtkXMLPolyDataWriter

parser = argparse.ArgumentParser()
parser.add_argument("--case", required=True)
parser.add_argument("--np", type=int, required=True)
parser.add_argument("--plugin", required=True)
parser.add_argument("--pvbatch", required=True)
parser.add_argument("--mpiexec", required=True)
parser.add_argument("--workdir", required=True)
parser.add_argument("--timeout", type=float, default=100)
args = parser.parse_args()
worker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mpi_distributed_worker.py")
problems = []
POINT_FILTERS = ("projection", "classifier", "sampler")  # outputs: points with GlobalPointIds
CONCATENATED = ("glyphs", "fits")  # the energy glyphs' two outputs: rank by rank, in sample order
FILTERS = POINT_FILTERS + ("grid", "glyphs", "mesh")  # grid: the sampler's own image, split by extent
GHOST_FILTERS = FILTERS  # what runs with GhostMargin > 0: every filter
GHOST_H = 0.13  # about the automatic h of the case's sphere, given: no gather on rank 0 (ghost-autoh tests that)
ERRORS = {"empty": "the point cloud is empty", "zeroh": "invalid surface parameters",
          "ghost-empty": "the point cloud is empty", "ghost-zeroh": "invalid surface parameters"}


def write_pieces(directory, name, xyz, piece_of, pieces, normals=None, viewpoint=None):
    """xyz as a .pvtp of `pieces` pieces (point i in piece piece_of[i]), with a StartId array, and
    `normals` as the point array Normals and `viewpoint` as every piece's field data Viewpoint when
    given."""
    sources = []
    for p in range(pieces):
        sel = np.nonzero(piece_of == p)[0]
        points = vtkPoints()
        points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[sel]), deep=1))
        poly = vtkPolyData()
        poly.SetPoints(points)
        ids = numpy_to_vtk(sel.astype(np.int64), deep=1)
        ids.SetName("StartId")
        poly.GetPointData().AddArray(ids)
        if normals is not None:
            n = numpy_to_vtk(np.ascontiguousarray(normals[sel]), deep=1)
            n.SetName("Normals")
            poly.GetPointData().SetNormals(n)
        if viewpoint is not None:
            v = numpy_to_vtk(np.asarray(viewpoint, dtype=np.float64), deep=1)
            v.SetName("Viewpoint")
            poly.GetFieldData().AddArray(v)
        writer = vtkXMLPolyDataWriter()
        writer.SetInputData(poly)
        writer.SetFileName(os.path.join(directory, "%s_%d.vtp" % (name, p)))
        writer.Write()
        sources.append('    <Piece Source="%s_%d.vtp"/>' % (name, p))
    with open(os.path.join(directory, name + ".pvtp"), "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0" byte_order="LittleEndian" '
                'header_type="UInt64">\n  <PPolyData GhostLevel="0">\n'
                '    <PPointData><PDataArray type="Int64" Name="StartId"/>'
                + ('<PDataArray type="Float64" Name="Normals" NumberOfComponents="3"/>' if normals is not None else "")
                + '</PPointData>\n'
                '    <PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>\n'
                + "\n".join(sources) + "\n  </PPolyData>\n</VTKFile>\n")
    return name + ".pvtp"


def slabs(xyz, pieces):
    """Piece of each point: `pieces` slabs of equal counts along x (NaN/Inf points in piece 0)."""
    x = np.where(np.isfinite(xyz[:, 0]), xyz[:, 0], -np.inf)
    rank = np.empty(len(x), dtype=np.int64)
    rank[np.argsort(x, kind="stable")] = np.arange(len(x))
    return rank * pieces // len(x)


def make_case(directory):
    rng = np.random.default_rng(16)
    n = 2500
    v = rng.normal(size=(n, 3))
    xyz = v / np.linalg.norm(v, axis=1)[:, None] * (1 + 0.02 * rng.normal(size=(n, 1)))
    case = {}
    if args.case == "rank0":
        case["cloud"] = write_pieces(directory, "cloud", xyz, np.zeros(n, dtype=np.int64), 1)
    elif args.case == "tiled":
        xyz[[7, 1500]] = [[np.nan, 0, 0], [0, np.inf, 0]]
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
        starts = 1.3 * rng.uniform(-1, 1, size=(600, 3))
        starts[[3, 400]] = [[np.nan, 1, 1], [-np.inf, 0, 0]]
        case["starts"] = write_pieces(directory, "starts", starts, slabs(starts, args.np - 1), args.np - 1)
    elif args.case == "emptyrank":
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np - 1), args.np - 1)
    elif args.case == "offset":
        xyz[[11]] = [[np.nan, np.nan, np.nan]]
        xyz += 5e6
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
    elif args.case == "nonfinite":
        bad = rng.choice(n, size=4 * args.np, replace=False)
        kinds = [[np.nan, 0, 0], [0, np.inf, 0], [0, 0, -np.inf], [np.nan, np.inf, np.nan]]
        xyz[bad] = [kinds[k % len(kinds)] for k in range(len(bad))]
        piece_of = slabs(xyz, args.np)
        piece_of[bad] = np.arange(len(bad)) % args.np  # every rank holds some of them
        case["cloud"] = write_pieces(directory, "cloud", xyz, piece_of, args.np)
        starts = 1.3 * rng.uniform(-1, 1, size=(600, 3))
        starts_of = slabs(starts, args.np - 1)
        bad_starts = np.array([[np.nan, 0, 0], [np.inf, np.inf, np.inf], [0, -np.inf, np.nan]])
        tail = np.arange(len(bad_starts) * args.np) % len(bad_starts)
        starts = np.concatenate([starts, bad_starts[tail]])
        starts_of = np.concatenate([starts_of, np.arange(len(tail)) % args.np])  # the last piece: NaN/Inf only
        case["starts"] = write_pieces(directory, "starts", starts, starts_of, args.np)
        case["skipped_cloud"] = int(len(bad))
        case["skipped_starts"] = int(len(tail))
    elif args.case == "normals":  # APSS on the cloud's own Normals array (gathered with the points)
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np,
                                     normals=xyz / np.linalg.norm(xyz, axis=1)[:, None])
        case["surface"] = {"Variant": "APSS (Algebraic Spheres)"}
    elif args.case == "frame":  # a Viewpoint: a sensor frame, so a scale per point, as in one process
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np, viewpoint=[0.0, 0.0, 4.0])
        case["viewpoint"] = True
    elif args.case == "badpiece":
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
        with open(os.path.join(directory, "cloud_1.vtp"), "w") as f:
            f.write("not a VTK file\n")
        unreadable = [1]
        if args.np > 2:
            os.remove(os.path.join(directory, "cloud_2.vtp"))
            unreadable.append(2)
        case["unreadable"] = unreadable
    elif args.case == "empty":
        case["cloud"] = write_pieces(directory, "cloud", xyz[:0], np.zeros(0, dtype=np.int64), args.np)
    elif args.case.startswith("ghost-"):
        case["surface"] = {"AutomaticScale": 0, "ScaleFactor": GHOST_H}
        case["ghost_margin"] = 0.25 if args.case == "ghost-narrow" else 4.0
        starts = 1.3 * rng.uniform(-1, 1, size=(600, 3))
        if args.case == "ghost-tiled":
            xyz[[7, 1500]] = [[np.nan, 0, 0], [0, np.inf, 0]]
            case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
            starts[[3, 400]] = [[np.nan, 1, 1], [-np.inf, 0, 0]]
            case["starts"] = write_pieces(directory, "starts", starts, slabs(starts, args.np - 1), args.np - 1)
        elif args.case == "ghost-narrow":
            case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
            case["surface"]["Variant"] = "Normalized MLS"  # a line search that stops at a tolerance
        elif args.case == "ghost-rank0":
            case["cloud"] = write_pieces(directory, "cloud", xyz, np.zeros(n, dtype=np.int64), 1)
            case["starts"] = write_pieces(directory, "starts", starts, slabs(starts, args.np), args.np)
        elif args.case == "ghost-offset":
            case["surface"]["Variant"] = "Levin MLS"
            xyz[[11]] = [[np.nan, np.nan, np.nan]]
            xyz += 5e6
            case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
        elif args.case == "ghost-emptyrank":
            case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np - 1), args.np - 1)
            case["surface"]["Variant"] = "Delta Energy"  # a Newton search for n_I that stops at a tolerance
        elif args.case == "ghost-empty":
            case["cloud"] = write_pieces(directory, "cloud", xyz[:0], np.zeros(0, dtype=np.int64), args.np)
        elif args.case == "ghost-zeroh":  # and one rank without points, which asks for no ghosts
            case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np - 1), args.np - 1)
            case["surface"] = {"AutomaticScale": 0, "ScaleFactor": 0.0}
        elif args.case == "ghost-autoh":
            xyz[[5, 2000]] = [[np.inf, 0, 0], [0, 0, np.nan]]
            case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
            case["surface"] = {}
        else:
            sys.exit("unknown case %s" % args.case)
    elif args.case == "zeroh":
        case["cloud"] = write_pieces(directory, "cloud", xyz, slabs(xyz, args.np), args.np)
        case["surface"] = {"AutomaticScale": 0, "ScaleFactor": 0.0}
    else:
        sys.exit("unknown case %s" % args.case)
    with open(os.path.join(directory, "case.json"), "w") as f:
        json.dump(case, f)


def run(command, name):
    # pvpython is itself an MPI singleton: its OpenMPI/PMIx variables would make mpiexec's ranks
    # join it instead of starting their own world.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_", "PRTE_"))}
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    start = time.time()
    try:
        done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        sys.exit("%s: no end within %g s (a hang?)" % (name, args.timeout))
    print("ran  %-9s in %.1f s (exit %d)" % (name, time.time() - start, done.returncode), flush=True)
    with open(os.path.join(args.workdir, args.case, name.replace(" ", "_") + ".log"), "w") as f:
        f.write(done.stdout + done.stderr)
    if done.returncode != 0:
        sys.stdout.write(done.stdout[-3000:] + done.stderr[-3000:])
        sys.exit("%s: exit status %d" % (name, done.returncode))
    return done.stdout + done.stderr


def read(path):
    """The dataset in path (.vtp or .vti), or an empty polydata when the worker wrote none."""
    if not os.path.exists(path):
        return vtkPolyData()
    reader = vtkXMLImageDataReader() if path.endswith(".vti") else vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def output_path(directory, run, name, rank):
    return os.path.join(directory, "%s_%s_%d.%s" % (run, name, rank, "vti" if name == "grid" else "vtp"))


def same_bits(a, b):
    if a.dtype.kind != "f":
        return np.array_equal(a, b)
    return a.shape == b.shape and np.array_equal(a.view(np.uint8), b.view(np.uint8))


def compare_grid(directory):
    """Each rank's part of the sampler's image against the one-process image, bitwise."""
    serial = read(output_path(directory, "serial", "grid", 0))
    whole = serial.GetExtent()
    dims = [whole[2 * a + 1] - whole[2 * a] + 1 for a in range(3)]
    want = {k: v.reshape(dims[2], dims[1], dims[0], -1) for k, v in arrays_of(serial).items()}
    covered = np.zeros((dims[2], dims[1], dims[0]), dtype=bool)
    for r in range(args.np):
        part = read(output_path(directory, "parallel", "grid", r))
        if part.GetNumberOfPoints() == 0:
            continue
        if part.GetOrigin() != serial.GetOrigin() or part.GetSpacing() != serial.GetSpacing():
            problems.append("grid: rank %d has origin %r spacing %r, one process %r %r" % (
                r, part.GetOrigin(), part.GetSpacing(), serial.GetOrigin(), serial.GetSpacing()))
        e = part.GetExtent()
        block = tuple(slice(e[2 * a] - whole[2 * a], e[2 * a + 1] - whole[2 * a] + 1) for a in (2, 1, 0))
        shape = [e[2 * a + 1] - e[2 * a] + 1 for a in (2, 1, 0)]
        got = arrays_of(part)
        for key, a in want.items():
            if key not in got:
                problems.append("grid: array %s missing on rank %d" % (key, r))
                continue
            a_part = np.ascontiguousarray(a[block])
            b_part = got[key].reshape(shape + [-1])
            if not same_bits(a_part, b_part):
                problems.append("grid: %s differs on rank %d (extent %r)" % (key, r, e))
        covered[block] = True
    if not covered.all():
        problems.append("grid: the ranks' parts miss %d of %d samples" % (int((~covered).sum()), covered.size))
    else:
        print("ok   %-10s %d samples in %d parts, %d arrays, bitwise equal" % (
            "grid", covered.size, sum(read(output_path(directory, "parallel", "grid", r)).GetNumberOfPoints() > 0
                                      for r in range(args.np)), len(want)), flush=True)


def arrays_of(poly):
    pd = poly.GetPointData()
    out = {}
    if hasattr(poly, "GetPoints"):  # an image's points are its origin, spacing and extent
        out["Points"] = vtk_to_numpy(poly.GetPoints().GetData()) if poly.GetNumberOfPoints() else np.zeros((0, 3))
    for i in range(pd.GetNumberOfArrays()):
        out[pd.GetArrayName(i)] = vtk_to_numpy(pd.GetArray(i))
    return out


def compare_concatenated(directory, name):
    """The ranks' outputs of `name`, one after the other, against the one-process output, bitwise."""
    def everything(poly):
        out = {"point " + k: v for k, v in arrays_of(poly).items()}
        cd = poly.GetCellData()
        out.update({"cell " + cd.GetArrayName(i): vtk_to_numpy(cd.GetArray(i)) for i in range(cd.GetNumberOfArrays())})
        return out
    want = everything(read(output_path(directory, "serial", name, 0)))
    parts = [everything(p) for p in (read(output_path(directory, "parallel", name, r)) for r in range(args.np))
             if p.GetNumberOfPoints() > 0]
    before = len(problems)
    for key, a in want.items():
        b = np.concatenate([p[key] for p in parts if key in p]) if parts else a[:0]
        if not same_bits(a, b):
            problems.append("%s: %s differs (%d values, one process %d)" % (name, key, len(b), len(a)))
    if len(problems) == before:
        print("ok   %-10s %d points, %d arrays, in %d parts, bitwise equal" % (
            name, len(want["point Points"]), len(want) - 1, len(parts)), flush=True)


def compare_mesh(directory):
    """The ranks' shares of the mesh, merged by GlobalPointIds, against the one-process mesh."""
    def cells(poly):
        c = poly.GetPolys() if poly.GetNumberOfPolys() else poly.GetLines()
        return vtk_to_numpy(c.GetConnectivityArray()), vtk_to_numpy(c.GetOffsetsArray())
    serial = read(output_path(directory, "serial", "mesh", 0))
    want = arrays_of(serial)
    conn, offsets = cells(serial)
    seen = np.zeros(serial.GetNumberOfPoints(), dtype=bool)
    merged_conn, merged_sizes = [], []
    before = len(problems)
    for r in range(args.np):
        part = read(output_path(directory, "parallel", "mesh", r))
        if part.GetNumberOfPoints() == 0:
            continue
        got = arrays_of(part)
        ids = got.pop("GlobalPointIds", None)
        if ids is None:
            problems.append("mesh: no GlobalPointIds on rank %d" % r)
            return
        for key, a in want.items():
            if key not in got or not same_bits(a[ids], got[key]):
                problems.append("mesh: %s differs on rank %d" % (key, r))
        seen[ids] = True
        c, o = cells(part)
        merged_conn.append(ids[c])
        merged_sizes.append(np.diff(o))
    merged = np.concatenate(merged_conn) if merged_conn else conn[:0]
    sizes = np.concatenate(merged_sizes) if merged_sizes else np.diff(offsets)[:0]
    if not (np.array_equal(merged, conn) and np.array_equal(sizes, np.diff(offsets))):
        problems.append("mesh: the ranks' %d cells are not the one-process %d cells" % (len(sizes), len(offsets) - 1))
    if not seen.all():
        problems.append("mesh: %d of %d vertices on no rank" % (int((~seen).sum()), len(seen)))
    if len(problems) == before:
        print("ok   %-10s %d points, %d cells, %d arrays, bitwise equal" % (
            "mesh", len(seen), len(offsets) - 1, len(want) - 1), flush=True)


def compare(directory, name, h):
    """The ranks' outputs of filter `name` against the one-process output (h: the one-process h)."""
    serial = read(output_path(directory, "serial", name, 0))
    pieces = [read(output_path(directory, "parallel", name, r)) for r in range(args.np)]
    n = serial.GetNumberOfPoints()
    for r, piece in enumerate(pieces):
        scale = piece.GetFieldData().GetArray("ScaleFactor")
        if piece.GetNumberOfPoints() == 0 or scale is None:  # the sampler's output is the probe's
            continue
        ph = scale.GetValue(0)
        if ph != h:
            problems.append("%s: rank %d used h = %r, one process %r" % (name, r, ph, h))
        per_point = piece.GetFieldData().GetArray("PointScales")
        if args.case == "frame" and (per_point is None or per_point.GetValue(0) != 1):
            problems.append("%s: rank %d took one h for a sensor frame (its Viewpoint was lost)" % (name, r))
    want = arrays_of(serial)
    parts = [arrays_of(p) for p in pieces if p.GetNumberOfPoints() > 0]
    got = {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}
    ids = got.get("GlobalPointIds")
    if ids is None:
        problems.append("%s: no GlobalPointIds in the distributed output" % name)
        return
    if len(ids) != n or not np.array_equal(np.sort(ids), np.arange(n)):
        problems.append("%s: %d distributed points with %d distinct ids, one process %d points"
                        % (name, len(ids), len(np.unique(ids)), n))
        return
    order = np.argsort(ids)
    bitwise = True
    for key, a in want.items():
        if key not in got:
            problems.append("%s: array %s missing from the distributed output" % (name, key))
            continue
        b = got[key][order]
        if a.dtype.kind == "f":
            if not same_bits(a, b):
                bitwise = False
                tol = np.maximum(1e-9 * h, 4 * np.spacing(np.abs(a)))
                bad = ~((np.abs(a - b) <= tol) | (np.isnan(a) & np.isnan(b)))
                if key != "Points" or bad.any():
                    problems.append("%s: %s differs at %d values (largest %g)"
                                    % (name, key, int(bad.sum()), float(np.nanmax(np.abs(a - b)))))
        elif not np.array_equal(a, b):
            problems.append("%s: %s differs at %d values" % (name, key, int((a != b).sum())))
    print("ok   %-10s %d points, %d arrays, h = %.17g, %s" % (
        name, n, len(want) - 1, h, "bitwise equal" if bitwise else "positions within tolerance"), flush=True)


# One line of VTK's log: the rank (no number in one process), then the message ("vtkClass (0x...): text").
LOG_LINE = re.compile(r"\[pvbatch(?:\.(\d+))?\s*\][^|]*\|\s*(vtk\w+) \(0x[0-9a-f]+\): (.*)")
SKIPPED = re.compile(r"(\d+) (cloud|start|sample) point\(s\) ")


def log_messages(log):
    """(rank, class, text) of every VTK message in log, in order; rank 0 in one process."""
    out = []
    for line in re.sub(r"\x1b\[[0-9;]*m", "", log).splitlines():
        m = LOG_LINE.search(line)
        if m:
            out.append((int(m.group(1) or 0), m.group(2), m.group(3)))
    return out


def check_skipped_reports(serial_log, parallel_log, case):
    """Skipped NaN/Inf points reported as in one process: every rank warns of the same number of
    cloud points as one process, filter by filter; the ranks' own start/sample counts add up."""
    def skipped(log):
        cloud, local = {}, {}
        for rank, cls, text in log_messages(log):
            m = SKIPPED.match(text)
            if not m:
                continue
            if m.group(2) == "cloud":
                cloud.setdefault(rank, []).append((cls, int(m.group(1))))
            else:
                key = (cls, m.group(2))
                local[key] = local.get(key, 0) + int(m.group(1))
        return cloud, local
    before = len(problems)
    serial_cloud, serial_local = skipped(serial_log)
    parallel_cloud, parallel_local = skipped(parallel_log)
    want = serial_cloud.get(0, [])
    for r in range(args.np):
        if parallel_cloud.get(r, []) != want:
            problems.append("rank %d reports skipped cloud points %r, one process %r" % (r, parallel_cloud.get(r, []), want))
    if parallel_local != serial_local:
        problems.append("the ranks' skipped start/sample points add up to %r, one process %r" % (parallel_local, serial_local))
    if "skipped_cloud" in case:  # the counts themselves, against what the case put in
        if len(want) != len(FILTERS) or any(count != case["skipped_cloud"] for _, count in want):
            problems.append("one process reports skipped cloud points %r, expected %d by each of %d filters"
                            % (want, case["skipped_cloud"], len(FILTERS)))
        starts = serial_local.get(("vtkPointSetSurfaceProjection", "start"))
        if starts != case["skipped_starts"]:
            problems.append("one process reports %r skipped start points, expected %d" % (starts, case["skipped_starts"]))
    if len(problems) == before:
        print("ok   skipped points reported alike: %d cloud point(s) on every rank by each filter, %r over the ranks"
              % (want[0][1] if want else 0, sorted(parallel_local.items())), flush=True)


def check_unreadable(directory, serial_log, parallel_log, case):
    """An unreadable piece: VTK's XML reader prints "File for piece k cannot be read" and still
    reports success (with no point in one process, with the other pieces under MPI). One process:
    every filter refuses the empty cloud. Under MPI the filters notice the reader's error on rank k
    (pss_vtk::UpstreamErrorWatch) and every rank stops in every filter with the same error, which
    names the ranks whose upstream failed (the reader's own error is in their log). Asserted: the
    reader's error on the right ranks, that same error from every filter on every rank, no output
    on any rank, and no hang (run()'s time limit)."""
    before = len(problems)
    first = "File for piece %d cannot be read" % case["unreadable"][0]  # one process stops there
    if not any(first in m for _, _, m in log_messages(serial_log)):
        problems.append("one process: no %r" % first)
    for k in case["unreadable"]:
        text = "File for piece %d cannot be read" % k
        ranks = sorted({r for r, _, m in log_messages(parallel_log) if text in m and "upstream" not in m})
        if ranks != [k]:
            problems.append("np %d: %r printed by ranks %r, expected [%d]" % (args.np, text, ranks, k))
    refused = [cls for _, cls, m in log_messages(serial_log) if "the point cloud is empty" in m]
    if len(refused) != len(FILTERS):
        problems.append("one process: %d filters refused the empty cloud, expected %d" % (len(refused), len(FILTERS)))
    want = "the pipeline upstream reported an error on rank(s) %s during this update" % (
        ", ".join(str(k) for k in case["unreadable"]))
    for r in range(args.np):
        stops = [m for rank, _, m in log_messages(parallel_log) if rank == r and "pipeline upstream" in m]
        if len(stops) != len(FILTERS) or not all(want in m for m in stops):
            problems.append("np %d: rank %d stopped %d filters of %d (%r), each expected to say %r"
                            % (args.np, r, len(stops), len(FILTERS), stops, want))
        for name in FILTERS:
            if os.path.exists(output_path(directory, "parallel", name, r)):
                problems.append("np %d: rank %d has output of the %s" % (args.np, r, name))
    if len(problems) == before:
        print("ok   pieces %r unreadable: the reader's error on their ranks; one process refuses the empty "
              "cloud in all %d filters; under MPI every rank stops in each of them with the same error naming "
              "those ranks" % (case["unreadable"], len(FILTERS)), flush=True)


def check_ghost_rounds(parallel_log):
    """The rounds each rank's filters took (printed by the worker): every filter with output must
    report at least one; in ghost-narrow the projection, the grid and the mesh must need more than one."""
    found = re.findall(r"rank (\d+): (\w+) ghost rounds (\d+)", parallel_log)
    for name in GHOST_FILTERS:
        rounds = {int(r): int(k) for r, f, k in found if f == name}
        print("ok   ghost rounds of the %s by rank: %r" % (name, sorted(rounds.items())), flush=True)
        if not rounds or min(rounds.values()) < 1:  # ranks without points have no output to say it
            problems.append("%s: ghost rounds reported by ranks %r" % (name, rounds))
        elif args.case == "ghost-narrow" and name in ("projection", "grid", "mesh") and max(rounds.values()) < 2:
            problems.append("ghost-narrow: no %s point needed a second round (%r): the case tests nothing"
                            % (name, rounds))


def check_same_error(parallel_log, message, filters, serial_log=None):
    """Every rank reports message from the same filters, in the same order, as one process (or,
    without serial_log: once from each of filters)."""
    def failing(log):
        by_rank = {}
        for rank, cls, text in log_messages(log):
            if message in text:
                by_rank.setdefault(rank, []).append(cls)
        return by_rank
    if serial_log is None:
        want = ["vtkPointSetSurface" + {"projection": "Projection", "classifier": "DomainClassifier",
                                        "sampler": "FieldSampler", "grid": "FieldSampler",
                                        "glyphs": "EnergyGlyphs", "mesh": "Mesher"}[f] for f in filters]
    else:
        want = failing(serial_log).get(0, [])
    if len(want) != len(filters):
        problems.append("one process: %d errors containing %r, expected %d" % (len(want), message, len(filters)))
    got = failing(parallel_log)
    for r in range(args.np):
        if got.get(r, []) != want:
            problems.append("rank %d: errors containing %r from %r, one process from %r" % (r, message, got.get(r, []), want))
    if sorted(got) != list(range(args.np)):
        problems.append("errors from ranks %r, expected 0..%d" % (sorted(got), args.np - 1))


def main():
    directory = os.path.join(args.workdir, args.case)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    make_case(directory)
    common = [worker, "--plugin", args.plugin, "--case", directory]
    serial_log = run([args.pvbatch] + common + ["--out", "serial"], "one process")
    parallel_log = run([args.mpiexec, "--oversubscribe", "-np", str(args.np), args.pvbatch, "--symmetric"]
                       + common + ["--out", "parallel"], "np %d" % args.np)
    with open(os.path.join(directory, "case.json")) as f:
        case = json.load(f)
    ghost = "ghost_margin" in case
    filters = GHOST_FILTERS if ghost else FILTERS
    if args.case in ERRORS:
        message = ERRORS[args.case]
        for name in filters:
            for r in range(args.np):
                if read(output_path(directory, "parallel", name, r)).GetNumberOfPoints():
                    problems.append("%s: rank %d has output on bad input" % (name, r))
        before = len(problems)
        check_same_error(parallel_log, message, filters, serial_log if not ghost else None)
        if len(problems) == before:
            print("ok   every rank failed with %r in each of the %d filters%s" % (
                message, len(filters), "" if ghost else ", as one process"))
    elif ghost:
        check_skipped_reports(serial_log, parallel_log, case)
        h = read(output_path(directory, "serial", "projection", 0)).GetFieldData().GetArray("ScaleFactor").GetValue(0)
        for name in POINT_FILTERS:
            compare(directory, name, h)
        compare_grid(directory)
        for name in CONCATENATED:
            compare_concatenated(directory, name)
        compare_mesh(directory)
        check_ghost_rounds(parallel_log)
    else:
        if "unreadable" in case:
            check_unreadable(directory, serial_log, parallel_log, case)
            return report()
        check_skipped_reports(serial_log, parallel_log, case)
        h = read(output_path(directory, "serial", "projection", 0)).GetFieldData().GetArray("ScaleFactor").GetValue(0)
        for name in POINT_FILTERS:
            compare(directory, name, h)
        compare_grid(directory)
        for name in CONCATENATED:
            compare_concatenated(directory, name)
        compare_mesh(directory)
    return report()


def report():
    for p in problems:
        print("FAIL:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

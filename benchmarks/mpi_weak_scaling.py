"""Points/s per rank of the distributed projection (the weak scaling of docs/distributed.md).

    mpiexec -np N pvbatch --symmetric benchmarks/mpi_weak_scaling.py --plugin PointSetSurfaces.so
        --bunny ../shared/data/stanford-bunny/bunny_scans_merged.ply --workdir DIR --mode weak|split

One thread per rank (vtkSMPTools' Sequential backend, set here after the plugin switched it), the
center-of-mass surface, plane procedure, h = 1 mm fixed, each rank projecting its piece's points.
  weak   N copies of the bunny, 0.5 m apart along x, one per piece: every rank has one bunny's
         work whatever N (np 1: the bunny alone), the weak-scaling rows
  split  the bunny in 2 slabs of equal counts along x (np 2: one slab per rank; np 1: both
         slabs in the one process, the same total work)
Each rank times the projection's update after the reader's (a barrier before and after; wall
clock, and the process's CPU time, which a machine shared with other work slows less), and a
second projection of one start point over the same cloud: its time is the gather of the whole
cloud plus the k-d tree built over it, the part every rank repeats with today's replicated cloud.
With --ghost-margin M > 0 the projection exchanges ghost points instead of gathering the cloud
(GhostMargin): each rank also reports the other ranks' points it held (GhostPoints) and the rounds
it took, and the one-start projection measures only a tiny exchange (its row is then not the
overhead; the ghost points are).
With --mesh the mesher (PointSetSurfaceMesh, default parameters, the same surface) is timed too:
every rank gathers the cloud and builds the same band, then computes its block of the grid
corners and of the crossings (pss::StageSplit), so its time at np 2 against np 1 in split mode is
the mesher's strong scaling (the sequential stages and the gather are repeated on every rank).
With --mesh and --ghost-margin the mesher exchanges ghost points too (no gather; the band from
every rank's occupied cells, each block of corners, crossings and hole centres in ghost rounds).
Rank 0 prints one line per rank and a summary; the pieces are written on first use.
"""
import argparse
import os
import time

import numpy as np
import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--bunny", required=True)
parser.add_argument("--workdir", required=True)
parser.add_argument("--mode", choices=("weak", "split"), default="weak")
parser.add_argument("--h", type=float, default=0.001)
parser.add_argument("--ghost-margin", type=float, default=0.0)
parser.add_argument("--mesh", action="store_true", help="time the mesher too")
args = parser.parse_args()

pvs.LoadPlugin(args.plugin, remote=False, ns=globals())
vtkSMPTools.SetBackend("Sequential")  # one thread per rank: the ranks are the parallelism here
pm = servermanager.vtkProcessModule.GetProcessModule()
controller = pm.GetGlobalController()
rank, ranks = pm.GetPartitionId(), pm.GetNumberOfLocalPartitions()


def write_vtp(path, xyz):
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz, dtype=np.float64), deep=1))
    poly = vtkPolyData()
    poly.SetPoints(points)
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(poly)
    writer.SetFileName(path)
    writer.SetDataModeToBinary()
    writer.Write()


def write_pvtp(path, sources):
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0" byte_order="LittleEndian" '
                'header_type="UInt64">\n  <PPolyData GhostLevel="0">\n'
                '    <PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>\n'
                + "".join('    <Piece Source="%s"/>\n' % s for s in sources) + "  </PPolyData>\n</VTKFile>\n")


pieces = ranks if args.mode == "weak" else 2
cloud_file = os.path.join(args.workdir, "%s_%d.pvtp" % (args.mode, pieces))
start_file = os.path.join(args.workdir, "one_start.vtp")
if rank == 0 and not os.path.exists(cloud_file):
    os.makedirs(args.workdir, exist_ok=True)
    reader = vtkPLYReader()
    reader.SetFileName(args.bunny)
    reader.Update()
    bunny = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)
    names = []
    for p in range(pieces):
        if args.mode == "weak":
            xyz = bunny + [0.5 * p, 0, 0]
        else:
            order = np.argsort(bunny[:, 0], kind="stable")
            xyz = bunny[np.sort(order[p * len(bunny) // 2:(p + 1) * len(bunny) // 2])]
        names.append("%s_%d_%d.vtp" % (args.mode, pieces, p))
        write_vtp(os.path.join(args.workdir, names[-1]), xyz)
    write_pvtp(cloud_file, names)
    write_vtp(start_file, bunny[:1])
controller.Barrier()

cloud = pvs.OpenDataFile(cloud_file)
cloud.UpdatePipeline()
local = cloud.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
surface = dict(Variant="Center of Mass", Procedure="Plane", AutomaticScale=0, ScaleFactor=args.h,
               GhostMargin=args.ghost_margin)


def timed(proxy):
    """Wall-clock and CPU seconds of the proxy's update on this rank."""
    controller.Barrier()
    start, cpu = time.perf_counter(), time.process_time()
    proxy.UpdatePipeline()
    seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
    controller.Barrier()
    return seconds, cpu


projection = PointSetSurfaceProjection(Input=cloud, **surface)
project_seconds, project_cpu = timed(projection)
output = projection.GetClientSideObject().GetOutputDataObject(0)
projected = output.GetNumberOfPoints()
ghost_points = output.GetFieldData().GetArray("GhostPoints")
ghost_rounds = output.GetFieldData().GetArray("GhostRounds")
ghost_points = ghost_points.GetValue(0) if ghost_points else 0
ghost_rounds = ghost_rounds.GetValue(0) if ghost_rounds else 0
# A one-file reader gives its point to rank 0 and nothing to the others.
overhead = PointSetSurfaceProjection(Input=cloud, StartPoints=pvs.OpenDataFile(start_file), **surface)
overhead_seconds, overhead_cpu = timed(overhead)

mesh_seconds = mesh_cpu = mesh_triangles = 0
if args.mesh:
    mesher = PointSetSurfaceMesh(Input=cloud, Variant="Center of Mass", AutomaticScale=0, ScaleFactor=args.h,
                                 GhostMargin=args.ghost_margin)
    mesh_seconds, mesh_cpu = timed(mesher)
    mesh_triangles = mesher.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPolys()

row = vtkDoubleArray()
row.SetNumberOfValues(11)
for i, value in enumerate((projected, project_seconds, overhead_seconds, local, project_cpu, overhead_cpu,
                           ghost_points, ghost_rounds, mesh_seconds, mesh_cpu, mesh_triangles)):
    row.SetValue(i, value)
gathered = vtkDoubleArray()
controller.Gather(row, gathered, 0)
if rank == 0:
    table = vtk_to_numpy(gathered).reshape(ranks, 11)
    total = 0
    print("mode %s, np %d, %d piece(s), h = %g m, ghost margin %g h, backend %s, %d thread(s) per rank"
          % (args.mode, ranks, pieces, args.h, args.ghost_margin, vtkSMPTools.GetBackend(),
             vtkSMPTools.GetEstimatedNumberOfThreads()))
    for r, (n, seconds, over, cloud_points, cpu, over_cpu, ghosts, rounds, _, _, _) in enumerate(table):
        total += n
        print("rank %d: %d cloud points read, %d projected in %.3f s (%.3f s CPU) = %.0f points/s (%.0f per CPU s); "
              "gather + index %.3f s (%.3f s CPU)%s" % (
                  r, cloud_points, n, seconds, cpu, n / seconds, n / cpu, over, over_cpu,
                  "; %d ghost points (%.1f%% of its own), %d round(s)" % (ghosts, 100.0 * ghosts / max(cloud_points, 1),
                                                                         rounds) if args.ghost_margin > 0 else ""))
    wall = table[:, 1].max()
    print("summary: %d points in %.3f s (slowest rank), %.0f points/s per rank, %.0f per CPU second per rank; "
          "gather + index %.3f s (%.0f%% of the slowest rank's time)" % (
              total, wall, total / ranks / wall, total / table[:, 4].sum(), table[:, 2].max(),
              100 * table[:, 2].max() / wall))
    if args.mesh:
        print("mesh: %d triangles (the ranks' shares) in %.3f s (slowest rank; %s), CPU %s s" % (
            table[:, 10].sum(), table[:, 8].max(), ", ".join("%.3f" % t for t in table[:, 8]),
            ", ".join("%.3f" % t for t in table[:, 9])))

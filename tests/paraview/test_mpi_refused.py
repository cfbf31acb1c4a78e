"""Run by `mpiexec -np 2 pvbatch --symmetric` (ctest ParaView.Mpi.RefusedInsteadOfWrong): a run with
more than one process must refuse what does not run distributed (the field sampler with
OrientationMode Propagate and the projection with PropagateNormals, spanning trees over every
sample or end point; APSS and RIMLS with ghost points, whose cloud normals do not travel with
them; a sensor frame with ghost points, where one process takes a scale per point
that the ghost margins do not follow yet, and one h would be another surface; the mesher's trim
with ghost points, whose local spacings need every point's neighbours: an error and an empty
output)
instead of computing on each rank's piece alone, which differs from the one-process answer near
every piece's border without saying so. (Every filter runs distributed otherwise:
test_mpi_distributed.py.)

Prints "ok" lines and ends normally on success; exits 1 with the reason otherwise.
usage: pvbatch --symmetric test_mpi_refused.py --plugin PointSetSurfaces.so
"""
import argparse
import sys

import paraview.simple as pvs
from paraview import servermanager

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
args = parser.parse_args()
pvs.LoadPlugin(args.plugin, remote=False, ns=globals())

pm = servermanager.vtkProcessModule.GetProcessModule()
ranks = pm.GetNumberOfLocalPartitions()
rank = pm.GetPartitionId()
if ranks < 2:
    sys.exit("expected an MPI run of at least 2 processes, got %d" % ranks)

cloud = PointSetSurfaceCloudSource(Scene="Noisy Curve", NumberOfPoints=400, Noise=0.5)
cloud.UpdatePipeline()
# The source makes the whole cloud on rank 0 (its piece 0) and nothing on the others: rank 0 then
# holds a complete cloud, and a filter there could compute the right answer; it must refuse anyway.
if rank == 0 and cloud.GetDataInformation().GetNumberOfPoints() == 0:
    sys.exit("the cloud source gave no points on rank 0")
# A small depth frame (field data GridDimensions and Viewpoint): one process takes a scale per point.
frame = PointSetSurfaceCloudSource(Scene="Depth Camera", ImageWidth=64, ImageHeight=48)
sphere = PointSetSurfaceCloudSource(Scene="Sphere", NumberOfPoints=2000)
refused = 0
for name, proxy in (("sampler", PointSetSurfaceFieldSampler(Input=cloud, GenerateSamplingGrid=1,
                                                            OrientationMode="Propagate")),
                    ("projection", PointSetSurfaceProjection(Input=cloud, PropagateNormals=1)),
                    ("rimls ghosts", PointSetSurfaceProjection(Input=cloud, Variant="RIMLS (Robust Implicit MLS)",
                                                               GhostMargin=3.0)),
                    ("frame ghosts", PointSetSurfaceProjection(Input=frame, GhostMargin=3.0)),
                    ("trim ghosts", PointSetSurfaceMesh(Input=sphere, GhostMargin=3.0, TrimDistance=2.5))):
    proxy.UpdatePipeline()
    points = proxy.GetDataInformation().GetNumberOfPoints()
    if points != 0:
        sys.exit("%s: %d output points in a %d-process run: it should have refused" % (name, points, ranks))
    refused += 1
    if rank == 0:
        print("ok   %-12s refused in a %d-process run" % (name, ranks), flush=True)
if refused != 5:
    sys.exit("only %d of 5 filters checked" % refused)
# The frame itself is fine: with the gathered cloud (no ghost points) it is projected.
gathered = PointSetSurfaceProjection(Input=frame)
gathered.UpdatePipeline()
if rank == 0:
    if gathered.GetDataInformation().GetNumberOfPoints() == 0:
        sys.exit("the frame with the gathered cloud gave no points")
    print("ok   the frame runs with the gathered cloud", flush=True)
# Success ends the script normally: pvbatch then finalizes MPI on every rank (sys.exit would not).

"""One side of a distributed-versus-serial comparison (driven by test_mpi_distributed.py).

    pvbatch mpi_distributed_worker.py --plugin PointSetSurfaces.so --case DIR --out NAME
    mpiexec -np N pvbatch --symmetric mpi_distributed_worker.py ... (the same arguments)

Reads DIR/case.json (the cloud .pvtp, optional start points .pvtp, surface settings), applies the
projection, the domain classifier, the field sampler (probing the start points, or the cloud) and
the energy glyphs (at the start points, or the cloud) and the mesher (when the case has a
"ghost_margin": with GhostMargin set; each rank then prints its ghost rounds), and writes each rank's own output of each
filter to DIR/NAME_<filter>_<rank>.vtp (double coordinates, binary: bit-exact; no file for an
empty output; the glyphs' two outputs as `glyphs` and `fits`); and the sampler's own grid, each
rank's part of it, to DIR/NAME_grid_<rank>.vti. Ends normally (pvbatch then finalizes MPI on every rank); the driver judges the files
and the error messages.
"""
import argparse
import json
import os

import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter, vtkXMLPolyDataWriter

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--case", required=True)
parser.add_argument("--out", required=True)
args = parser.parse_args()
pvs.LoadPlugin(args.plugin, remote=False, ns=globals())

pm = servermanager.vtkProcessModule.GetProcessModule()
rank = pm.GetPartitionId()
with open(os.path.join(args.case, "case.json")) as f:
    case = json.load(f)

cloud = pvs.OpenDataFile(os.path.join(args.case, case["cloud"]))
inputs = {"Input": cloud}
if case.get("starts"):
    inputs["StartPoints"] = pvs.OpenDataFile(os.path.join(args.case, case["starts"]))
surface = case.get("surface", {})


def sampler(**kwargs):
    return PointSetSurfaceFieldSampler(Input=cloud, ComputeDomainLabels=1, **kwargs)


filters = (
    ("projection", lambda: PointSetSurfaceProjection(**inputs)),
    ("classifier", lambda: PointSetSurfaceDomainClassifier(**inputs)),
    ("sampler", lambda: sampler(Probe=inputs.get("StartPoints", cloud))),
    ("grid", lambda: sampler(GenerateSamplingGrid=1, SampleDimensions=[13, 11, 9])),
    ("glyphs", lambda: PointSetSurfaceEnergyGlyphs(Input=cloud, SamplePoints=inputs.get("StartPoints", cloud),
                                                   Resolution=8)),
    ("mesh", lambda: PointSetSurfaceMesh(Input=cloud)),
)
ghost_margin = case.get("ghost_margin")  # ghost-point runs
for name, make in filters:
    proxy = make()
    for key, value in surface.items():
        setattr(proxy, key, value)
    if ghost_margin is not None:
        proxy.GhostMargin = ghost_margin
    proxy.UpdatePipeline()
    rounds = proxy.GetClientSideObject().GetOutputDataObject(0).GetFieldData().GetArray("GhostRounds")
    if rounds is not None:
        print("rank %d: %s ghost rounds %d" % (rank, name, rounds.GetValue(0)), flush=True)
    for port, output_name in enumerate(("glyphs", "fits") if name == "glyphs" else (name,)):
        output = proxy.GetClientSideObject().GetOutputDataObject(port)
        if output.GetNumberOfPoints() == 0:
            continue  # no file: VTK's reader complains about a piece without points
        writer = vtkXMLImageDataWriter() if name == "grid" else vtkXMLPolyDataWriter()
        writer.SetInputData(output)
        writer.SetFileName(os.path.join(args.case, "%s_%s_%d.%s" % (
            args.out, output_name, rank, "vti" if name == "grid" else "vtp")))
        writer.Write()

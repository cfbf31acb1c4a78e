"""One side of a distributed-versus-serial comparison (driven by test_mpi_distributed.py).

    pvbatch mpi_distributed_worker.py --plugin PointSetSurfaces.so --case DIR --out NAME
    mpiexec -np N pvbatch --symmetric mpi_distributed_worker.py ... (the same arguments)

Reads DIR/case.json (the cloud .pvtp, optional start points .pvtp, surface settings), applies the
projection and the domain classifier, and writes each rank's own output of each filter to
DIR/NAME_<filter>_<rank>.vtp (double coordinates, binary: bit-exact; no file for an empty
output). Ends normally (pvbatch then finalizes MPI on every rank); the driver judges the files
and the error messages.
"""
import argparse
import json
import os

import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

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
for name, make in (("projection", PointSetSurfaceProjection), ("classifier", PointSetSurfaceDomainClassifier)):
    proxy = make(**inputs)
    for key, value in case.get("surface", {}).items():
        setattr(proxy, key, value)
    proxy.UpdatePipeline()
    output = proxy.GetClientSideObject().GetOutputDataObject(0)
    if output.GetNumberOfPoints() == 0:
        continue  # no file: VTK's reader complains about a piece without points
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(output)
    writer.SetFileName(os.path.join(args.case, "%s_%s_%d.vtp" % (args.out, name, rank)))
    writer.Write()

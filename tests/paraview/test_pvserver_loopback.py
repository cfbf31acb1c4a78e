"""The projection on a 2-rank pvserver over loopback, driven from pvpython (ctest
ParaView.Mpi.PvserverLoopback):

    pvpython test_pvserver_loopback.py --plugin PointSetSurfaces.so --pvserver pvserver
        --mpiexec mpiexec --workdir DIR

Writes a noisy sphere (2000 points) as a .pvtp of two slabs, projects it in pvpython's own
(built-in, one-process) session, then starts `mpiexec -np 2 pvserver` on a free local port,
Connect()s, loads the plugin on the server, applies the same pipeline there and fetches the
result: it must hold every point once (GlobalPointIds) with every array and position bitwise equal
to the one-process run, and h identical. Exits 0 on success, 1 with the reason.
"""
import argparse
import os
import shutil
import socket
import subprocess
import sys
import time

import numpy as np
import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--pvserver", required=True)
parser.add_argument("--mpiexec", required=True)
parser.add_argument("--workdir", required=True)
args = parser.parse_args()


def write_cloud(directory):
    rng = np.random.default_rng(5)
    v = rng.normal(size=(2000, 3))
    xyz = v / np.linalg.norm(v, axis=1)[:, None] * (1 + 0.02 * rng.normal(size=(2000, 1)))
    sources = []
    for p, sel in enumerate((xyz[:, 0] < 0.1, xyz[:, 0] >= 0.1)):
        points = vtkPoints()
        points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[sel]), deep=1))
        poly = vtkPolyData()
        poly.SetPoints(points)
        writer = vtkXMLPolyDataWriter()
        writer.SetInputData(poly)
        writer.SetFileName(os.path.join(directory, "sphere_%d.vtp" % p))
        writer.Write()
        sources.append('    <Piece Source="sphere_%d.vtp"/>' % p)
    path = os.path.join(directory, "sphere.pvtp")
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0" byte_order="LittleEndian" '
                'header_type="UInt64">\n  <PPolyData GhostLevel="0">\n'
                '    <PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>\n'
                + "\n".join(sources) + "\n  </PPolyData>\n</VTKFile>\n")
    return path


def project(path, remote):
    pvs.LoadPlugin(args.plugin, remote=remote, ns=globals())
    cloud = pvs.OpenDataFile(path)
    proxy = PointSetSurfaceProjection(Input=cloud)  # noqa: F821 (defined by LoadPlugin)
    proxy.UpdatePipeline()
    data = servermanager.Fetch(proxy)
    out = {"Points": vtk_to_numpy(data.GetPoints().GetData()).copy()}
    pd = data.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        out[pd.GetArrayName(i)] = vtk_to_numpy(pd.GetArray(i)).copy()
    out["h"] = data.GetFieldData().GetArray("ScaleFactor").GetValue(0)
    return out


def main():
    directory = os.path.join(args.workdir, "pvserver-loopback")
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    path = write_cloud(directory)
    serial = project(path, remote=False)

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    # pvpython is itself an MPI singleton: its OpenMPI/PMIx variables would make mpiexec's ranks
    # join it instead of starting their own world.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_", "PRTE_"))}
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    server = subprocess.Popen([args.mpiexec, "--oversubscribe", "-np", "2", args.pvserver, "--server-port=%d" % port],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        connection = None
        for _ in range(60):
            if server.poll() is not None:
                sys.exit("pvserver ended with status %d before accepting a connection" % server.returncode)
            time.sleep(1)
            try:
                connection = pvs.Connect("localhost", port)
            except Exception:
                connection = None
            if connection:
                break
        if not connection:
            sys.exit("could not connect to the 2-rank pvserver on port %d" % port)
        ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
        if ranks != 2:
            sys.exit("the server has %d ranks, expected 2" % ranks)
        parallel = project(path, remote=True)
        pvs.Disconnect()
    finally:
        # pvserver ends when its client disconnects; stop it only if it did not.
        try:
            server.wait(timeout=5)
        except subprocess.TimeoutExpired:
            server.terminate()
            server.wait(timeout=30)

    problems = []
    n = len(serial["Points"])
    ids = parallel.get("GlobalPointIds")
    if ids is None or len(ids) != n or not np.array_equal(np.sort(ids), np.arange(n)):
        sys.exit("FAIL: the fetched output does not hold each of the %d points once" % n)
    order = np.argsort(ids)
    if parallel["h"] != serial["h"]:
        problems.append("h %r on the server, %r in one process" % (parallel["h"], serial["h"]))
    for key, a in serial.items():
        if key == "h":
            continue
        b = parallel[key][order]
        same = np.array_equal(a.view(np.int64), b.view(np.int64)) if a.dtype == np.float64 else np.array_equal(a, b)
        if not same:
            problems.append("%s differs from the one-process run" % key)
    for p in problems:
        print("FAIL:", p)
    if not problems:
        print("ok   2-rank pvserver: %d points, %d arrays bitwise equal to one process, h = %.17g"
              % (n, len(serial) - 2, serial["h"]))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

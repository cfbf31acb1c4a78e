"""pvpython: load the installed ParaView plugin from its install prefix and run one of its proxies.

Checks that LoadPlugin() on the installed PointSetSurfaces.so works, that the module library it
pulls in (libPointSetSurfacesFilters.so) is the installed one (through the plugin's RUNPATH, not
the build tree), and that a synthetic sphere projected by the plugin's proxy lands on the sphere.
Exit status 0 on success, 1 on failure.
"""
import argparse
import math
import os
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="the installed PointSetSurfaces.so")
    parser.add_argument("--prefix", required=True, help="the install prefix")
    args = parser.parse_args()
    if not os.path.isfile(args.plugin):
        fail("no installed plugin at " + args.plugin)

    proxies = {"__name__": "installed_plugin"}  # non-empty: LoadPlugin ignores an empty namespace
    LoadPlugin(args.plugin, remote=False, ns=proxies)
    prefix = os.path.realpath(args.prefix)
    with open("/proc/self/maps") as maps:
        loaded = {line.split()[-1] for line in maps if "PointSetSurfaces" in line}
    module = sorted(path for path in loaded if os.path.basename(path).startswith("libPointSetSurfacesFilters"))
    if not module:
        fail("libPointSetSurfacesFilters was not loaded with the plugin")
    for path in module:
        if not os.path.realpath(path).startswith(prefix + os.sep):
            fail("the module library came from %s, not from the install prefix %s" % (path, prefix))
    for name in ("PointSetSurfaceCloudSource", "PointSetSurfaceProjection"):
        if name not in proxies:
            fail("the plugin did not register the %s proxy" % name)

    # A noisy sphere of radius 10, projected with the centre-of-mass definition: every point
    # converges and the cloud comes closer to the sphere.
    source = proxies["PointSetSurfaceCloudSource"](Scene="Sphere", Dimension="3D", NumberOfPoints=6000, Size=20,
                                                   Noise=0.3, Seed=5)
    projection = proxies["PointSetSurfaceProjection"](Input=source, Variant="Center of Mass", AutomaticScale=0,
                                                      ScaleFactor=1.0)
    cloud = servermanager.Fetch(source)
    projected = servermanager.Fetch(projection)

    def mean_distance(data):
        total = 0.0
        for i in range(data.GetNumberOfPoints()):
            x, y, z = data.GetPoint(i)
            total += abs(math.sqrt(x * x + y * y + z * z) - 10.0)
        return total / max(1, data.GetNumberOfPoints())

    if projected is None or projected.GetNumberOfPoints() != cloud.GetNumberOfPoints() or cloud.GetNumberOfPoints() != 6000:
        fail("the projection did not return one point per cloud point")
    converged = projected.GetPointData().GetArray("Converged")
    if converged is None or any(converged.GetTuple1(i) != 1 for i in range(converged.GetNumberOfTuples())):
        fail("not every projection converged")
    before, after = mean_distance(cloud), mean_distance(projected)
    if not after < 0.5 * before:
        fail("projected cloud not closer to the sphere: %.4f -> %.4f" % (before, after))
    print("loaded %s; module %s; mean distance to the sphere %.4f -> %.4f" % (args.plugin, ", ".join(module), before, after))
    return 0


if __name__ == "__main__":
    sys.exit(main())

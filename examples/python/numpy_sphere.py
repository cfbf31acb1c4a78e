#!/usr/bin/env python3
"""A noisy sphere from numpy -> pointsetsurfaces.mesh -> counts, and the same cloud projected.

The numpy face of the package: no VTK object in sight. Runs in Debian's python3 and in pvpython,
with the package on PYTHONPATH (build tree or install prefix):

    PYTHONPATH=build/lib/python3.11/site-packages python3 examples/python/numpy_sphere.py
    PYTHONPATH=build/lib/python3.11/site-packages pvpython examples/python/numpy_sphere.py

--check makes the exit status 1 unless the mesh is one closed piece (Euler characteristic 2)
whose vertices all lie within 3% of the true radius, and the projected points' radii spread less
than the cloud's.
"""
import argparse
import sys

import numpy as np

import pointsetsurfaces as pss


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--points", type=int, default=5000, help="points on the sphere (default 5000)")
    parser.add_argument("--radius", type=float, default=10.0, help="radius of the sphere (default 10)")
    parser.add_argument("--noise", type=float, default=0.002, help="radial noise, relative to the radius")
    parser.add_argument("--variant", default="com", choices=pss.VARIANTS, help="surface definition (default com)")
    parser.add_argument("--threads", type=int, default=0, help="worker threads (default 0: every core)")
    parser.add_argument("--check", action="store_true", help="exit 1 unless the mesh is the sphere")
    args = parser.parse_args()

    rng = np.random.default_rng(7)
    directions = rng.normal(size=(args.points, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    cloud = args.radius * directions * (1.0 + args.noise * rng.normal(size=(args.points, 1)))

    def report(fraction):
        # Called with increasing fractions, the last 1.0; print every quarter.
        if int(fraction * 4) > report.quarter:
            report.quarter = int(fraction * 4)
            print("  mesh %3.0f%%" % (100 * fraction), flush=True)

    report.quarter = 0
    surface = pss.mesh(cloud, variant=args.variant, threads=args.threads, progress=report)
    radius = np.linalg.norm(surface.vertices, axis=1)
    info = surface.info
    print("cloud: %d points, h = %.4g (automatic)" % (len(cloud), info["h"]))
    print("mesh:  %d vertices, %d triangles, %d piece(s), %d boundary edges, Euler characteristic %d"
          % (len(surface.vertices), len(surface.triangles), info["Components"], info["BoundaryEdges"],
             info["EulerCharacteristic"]))
    print("       vertex radius %.4f .. %.4f (true radius %g)" % (radius.min(), radius.max(), args.radius))

    # Projection smooths the noise away (a narrower spread of radii) and, like every MLS surface of
    # a curved cloud, sits slightly inside it (about h^2 / R).
    projected = pss.project(cloud, variant=args.variant, threads=args.threads)
    converged = np.count_nonzero(projected.StopReason == 0)
    before = np.linalg.norm(cloud, axis=1)
    after = np.linalg.norm(projected.points, axis=1)
    print("project: %d of %d points converged in %.1f iterations on average" % (converged, len(cloud),
                                                                                 projected.Iterations.mean()))
    print("         radius %.4f +- %.4f before, %.4f +- %.4f after" % (before.mean(), before.std(), after.mean(),
                                                                        after.std()))

    if args.check:
        failures = []
        if info["EulerCharacteristic"] != 2 or info["Components"] != 1 or info["BoundaryEdges"] != 0:
            failures.append("the mesh is not one closed piece of Euler characteristic 2")
        if np.abs(radius - args.radius).max() > 0.03 * args.radius:
            failures.append("a vertex is more than 3% off the radius")
        if not after.std() < before.std():
            failures.append("the projected points are not smoother than the cloud")
        for failure in failures:
            print("FAIL:", failure)
        return 1 if failures else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())

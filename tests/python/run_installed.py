"""Imports `pointsetsurfaces` from an install prefix (PYTHONPATH points into it), checks that the
package and the module library it loads come from that prefix, then runs the example given with
the arguments after `--`. Exit status 0 on success, 1 on failure."""
import argparse
import os
import runpy
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--prefix", required=True)
    parser.add_argument("--example", required=True)
    parser.add_argument("rest", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    prefix = os.path.realpath(args.prefix) + os.sep

    import pointsetsurfaces
    from pointsetsurfaces import vtkPointSetSurfaceProjection  # noqa: F401

    if not os.path.realpath(pointsetsurfaces.__file__).startswith(prefix):
        print("FAIL: pointsetsurfaces came from %s, not from %s" % (pointsetsurfaces.__file__, prefix))
        return 1
    with open("/proc/self/maps") as maps:
        libraries = sorted({line.split()[-1] for line in maps if "libPointSetSurfacesFilters" in line})
    if not libraries or any(not os.path.realpath(path).startswith(prefix) for path in libraries):
        print("FAIL: the module library was loaded from %s, not from %s" % (libraries, prefix))
        return 1
    print("pointsetsurfaces from %s; module library %s" % (os.path.dirname(pointsetsurfaces.__file__), libraries[0]))

    from vtkmodules.vtkCommonCore import vtkSMPTools

    if "VTK_SMP_BACKEND_IN_USE" not in os.environ and vtkSMPTools.GetBackend() != "STDThread":
        print("FAIL: importing pointsetsurfaces left vtkSMPTools on %s, not STDThread" % vtkSMPTools.GetBackend())
        return 1

    rest = [a for a in args.rest if a != "--"]
    sys.argv = [args.example] + rest
    try:
        runpy.run_path(args.example, run_name="__main__")
    except SystemExit as done:
        return done.code or 0
    return 0


if __name__ == "__main__":
    sys.exit(main())

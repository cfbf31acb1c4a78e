"""Run a pvpython example under xvfb-run with pvbatch and check the PNG it saves.

    pvpython run_example.py --xvfb-run xvfb-run --pvbatch pvbatch --example EXAMPLE.py
        --plugin PointSetSurfaces.so --output out.png --size 800x600
        [--min-std 20] [--colour NAME:R,G,B:MIN_PIXELS ...] [--timeout 120] [--skip-unless FILE]
        [-- EXAMPLE ARGS]

Fails unless: pvbatch exits with 0; the PNG exists and is newer than the start of the run; it
has exactly the requested size; the standard deviation of its luminance is at least --min-std
(a blank or single-colour image has about 0); and, for each --colour, at least MIN_PIXELS pixels
lie within 60 (Euclidean RGB distance) of R,G,B, i.e. the things drawn in that colour were drawn.
Prints the measured numbers. With --skip-unless FILE, exits with 77 (ctest's SKIP_RETURN_CODE for
these tests) without running anything when FILE is absent (data that is not always there).
"""
import argparse
import os
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pss_xvfb  # noqa: E402


def colour(text):
    name, rgb, count = text.split(":")
    return name, np.array([float(v) for v in rgb.split(",")]), int(count)


parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--xvfb-run", required=True)
parser.add_argument("--pvbatch", required=True)
parser.add_argument("--example", required=True)
parser.add_argument("--plugin", required=True)
parser.add_argument("--output", required=True)
parser.add_argument("--size", required=True)
parser.add_argument("--min-std", type=float, default=20.0)
parser.add_argument("--colour", type=colour, action="append", default=[])
parser.add_argument("--timeout", type=int, default=120)
parser.add_argument("--skip-unless", help="skip (exit status 77) when this file is absent")
parser.add_argument("extra", nargs="*", help="more arguments for the example (after --)")
args = parser.parse_args()

if args.skip_unless and not os.path.isfile(args.skip_unless):
    print("SKIP: %s is absent" % args.skip_unless)
    sys.exit(77)
width, height = (int(v) for v in args.size.split("x"))
if os.path.exists(args.output):
    os.remove(args.output)
os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
started = time.time()
status, output = pss_xvfb.run(args.xvfb_run, [args.pvbatch, args.example, "--plugin", args.plugin,
                                              "--output", args.output, "--size", args.size] + args.extra,
                              timeout=args.timeout)
print(output.strip())
print("pvbatch exit status %d after %.1f s" % (status, time.time() - started))
failures = []
if status != 0:
    failures.append("pvbatch exited with %d" % status)
if not os.path.isfile(args.output):
    failures.append("no PNG at %s" % args.output)
else:
    if os.path.getmtime(args.output) < started - 1:
        failures.append("%s is older than this run" % args.output)
    reader = vtkPNGReader()
    reader.SetFileName(args.output)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(np.float64)
    rgb = pixels[:, :3] if pixels.ndim == 2 and pixels.shape[1] >= 3 else np.repeat(pixels.reshape(-1, 1), 3, axis=1)
    luminance = rgb @ np.array([0.2126, 0.7152, 0.0722])
    std = float(luminance.std())
    distinct = len(np.unique(rgb.astype(np.uint32) @ np.array([65536, 256, 1])))
    print("%s: %d x %d pixels, %d bytes, luminance mean %.1f std %.1f, %d distinct colours" % (
        args.output, w, h, os.path.getsize(args.output), luminance.mean(), std, distinct))
    if (w, h) != (width, height):
        failures.append("image is %d x %d, requested %d x %d" % (w, h, width, height))
    if std < args.min_std:
        failures.append("luminance std %.2f below %.2f: blank image?" % (std, args.min_std))
    for name, target, minimum in args.colour:
        n = int(np.count_nonzero(np.linalg.norm(rgb - target, axis=1) < 60.0))
        print("  %-10s pixels near RGB %s: %d (need %d)" % (name, target.astype(int).tolist(), n, minimum))
        if n < minimum:
            failures.append("only %d %s pixels (need %d)" % (n, name, minimum))
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)

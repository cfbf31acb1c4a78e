#!/usr/bin/env python3
"""Stanford bunny -> projection -> domain classifier -> VTK XML file, from Python, with progress.

The Python face of the VTK module: vtkPointSetSurfaceProjection and
vtkPointSetSurfaceDomainClassifier (package ``pointsetsurfaces``) in one pipeline with stock
``vtkmodules`` classes (vtkPLYReader, vtkMaskPoints, vtkXMLPolyDataWriter), and a ProgressEvent
observer on each of ours. Runs in Debian's python3 (next to python3-paraview's vtkmodules) and in
pvpython, with the package on PYTHONPATH (build tree or install prefix):

    PYTHONPATH=build/lib/python3.11/site-packages python3 examples/python/bunny_pipeline.py -o bunny.vtp
    PYTHONPATH=build/lib/python3.11/site-packages pvpython examples/python/bunny_pipeline.py -o bunny.vtp

Input: the merged Stanford bunny scans (../shared/data/stanford-bunny/bunny_scans_merged.ply beside
the repository, or --input FILE.ply); when absent, or with --synthetic, a noisy sphere from
vtkPointSetSurfaceCloudSource. --max-points keeps about that many points (vtkMaskPoints, evenly).
The cloud's points are projected onto the centre-of-mass surface (automatic h), then the projected
points are classified against the same cloud (DomainLabel: 0 InDomain, 1 Spurious, 2 Undefined,
3 NotConverged) and written with every array. With --check the exit status is 1 unless progress
reached 1 in both filters, every point was labelled and at least --min-in-domain of them are InDomain.
"""
import argparse
import os
import sys

from vtkmodules.vtkFiltersCore import vtkMaskPoints
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

from pointsetsurfaces import (vtkPointSetSurfaceCloudSource, vtkPointSetSurfaceDomainClassifier,
                              vtkPointSetSurfaceProjection)

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_BUNNY = os.path.join(HERE, "..", "..", "..", "shared", "data", "stanford-bunny", "bunny_scans_merged.ply")
LABELS = ("InDomain", "Spurious", "Undefined", "NotConverged")


def progress_observer(name, seen):
    """A ProgressEvent observer that prints every 25% and records the last value in seen[name]."""
    seen[name] = 0.0

    def observe(caller, _event):
        progress = caller.GetProgress()
        if int(progress * 4) > int(seen[name] * 4) or progress >= 1.0 > seen[name]:
            print("  %-10s %3.0f%%" % (name, 100.0 * progress), flush=True)
        seen[name] = max(seen[name], progress)

    return observe


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--input", default=DEFAULT_BUNNY, help="a .ply point cloud (default: the merged bunny scans)")
    parser.add_argument("--synthetic", action="store_true", help="use a noisy sphere even if the bunny is there")
    parser.add_argument("--require-input", action="store_true",
                        help="exit 77 (skipped) instead of using the sphere when --input is absent")
    parser.add_argument("--max-points", type=int, default=20000, help="keep about this many points (0: all)")
    parser.add_argument("-o", "--output", default="bunny_classified.vtp", help="the .vtp file to write")
    parser.add_argument("--check", action="store_true", help="exit 1 unless the checks above hold")
    parser.add_argument("--min-in-domain", type=float, default=0.9, help="fraction InDomain --check wants")
    args = parser.parse_args()

    if args.require_input and not os.path.isfile(args.input):
        print("skipped: %s is absent" % args.input)
        return 77
    if not args.synthetic and os.path.isfile(args.input):
        print("input: %s" % os.path.normpath(args.input))
        source = vtkPLYReader()
        source.SetFileName(args.input)
    else:
        print("input: a noisy sphere of radius 50 (vtkPointSetSurfaceCloudSource)")
        source = vtkPointSetSurfaceCloudSource()
        source.SetSceneToSphere()
        source.SetDimension(3)
        source.SetSize(100.0)
        source.SetNoise(0.5)
        source.SetNumberOfPoints(max(args.max_points, 1000))
    source.Update()
    total = source.GetOutput().GetNumberOfPoints()

    # vtkmodules' own filter in the middle of the pipeline: an even subsample, as vertices.
    mask = vtkMaskPoints()
    mask.SetInputConnection(source.GetOutputPort())
    mask.SetOnRatio(max(1, total // args.max_points) if args.max_points > 0 else 1)
    mask.SetMaximumNumberOfPoints(total)
    mask.GenerateVerticesOn()
    mask.SingleVertexPerCellOn()

    seen = {}
    projection = vtkPointSetSurfaceProjection()
    projection.SetInputConnection(mask.GetOutputPort())
    projection.GetSurface().SetVariantToCenterOfMass()
    projection.AddObserver("ProgressEvent", progress_observer("projection", seen))

    classifier = vtkPointSetSurfaceDomainClassifier()
    classifier.SetInputConnection(0, mask.GetOutputPort())
    classifier.SetStartPointsConnection(projection.GetOutputPort())
    classifier.GetSurface().SetVariantToCenterOfMass()
    classifier.AddObserver("ProgressEvent", progress_observer("classifier", seen))

    writer = vtkXMLPolyDataWriter()
    writer.SetInputConnection(classifier.GetOutputPort())
    writer.SetFileName(args.output)
    print("projecting and classifying about %d of %d points" % (total // max(1, mask.GetOnRatio()), total))
    if not writer.Write():
        print("FAIL: could not write %s" % args.output)
        return 1

    output = classifier.GetOutput()
    labels = output.GetPointData().GetArray("DomainLabel")
    counts = [0] * len(LABELS)
    for i in range(labels.GetNumberOfTuples() if labels else 0):
        counts[int(labels.GetTuple1(i))] += 1
    h = output.GetFieldData().GetArray("ScaleFactor")
    print("h = %s; %s; written to %s" % (
        "%.4g" % h.GetTuple1(0) if h else "?",
        ", ".join("%s %d" % (name, count) for name, count in zip(LABELS, counts)), args.output))

    if args.check:
        problems = []
        for name in ("projection", "classifier"):
            if seen.get(name, 0.0) < 1.0:
                problems.append("%s progress stopped at %.2f" % (name, seen.get(name, 0.0)))
        n = output.GetNumberOfPoints()
        if labels is None or n == 0 or labels.GetNumberOfTuples() != n:
            problems.append("not every point has a DomainLabel")
        elif counts[0] < args.min_in_domain * n:
            problems.append("only %d of %d points InDomain" % (counts[0], n))
        for problem in problems:
            print("FAIL: " + problem)
        if problems:
            return 1
        print("checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

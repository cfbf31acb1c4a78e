"""The plugin's PCD reader and writer in pvpython: File > Open's reader factory picks the reader
for .pcd, Save Data's writer factory the writer.

    pvpython test_pcd_reader.py --plugin PointSetSurfaces.so --pss build/bin/pss --workdir DIR
                                [--real-scans shared/data/real-scans]

Checks: a sphere written as .pcd by the pss tool opens through OpenDataFile with the PCDReader
proxy and has every point; saved again with SaveData (ASCII, binary, binary compressed) and
reopened it has the same coordinates; each file of the real-scans folder, when it is there, opens
with the PCDReader, its kept and skipped points add up to the header's POINTS, the organized ones
are 640 x 480 with a Viewpoint. Exit status 0 on success, 1 with a message per failure.
"""
import argparse
import os
import subprocess
import sys

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", required=True)
parser.add_argument("--pss", required=True)
parser.add_argument("--workdir", required=True)
parser.add_argument("--real-scans", default="")
args = parser.parse_args()

import paraview.simple as pvs  # noqa: E402
from paraview import servermanager  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def header_points(path):
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("ascii", "replace").strip()
            if line.startswith("POINTS "):
                return int(line.split()[1])
            if line.startswith("DATA"):
                break
    return -1


def open_pcd(path):
    reader = pvs.OpenDataFile(path)
    check(reader is not None and reader.GetXMLName() == "PCDReader",
          "%s: File > Open chose %s, not the PCDReader" % (path, reader.GetXMLName() if reader else None))
    data = servermanager.Fetch(reader)
    return reader, data


def field_value(data, name, index=0):
    array = data.GetFieldData().GetArray(name)
    return None if array is None else array.GetComponent(index, 0)


pvs.LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.workdir, exist_ok=True)

# A cloud written by the pss tool, opened and saved again in each DATA kind.
sphere = os.path.join(args.workdir, "sphere.pcd")
subprocess.run([args.pss, "generate", "--scene", "sphere", "--count", "500", "--size", "10", "-o", sphere], check=True)
reader, data = open_pcd(sphere)
check(data.GetNumberOfPoints() == 500, "sphere.pcd: %d points, expected 500" % data.GetNumberOfPoints())
for mode, label in ((0, "ascii"), (1, "binary"), (2, "compressed")):
    again = os.path.join(args.workdir, "sphere-%s.pcd" % label)
    pvs.SaveData(again, proxy=reader, DataMode=mode)
    with open(again, "rb") as f:
        text = f.read(400).decode("ascii", "replace")
    kind = {0: "DATA ascii", 1: "DATA binary\n", 2: "DATA binary_compressed"}[mode]
    check(kind in text, "%s: SaveData did not write '%s'" % (again, kind.strip()))
    _, back = open_pcd(again)
    same = back.GetNumberOfPoints() == 500 and all(
        back.GetPoint(i) == data.GetPoint(i) for i in range(0, 500, 7))
    check(same, "%s: the points read back differ from the ones saved" % again)

# The real frames, when the shared data is beside the clone.
if args.real_scans and os.path.isdir(args.real_scans):
    for name in sorted(os.listdir(args.real_scans)):
        if not name.endswith(".pcd"):
            continue
        path = os.path.join(args.real_scans, name)
        reader, data = open_pcd(path)
        points = header_points(path)
        skipped = field_value(data, "SkippedPoints")
        kept = data.GetNumberOfPoints()
        print("%s: POINTS %d, %d read, %s NaN skipped" % (name, points, kept, skipped))
        check(skipped is not None and kept + skipped == points, "%s: %d + %s points, header says %d" % (name, kept, skipped, points))
        check(field_value(data, "Viewpoint") is not None, "%s: no Viewpoint" % name)
        height = field_value(data, "GridDimensions", 1)
        if height and height > 1:
            check((field_value(data, "GridDimensions", 0), height) == (640, 480), "%s: not 640 x 480" % name)
            check(data.GetPointData().GetArray("Pixel") is not None, "%s: no Pixel array" % name)
else:
    print("real scans skipped: no folder %r (the shared data is not beside this clone)" % args.real_scans)

sys.exit(1 if failures else 0)

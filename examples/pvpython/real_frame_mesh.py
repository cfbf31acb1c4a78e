"""A depth-camera frame (a PCD file) and its point-set surface mesh side by side, in ParaView, seen
from the sensor.

    pvbatch examples/pvpython/real_frame_mesh.py [--plugin PATH] [--output real_frame.png]
            [--size 1600x640] [--frame ../shared/data/real-scans/test9.pcd] [--variant com]

(under xvfb-run on a machine without a display: `xvfb-run -a pvbatch ...`.)

File > Open's reader for .pcd (the plugin's PCD reader) reads the frame: its finite points with
their colours, the image's size and the sensor's VIEWPOINT. Point Set Surface Mesh runs with every
default (a scale per point for a sensor frame: docs/adaptive-scale.md). Both views look from the viewpoint towards the
cloud's centre, image rows downwards as the camera saw them: on the left the points in their own
colours, on the right the mesh coloured by Stability, with the counts a user checks first (points,
h, triangles, pieces, boundary edges) and the mesher's time in the titles.

Options:
  --plugin PATH   PointSetSurfaces.so or its folder (default: found as bunny_mesh.py finds it)
  --output FILE   the PNG (default real_frame.png)
  --size WxH      image size in pixels, both views together (default 1600x640)
  --frame FILE    the PCD frame (default ../shared/data/real-scans/test9.pcd, relative to this
                  source tree's root)
  --variant NAME  levin | normalized | com | integral | delta (default com)
"""
import argparse
import os
import sys
import time

import paraview.simple as pvs

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pss_example import TREE, VARIANTS, black_scalar_bar, find_plugin, parse_size, white_view  # noqa: E402
from paraview import servermanager  # noqa: E402


def field_value(data, name, index=0):
    array = data.GetFieldData().GetArray(name)
    return None if array is None else array.GetComponent(index, 0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin")
    parser.add_argument("--output", default="real_frame.png")
    parser.add_argument("--size", type=parse_size, default=[1600, 640])
    parser.add_argument("--frame", default=os.path.join(TREE, "..", "shared", "data", "real-scans", "test9.pcd"))
    parser.add_argument("--variant", choices=sorted(VARIANTS), default="com")
    args = parser.parse_args()
    if not os.path.isfile(args.frame):
        sys.exit("error: no frame %s (the shared data is not beside this clone)" % args.frame)

    plugin = find_plugin(args.plugin, "PointSetSurfaceMesh")
    if plugin:
        pvs.LoadPlugin(plugin, remote=False, ns=globals())
    mesher = getattr(pvs, "PointSetSurfaceMesh", None) or globals()["PointSetSurfaceMesh"]

    frame = pvs.OpenDataFile(args.frame)
    frame.UpdatePipeline()
    cloud = servermanager.Fetch(frame)
    npoints = cloud.GetNumberOfPoints()
    skipped = int(field_value(cloud, "SkippedPoints") or 0)
    viewpoint = [field_value(cloud, "Viewpoint", k) or 0.0 for k in range(3)]

    mesh = mesher(Input=frame, Variant=VARIANTS[args.variant])
    started = time.time()
    mesh.UpdatePipeline()
    seconds = time.time() - started
    data = servermanager.Fetch(mesh)
    triangles = data.GetNumberOfPolys()
    pieces, boundary = int(field_value(data, "Components") or 0), int(field_value(data, "BoundaryEdges") or 0)
    h = field_value(data, "ScaleFactor") or 0.0
    scale = ("a scale per point, median h = %.3g" if field_value(data, "PointScales") else "one automatic h = %.3g") % h

    layout = pvs.CreateLayout("Frame and mesh")
    layout.SplitHorizontal(0, 0.5)
    lut = pvs.GetColorTransferFunction("Stability")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    name = os.path.basename(args.frame)
    titles = [
        "%s: %s points (%s invalid pixels left out)" % (name, "{:,}".format(npoints), "{:,}".format(skipped)),
        "Point Set Surface Mesh, %s, %s\n%s triangles, %s pieces, %s boundary edges, %.1f s"
        % (VARIANTS[args.variant], scale, "{:,}".format(triangles), "{:,}".format(pieces), "{:,}".format(boundary), seconds),
    ]
    x0, x1, y0, y1, z0, z1 = cloud.GetBounds()
    centre = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
    for cell, title in zip((1, 2), titles):
        view = white_view(layout, cell)
        if cell == 1:
            # The points in their own colours; an RGBA frame's alpha (often 0) is left out.
            shown = frame
            if "RGBA" in frame.PointData.keys():
                # Floating-point colours drawn directly are read in [0, 1].
                shown = pvs.PythonCalculator(Input=frame, Expression="RGBA[:, 0:3] / 255.0", ArrayName="RGB")
            d = pvs.Show(shown, view)
            d.SetRepresentationType("Points")
            if "RGB" in shown.PointData.keys():
                pvs.ColorBy(d, ("POINTS", "RGB"))
                d.MapScalars = 0
            d.PointSize = 2.0
        else:
            d = pvs.Show(mesh, view)
            pvs.ColorBy(d, ("POINTS", "Stability"))
            d.LookupTable = lut
            d.SetScalarBarVisibility(view, True)
            bar = black_scalar_bar(lut, view, "Stability", [0.88, 0.1])
            bar.ScalarBarLength = 0.5
        t = pvs.Show(pvs.Text(Text=title), view)
        t.Color = [0, 0, 0]
        t.FontSize = 13
        t.WindowLocation = "Upper Center"
        # From the sensor towards the cloud, image rows downwards (a depth camera's y points down).
        view.CameraPosition = viewpoint
        view.CameraFocalPoint = centre
        view.CameraViewUp = [0, -1, 0]
        view.CameraViewAngle = 50
    layout.SetSize(*args.size)
    pvs.SaveScreenshot(args.output, layout, ImageResolution=args.size, TransparentBackground=0, CompressionLevel="9")
    print("%s: %s, %d points (%d invalid pixels), h = %.4g: %d triangles, %d pieces, %d boundary edges; mesher %.1f s"
          % (args.output, name, npoints, skipped, h, triangles, pieces, boundary, seconds))


if __name__ == "__main__":
    main()

"""The Stanford bunny's merged range scans and their point-set surface mesh side by side, in ParaView.

    pvbatch examples/pvpython/bunny_mesh.py [--plugin PATH] [--output bunny_mesh.png]
            [--size 1600x800] [--cloud ../shared/data/stanford-bunny/bunny_scans_merged.ply]
            [--synthetic] [--subsample K] [--variant com] [--h H] [--cell C] [--band B]

(under xvfb-run on a machine without a display: `xvfb-run -a pvbatch ...`; pvpython works too.)

Reads the cloud (a .ply, .vtp, .vtu, .csv or .xyz point file; by default the 362,272 merged bunny
scans of ../shared/data/stanford-bunny, next to this source tree), keeps every K-th point with
--subsample K, and runs Point Set Surface Mesh on it: the extremal surface extracted from a sparse
band of grid cells around the points, only where it is defined. Two views of one layout share one
camera: on the left the cloud (red points, darker farther from the camera: a dense cloud would
otherwise be a flat silhouette), on the right the mesh coloured by Stability (how
sharply the energy picks n: low where the surface bends fast compared with h or where the scans
are thin), with a colour bar. Each view's title gives the counts: points and h on the left;
triangles, pieces and boundary edges (holes of the scans, or the mesh stopping where the surface
is not defined) on the right.

When the cloud file is absent, or with --synthetic, a synthetic sphere (Point Set Surface Cloud
Source, 4,000 points, radius 50, noise 0.3) stands in for the bunny, so that the example runs
anywhere; it says so on stdout and in the title.

Options:
  --plugin PATH   PointSetSurfaces.so, or the folder that holds it. Default: nothing to load when
                  the plugin is already loaded through PV_PLUGIN_PATH; otherwise the first
                  PointSetSurfaces.so found in $PV_PLUGIN_PATH, then under lib/paraview-plugins/
                  of $PSS_BUILD_DIR, build/ or the newest build*/ folder of this source tree.
  --output FILE   the PNG (default bunny_mesh.png)
  --size WxH      image size in pixels, both views together (default 1600x800)
  --cloud FILE    the cloud (default ../shared/data/stanford-bunny/bunny_scans_merged.ply,
                  relative to this source tree's root)
  --synthetic     use the synthetic sphere even when the cloud file exists
  --plain-cloud   draw every cloud point dark red (no depth shading)
  --subsample K   keep every K-th point of the cloud (default 1: all of them)
  --variant NAME  levin | normalized | com | integral | delta (default com: the centre of mass,
                  fast and with a wide domain on smooth scans)
  --h H           Gaussian scale h in the cloud's units (default: automatic, from the spacing;
                  0.72 mm on the merged bunny scans)
  --cell C        the mesher's cell size, in h (default: the filter's, 1)
  --band B        how far from the cloud the mesher looks, in h (default: the filter's, 1)
"""
import argparse
import os
import sys
import time

import paraview.simple as pvs

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pss_example import TREE, VARIANTS, black_scalar_bar, find_plugin, parse_size, white_view  # noqa: E402 (after the path above)
from paraview import servermanager

DEFAULT_CLOUD = os.path.join("..", "shared", "data", "stanford-bunny", "bunny_scans_merged.ply")
CLOUD_COLOUR = [0.6, 0.1, 0.1]
# The cloud's depth shading, near to far: light red to the plain cloud's dark red to near black
# (no colour of Viridis, the mesh's map, is within reach of these).
DEPTH_COLOURS = [0.0, 1.0, 0.55, 0.5, 0.5, 0.6, 0.1, 0.1, 1.0, 0.25, 0.03, 0.03]



def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("expected a positive integer, got %r" % text)
    return value


def positive_float(text):
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError("expected a positive number, got %r" % text)
    return value



def read_cloud(filename):
    """A reader proxy for the cloud file, chosen by its extension."""
    ext = os.path.splitext(filename)[1].lower()
    if ext == ".ply":
        return pvs.PLYReader(FileNames=[filename])
    if ext == ".csv":
        table = pvs.CSVReader(FileName=[filename])
        return pvs.TableToPoints(Input=table, XColumn="x", YColumn="y", ZColumn="z")
    if ext == ".xyz":
        table = pvs.CSVReader(FileName=[filename], FieldDelimiterCharacters=" ", HaveHeaders=0)
        return pvs.TableToPoints(Input=table, XColumn="Field 0", YColumn="Field 1", ZColumn="Field 2")
    return pvs.OpenDataFile(filename)


def field_value(data, name):
    a = data.GetFieldData().GetArray(name)
    return a.GetValue(0) if a is not None else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin")
    parser.add_argument("--output", default="bunny_mesh.png")
    parser.add_argument("--size", type=parse_size, default=[1600, 800])
    parser.add_argument("--cloud", default=os.path.join(TREE, DEFAULT_CLOUD))
    parser.add_argument("--synthetic", action="store_true")
    parser.add_argument("--plain-cloud", action="store_true")
    parser.add_argument("--subsample", type=positive_int, default=1)
    parser.add_argument("--variant", choices=sorted(VARIANTS), default="com")
    parser.add_argument("--h", type=positive_float)
    parser.add_argument("--cell", type=positive_float)
    parser.add_argument("--band", type=positive_float)
    args = parser.parse_args()

    plugin = find_plugin(args.plugin, "PointSetSurfaceMesh")
    if plugin:
        pvs.LoadPlugin(plugin, remote=False, ns=globals())
    P = {name: getattr(pvs, name, None) or globals()[name]
         for name in ("PointSetSurfaceCloudSource", "PointSetSurfaceMesh")}

    # The cloud: the scans, or the synthetic sphere when they are absent. Mask Points keeps every
    # K-th point and gives each its own vertex cell (a .ply of bare points has none to draw).
    synthetic = args.synthetic or not os.path.isfile(args.cloud)
    if synthetic:
        if not args.synthetic:
            print("note: %s not found: meshing a synthetic sphere instead" % args.cloud, flush=True)
        raw = P["PointSetSurfaceCloudSource"](Scene="Sphere", Dimension="3D", NumberOfPoints=4000, Size=100.0, Noise=0.3)
        name = "synthetic sphere"
    else:
        raw = read_cloud(args.cloud)
        name = os.path.basename(args.cloud)
    cloud = pvs.MaskPoints(Input=raw, OnRatio=args.subsample, MaximumNumberofPoints=2**31 - 1, GenerateVertices=1,
                           SingleVertexPerCell=1, RandomSampling=0)
    cloud.UpdatePipeline()
    npoints = cloud.GetDataInformation().GetNumberOfPoints()
    if npoints == 0:
        sys.exit("error: no points in %s" % args.cloud)

    surface = dict(Variant=VARIANTS[args.variant])
    if args.h:
        surface.update(AutomaticScale=0, ScaleFactor=args.h)
    knobs = {}
    if args.cell:
        knobs["CellSize"] = args.cell
    if args.band:
        knobs["Band"] = args.band
    mesh = P["PointSetSurfaceMesh"](Input=cloud, **surface, **knobs)
    started = time.time()
    mesh.UpdatePipeline()
    seconds = time.time() - started
    data = servermanager.Fetch(mesh)
    triangles = data.GetNumberOfPolys()
    if triangles == 0:
        sys.exit("error: the mesher gave no triangles (see its error message above)")
    h = field_value(data, "ScaleFactor")
    pieces, boundary = int(field_value(data, "Components")), int(field_value(data, "BoundaryEdges"))
    x0, x1, y0, y1, z0, z1 = cloud.GetDataInformation().GetBounds()

    layout = pvs.CreateLayout("Cloud and mesh")
    layout.SplitHorizontal(0, 0.5)
    lut = pvs.GetColorTransferFunction("Stability")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    stability = mesh.PointData["Stability"].GetRange()
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(stability[0], stability[1])

    # The same camera in both views, looking along -z with y up (in the scans' frame, the bunny's
    # side), far enough for the bounding sphere; the mesh's view looks a little to the right so
    # that the colour bar has room.
    cx, cy, cz = (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2
    radius = 0.5 * ((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) ** 0.5
    direction = [0.13, 0.09, 0.99]  # from the focal point towards the camera

    # The points' distance along the view direction, for the depth shading of the cloud.
    depth = pvs.Calculator(Input=cloud, ResultArrayName="Depth",
                           Function="-(coordsX*%.17g + coordsY*%.17g + coordsZ*%.17g)" % tuple(direction))
    depth.UpdatePipeline()
    near, far = depth.PointData["Depth"].GetRange()
    far = near + 0.4 * (far - near)  # the visible points are the near ones: spend the colours there
    every = " (every %d-th)" % args.subsample if args.subsample > 1 else ""
    titles = [
        "%s: %s points%s\nh = %.3g (%s)" % (name, "{:,}".format(npoints), every, h, "given" if args.h else "automatic"),
        "Point Set Surface Mesh, %s, coloured by Stability\n%s triangles, %d piece%s, %s boundary edges"
        % (VARIANTS[args.variant], "{:,}".format(triangles), pieces, "" if pieces == 1 else "s", "{:,}".format(boundary)),
    ]
    for cell, title_text in zip((1, 2), titles):
        view = white_view(layout, cell)
        if cell == 1:
            d = pvs.Show(depth, view)
            d.SetRepresentationType("Points")
            d.AmbientColor = d.DiffuseColor = CLOUD_COLOUR
            if args.plain_cloud:
                d.ColorArrayName = ["POINTS", ""]
            else:
                pvs.ColorBy(d, ("POINTS", "Depth"))
                depth_lut = pvs.GetColorTransferFunction("Depth")
                depth_lut.AutomaticRescaleRangeMode = "Never"
                depth_lut.RGBPoints = [near + t * (far - near) if i % 4 == 0 else t
                                       for i, t in enumerate(DEPTH_COLOURS)]
                d.LookupTable = depth_lut
                d.SetScalarBarVisibility(view, False)
            d.PointSize = 1.0 if npoints > 10000 else 2.0
        else:
            d = pvs.Show(mesh, view)
            d.SetRepresentationType("Surface")
            pvs.ColorBy(d, ("POINTS", "Stability"))
            d.LookupTable = lut
            d.Specular = 0.3
            d.SetScalarBarVisibility(view, True)
            bar = black_scalar_bar(lut, view, "Stability", [0.86, 0.1])
            bar.TitleFontSize = bar.LabelFontSize = 13
            bar.AutomaticLabelFormat = 0
            bar.LabelFormat = bar.RangeLabelFormat = "%.2f"
            bar.ScalarBarLength = 0.5
        t = pvs.Show(pvs.Text(Text=title_text), view)
        t.Color = [0, 0, 0]
        t.FontSize = 13
        t.WindowLocation = "Upper Center"
        focal = [cx + (0.0 if cell == 1 else 0.08 * radius), cy, cz]
        view.CameraFocalPoint = focal
        view.CameraPosition = [f + 3.3 * radius * u for f, u in zip(focal, direction)]
        view.CameraViewUp = [0, 1, 0]
        view.CameraViewAngle = 30

    layout.SetSize(*args.size)
    pvs.SaveScreenshot(args.output, layout, ImageResolution=args.size, TransparentBackground=0, CompressionLevel="9")
    print("%s: %s, %d points, %s, h = %.4g: %d vertices, %d triangles, %d piece(s), %d boundary edges, "
          "%d non-manifold edges, Stability %.3g..%.3g; mesher %.1f s"
          % (args.output, name, npoints, VARIANTS[args.variant], h, data.GetNumberOfPoints(), triangles, pieces,
             boundary, int(field_value(data, "NonManifoldEdges")), stability[0], stability[1], seconds))


if __name__ == "__main__":
    main()

"""A noisy curve projected by two surface definitions side by side, with the projection lines
(Figure 1 of Amenta & Kil, "The Domain of a Point Set Surface"), in ParaView.

    pvbatch examples/pvpython/noisy_curve_two_variants.py [--plugin PATH]
            [--output noisy_curve_two_variants.png] [--size 1600x600] [--variants levin,com]
            [--h 5] [--count 600] [--noise 6] [--max-travel 100]

(under xvfb-run on a machine without a display: `xvfb-run -a pvbatch ...`; pvpython works too.)

The cloud is the pss-domain-demo's: --count points of an open sine arc of length 200 whose
density falls and whose noise grows along it, from --noise/5 to --noise, so that towards its right
end the noise exceeds h. Every cloud point is projected (Point Set Surface Projection, Generate
Projection Lines on) by each of two definitions, shown in two views of one layout: the cloud in
black, each start-to-end segment coloured by StopReason (blue: converged; orange, purple, teal:
iteration limit, n undefined, no extremum along the line), the projected points in red. Where a definition's domain is narrow (Levin MLS) points far from the curve move
along it or away from it; the centre of mass and integral definitions pull them onto it. Each
view's title counts the converged projections.

Options:
  --plugin PATH      PointSetSurfaces.so, or the folder that holds it. Default: nothing to load
                     when PV_PLUGIN_PATH already loaded the plugin; otherwise the first
                     PointSetSurfaces.so found in $PV_PLUGIN_PATH, then under
                     lib/paraview-plugins/ of $PSS_BUILD_DIR, build/ or the newest build*/ folder
                     of this source tree.
  --output FILE      the PNG (default noisy_curve_two_variants.png)
  --size WxH         image size in pixels, both views together (default 1600x600)
  --variants A,B     two of levin, normalized, com, integral, delta (default levin,com)
  --h H              Gaussian scale h (default 5)
  --count N          number of cloud points (default 600)
  --noise SIGMA      noise at the noisy end of the curve (default 6)
  --max-travel L     a line search that finds no extremum within L h gives up (default 100; the
                     filter's default, 1000, draws the same picture, only slower)
"""
import argparse
import os
import sys

import paraview.simple as pvs

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pss_example import VARIANTS, black_scalar_bar, find_plugin, parse_size, white_view  # noqa: E402 (after the path above)
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

RED = [0.85, 0.1, 0.1]



def parse_variants(text):
    names = text.split(",")
    if len(names) != 2 or any(n not in VARIANTS for n in names):
        raise argparse.ArgumentTypeError("expected two of %s separated by a comma, got %r" % (",".join(sorted(VARIANTS)), text))
    return names



def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin")
    parser.add_argument("--output", default="noisy_curve_two_variants.png")
    parser.add_argument("--size", type=lambda text: parse_size(text, min_width=32), default=[1600, 600])
    parser.add_argument("--variants", type=parse_variants, default=["levin", "com"])
    parser.add_argument("--h", type=float, default=5.0)
    parser.add_argument("--count", type=int, default=600)
    parser.add_argument("--noise", type=float, default=6.0)
    parser.add_argument("--max-travel", type=float, default=100.0)
    args = parser.parse_args()

    plugin = find_plugin(args.plugin)
    if plugin:
        pvs.LoadPlugin(plugin, remote=False, ns=globals())
    P = {name: getattr(pvs, name, None) or globals()[name]
         for name in ("PointSetSurfaceCloudSource", "PointSetSurfaceProjection")}

    cloud = P["PointSetSurfaceCloudSource"](Scene="Noisy Curve", NumberOfPoints=args.count, Size=200.0, Noise=args.noise)
    cloud.UpdatePipeline()
    x0, x1, y0, y1, _, _ = cloud.GetDataInformation().GetBounds()

    layout = pvs.CreateLayout("Two variants")
    layout.SplitHorizontal(0, 0.5)
    # Text of the lines' colour legend: StopReason 0 converged, 1..4 the ways a projection fails.
    lut = pvs.GetColorTransferFunction("StopReason")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = ["0", "converged", "1", "iteration limit", "2", "n undefined", "3", "no extremum", "4", "NaN start"]
    lut.IndexedColors = [0.25, 0.5, 0.85, 1.0, 0.55, 0.0, 0.6, 0.0, 0.8, 0.0, 0.6, 0.6, 0.3, 0.3, 0.3]

    summary = []
    for cell, variant in zip((1, 2), args.variants):
        projection = P["PointSetSurfaceProjection"](Input=cloud, Variant=VARIANTS[variant], AutomaticScale=0,
                                                    ScaleFactor=args.h, MaxTravel=args.max_travel,
                                                    GenerateProjectionLines=1)
        projection.UpdatePipeline()
        view = white_view(layout, cell)
        view.CameraParallelProjection = 1

        lines = pvs.Show(pvs.OutputPort(projection, 1), view)
        pvs.ColorBy(lines, ("CELLS", "StopReason"))
        lines.LookupTable = lut
        lines.LineWidth = 1.5
        ends = pvs.Show(pvs.OutputPort(projection, 0), view)
        ends.ColorArrayName = ["POINTS", ""]
        ends.AmbientColor = ends.DiffuseColor = RED
        ends.SetRepresentationType("Points")
        ends.PointSize = 3.0
        points = pvs.Show(cloud, view)
        points.ColorArrayName = ["POINTS", ""]
        points.AmbientColor = points.DiffuseColor = [0, 0, 0]
        points.PointSize = 2.0

        # How many converged: Converged is 0/1 per projected point.
        data = servermanager.Fetch(projection, 0)
        total = data.GetNumberOfPoints()
        n_conv = int(vtk_to_numpy(data.GetPointData().GetArray("Converged")).sum())
        summary.append("%s: %d of %d converged" % (VARIANTS[variant], n_conv, total))
        title = pvs.Text(Text="%s, h = %g: %d of %d projections converged" % (VARIANTS[variant], args.h, n_conv, total))
        t = pvs.Show(title, view)
        t.Color = [0, 0, 0]
        t.FontSize = 13
        t.WindowLocation = "Upper Center"

        # 2D camera on the cloud's bounds, with 5 % of margin, in a view of half the image width.
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        aspect = (args.size[0] / 2.0) / args.size[1]
        view.CameraPosition = [cx, cy, 10 * (x1 - x0)]
        view.CameraFocalPoint = [cx, cy, 0]
        view.CameraViewUp = [0, 1, 0]
        view.CameraParallelScale = 1.1 * max((y1 - y0) / 2, (x1 - x0) / 2 / aspect)

    lines.SetScalarBarVisibility(view, True)
    # Lower left of the right view: the curve is elsewhere.
    bar = black_scalar_bar(lut, view, "projection line", [0.03, 0.04])
    bar.TitleFontSize = bar.LabelFontSize = 12
    bar.TextPosition = "Ticks left/bottom, annotations right/top"
    bar.ScalarBarLength = 0.3

    layout.SetSize(*args.size)
    pvs.SaveScreenshot(args.output, layout, ImageResolution=args.size, TransparentBackground=0)
    print("%s: %d points, noise %.3g..%.3g, h = %g; %s" % (args.output, args.count, args.noise / 5, args.noise, args.h, "; ".join(summary)))


if __name__ == "__main__":
    main()

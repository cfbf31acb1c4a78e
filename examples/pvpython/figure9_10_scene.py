"""The scene of Figures 9 and 10 of Amenta & Kil, "The Domain of a Point Set Surface", in ParaView.

    pvbatch examples/pvpython/figure9_10_scene.py [--plugin PATH] [--output figure9_10_scene.png]
            [--size 1200x800] [--variant levin] [--scene corner] [--h 10] [--grid 161] [--starts 40]
            [--max-travel 30]

(under xvfb-run on a machine without a display: `xvfb-run -a pvbatch ...`; pvpython works too.)

A 2D cloud (default: a sharp corner, the paper's Figure 6) and one surface definition (default
Levin MLS, Figure 9; `--variant integral` gives Figure 10). The Point Set Surface Field Sampler
samples n, e and g on an image slice around the cloud, with n oriented by propagation so that a
stream tracer can follow it; then
- Stream Tracer With Custom Source on the oriented Normal (grey streamlines of n, seeded on a grid),
- Contour of Energy at ten quantiles of e (iso-contours coloured by e on a log scale),
- Point Set Surface Projection of a grid of start points to the minima of e along n (blue: the
  point-set surface, inside and outside its domain) and, with Seek Maxima, to the maxima (green:
  the rest of the implicit surface g = 0 of Equation 2),
- the cloud in black,
saved as a PNG of the requested size.

Options:
  --plugin PATH   PointSetSurfaces.so, or the folder that holds it. Default: nothing to load when
                  the plugin is already loaded through PV_PLUGIN_PATH; otherwise the first
                  PointSetSurfaces.so found in $PV_PLUGIN_PATH, then under lib/paraview-plugins/
                  of $PSS_BUILD_DIR, build/ or the newest build*/ folder of this source tree.
  --output FILE   the PNG (default figure9_10_scene.png)
  --size WxH      image size in pixels (default 1200x800)
  --variant NAME  levin | normalized | com | integral | delta (default levin)
  --scene NAME    corner | noisy-curve | circle | line | two-sheets (default corner)
  --h H           Gaussian scale h (default 10, as in the paper)
  --grid N        samples of the field image along its longer side (default 161)
  --starts N      start points per side of the projection grid (default 40)
  --max-travel L  a line search that finds no extremum within L h gives up (default 30: the
                  picture is about 15 h wide; the filter's default, 1000, gives the same
                  extrema here, only much more slowly)
"""
import argparse
import os
import sys

import paraview.simple as pvs

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pss_example import VARIANTS, black_scalar_bar, find_plugin, parse_size, white_view  # noqa: E402 (after the path above)

SCENES = {"corner": "Corner", "noisy-curve": "Noisy Curve", "circle": "Circle", "line": "Line",
          "two-sheets": "Two Sheets"}
BLUE = [0.1, 0.25, 1.0]
GREEN = [0.0, 0.75, 0.1]




def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin")
    parser.add_argument("--output", default="figure9_10_scene.png")
    parser.add_argument("--size", type=parse_size, default=[1200, 800])
    parser.add_argument("--variant", choices=sorted(VARIANTS), default="levin")
    parser.add_argument("--scene", choices=sorted(SCENES), default="corner")
    parser.add_argument("--h", type=float, default=10.0)
    parser.add_argument("--grid", type=int, default=161)
    parser.add_argument("--starts", type=int, default=40)
    parser.add_argument("--max-travel", type=float, default=30.0)
    args = parser.parse_args()

    plugin = find_plugin(args.plugin)
    if plugin:
        pvs.LoadPlugin(plugin, remote=False, ns=globals())
    P = vars(pvs) if hasattr(pvs, "PointSetSurfaceProjection") else globals()

    surface = dict(Variant=VARIANTS[args.variant], AutomaticScale=0, ScaleFactor=args.h)

    # The cloud: 2D, a little noise. Size 120: corner segments of 60, i.e. 6 h with the paper's h.
    cloud = P["PointSetSurfaceCloudSource"](Scene=SCENES[args.scene], NumberOfPoints=160, Size=120.0, Noise=0.4,
                                            CornerAngle=60.0, SheetGap=3 * args.h, Dimension="2D (xy-plane)")
    cloud.UpdatePipeline()
    xmin, xmax, ymin, ymax, _, _ = cloud.GetDataInformation().GetBounds()

    # n, e, g on an image slice around the cloud (3 h of margin), n oriented by propagation.
    margin = 3.0
    width, height = xmax - xmin + 2 * margin * args.h, ymax - ymin + 2 * margin * args.h
    nx = args.grid if width >= height else max(2, int(round(args.grid * width / height)))
    ny = args.grid if height >= width else max(2, int(round(args.grid * height / width)))
    field = P["PointSetSurfaceFieldSampler"](Input=cloud, GenerateSamplingGrid=1, SampleDimensions=[nx, ny, 1],
                                             SamplingMargin=margin, OrientationMode="Propagate", **surface)
    field.UpdatePipeline()
    bx0, bx1, by0, by1, _, _ = field.GetDataInformation().GetBounds()

    # Streamlines of the oriented n, seeded on a regular grid over the slice.
    seeds = pvs.Plane(Origin=[bx0, by0, 0], Point1=[bx1, by0, 0], Point2=[bx0, by1, 0], XResolution=13, YResolution=9)
    stream = pvs.StreamTracerWithCustomSource(Input=field, SeedSource=seeds)
    stream.Vectors = ["POINTS", "Normal"]
    stream.IntegrationDirection = "BOTH"
    stream.MaximumStreamlineLength = 2.0 * max(bx1 - bx0, by1 - by0)

    # Iso-contours of e at ten quantiles of its samples (e spans many decades for Levin's MLS).
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np
    energy = vtk_to_numpy(servermanager.Fetch(field, 0).GetPointData().GetArray("Energy"))
    positive = energy[energy > 0]
    levels = sorted(set(float(v) for v in np.quantile(positive if positive.size else energy, np.linspace(0.05, 0.95, 10))))
    contour = pvs.Contour(Input=field, ContourBy=["POINTS", "Energy"], Isosurfaces=levels, ComputeScalars=1)

    # Minima (blue) and maxima (green) of e along n, from a grid of start points.
    k = max(2, args.starts)
    starts = pvs.Plane(Origin=[bx0, by0, 0], Point1=[bx1, by0, 0], Point2=[bx0, by1, 0], XResolution=k - 1, YResolution=k - 1)
    extrema = {}
    for kind, seek in (("minima", 0), ("maxima", 1)):
        projection = P["PointSetSurfaceProjection"](Input=cloud, StartPoints=starts, SeekMaxima=seek,
                                                    MaxTravel=args.max_travel, **surface)
        converged = pvs.Threshold(Input=projection, Scalars=["POINTS", "StopReason"], LowerThreshold=0, UpperThreshold=0)
        inside = pvs.Clip(Input=converged, ClipType="Box", Invert=1, Crinkleclip=1)
        inside.ClipType.Position = [bx0, by0, -1]
        inside.ClipType.Length = [bx1 - bx0, by1 - by0, 2]
        inside.UpdatePipeline()
        extrema[kind] = inside

    view = white_view()
    view.ViewSize = args.size
    view.CameraParallelProjection = 1

    d = pvs.Show(stream, view)
    d.ColorArrayName = ["POINTS", ""]
    d.AmbientColor = d.DiffuseColor = [0.55, 0.55, 0.58]
    d.LineWidth = 1.0

    d = pvs.Show(contour, view)
    pvs.ColorBy(d, ("POINTS", "Energy"))
    lut = pvs.GetColorTransferFunction("Energy")
    # Plasma: no black end (the cloud is black), and no pure blue or green (the extrema are).
    lut.ApplyPreset("Plasma (matplotlib)", True)
    lo, hi = levels[0], levels[-1]
    if lo > 0 and hi > lo:
        lut.AutomaticRescaleRangeMode = "Never"
        lut.RescaleTransferFunction(lo, hi)
        lut.MapControlPointsToLogSpace()
        lut.UseLogScale = 1
    d.LineWidth = 2.0
    d.SetScalarBarVisibility(view, True)
    bar = black_scalar_bar(lut, view, "e(x, n(x))", [0.84, 0.1])
    bar.ScalarBarLength = 0.5

    for kind, colour in (("minima", BLUE), ("maxima", GREEN)):
        d = pvs.Show(extrema[kind], view)
        d.ColorArrayName = ["POINTS", ""]
        d.AmbientColor = d.DiffuseColor = colour
        d.SetRepresentationType("Points")
        d.PointSize = 4.0

    d = pvs.Show(cloud, view)
    d.ColorArrayName = ["POINTS", ""]
    d.AmbientColor = d.DiffuseColor = [0, 0, 0]
    d.PointSize = 3.0

    title = pvs.Text(Text="%s, h = %g: streamlines of n, iso-contours of e, minima (blue) and maxima (green) of e along n"
                     % (VARIANTS[args.variant], args.h))
    t = pvs.Show(title, view)
    t.Color = [0, 0, 0]
    t.FontSize = 14
    t.WindowLocation = "Upper Center"

    # 2D camera on the sampled slice, room left for the title and the colour bar.
    cx, cy = (bx0 + bx1) / 2, (by0 + by1) / 2
    aspect = args.size[0] / float(args.size[1])
    view.CameraPosition = [cx + 0.06 * (bx1 - bx0), cy, 10 * max(bx1 - bx0, by1 - by0)]
    view.CameraFocalPoint = [cx + 0.06 * (bx1 - bx0), cy, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelScale = 1.06 * max((by1 - by0) / 2, 1.12 * (bx1 - bx0) / 2 / aspect)
    pvs.Render(view)
    pvs.SaveScreenshot(args.output, view, ImageResolution=args.size, TransparentBackground=0)

    counts = {k: v.GetDataInformation().GetNumberOfPoints() for k, v in extrema.items()}
    print("%s: %s on a %s cloud, h = %g: %d x %d samples, %d streamline points, %d contour points, "
          "%d minima and %d maxima from %d start points"
          % (args.output, VARIANTS[args.variant], args.scene, args.h, nx, ny,
             stream.GetDataInformation().GetNumberOfPoints(), contour.GetDataInformation().GetNumberOfPoints(),
             counts["minima"], counts["maxima"], k * k))


if __name__ == "__main__":
    main()

# SPDX-License-Identifier: BSD-3-Clause
"""Renders the figures of Amenta & Kil, "The Domain of a Point Set Surface", from the files that
pss-paper-figures wrote. Reads them with stock ParaView readers only (no plugin needed).

    xvfb-run -a pvbatch render_paper_figures.py OUTDIR      (no display: Debian's ParaView needs X)
    pvbatch render_paper_figures.py OUTDIR                  (with a display)

Writes OUTDIR/fig01_02_projection_lines.png, fig05_line_glyphs.png, fig06_corner.png,
fig07_delta.png, fig09_levin_h10.png, fig10_integral_h10.png, fig03_planes.png, fig04_legend.png and
fig08_noisy_band.png, and domains_2d.png (the seven definitions' domains on two scenes). Each panel is rendered on its
own (2D, parallel projection) and the panels are put together with vtkImageAppend, then saved as
8-bit palette PNGs (small enough for the docs). PSS_KEEP_PANELS=1 keeps the single panels in
OUTDIR/.panels. Figures 6, 9 and 10 draw the polyline of vtkPointSetSurfaceMesher (fig06_*_mesh.vtp,
fig09_levin_mesh.vtp, fig10_integral_mesh.vtp) over the surface points, with the result of its check
against them from paper_checks.json.
"""
import csv
import json
import os
import shutil
import struct
import sys
import zlib

from paraview.simple import (CreateView, Delete, GetDisplayProperties, GetColorTransferFunction, Line,
                             PointSource, Render, SaveScreenshot, Show, Text, Threshold, XMLImageDataReader,
                             XMLPolyDataReader, ColorBy)
from vtkmodules.vtkFiltersCore import vtkImageAppend
from vtkmodules.vtkImagingColor import vtkImageQuantizeRGBToIndex
from vtkmodules.vtkImagingCore import vtkImageCast
from vtkmodules.vtkIOImage import vtkPNGReader

OUT = sys.argv[1] if len(sys.argv) > 1 else "paper-figures"
PANELS = os.path.join(OUT, ".panels")

BLACK = [0.0, 0.0, 0.0]
GREY = [0.55, 0.55, 0.55]
LIGHT = [0.78, 0.78, 0.78]
RED = [0.85, 0.1, 0.1]
ORANGE = [0.95, 0.55, 0.0]
BLUE = [0.1, 0.3, 0.95]
GREEN = [0.0, 0.7, 0.2]
YELLOW = [1.0, 0.85, 0.0]
STEEL = [0.35, 0.5, 0.7]
MAGENTA = [0.85, 0.0, 0.75]


# --------------------------------------------------------------------------------------------
# Data

def path(name):
    return os.path.join(OUT, name)


def poly(name):
    return XMLPolyDataReader(FileName=[path(name)])


def image(name):
    return XMLImageDataReader(FileName=[path(name)])


def table():
    rows = {}
    with open(path("paper_table.csv")) as f:
        for r in csv.DictReader(f):
            rows[(r["scene"].split(" (")[0], r["variant"])] = r
    return rows


def pct(row):
    return "%.1f %%" % (100.0 * float(row["on_curve_fraction"]))


def checks():
    with open(path("paper_checks.json")) as f:
        return {c["name"]: c for c in json.load(f)["checks"]}


def mesh_agreement(check):
    """The result of a *_mesh_agrees check, for a caption: far end points plus unconfirmed pieces."""
    return "%s (%d disagreements)" % ("agrees" if check["pass"] else "DISAGREES", int(check["value"]))


# --------------------------------------------------------------------------------------------
# Views and panels

counter = [0]
bounds_of_view = {}


def place_camera(v):
    """Shows the view's bounds (after every Show, which may have reset the camera)."""
    bounds = bounds_of_view[id(v)]
    width, height = v.ViewSize
    cx = 0.5 * (bounds[0] + bounds[1])
    cy = 0.5 * (bounds[2] + bounds[3])
    v.CameraPosition = [cx, cy, 1000.0]
    v.CameraFocalPoint = [cx, cy, 0.0]
    v.CameraViewUp = [0.0, 1.0, 0.0]
    half_h = 0.5 * (bounds[3] - bounds[2])
    half_w = 0.5 * (bounds[1] - bounds[0])
    v.CameraParallelScale = max(half_h, half_w * height / float(width)) * 1.02


def panel_view(width, height, bounds):
    """A white 2D view of width x height pixels showing bounds = (xmin, xmax, ymin, ymax)."""
    v = CreateView("RenderView")
    v.ViewSize = [width, height]
    v.OrientationAxesVisibility = 0
    try:
        v.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    v.Background = [1.0, 1.0, 1.0]
    v.CameraParallelProjection = 1
    bounds_of_view[id(v)] = bounds
    return v


def points(src, view, color, size, spheres=False, z=1.0):
    d = Show(src, view)
    d.ColorArrayName = ["POINTS", ""]
    d.SetRepresentationType("Points")
    d.PointSize = size
    d.RenderPointsAsSpheres = 1 if spheres else 0
    d.Position = [0.0, 0.0, z]  # in front of images and lines
    d.AmbientColor = color
    d.DiffuseColor = color
    return d


def lines(src, view, color, width=1.0, opacity=1.0, z=0.0):
    d = Show(src, view)
    d.ColorArrayName = ["POINTS", ""]
    d.SetRepresentationType("Wireframe")
    d.LineWidth = width
    d.AmbientColor = color
    d.DiffuseColor = color
    d.Opacity = opacity
    d.Position = [0.0, 0.0, z]  # above 1: in front of the points
    return d


def mesh_polyline(name, view):
    """The mesher's polyline, thick and in front of the end points that it is checked against."""
    return lines(poly(name), view, MAGENTA, 2.5, 1.0, 1.5)


def by_value(src, view, array, association, rng, preset="Grayscale", invert=False, log=False, width=1.0,
             representation="Wireframe"):
    d = Show(src, view)
    d.SetRepresentationType(representation)
    d.LineWidth = width
    ColorBy(d, (association, array))
    lut = GetColorTransferFunction(array + str(counter[0]))
    counter[0] += 1
    lut.ApplyPreset(preset, True)
    if invert:
        lut.InvertTransferFunction()
    lut.RescaleTransferFunction(rng[0], rng[1])
    lut.AutomaticRescaleRangeMode = "Never"
    if log:
        lut.UseLogScale = 1
    d.LookupTable = lut
    d.SetScalarBarVisibility(view, False)
    return d


def subset(src, array, association, lo, hi):
    t = Threshold(Input=src)
    t.Scalars = [association, array]
    t.LowerThreshold = lo
    t.UpperThreshold = hi
    return t


def title(view, text, size=15, location="Upper Center"):
    t = Text(Text=text)
    d = Show(t, view)
    d.WindowLocation = location
    d.Justification = "Left" if "Left" in location else "Center"
    d.FontSize = size
    d.Color = BLACK
    return t


def snap(view, name):
    Render(view)  # the first render of a view resets its camera: place it afterwards
    place_camera(view)
    Render(view)
    os.makedirs(PANELS, exist_ok=True)
    f = os.path.join(PANELS, name + ".png")
    SaveScreenshot(f, view, ImageResolution=list(view.ViewSize), TransparentBackground=0)
    Delete(view)
    return f


def caption_panel(width, height, text, size=14, location="Upper Left Corner"):
    v = panel_view(width, height, (0, 1, 0, 1))
    title(v, text, size, location)
    counter[0] += 1
    return snap(v, "caption%d" % counter[0])


def write_indexed_png(rgb, filename, colors=256):
    """An 8-bit palette PNG of an RGB vtkImageData: line drawings need few colours, and a palette
    image is a third of the size of an RGB one (docs/paper.md shows these files)."""
    q = vtkImageQuantizeRGBToIndex()
    q.SetInputData(rgb)
    q.SetNumberOfColors(colors)
    q.Update()
    c = vtkImageCast()
    c.SetInputConnection(q.GetOutputPort())
    c.SetOutputScalarTypeToUnsignedChar()
    c.Update()
    img = c.GetOutput()
    w, h, _ = img.GetDimensions()
    data = bytes(memoryview(img.GetPointData().GetScalars()))
    lut = q.GetLookupTable()
    palette = bytearray()
    for i in range(colors):
        r, g, b, _ = lut.GetTableValue(i)
        palette += bytes((int(round(255 * r)), int(round(255 * g)), int(round(255 * b))))
    raw = bytearray()
    for row in range(h - 1, -1, -1):  # VTK images start with the bottom row, PNG with the top one
        raw.append(0)  # filter type: none
        raw += data[row * w:(row + 1) * w]

    def chunk(tag, payload):
        return (struct.pack(">I", len(payload)) + tag + payload
                + struct.pack(">I", zlib.crc32(tag + payload) & 0xffffffff))

    with open(filename, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 3, 0, 0, 0)))
        f.write(chunk(b"PLTE", bytes(palette)))
        f.write(chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
        f.write(chunk(b"IEND", b""))


def compose(grid, name, colors=256):
    """grid: list of rows (top first) of panel PNG files; rows of equal total width. colors: size
    of the palette (the quantization's time grows with it)."""
    rows = []
    for row in grid:
        a = vtkImageAppend()
        a.SetAppendAxis(0)
        for f in row:
            r = vtkPNGReader()
            r.SetFileName(f)
            r.Update()
            a.AddInputData(r.GetOutput())
        a.Update()
        rows.append(a.GetOutput())
    v = vtkImageAppend()
    v.SetAppendAxis(1)
    for img in reversed(rows):  # image y grows upwards
        v.AddInputData(img)
    v.Update()
    write_indexed_png(v.GetOutput(), path(name), colors)
    print("wrote", path(name), "(%d KB)" % (os.path.getsize(path(name)) // 1024))


def array_range(src, name, association="POINTS"):
    src.UpdatePipeline()
    info = src.GetDataInformation()
    info = info.GetPointDataInformation() if association == "POINTS" else info.GetCellDataInformation()
    return info.GetArrayInformation(name).GetComponentRange(0)


def grown(bounds, margin):
    return (bounds[0] - margin, bounds[1] + margin, bounds[2] - margin, bounds[3] + margin)


def count_points(src):
    src.UpdatePipeline()
    return src.GetDataInformation().GetNumberOfPoints()


def data_bounds(src):
    src.UpdatePipeline()
    b = src.GetDataInformation().GetBounds()
    return (b[0], b[1], b[2], b[3])


# --------------------------------------------------------------------------------------------
# Figures

def figures_1_2(rows):
    cloud = poly("noisy_curve_cloud.vtp")
    b = grown(data_bounds(cloud), 6.0)
    files = []
    for stem, key, fig in (("fig01_levin", "levin", "Figure 1"), ("fig02_integral", "integral", "Figure 2")):
        r = rows[("noisy curve", key)]
        v = panel_view(1400, int(round(1400 * (b[3] - b[2]) / (b[1] - b[0]))), b)
        ln = poly(stem + "_lines.vtp")
        lines(subset(ln, "Outcome", "CELLS", 0, 0), v, GREY, 1.0)
        lines(subset(ln, "Outcome", "CELLS", 1, 3), v, RED, 2.0)
        points(cloud, v, GREY, 4)
        projected = poly(stem + "_projected.vtp")
        points(subset(projected, "Outcome", "POINTS", 0, 0), v, BLACK, 3)
        points(subset(projected, "Outcome", "POINTS", 1, 3), v, RED, 6)
        name = "Levin's MLS" if key == "levin" else "integral variant (e_I)"
        files.append([caption_panel(1400, 30, "%s: %s, h = 5 -- %s of the input points land within 0.5 h of the "
                                    "true curve" % (fig, name, pct(r)), 16, "Upper Center")])
        files.append([snap(v, stem)])
    files.append([caption_panel(1400, 50,
                                "grey: input point x; black: f(x); grey line: x -> f(x) landing on the curve; "
                                "red: f(x) farther than 0.5 h from the true curve, or not converged (x outside the "
                                "domain).\n"
                                "Noise sigma grows from 0.6 to 3 along the curve (the +-sigma band from 1.2 to 6, "
                                "slightly wider than h = 5 at the right end), density falls.", 13)])
    compose(files, "fig01_02_projection_lines.png")


def figure_5(checks_flip):
    cloud = poly("line_cloud.vtp")
    h = 5.0
    b = (-1.3 * h, 1.3 * h, -0.3 * h, 2.25 * h)
    row = []
    for key, name in (("levin", "Levin's MLS energy"), ("integral", "integral energy e_I")):
        v = panel_view(560, 560, b)
        points(cloud, v, BLACK, 5)
        flip = Line(Point1=[-1.3 * h, h / 2 ** 0.5, 0], Point2=[1.3 * h, h / 2 ** 0.5, 0])
        lines(flip, v, LIGHT, 1.0)
        lines(poly("fig05_%s_glyphs.vtp" % key), v, BLUE, 2.0)
        lines(poly("fig05_%s_fits.vtp" % key), v, RED, 3.0)
        title(v, name)
        row.append(snap(v, "fig05_" + key))
    cap = caption_panel(1120, 70,
                        "Figure 5: points on a horizontal line (h = 5, spacing 0.1 h); heights 0 .. 2 h. Blue: energy "
                        "plot x + c e(x, a) a (each scaled on its own; its\nnarrowest direction is n(x)); red: the "
                        "best-fitting line, normal to n(x). Grey line: h / sqrt 2. Measured flip of n_MLS: %s h; "
                        "n_I never flips (scanned to 5 h)." % checks_flip, 13)
    compose([row, [cap]], "fig05_line_glyphs.png")


def figure_6(rows, checked):
    cloud = poly("corner_cloud.vtp")
    b = data_bounds(image("fig06_levin_field.vti"))
    w, hgt = 300, 336
    zoom = (-20.0, 20.0, -17.0, 17.0)  # +-4 h around the apex (h = 5)
    grid = [[], [], [], [], []]
    for key, name in (("levin", "Levin's MLS"), ("normalized", "normalized MLS"), ("com", "center of mass"),
                      ("integral", "integral (e_I)")):
        r = rows[("corner", key)]
        grid[0].append(caption_panel(w, 30, name, 17, "Upper Center"))
        # Row 1: energy glyphs and best-fitting lines.
        v = panel_view(w, hgt, b)
        points(cloud, v, BLACK, 3)
        lines(poly("fig06_%s_glyphs.vtp" % key), v, BLUE, 1.0)
        lines(poly("fig06_%s_fits.vtp" % key), v, RED, 1.0)
        grid[1].append(snap(v, "fig06_%s_glyphs" % key))
        # Row 2: streamlines of n and iso-contours of e(x, n(x)) (lighter grey = lower energy).
        v = panel_view(w, hgt, b)
        lines(poly("fig06_%s_streamlines.vtp" % key), v, STEEL, 1.0)
        c = poly("fig06_%s_contours.vtp" % key)
        rng = array_range(c, "LogEnergy")
        by_value(c, v, "LogEnergy", "POINTS", (rng[0] - 0.5 * (rng[1] - rng[0]), rng[1]), "Grayscale", True, False,
                 1.2)
        points(cloud, v, BLACK, 3)
        grid[2].append(snap(v, "fig06_%s_fields" % key))
        # Row 3: where 2000 uniform random starts end, over the mesher's polyline.
        v = panel_view(w, hgt, b)
        sp = poly("fig06_%s_surface_points.vtp" % key)
        points(cloud, v, LIGHT, 6, z=0.0)
        mesh_polyline("fig06_%s_mesh.vtp" % key, v)
        points(subset(sp, "Outcome", "POINTS", 0, 0), v, BLACK, 3)
        points(subset(sp, "Outcome", "POINTS", 1, 1), v, ORANGE, 4)
        points(subset(sp, "Outcome", "POINTS", 2, 2), v, RED, 4)
        title(v, "on curve %s, spurious %s\nmesh %s" % (pct(r), r["spurious"],
                                                        mesh_agreement(checked["corner.%s_mesh_agrees" % key])),
              13, "Lower Center")
        grid[3].append(snap(v, "fig06_%s_points" % key))
        # Row 4: the same end points around the apex.
        v = panel_view(w, int(w * (zoom[3] - zoom[2]) / (zoom[1] - zoom[0])), zoom)
        points(cloud, v, LIGHT, 7, z=0.0)
        mesh_polyline("fig06_%s_mesh.vtp" % key, v)
        points(subset(sp, "Outcome", "POINTS", 0, 0), v, BLACK, 4)
        points(subset(sp, "Outcome", "POINTS", 1, 1), v, ORANGE, 5)
        points(subset(sp, "Outcome", "POINTS", 2, 2), v, RED, 5)
        grid[4].append(snap(v, "fig06_%s_apex" % key))
    cap = caption_panel(4 * w, 84,
                        "Figure 6: a 45-degree corner with open arms (h = 5). Row 1: energy plots (blue) and "
                        "best-fitting lines (red). Row 2: streamlines of n (blue-grey) and\niso-contours of "
                        "e(x, n(x)) (lighter = lower). Row 3: end points of 2000 uniform random starts: black within "
                        "0.5 h of the corner, orange off it but\nwithin 2 h of the cloud, red spurious (farther than "
                        "2 h from every input point); non-converged starts not drawn. Row 4: row 3 around the apex "
                        "(+-4 h).\nRows 3 and 4, magenta: the polyline of vtkPointSetSurfaceMesher, checked: every "
                        "black end point within 0.5 h of it, and every piece of it with an end point within 0.5 h.",
                        12)
    compose(grid + [[cap]], "fig06_corner.png")


def figure_7():
    cloud = poly("noisy_curve_cloud.vtp")
    field = image("fig07_delta.vti")
    b = data_bounds(field)
    v = panel_view(1400, int(round(1400 * (b[3] - b[2]) / (b[1] - b[0]))), b)
    rng = array_range(field, "Delta")
    by_value(field, v, "Delta", "POINTS", (max(rng[0], 1e-3), rng[1]), "Grayscale", False, True, 1.0, "Slice")
    points(cloud, v, RED, 2)
    top = [caption_panel(1400, 30, "Figure 7 (top): delta(x), the approximate squared distance, as intensity "
                                   "(log scale; dark = low); red: the input points", 15, "Upper Center"),
           snap(v, "fig07_image")]
    zoom = (110.0, 205.0, -40.0, 10.0)
    v = panel_view(1400, int(round(1400 * (zoom[3] - zoom[2]) / (zoom[1] - zoom[0]))), zoom)
    c = poly("fig07_delta_contours.vtp")
    by_value(c, v, "Delta", "POINTS", (0.3, 2500.0), "Grayscale", True, True, 1.5)
    points(cloud, v, RED, 5)
    bottom = [caption_panel(1400, 30, "Figure 7 (bottom): iso-contours of delta from h^2/16 to 32 h^2 (ratio "
                                      "sqrt 2; lighter = lower) near the sparse, noisy end (h = 5)", 15, "Upper Center"),
              snap(v, "fig07_contours")]
    compose([[top[0]], [top[1]], [bottom[0]], [bottom[1]]], "fig07_delta.png")


def figures_9_10(rows, checked):
    cloud = poly("noisy_curve_cloud.vtp")
    for stem, key, fig, name in (("fig09_levin", "levin", "Figure 9", "Levin's MLS"),
                                 ("fig10_integral", "integral", "Figure 10", "integral variant e_I")):
        field = image(stem + "_field.vti")
        b = data_bounds(field)
        w = 1000
        hgt = int(round(w * (b[3] - b[2]) / (b[1] - b[0])))
        panels = []
        v = panel_view(w, hgt, b)
        lines(poly(stem + "_streamlines.vtp"), v, STEEL, 1.0)
        points(cloud, v, BLACK, 2)
        panels.append([caption_panel(w, 30, "%s (a): streamlines of n, %s, h = 10" % (fig, name), 15,
                                     "Upper Center")])
        panels.append([snap(v, stem + "_a")])
        v = panel_view(w, hgt, b)
        c = poly(stem + "_contours.vtp")
        rng = array_range(c, "LogEnergy")
        by_value(c, v, "LogEnergy", "POINTS", (rng[0] - 0.4 * (rng[1] - rng[0]), rng[1]), "Grayscale", True, False,
                 1.5)
        points(cloud, v, BLACK, 2)
        panels.append([caption_panel(w, 30, "%s (b): iso-contours of e(x, n(x)) (lighter = lower)" % fig, 15,
                                     "Upper Center")])
        panels.append([snap(v, stem + "_b")])
        v = panel_view(w, hgt, b)
        lines(poly(stem + "_streamlines.vtp"), v, LIGHT, 1.0)
        mesh_polyline(stem + "_mesh.vtp", v)
        points(cloud, v, GREY, 2)
        maxima = poly(stem + "_maxima.vtp")
        minima = poly(stem + "_minima.vtp")
        points(maxima, v, GREEN, 4)
        points(minima, v, BLUE, 4)
        points(poly(stem + "_singular.vtp"), v, YELLOW, 8, True)
        n_min = count_points(minima)
        n_max = count_points(maxima)
        panels.append([caption_panel(w, 66, "%s (c): streamlines and the surface points reached from 2000 random "
                                     "starts: %d minima (blue), %s;\nyellow: near-singular n (local minima of "
                                     "its stability below 0.05); magenta: vtkPointSetSurfaceMesher's polyline,\n"
                                     "checked: every end point on the curve within 0.5 h of it, every piece "
                                     "with one within 0.5 h: %s"
                                     % (fig, n_min, ("%d maxima (green)" % n_max) if n_max else "no maxima found",
                                        mesh_agreement(checked["noisy10.%s_mesh_agrees" % key])),
                                     14,
                                     "Upper Center")])
        panels.append([snap(v, stem + "_c")])
        compose(panels, stem + "_h10.png")


def read_csv(name):
    with open(path(name)) as f:
        return [r for r in csv.DictReader(f) if not next(iter(r.values()), "").startswith("#")]


def selected(src, *conditions):
    """Cells of src whose cell arrays equal the given values: conditions = (array, value), ..."""
    out = src
    for array, value in conditions:
        out = subset(out, array, "CELLS", value, value)
    return out


def percentiles(src, name, lo, hi):
    """The lo and hi quantiles of a point array (an image's intensity range that ignores outliers)."""
    from paraview import servermanager
    data = servermanager.Fetch(src)
    a = data.GetPointData().GetArray(name)
    v = sorted(a.GetValue(i) for i in range(a.GetNumberOfTuples()))
    return (v[int(lo * (len(v) - 1))], v[int(hi * (len(v) - 1))])


def label_at(view, text, fx, fy, size=13):
    """Text at a fraction (fx, fy) of the view (its lower left corner there)."""
    t = Text(Text=text)
    d = Show(t, view)
    d.WindowLocation = "Any Location"
    d.Position = [fx, fy]
    d.FontSize = size
    d.Color = BLACK
    return t


def figure_3():
    """One view: pss-paper-figures lays the ten panels out (PaperFiguresExtra.cxx, Figure3Offset:
    columns 7 h apart, the perpendicular row 5.6 h below the parallel one); the chart is drawn below
    them (scaled by the display) and the caption below that."""
    h = 5.0
    energies = {float(r["height_over_h"]): r for r in read_csv("fig03_plane_energies.csv")}
    cross = ""
    with open(path("fig03_plane_energies.csv")) as f:
        for line in f:
            if line.startswith("# crossing_over_h"):
                cross = line.strip().split(",")[1]
    drawn = (0.25, 0.5, 1.0, 1.5, 2.0)
    chart_origin, chart_scale = (50.0, -15.0 * h), (4.0, 2.4)  # chart units (x 0..20, y 0..10) -> world
    b = (-3.3 * h, 4 * 7.0 * h + 3.3 * h, -18.5 * h, 3.9 * h)
    w = 1000
    v = panel_view(w, int(round(w * (b[3] - b[2]) / (b[1] - b[0]))), b)
    by_value(poly("fig03_residuals.vtp"), v, "Weight", "CELLS", (0.0, 1.0), "Reds", True, False, 1.5)
    lines(poly("fig03_circles.vtp"), v, LIGHT, 1.0)
    lines(poly("fig03_planes.vtp"), v, BLUE, 2.5)
    d = by_value(poly("fig03_points.vtp"), v, "Weight", "POINTS", (0.0, 1.0), "Grayscale", True, False, 1.0, "Points")
    d.PointSize = 4
    d.Position = [0.0, 0.0, 1.0]
    points(poly("fig03_x.vtp"), v, BLACK, 9, True, 2.0)

    def fraction(x, y):
        return [(x - b[0]) / (b[1] - b[0]), (y - b[2]) / (b[3] - b[2])]

    for plane, label in ((0, "parallel"), (1, "perpendicular")):
        for k, t in enumerate(drawn):
            e = float(energies[t]["energy_%s" % label])
            fx, fy = fraction(7.0 * h * k - 1.6 * h, -5.6 * h * plane + 3.25 * h)
            label_at(v, "t = %.2f h: e = %.1f" % (t, e), fx, fy, 12)
    chart = poly("fig03_chart.vtp")
    for curve, color, width in ((0, BLUE, 2.5), (1, RED, 2.5), (2, GREY, 1.0), (4, BLACK, 1.0)):
        dc = lines(selected(chart, ("Curve", curve)), v, color, width)
        dc.Scale = [chart_scale[0], chart_scale[1], 1.0]
        dc.Position = [chart_origin[0], chart_origin[1], 0.0]
    fx, fy = fraction(chart_origin[0] - 30.0, chart_origin[1] + 10.6 * chart_scale[1])
    label_at(v, "e_MLS(x, a) against the height t of x (0 .. 2 h): blue, parallel plane; red, perpendicular plane; "
             "grey: t = h / sqrt 2", fx, fy, 12)
    title(v, "Figure 3: Levin's MLS (h = 5) at x = (0, t) (black dot) above a line of points 0.1 h apart; top "
             "row: the plane (line) through x\nparallel to the line, a = (0, 1); bottom row: the plane perpendicular "
             "to it, a = (1, 0). Grey dots: the points, darker = larger\nweight theta(x, p); red: their distances to "
             "the plane, darker = more weight (below, they lie along the line); grey circle: radius h.\ne_MLS sums "
             "weight x squared distance. Up to h / sqrt 2 the parallel plane has the lower energy, above it the "
             "perpendicular one:\nmeasured crossing %s h (h / sqrt 2 = 0.7071 h)." % cross, 12, "Lower Left Corner")
    compose([[snap(v, "fig03")]], "fig03_planes.png", 64)


def figure_4():
    """One view: pss-paper-figures puts the three samples in columns -1.2 h, 0 and 1.2 h."""
    legend = read_csv("fig04_legend.csv")
    h = 5.0
    names = ("strong minimum: dumbbell", "weaker minimum: ellipse", "unstable: circle")
    b = (-1.8 * h, 1.8 * h, -0.55 * h, 1.45 * h)
    v = panel_view(780, int(round(780 * (b[3] - b[2]) / (b[1] - b[0]))), b)
    lines(poly("fig04_glyphs.vtp"), v, BLUE, 2.5)
    lines(poly("fig04_fits.vtp"), v, RED, 2.0)
    for k, r in enumerate(legend):
        fx = (float(r["x_over_h"]) * h - 0.5 * h - b[0]) / (b[1] - b[0])
        label_at(v, "%s\nat %s h, stability %s" % (names[k], r["height_over_h"], r["stability"]), fx, 0.88, 12)
    title(v, "Figure 4: the energy plot x + c e(x, a) a over directions a (blue) is narrowest along n(x); red: the "
             "best-fitting line,\nnormal to n(x). Levin's MLS 0.1 h, 0.5 h and 0.7 h above the line of Figure 5 "
             "(h = 5); stability = (e_max - e_min) / (e_max + e_min).", 12, "Lower Left Corner")
    compose([[snap(v, "fig04")]], "fig04_legend.png", 32)


def figure_8():
    """Two views: the glyph panels (Levin above, integral below, shifted by the display) and the
    fields (the same), then the caption."""
    band = {r["variant"]: r for r in read_csv("fig08_noisy_band.csv")}
    gw = (163.0, 197.0, -32.0, 2.0)
    big = (128.0, 204.0, -40.0, 10.0)
    gshift = -(gw[3] - gw[2]) - 1.0
    bshift = -(big[3] - big[2]) - 1.5
    vg = panel_view(420, 850, (gw[0], gw[1], gw[2] + gshift, gw[3]))
    vb = panel_view(640, 850, (big[0], big[1], big[2] + bshift, big[3]))
    for row, (key, name) in enumerate((("levin", "Levin's MLS energy e_MLS"), ("integral", "integral energy e_I"))):
        # A source has one display per view: each row reads its own copy.
        cloud = poly("noisy_curve_cloud.vtp")
        shown = [lines(poly("fig08_%s_glyphs.vtp" % key), vg, BLUE, 1.2)]
        shown.append(lines(poly("fig08_%s_glyph_fits.vtp" % key), vg, RED, 1.2))
        for d in shown:
            d.Position = [0.0, row * gshift, d.Position[2]]
        label_at(vg, name, 0.01, 0.97 - 0.5 * row, 14)
        field = image("fig08_%s_field.vti" % key)
        rng = percentiles(field, "LogEnergy", 0.02, 0.98)
        shown = [by_value(field, vb, "LogEnergy", "POINTS", rng, "Grayscale", False, False, 1.0, "Slice")]
        shown.append(lines(poly("fig08_%s_fits.vtp" % key), vb, [0.6, 0.6, 0.6], 1.5))
        shown.append(lines(poly("fig08_band.vtp"), vb, STEEL, 0.8))
        shown.append(points(cloud, vb, RED, 2))
        shown.append(points(poly("fig08_%s_turns.vtp" % key), vb, YELLOW, 6, True, 2.0))
        for d in shown:
            d.Position = [0.0, row * bshift, d.Position[2]]
    left = snap(vg, "fig08_glyphs")
    right = snap(vb, "fig08_fields")
    lv, it = band["levin"], band["integral"]
    cap = caption_panel(1060, 100,
                        "Figure 8: the noisy end of the noisy curve (h = 5; red dots: the points); top Levin's MLS, "
                        "bottom the integral variant. Left: energy plots (blue) and\nbest-fitting lines (red) on a "
                        "lattice 0.4 h apart. Right: best-fitting lines (grey) over e(x, n(x)) (log scale, 2nd to 98th "
                        "percentile, dark = low); blue-grey:\nthe band, 2 sigma around the true curve, and %s paths "
                        "across it; yellow: where n first passes 45 degrees from the true normal. n_MLS does so in the "
                        "band's\nouter part (median %s sigma = %s h out; on %s/%s paths within the band), n_I on %s/%s "
                        "paths; median largest angle in the band %s deg (MLS) and %s deg (e_I);\nmedian total "
                        "variation of n along a path in the band %s deg (MLS) and %s deg (e_I)."
                        % (lv["paths"], lv["median_turn_over_sigma"], lv["median_turn_over_h"],
                           lv["paths_past_45_in_band"], lv["paths"], it["paths_past_45_in_band"], it["paths"],
                           lv["median_max_angle_in_band_deg"], it["median_max_angle_in_band_deg"],
                           lv["median_total_variation_in_band_deg"], it["median_total_variation_in_band_deg"]), 12)
    compose([[left, right], [cap]], "fig08_noisy_band.png")


DEFINITIONS = (("levin", "Levin's MLS"), ("normalized", "normalized MLS"), ("com", "center of mass"),
               ("integral", "integral (e_I)"), ("delta", "delta"), ("apss", "APSS"), ("rimls", "RIMLS"))
LABEL_COLORS = ((0, [0.55, 0.85, 0.55]), (1, RED), (2, ORANGE), (3, BLUE))  # DomainLabel 0..3


def domains_2d():
    """Where each of the seven definitions is defined: the random starts of the corner (h = 5) and
    of the noisy curve at h = 10, coloured by the DomainLabel of their projections."""
    corner_box = data_bounds(image("fig06_levin_field.vti"))
    wide_box = data_bounds(image("fig09_levin_field.vti"))
    ch = 230
    cw = int(round(ch * (corner_box[1] - corner_box[0]) / (corner_box[3] - corner_box[2])))
    nw = int(round(ch * (wide_box[1] - wide_box[0]) / (wide_box[3] - wide_box[2])))
    grid = []
    for key, name in DEFINITIONS:
        shares = []
        row = []
        for scene, cloud_file, box, width in (("corner", "corner_cloud.vtp", corner_box, cw),
                                              ("noisy10", "noisy_curve_cloud.vtp", wide_box, nw)):
            starts = poly("domain_%s_%s.vtp" % (scene, key))
            total = count_points(starts)
            v = panel_view(width, ch, box)
            for label, color in LABEL_COLORS:
                part = subset(starts, "DomainLabel", "POINTS", label, label)
                if label == 0:
                    shares.append(100.0 * count_points(part) / max(total, 1))
                points(part, v, color, 3, z=0.0)
            points(poly(cloud_file), v, BLACK, 2)
            row.append(snap(v, "domain_%s_%s" % (scene, key)))
        grid.append([caption_panel(cw + nw, 26, "%s: in the domain %.0f%% of the corner's starts, %.0f%% of the noisy "
                                                "curve's (h = 10)" % (name, shares[0], shares[1]), 14)])
        grid.append(row)
    grid.append([caption_panel(cw + nw, 66,
                               "Random starts coloured by the DomainLabel of their projection (Domain Classifier, "
                               "default thresholds):\ngreen InDomain, red Spurious, orange Undefined, blue NotConverged; "
                               "black: the cloud.\nLeft: the 45-degree corner, h = 5 (Figure 6). Right: the noisy curve, "
                               "h = 10 (Figures 9, 10).\nAPSS and RIMLS fit normals estimated from the cloud and oriented "
                               "by propagation.", 12)])
    compose(grid, "domains_2d.png", 64)


def main():
    rows = table()
    checked = checks()
    flip = rows[("line", "levin")]["flip_height_over_h"]
    figures_1_2(rows)
    figure_5(flip)
    figure_6(rows, checked)
    figure_7()
    figures_9_10(rows, checked)
    figure_3()
    figure_4()
    figure_8()
    domains_2d()
    if not os.environ.get("PSS_KEEP_PANELS"):
        shutil.rmtree(PANELS, ignore_errors=True)


main()

"""What the pvpython/pvbatch examples of PointSetSurfaces share: finding the plugin, the names of
the surface definitions and reading an image size from the command line.

Imported by the example scripts beside it (each puts this folder on sys.path first, so they run
from any working directory under pvpython or pvbatch).
"""
import argparse
import glob
import os
import sys

import paraview.simple as pvs

TREE = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

# The surface definitions: the pss tool's name of each (--variant) -> the plugin's label of it
# (the Variant property). Both come from the core's variant table; the test
# VariantTable.EveryFaceAgrees fails if this dictionary drifts from it.
VARIANTS = {"levin": "Levin MLS", "normalized": "Normalized MLS", "com": "Center of Mass",
            "integral": "Integral Energy", "delta": "Delta Energy", "apss": "APSS (Algebraic Spheres)",
            "rimls": "RIMLS (Robust Implicit MLS)"}


def parse_size(text, min_width=16, min_height=16):
    """'WxH' as [W, H], for argparse; smaller images than min_width x min_height are refused."""
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError("expected WxH, e.g. 1200x800, got %r" % text)
    if w < min_width or h < min_height:
        raise argparse.ArgumentTypeError("image too small: %r" % text)
    return [w, h]


def find_plugin(given, probe="PointSetSurfaceProjection"):
    """Path of PointSetSurfaces.so to load, or None when it is loaded already (PV_PLUGIN_PATH):
    @p given (the file or its folder), else the first found in $PV_PLUGIN_PATH, then in the build
    tree of this checkout ($PSS_BUILD_DIR, build/, then the newest build*/ folder). Exits with a
    message when there is none. @p probe: a proxy the plugin adds to paraview.simple."""
    if given:
        if os.path.isdir(given):
            given = os.path.join(given, "PointSetSurfaces.so")
        if not os.path.isfile(given):
            sys.exit("error: no plugin at %s" % given)
        return given
    if hasattr(pvs, probe):
        return None
    candidates = [os.path.join(d, "PointSetSurfaces.so") for d in os.environ.get("PV_PLUGIN_PATH", "").split(os.pathsep) if d]
    build_dirs = [os.environ.get("PSS_BUILD_DIR", ""), os.path.join(TREE, "build")]
    build_dirs += sorted(glob.glob(os.path.join(TREE, "build*")), key=os.path.getmtime, reverse=True)
    candidates += [os.path.join(d, "lib", "paraview-plugins", "PointSetSurfaces", "PointSetSurfaces.so") for d in build_dirs if d]
    for c in candidates:
        if os.path.isfile(c):
            return os.path.abspath(c)
    sys.exit("error: PointSetSurfaces.so not found: give --plugin PATH or set PV_PLUGIN_PATH")


def white_view(layout=None, cell=0):
    """A render view with a white background and no orientation axes (in @p layout's @p cell when
    given): what every figure of the examples is drawn in."""
    view = pvs.CreateView("RenderView")
    if layout is not None:
        pvs.AssignViewToLayout(view=view, layout=layout, hint=cell)
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0  # ParaView 5.10+: else the palette overrides Background
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 0
    return view


def black_scalar_bar(lut, view, title, position):
    """@p lut's scalar bar in @p view: black text on the white view, titled @p title, placed at
    @p position (view fractions); returned for the caller's own touches."""
    bar = pvs.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    bar.WindowLocation = "Any Location"
    bar.Position = position
    return bar

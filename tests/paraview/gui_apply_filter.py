"""Script for the ParaView GUI: `paraview --dr --script=gui_apply_filter.py --exit`, with the plugin's
folder on PV_PLUGIN_PATH and a marker file named by PSS_GUI_MARKER (run_gui.py does all this).

Inside the GUI it checks that the plugin was loaded at start-up through PV_PLUGIN_PATH (no
LoadPlugin here), creates a synthetic circle with the plugin's cloud source, applies the Point Set
Surface Projection filter, shows it in the GUI's render view coloured by Stability, and checks the
output: every point projected and converged, the documented arrays present, the projected points
on the circle of radius 25 (median distance below 0.25; h = 4, the plane-fit bias h^2 / 4R is
0.16) with less than half the radial spread of the noisy start points. It writes
"OK ..." or "FAIL ..." to the marker file. The GUI exits with status 0 whatever a script does
unless the script calls sys.exit, so the marker is what run_gui.py trusts; sys.exit(1) after a
failure makes the exit status say so too.
"""
import os
import sys
import traceback

marker = os.environ.get("PSS_GUI_MARKER", "pss_gui_marker.txt")


def finish(ok, message):
    with open(marker, "w") as f:
        f.write(("OK " if ok else "FAIL ") + message + "\n")
    print(("OK " if ok else "FAIL ") + message, flush=True)
    if not ok:
        sys.exit(1)


try:
    import paraview.simple as pvs
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np

    if not hasattr(pvs, "PointSetSurfaceProjection"):
        raise RuntimeError("the plugin was not loaded through PV_PLUGIN_PATH=%s" % os.environ.get("PV_PLUGIN_PATH"))
    cloud = pvs.PointSetSurfaceCloudSource(Scene="Circle", NumberOfPoints=200, Size=50.0, Noise=0.5)
    pvs.RenameSource("circle", cloud)
    projection = pvs.PointSetSurfaceProjection(Input=cloud, Variant="Center of Mass", AutomaticScale=0,
                                               ScaleFactor=4.0, GenerateProjectionLines=1)
    view = pvs.GetActiveViewOrCreate("RenderView")
    display = pvs.Show(projection, view)
    pvs.ColorBy(display, ("POINTS", "Stability"))
    pvs.Show(pvs.OutputPort(projection, 1), view)
    pvs.ResetCamera(view)
    pvs.Render(view)

    data = servermanager.Fetch(projection, 0)
    names = {data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())}
    expected = {"Normal", "Energy", "Displacement", "Iterations", "Converged", "Stability", "ExtremumType", "StopReason",
                "DistanceToShape"}
    if names != expected:
        raise RuntimeError("arrays %s, expected %s" % (sorted(names), sorted(expected)))
    points = vtk_to_numpy(data.GetPoints().GetData())
    converged = vtk_to_numpy(data.GetPointData().GetArray("Converged"))
    radius = np.linalg.norm(points[:, :2], axis=1)
    if data.GetNumberOfPoints() != 200 or converged.sum() != 200:
        raise RuntimeError("%d points, %d converged" % (data.GetNumberOfPoints(), converged.sum()))
    start = vtk_to_numpy(servermanager.Fetch(cloud, 0).GetPoints().GetData())
    start_radius = np.linalg.norm(start[:, :2], axis=1)
    if np.median(np.abs(radius - 25.0)) > 0.25 or radius.std() > 0.5 * start_radius.std():
        raise RuntimeError("projected radius %.4f +- %.4f (start %.4f +- %.4f), expected 25 +- 0.25 and half the spread"
                           % (np.median(radius), radius.std(), np.median(start_radius), start_radius.std()))
    lines = servermanager.Fetch(projection, 0, idx=1)
    if lines.GetNumberOfCells() != 200:
        raise RuntimeError("%d projection lines" % lines.GetNumberOfCells())
    if projection not in pvs.GetSources().values():
        raise RuntimeError("the filter is not in the pipeline browser")
    finish(True, "GUI: PointSetSurfaceProjection applied to %d points, radius %.4f +- %.4f (start +- %.4f), shown in %s"
           % (data.GetNumberOfPoints(), np.median(radius), radius.std(), start_radius.std(), view.GetXMLName()))
except SystemExit:
    raise
except Exception:
    finish(False, traceback.format_exc().replace("\n", " | "))

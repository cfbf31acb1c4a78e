"""PointSetSurfaces for Python: MLS point-set surfaces and their domain.

Two levels. The numpy functions take an (N, 3) (or (N, 2)) array or a file path and return numpy
arrays, every surface definition and parameter by keyword::

    import numpy as np
    import pointsetsurfaces as pss

    points = np.random.default_rng(1).normal(size=(5000, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    surface = pss.mesh(points, variant="com")
    print(surface.vertices.shape, surface.triangles.shape, surface.info["EulerCharacteristic"])

``project``, ``classify``, ``sample``, ``mesh`` and ``read`` (see their docstrings); failures raise
``pointsetsurfaces.Error`` with the C++ filter's message.

Below them, the classes of the VTK module PointSetSurfaces::Filters, wrapped by
vtk_module_wrap_python. They derive from the classes of ``vtkmodules`` (imported on the way) and
compose with its filters::

    from vtkmodules.vtkIOPLY import vtkPLYReader
    from pointsetsurfaces import vtkPointSetSurfaceProjection

    reader = vtkPLYReader()
    reader.SetFileName("cloud.ply")
    projection = vtkPointSetSurfaceProjection()
    projection.SetInputConnection(reader.GetOutputPort())
    projection.GetSurface().SetVariantToCenterOfMass()

Importing the package lets the filters use every core: vtkSMPTools' Sequential backend becomes
STDThread unless VTK_SMP_BACKEND_IN_USE chose one (vtkPointSetSurface.UseThreadedBackend).
"""
from .PointSetSurfacesFilters import *  # noqa: F401,F403
from .PointSetSurfacesFilters import vtkPointSetSurface as _Surface

_Surface.UseThreadedBackend()

try:
    from ._numpy_api import (VARIANTS, Error, InputError, Result, SurfaceWarning, classify,  # noqa: F401
                             mesh, project, read, sample)
except ModuleNotFoundError as _missing:
    if _missing.name != "numpy":
        raise

    # The VTK classes work without numpy; the functions say what they need when called.
    class Error(RuntimeError):
        """A PointSetSurfaces computation failed."""

    def _needs_numpy(*_args, **_kwargs):
        raise ImportError("the numpy functions of pointsetsurfaces need numpy (Debian: python3-numpy)")

    project = classify = sample = mesh = read = _needs_numpy

"""PointSetSurfaces' VTK filters for Python: MLS point-set surfaces and their domain.

The classes of the VTK module PointSetSurfaces::Filters, wrapped by vtk_module_wrap_python. They
derive from the classes of ``vtkmodules`` (imported on the way) and compose with its filters::

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

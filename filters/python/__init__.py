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
"""
from .PointSetSurfacesFilters import *  # noqa: F401,F403

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesVertexCells.h
 * @brief One vertex cell per point, for the module's point outputs and vtkPCDReader (VTK only, no
 *        core: the PCD fuzz target compiles it on its own).
 */
#ifndef PointSetSurfacesVertexCells_h
#define PointSetSurfacesVertexCells_h

#include "vtkCellArray.h"
#include "vtkSmartPointer.h"

namespace pss_vtk
{

/// One vertex cell per point 0..n-1: 32-bit ids while they fit (half the memory of a large cloud's
/// vertices, and readable by every VTK reader: the XML files record the type), filled on every
/// vtkSMPTools thread.
vtkSmartPointer<vtkCellArray> VertexCells(vtkIdType n);

}

#endif

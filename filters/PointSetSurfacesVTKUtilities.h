// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesVTKUtilities.h
 * @brief Private helpers shared by the filters: conversions between VTK and the core, output
 *        arrays and cells. No mathematics lives here.
 */
#ifndef PointSetSurfacesVTKUtilities_h
#define PointSetSurfacesVTKUtilities_h

#include "vtkCellArray.h"
#include "vtkIndent.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"

#include "pss/Types.h"

#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkObject;
class vtkPointSet;
class vtkPointSetSurface;

namespace pss_vtk
{

/// Coordinates of @p points as core vectors (empty for nullptr).
std::vector<pss::Vec3> ToVectors(vtkPoints* points);

/// A named array of @p tuples tuples with @p components components.
template <class ArrayT>
vtkSmartPointer<ArrayT> NewArray(const char* name, vtkIdType tuples, int components)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

/// One vertex cell per point 0..n-1.
vtkSmartPointer<vtkCellArray> VertexCells(vtkIdType n);

/// Records the h and the dimension a prepared @p surface used as field data "ScaleFactor" and
/// "Dimension" of @p output, so files written downstream say how they were made.
void AddSurfaceFieldData(vtkDataObject* output, vtkPointSetSurface* surface);

/// The later of @p own and the modification time of @p part (just @p own when part is null):
/// how the filters fold their vtkPointSetSurface into GetMTime().
vtkMTimeType LatestMTime(vtkMTimeType own, vtkObject* part);

/// The "Surface:" block of the filters' PrintSelf.
void PrintSurface(ostream& os, vtkIndent indent, vtkPointSetSurface* surface);

/**
 * What every filter does first: prepares @p surface on @p cloud, reporting a missing surface or a
 * failed Prepare() as an error of @p algorithm ("cannot define the surface<what>: ...") and
 * returning false, and warning when cloud points with NaN/Inf coordinates were left out.
 */
bool PrepareSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkPointSet* cloud, const char* what = "");

}

#endif

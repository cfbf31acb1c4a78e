// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesVTKUtilities.h
 * @brief Private helpers shared by the filters: conversions between VTK and the core, output
 *        arrays and cells, the filters' field data and PrintSelf blocks. No mathematics and no
 *        MPI live here (PointSetSurfacesDistributed.h holds the distributed protocol).
 */
#ifndef PointSetSurfacesVTKUtilities_h
#define PointSetSurfacesVTKUtilities_h

#include "vtkCellArray.h"
#include "vtkIndent.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"

#include "PointSetSurfacesVertexCells.h"

#include "pss/ExtremalSurface.h"
#include "pss/Memory.h"
#include "pss/Types.h"

#include <vector>

class vtkDataObject;
class vtkObject;
class vtkPointSetSurface;

namespace pss_vtk
{

/// Coordinates of @p points as core vectors (empty for nullptr), copied on @p threads threads.
std::vector<pss::Vec3> ToVectors(vtkPoints* points, int threads = 1);

/// A named array of @p tuples tuples with @p components components.
template <class ArrayT>
vtkSmartPointer<ArrayT> NewArray(const char* name, vtkIdType tuples, int components)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  // Filled in the input's order while the points are visited in spatial order (pss/Memory.h).
  pss::adviseHugePages(array->GetVoidPointer(0),
    static_cast<std::size_t>(tuples) * static_cast<std::size_t>(components) * sizeof(typename ArrayT::ValueType));
  return array;
}

/// The sensor position a cloud carries (its field data `Viewpoint`, the first three values, as
/// vtkPCDReader and the depth-camera source write it) into @p xyz; false when it has none.
bool CloudViewpoint(vtkDataObject* cloud, double xyz[3]);

/// Whether @p cloud says it is a depth or LiDAR frame: an organized image (field data
/// GridDimensions, both sides > 1) or the sensor's position (Viewpoint), as vtkPCDReader and the
/// depth-camera source write them. The automatic PointScales takes a scale per point for one.
bool IsSensorFrame(vtkDataObject* cloud);

/// The first of @p points at @p x (within 1e-12 of the points' bounding-box diagonal), or -1.
vtkIdType PointAt(vtkPoints* points, const double x[3]);

/// n's orientation: toward @p viewpoint when it is given (a sensor's position, three values),
/// else away from @p centroid (the rule for closed shapes).
pss::Orientation OrientationFor(const double* viewpoint, const pss::Vec3& centroid);

/// Records the h, the dimension and whether each point had its own scale (h is then their median)
/// that a prepared @p surface used as field data "ScaleFactor", "Dimension" and "PointScales"
/// (0 or 1) of @p output, so files written downstream say how they were made.
void AddSurfaceFieldData(vtkDataObject* output, vtkPointSetSurface* surface);
/// The same from the values themselves (a distributed run's h and dimension, whatever surface
/// the rank prepared last).
void AddSurfaceFieldData(vtkDataObject* output, double h, int dimension, bool pointScales = false);

/// The later of @p own and the modification time of @p part (just @p own when part is null):
/// how the filters fold their vtkPointSetSurface into GetMTime().
vtkMTimeType LatestMTime(vtkMTimeType own, vtkObject* part);

/// The "Surface:" block of the filters' PrintSelf.
void PrintSurface(ostream& os, vtkIndent indent, vtkPointSetSurface* surface);

}

#endif

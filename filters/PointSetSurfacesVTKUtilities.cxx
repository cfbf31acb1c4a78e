// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesVTKUtilities.h"

#include "vtkAlgorithm.h"
#include "vtkObject.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkIdTypeArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkMultiProcessController.h"
#include "vtkPointSetSurface.h"

#include <algorithm>
#include <cstdint>

namespace pss_vtk
{

std::vector<pss::Vec3> ToVectors(vtkPoints* points)
{
  std::vector<pss::Vec3> out;
  if (!points)
  {
    return out;
  }
  const vtkIdType n = points->GetNumberOfPoints();
  out.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->GetPoint(i, out[static_cast<std::size_t>(i)].data());
  }
  return out;
}

namespace
{

template <class ArrayT>
vtkSmartPointer<vtkCellArray> VertexCellsOf(vtkIdType n)
{
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    offsets->SetValue(i, static_cast<typename ArrayT::ValueType>(i));
    connectivity->SetValue(i, static_cast<typename ArrayT::ValueType>(i));
  }
  offsets->SetValue(n, static_cast<typename ArrayT::ValueType>(n));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

} // namespace

vtkSmartPointer<vtkCellArray> VertexCells(vtkIdType n)
{
  // 32-bit ids while they fit: half the memory of a large cloud's vertices, and readable by every
  // VTK reader (the XML files record the type).
  return n < vtkIdType(INT32_MAX) ? VertexCellsOf<vtkTypeInt32Array>(n) : VertexCellsOf<vtkTypeInt64Array>(n);
}

void AddSurfaceFieldData(vtkDataObject* output, vtkPointSetSurface* surface)
{
  auto scale = NewArray<vtkDoubleArray>("ScaleFactor", 1, 1);
  scale->SetValue(0, surface->GetEffectiveScale());
  auto dimension = NewArray<vtkIntArray>("Dimension", 1, 1);
  dimension->SetValue(0, surface->GetEffectiveDimension());
  output->GetFieldData()->AddArray(scale);
  output->GetFieldData()->AddArray(dimension);
}

vtkMTimeType LatestMTime(vtkMTimeType own, vtkObject* part)
{
  return part ? std::max(own, part->GetMTime()) : own;
}

void PrintSurface(ostream& os, vtkIndent indent, vtkPointSetSurface* surface)
{
  os << indent << "Surface: ";
  if (surface)
  {
    os << "\n";
    surface->PrintSelf(os, indent.GetNextIndent());
  }
  else
  {
    os << "(none)\n";
  }
}

bool PrepareSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkPointSet* cloud, const char* what)
{
  if (!surface)
  {
    vtkErrorWithObjectMacro(algorithm, << "no vtkPointSetSurface is set");
    return false;
  }
  // Until the filters run distributed, each rank of an MPI run would take its own piece as the
  // whole cloud (its own h, centroid and neighbours) and silently differ from a one-process run
  // near every piece's border: refuse instead.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    vtkErrorWithObjectMacro(algorithm, << "runs in one process only, and this run has "
                                       << controller->GetNumberOfProcesses()
                                       << " (MPI): each rank would see only its piece of the cloud. Run it in one "
                                          "process (pvpython, or pvbatch without mpiexec), or on the merged cloud");
    return false;
  }
  if (!surface->Prepare(cloud))
  {
    vtkErrorWithObjectMacro(algorithm, << "cannot define the surface" << what << ": " << surface->GetLastError());
    return false;
  }
  const vtkIdType skipped = surface->GetNumberOfSkippedPoints();
  if (skipped > 0)
  {
    vtkWarningWithObjectMacro(algorithm, << skipped
                                         << " cloud point(s) with NaN or infinite coordinates were left out of the surface");
  }
  return true;
}

}

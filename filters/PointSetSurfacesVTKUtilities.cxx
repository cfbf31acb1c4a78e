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
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <climits>
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

bool PrepareSurface(
  vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkPointSet* cloud, const char* what, bool gathered)
{
  if (!surface)
  {
    vtkErrorWithObjectMacro(algorithm, << "no vtkPointSetSurface is set");
    return false;
  }
  // A filter that does not gather the cloud would take each rank's piece as the whole cloud (its
  // own h, centroid and neighbours) and silently differ from a one-process run near every piece's
  // border: refuse instead.
  vtkMultiProcessController* controller = MultiProcessController();
  if (!gathered && controller)
  {
    vtkErrorWithObjectMacro(algorithm, << "runs in one process only (it does not run distributed yet), and this "
                                          "run has "
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

vtkMultiProcessController* MultiProcessController()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

bool PrepareDistributedSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface,
  vtkMultiProcessController* controller, vtkPointSet* cloud, const char* what, vtkSmartPointer<vtkPolyData>& gathered)
{
  if (!controller)
  {
    gathered = nullptr;
    return PrepareSurface(algorithm, surface, cloud, what);
  }
  // The whole cloud on every rank makes h, centroid, bounds and every neighbourhood those of the
  // one-process run by construction, whatever the split.
  gathered = GatherCloud(algorithm, controller, cloud);
  return gathered && PrepareSurface(algorithm, surface, gathered, what, true);
}

vtkSmartPointer<vtkPolyData> GatherCloud(
  vtkAlgorithm* algorithm, vtkMultiProcessController* controller, vtkPointSet* cloud)
{
  const vtkIdType n = cloud ? cloud->GetNumberOfPoints() : 0;
  std::vector<double> local(static_cast<std::size_t>(3 * n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    cloud->GetPoint(i, local.data() + 3 * i);
  }
  const int ranks = controller->GetNumberOfProcesses();
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks));
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks));
  const vtkIdType sendLength = 3 * n;
  controller->AllGather(&sendLength, lengths.data(), 1);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    offsets[static_cast<std::size_t>(r)] = total;
    total += lengths[static_cast<std::size_t>(r)];
  }
  // MPI counts are ints; every rank knows the total, so all of them fail here together.
  if (total > vtkIdType(INT_MAX))
  {
    vtkErrorWithObjectMacro(algorithm, << "the cloud of all ranks (" << total / 3
                                       << " points) exceeds one MPI message (2^31 - 1 coordinates)");
    return nullptr;
  }
  auto coordinates = vtkSmartPointer<vtkDoubleArray>::New();
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(total / 3);
  if (total > 0)
  {
    controller->AllGatherV(local.data(), coordinates->GetPointer(0), sendLength, lengths.data(), offsets.data());
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  auto whole = vtkSmartPointer<vtkPolyData>::New();
  whole->SetPoints(points);
  return whole;
}

void AddGlobalPointIds(vtkPointData* pd, vtkIdType first, vtkIdType n)
{
  if (pd->GetGlobalIds())
  {
    return;
  }
  auto ids = NewArray<vtkIdTypeArray>("GlobalPointIds", n, 1);
  for (vtkIdType i = 0; i < n; ++i)
  {
    ids->SetValue(i, first + i);
  }
  pd->SetGlobalIds(ids);
}

vtkIdType GlobalOffset(vtkMultiProcessController* controller, vtkIdType count)
{
  std::vector<vtkIdType> counts(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  controller->AllGather(&count, counts.data(), 1);
  vtkIdType offset = 0;
  for (int r = 0; r < controller->GetLocalProcessId(); ++r)
  {
    offset += counts[static_cast<std::size_t>(r)];
  }
  return offset;
}

}

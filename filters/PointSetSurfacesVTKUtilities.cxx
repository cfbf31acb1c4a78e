// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesVTKUtilities.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkObject.h"
#include "vtkPointSetSurface.h"

#include "pss/Parallel.h"

#include <algorithm>

namespace pss_vtk
{

std::vector<pss::Vec3> ToVectors(vtkPoints* points, int threads)
{
  std::vector<pss::Vec3> out;
  if (!points)
  {
    return out;
  }
  const vtkIdType n = points->GetNumberOfPoints();
  pss::resizeOnHugePages(out, static_cast<std::size_t>(n));
  // Double coordinates (what the readers and sources here produce) are read from the array's
  // memory directly: a virtual GetPoint per point costs more than the copy itself.
  vtkDoubleArray* doubles = vtkDoubleArray::FastDownCast(points->GetData());
  const double* raw = doubles && doubles->GetNumberOfComponents() == 3 ? doubles->GetPointer(0) : nullptr;
  // Few points stay on this thread: starting threads would cost more than the copy.
  const int copyThreads = n < (vtkIdType(1) << 14) ? 1 : threads;
  pss::parallelFor(static_cast<std::size_t>(n), copyThreads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      if (raw)
      {
        out[i] = pss::Vec3(raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]);
      }
      else
      {
        points->GetPoint(static_cast<vtkIdType>(i), out[i].data());
      }
    }
  });
  return out;
}

bool CloudViewpoint(vtkDataObject* cloud, double xyz[3])
{
  vtkDataArray* field = cloud ? cloud->GetFieldData()->GetArray("Viewpoint") : nullptr;
  if (!field || field->GetNumberOfValues() < 3)
  {
    return false;
  }
  const int components = field->GetNumberOfComponents();
  for (int k = 0; k < 3; ++k)
  {
    xyz[k] = field->GetComponent(k / components, k % components);
  }
  return true;
}

bool IsSensorFrame(vtkDataObject* cloud)
{
  vtkFieldData* field = cloud ? cloud->GetFieldData() : nullptr;
  if (!field)
  {
    return false;
  }
  if (field->GetArray("Viewpoint"))
  {
    return true;
  }
  vtkDataArray* grid = field->GetArray("GridDimensions");
  if (!grid || grid->GetNumberOfValues() < 2)
  {
    return false;
  }
  const int components = grid->GetNumberOfComponents();
  return grid->GetComponent(0, 0) > 1 && grid->GetComponent(1 / components, 1 % components) > 1;
}

vtkIdType PointAt(vtkPoints* points, const double x[3])
{
  if (!points || points->GetNumberOfPoints() == 0)
  {
    return -1;
  }
  double bounds[6];
  points->GetBounds(bounds);
  const double diagonalSq = (bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) + (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]);
  const double toleranceSq = 1e-24 * diagonalSq;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    const double dSq = (p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]) + (p[2] - x[2]) * (p[2] - x[2]);
    if (dSq <= toleranceSq)
    {
      return i;
    }
  }
  return -1;
}

pss::Orientation OrientationFor(const double* viewpoint, const pss::Vec3& centroid)
{
  return viewpoint ? pss::Orientation::toward(pss::Vec3(viewpoint[0], viewpoint[1], viewpoint[2]))
                   : pss::Orientation::awayFrom(centroid);
}

void AddSurfaceFieldData(vtkDataObject* output, vtkPointSetSurface* surface)
{
  AddSurfaceFieldData(
    output, surface->GetEffectiveScale(), surface->GetEffectiveDimension(), surface->GetUsesPointScales());
}

void AddSurfaceFieldData(vtkDataObject* output, double h, int dimension, bool pointScales)
{
  auto scale = NewArray<vtkDoubleArray>("ScaleFactor", 1, 1);
  scale->SetValue(0, h);
  auto dimensionArray = NewArray<vtkIntArray>("Dimension", 1, 1);
  dimensionArray->SetValue(0, dimension);
  output->GetFieldData()->AddArray(scale);
  output->GetFieldData()->AddArray(dimensionArray);
  auto perPoint = NewArray<vtkIntArray>("PointScales", 1, 1);
  perPoint->SetValue(0, pointScales ? 1 : 0);
  output->GetFieldData()->AddArray(perPoint);
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

}

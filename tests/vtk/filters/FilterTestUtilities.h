// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FilterTestUtilities.h
 * @brief Small helpers of the filter tests: point sets from coordinates, array access, and the
 *        "no NaN without a flag" check.
 */
#pragma once

#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace pss_test
{

using Point = std::array<double, 3>;

/// A vtkPolyData with the given points and one vertex cell each.
inline vtkSmartPointer<vtkPolyData> MakePoints(const std::vector<Point>& coordinates)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts;
  for (const Point& p : coordinates)
  {
    const vtkIdType id = points->InsertNextPoint(p.data());
    verts->InsertNextCell(1, &id);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetVerts(verts);
  return pd;
}

/// Point-data array @p name of @p pd, failing the test when absent.
inline vtkDataArray* PointArray(vtkPolyData* pd, const char* name)
{
  vtkDataArray* a = pd->GetPointData()->GetArray(name);
  EXPECT_NE(a, nullptr) << "missing point array " << name;
  return a;
}

inline double Value(vtkPolyData* pd, const char* name, vtkIdType i, int component = 0)
{
  vtkDataArray* a = PointArray(pd, name);
  return a ? a->GetComponent(i, component) : std::nan("");
}

inline Point Coordinates(vtkPolyData* pd, vtkIdType i)
{
  Point p;
  pd->GetPoint(i, p.data());
  return p;
}

inline double Dot(const Point& a, const Point& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline double Norm(const Point& a)
{
  return std::sqrt(Dot(a, a));
}

inline Point Sub(const Point& a, const Point& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

/**
 * Every NaN or infinite value among the points and point arrays of @p pd belongs to a point that
 * @p flagged says is flagged (e.g. StopReason 4, DomainLabel 2 or 3). Returns the number of
 * unflagged non-finite values (0 is the contract).
 */
inline int CountUnflaggedNonFinite(vtkPolyData* pd, const std::function<bool(vtkIdType)>& flagged)
{
  int bad = 0;
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    if (flagged(i))
    {
      continue;
    }
    const Point p = Coordinates(pd, i);
    bad += std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) ? 0 : 1;
    for (int a = 0; a < pd->GetPointData()->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = pd->GetPointData()->GetArray(a);
      for (int c = 0; array && c < array->GetNumberOfComponents(); ++c)
      {
        bad += std::isfinite(array->GetComponent(i, c)) ? 0 : 1;
      }
    }
  }
  return bad;
}

}

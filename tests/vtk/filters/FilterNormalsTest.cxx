// SPDX-License-Identifier: BSD-3-Clause
// vtkPointSetSurfaceProjection's PropagateNormals: a torus cloud projected onto itself gives its
// oriented normals, every one outward, where the default rule (away from the centroid) turns the
// inner ring inward; the same bytes on 1 and 2 threads.
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceProjection.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
using pss_test::Point;

constexpr double kMajor = 10.0;
constexpr double kMinor = 3.0;

std::vector<Point> torus()
{
  std::vector<Point> pts;
  for (int i = 0; i < 160; ++i)
  {
    for (int j = 0; j < 50; ++j)
    {
      const double u = 2.0 * M_PI * (i + 0.5 * (j % 2)) / 160.0, v = 2.0 * M_PI * j / 50.0;
      const double r = kMajor + kMinor * std::cos(v);
      pts.push_back({ r * std::cos(u), r * std::sin(u), kMinor * std::sin(v) });
    }
  }
  return pts;
}

// The share of the output's Normal that points out of the torus.
double outwardShare(vtkPolyData* out)
{
  vtkIdType outward = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const Point p = pss_test::Coordinates(out, i);
    const double radial = std::hypot(p[0], p[1]);
    const Point tubeCentre{ kMajor * p[0] / radial, kMajor * p[1] / radial, 0.0 };
    const Point n{ pss_test::Value(out, "Normal", i, 0), pss_test::Value(out, "Normal", i, 1),
      pss_test::Value(out, "Normal", i, 2) };
    outward += pss_test::Dot(n, pss_test::Sub(p, tubeCentre)) > 0.0 ? 1 : 0;
  }
  return static_cast<double>(outward) / static_cast<double>(out->GetNumberOfPoints());
}

vtkSmartPointer<vtkPolyData> project(vtkPolyData* cloud, bool propagate)
{
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputData(cloud);
  projection->GetSurface()->SetVariantToCenterOfMass();
  projection->SetProcedureToPlane();
  projection->SetPropagateNormals(propagate);
  projection->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(projection->GetOutput());
  return out;
}

} // namespace

TEST(ProjectionNormals, PropagatedNormalsOfATorusPointOutward)
{
  const vtkSmartPointer<vtkPolyData> cloud = pss_test::MakePoints(torus());
  const vtkSmartPointer<vtkPolyData> propagated = project(cloud, true);
  ASSERT_EQ(propagated->GetNumberOfPoints(), cloud->GetNumberOfPoints());
  EXPECT_EQ(outwardShare(propagated), 1.0);
  EXPECT_LT(outwardShare(project(cloud, false)), 0.75) << "the centroid rule turns the inner ring inward";

  // The test main runs the threaded backend (vtkPointSetSurface::UseThreadedBackend).
  vtkSMPTools::Initialize(1);
  const vtkSmartPointer<vtkPolyData> single = project(cloud, true);
  vtkSMPTools::Initialize(2);
  const vtkSmartPointer<vtkPolyData> dual = project(cloud, true);
  vtkSMPTools::Initialize();
  vtkDataArray* a = single->GetPointData()->GetArray("Normal");
  vtkDataArray* b = dual->GetPointData()->GetArray("Normal");
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    ASSERT_EQ(a->GetComponent(i / 3, static_cast<int>(i % 3)), b->GetComponent(i / 3, static_cast<int>(i % 3)));
  }
}

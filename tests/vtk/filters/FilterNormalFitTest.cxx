// SPDX-License-Identifier: BSD-3-Clause
// APSS and RIMLS through the filters: a sphere cloud with its exact normals as a `Normals` array
// projects onto the sphere; without the array the normals are estimated and oriented (the
// surface says so) and the projection still lands on it; the same bytes on 1 and 2 threads; the
// mesher closes the sphere; bad normals fail with a message naming the problem.
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceMesher.h"
#include "vtkPointSetSurfaceProjection.h"
#include "vtkSMPTools.h"

#include "pss/PointIndex.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
using pss_test::Point;

constexpr double kRadius = 5.0;

std::vector<Point> sphere(int count)
{
  std::vector<Point> pts;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / count;
    const double r = std::sqrt(1.0 - z * z);
    pts.push_back({ kRadius * r * std::cos(golden * i), kRadius * r * std::sin(golden * i), kRadius * z });
  }
  return pts;
}

// The cloud with its outward normals as the point array "Normals" (@p components per tuple).
vtkSmartPointer<vtkPolyData> sphereWithNormals(int components = 3)
{
  auto cloud = pss_test::MakePoints(sphere(2000));
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(components);
  normals->SetNumberOfTuples(cloud->GetNumberOfPoints());
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    const Point p = pss_test::Coordinates(cloud, i);
    for (int k = 0; k < components; ++k)
    {
      normals->SetComponent(i, k, k < 3 ? p[k] / kRadius : 0.0);
    }
  }
  cloud->GetPointData()->AddArray(normals);
  return cloud;
}

// Projects @p cloud onto itself; @p h receives the scale used.
vtkSmartPointer<vtkPolyData> project(vtkPolyData* cloud, int variant, ErrorObserver* log = nullptr, double* h = nullptr)
{
  vtkNew<vtkPointSetSurfaceProjection> projection;
  if (log)
  {
    log->Attach(projection);
  }
  projection->SetInputData(cloud);
  projection->GetSurface()->SetVariant(variant);
  projection->SetProcedureToPlane();
  projection->Update();
  if (h)
  {
    *h = projection->GetSurface()->GetEffectiveScale();
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(projection->GetOutput());
  return out;
}

// RIMLS averages the planes through the neighbours and their normals: on a sphere of radius R
// that puts f's zero about <d^2> / (2R) = h^2 / (2R) out of it (d the neighbours' distance along
// the surface, Gaussian-weighted over the plane). APSS has no such bias.
double expectedBias(int variant, double h)
{
  return variant == vtkPointSetSurface::APSS ? 0.0 : h * h / (2.0 * kRadius);
}

double worstRadiusError(vtkPolyData* out)
{
  double worst = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    worst = std::max(worst, std::abs(pss_test::Norm(pss_test::Coordinates(out, i)) - kRadius));
  }
  return worst;
}

} // namespace

TEST(FilterNormalFit, GivenNormalsProjectOntoTheSphere)
{
  const auto cloud = sphereWithNormals();
  for (const int variant : { vtkPointSetSurface::APSS, vtkPointSetSurface::RIMLS })
  {
    double h = 0.0;
    const auto out = project(cloud, variant, nullptr, &h);
    ASSERT_EQ(out->GetNumberOfPoints(), cloud->GetNumberOfPoints()) << variant;
    // APSS reproduces the sphere from exact normals (rounding only); RIMLS within 20% of its bias.
    EXPECT_NEAR(worstRadiusError(out), expectedBias(variant, h), 1e-9 + 0.2 * expectedBias(variant, h)) << variant;
  }
}

TEST(FilterNormalFit, EstimatedNormalsAreOrientedAndTheSameOnAnyThreadCount)
{
  const auto cloud = pss_test::MakePoints(sphere(2000));
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputData(cloud);
  projection->GetSurface()->SetVariantToAPSS();
  projection->SetProcedureToPlane();
  projection->Update();
  EXPECT_EQ(std::string(projection->GetSurface()->GetNormalsSource()), "estimated");
  EXPECT_EQ(projection->GetSurface()->GetBorrowedNormals(), 0);
  auto two = vtkSmartPointer<vtkPolyData>::New();
  two->ShallowCopy(projection->GetOutput());
  EXPECT_LT(worstRadiusError(two), 0.02);

  vtkSMPTools::Initialize(1);
  projection->Modified();
  projection->GetSurface()->Modified();
  projection->Update();
  vtkSMPTools::Initialize(2);
  vtkPolyData* one = projection->GetOutput();
  ASSERT_EQ(one->GetNumberOfPoints(), two->GetNumberOfPoints());
  for (vtkIdType i = 0; i < one->GetNumberOfPoints(); ++i)
  {
    const Point a = pss_test::Coordinates(one, i);
    const Point b = pss_test::Coordinates(two, i);
    ASSERT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) << "point " << i;
  }
}

// Given normals flipped on half of the sphere: taken as given they cancel along the seam, where
// APSS has no direction; ReorientNormals turns every normal outward and every fit is firm again.
TEST(FilterNormalFit, ReorientNormalsRepairsAHalfFlippedSphere)
{
  auto cloud = sphereWithNormals();
  vtkDataArray* normals = cloud->GetPointData()->GetArray("Normals");
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    if (pss_test::Coordinates(cloud, i)[0] < 0.0)
    {
      double n[3];
      normals->GetTuple(i, n);
      normals->SetTuple3(i, -n[0], -n[1], -n[2]);
    }
  }
  // Taken as given, the normals cancel along the seam x = 0: n is undefined there.
  const auto asGiven = project(cloud, vtkPointSetSurface::APSS);
  vtkIdType weak = 0;
  for (vtkIdType i = 0; i < asGiven->GetNumberOfPoints(); ++i)
  {
    weak += pss_test::Value(asGiven, "Stability", i) < 0.5 ? 1 : 0;
  }
  EXPECT_GT(weak, 20) << "flipped normals taken as given";
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputData(cloud);
  projection->GetSurface()->SetVariantToAPSS();
  projection->GetSurface()->ReorientNormalsOn();
  projection->SetProcedureToPlane();
  projection->Update();
  EXPECT_EQ(std::string(projection->GetSurface()->GetNormalsSource()), "reoriented");
  const pss::PointIndex* index = projection->GetSurface()->GetIndex();
  ASSERT_NE(index, nullptr);
  for (std::size_t i = 0; i < index->size(); ++i)
  {
    ASSERT_GT(index->normal(i).dot(index->point(i)), 0.0) << "point " << index->originalId(i) << " not outward";
  }
  vtkPolyData* out = projection->GetOutput();
  EXPECT_LT(worstRadiusError(out), 1e-9);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    ASSERT_GT(pss_test::Value(out, "Stability", i), 0.5) << "point " << i;
  }
}

TEST(FilterNormalFit, TheMesherClosesTheSphere)
{
  for (const int variant : { vtkPointSetSurface::APSS, vtkPointSetSurface::RIMLS })
  {
    vtkNew<vtkPointSetSurfaceMesher> mesher;
    mesher->SetInputData(sphereWithNormals());
    mesher->GetSurface()->SetVariant(variant);
    mesher->Update();
    vtkPolyData* mesh = mesher->GetOutput();
    ASSERT_GT(mesh->GetNumberOfPolys(), 1000) << variant;
    vtkFieldData* fd = mesh->GetFieldData();
    EXPECT_EQ(fd->GetArray("Components")->GetComponent(0, 0), 1.0) << variant;
    EXPECT_EQ(fd->GetArray("BoundaryEdges")->GetComponent(0, 0), 0.0) << variant;
    const double bias = expectedBias(variant, mesher->GetSurface()->GetEffectiveScale());
    EXPECT_NEAR(worstRadiusError(mesh), bias, 1e-6 + 0.2 * bias) << variant;
  }
}

TEST(FilterNormalFit, BadNormalsFailWithAMessage)
{
  {
    vtkNew<ErrorObserver> log;
    const auto out = project(sphereWithNormals(2), vtkPointSetSurface::APSS, log);
    EXPECT_TRUE(log->HasError("must have 3 components")) << (log->Errors.empty() ? "no error" : log->Errors[0]);
    EXPECT_EQ(out->GetNumberOfPoints(), 0);
  }
  for (const double bad : { 0.0, std::numeric_limits<double>::quiet_NaN() })
  {
    auto cloud = sphereWithNormals();
    vtkDataArray* normals = cloud->GetPointData()->GetArray("Normals");
    normals->SetTuple3(7, bad, bad, bad);
    vtkNew<ErrorObserver> log;
    const auto out = project(cloud, vtkPointSetSurface::RIMLS, log);
    EXPECT_TRUE(log->HasError("the normal of point 7")) << (log->Errors.empty() ? "no error" : log->Errors[0]);
    EXPECT_EQ(out->GetNumberOfPoints(), 0);
  }
  {
    // Points too far apart for any normal: nothing to orient.
    auto cloud = pss_test::MakePoints({ { 0.0, 0.0, 0.0 }, { 100.0, 0.0, 0.0 }, { 0.0, 100.0, 0.0 }, { 0.0, 0.0, 100.0 } });
    vtkNew<vtkPointSetSurfaceProjection> projection;
    vtkNew<ErrorObserver> log;
    log->Attach(projection);
    projection->SetInputData(cloud);
    projection->GetSurface()->SetVariantToAPSS();
    projection->GetSurface()->AutomaticScaleOff();
    projection->GetSurface()->SetScaleFactor(1.0);
    projection->Update();
    EXPECT_TRUE(log->HasError("no cloud point has a normal")) << (log->Errors.empty() ? "no error" : log->Errors[0]);
  }
}

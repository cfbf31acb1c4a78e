// SPDX-License-Identifier: BSD-3-Clause
/**
 * A scale per point through the filters (vtkPointSetSurface's PointScales): a Scale array of
 * equal values gives the single-h projection; scales that vary tenfold over a plane still project
 * onto it; the automatic mode keeps one h on an evenly sampled cloud and turns per-point scales
 * on for a sensor frame; bad Scale arrays and a viewpoint at a cloud point are clear errors.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceProjection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace pss_test;

namespace
{

// A 31 x 31 grid in z = 0 whose spacing along x grows geometrically, by @p growth over the patch.
std::vector<Point> GradedPlane(double growth)
{
  std::vector<Point> points;
  const int n = 31;
  const double ratio = std::pow(growth, 1.0 / (n - 2));
  double x = 0.0, step = 0.05;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      points.push_back({ x, (j - n / 2) * step, 0.0 });
    }
    x += step;
    step *= ratio;
  }
  return points;
}

vtkSmartPointer<vtkPolyData> WithScaleArray(vtkPolyData* cloud, const std::vector<double>& values, int components = 1)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(cloud);
  vtkNew<vtkDoubleArray> scale;
  scale->SetName("Scale");
  scale->SetNumberOfComponents(components);
  for (double v : values)
  {
    for (int c = 0; c < components; ++c)
    {
      scale->InsertNextValue(v);
    }
  }
  copy->GetPointData()->AddArray(scale);
  return copy;
}

// Projects the cloud's own points (Center of Mass, the extremal procedure), the filter updated.
vtkSmartPointer<vtkPointSetSurfaceProjection> Project(
  vtkPolyData* cloud, const std::function<void(vtkPointSetSurface*)>& configure, ErrorObserver* log = nullptr)
{
  auto projection = vtkSmartPointer<vtkPointSetSurfaceProjection>::New();
  if (log)
  {
    log->Attach(projection);
  }
  projection->SetInputData(cloud);
  configure(projection->GetSurface());
  projection->Update();
  return projection;
}

} // namespace

TEST(PointScales, EqualScalesFromAnArrayGiveTheSingleScale)
{
  auto cloud = MakePoints(GradedPlane(1.0));
  for (auto& p : std::vector<vtkIdType>{ 5, 100, 480 })
  {
    double x[3];
    cloud->GetPoint(p, x);
    cloud->GetPoints()->SetPoint(p, x[0], x[1], 0.01); // something to project
  }
  const double h = 0.12;
  auto singleFilter = Project(cloud, [h](vtkPointSetSurface* s) {
    s->AutomaticScaleOff();
    s->SetScaleFactor(h);
  });
  vtkPolyData* single = singleFilter->GetOutput();
  auto arrayCloud = WithScaleArray(cloud, std::vector<double>(static_cast<std::size_t>(cloud->GetNumberOfPoints()), h));
  auto filter = Project(arrayCloud, [](vtkPointSetSurface* s) { s->SetPointScalesToFromArray(); });
  EXPECT_TRUE(filter->GetSurface()->GetUsesPointScales());
  EXPECT_DOUBLE_EQ(filter->GetSurface()->GetEffectiveScale(), h);
  vtkPolyData* perPoint = filter->GetOutput();
  ASSERT_EQ(single->GetNumberOfPoints(), perPoint->GetNumberOfPoints());
  for (vtkIdType i = 0; i < single->GetNumberOfPoints(); ++i)
  {
    const Point a = Coordinates(single, i), b = Coordinates(perPoint, i);
    EXPECT_LE(Norm(Sub(a, b)), 1e-12 * h) << "point " << i;
  }
}

TEST(PointScales, TenfoldScalesStayOnThePlane)
{
  auto cloud = MakePoints(GradedPlane(10.0));
  auto starts = MakePoints(GradedPlane(10.0));
  for (vtkIdType i = 0; i < starts->GetNumberOfPoints(); ++i)
  {
    double x[3];
    starts->GetPoint(i, x);
    starts->GetPoints()->SetPoint(i, x[0], x[1], 0.02 * std::sin(7.0 * i)); // off the plane, both sides
  }
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputData(cloud);
  projection->SetStartPointsData(starts);
  projection->GetSurface()->SetPointScalesToEstimated();
  projection->Update();
  vtkPolyData* out = projection->GetOutput();
  EXPECT_TRUE(projection->GetSurface()->GetUsesPointScales());
  EXPECT_GT(projection->GetSurface()->GetScaleSpread(), 3.0);
  ASSERT_EQ(out->GetNumberOfPoints(), starts->GetNumberOfPoints());
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    ASSERT_EQ(Value(out, "StopReason", i), 0.0) << "point " << i;
    EXPECT_LE(std::abs(Coordinates(out, i)[2]), 1e-6) << "point " << i;
  }
}

TEST(PointScales, AutomaticKeepsOneScaleOnEvenCloudsAndFollowsSensorFrames)
{
  auto cloud = MakePoints(GradedPlane(1.0));
  auto automatic = Project(cloud, [](vtkPointSetSurface*) {});
  EXPECT_FALSE(automatic->GetSurface()->GetUsesPointScales()) << "spread " << automatic->GetSurface()->GetScaleSpread();
  auto off = Project(cloud, [](vtkPointSetSurface* s) { s->SetPointScalesToOff(); });
  ASSERT_EQ(automatic->GetOutput()->GetNumberOfPoints(), off->GetOutput()->GetNumberOfPoints());
  for (vtkIdType i = 0; i < off->GetOutput()->GetNumberOfPoints(); ++i)
  {
    EXPECT_EQ(Coordinates(automatic->GetOutput(), i), Coordinates(off->GetOutput(), i)) << "point " << i;
  }

  // The same points as a sensor frame: a viewpoint, then (separately) an organized image.
  for (const char* kind : { "Viewpoint", "GridDimensions" })
  {
    auto frame = vtkSmartPointer<vtkPolyData>::New();
    frame->ShallowCopy(cloud);
    if (std::string(kind) == "Viewpoint")
    {
      vtkNew<vtkDoubleArray> viewpoint;
      viewpoint->SetName("Viewpoint");
      for (double v : { 0.7, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0 })
      {
        viewpoint->InsertNextValue(v);
      }
      frame->GetFieldData()->AddArray(viewpoint);
    }
    else
    {
      vtkNew<vtkIntArray> grid;
      grid->SetName("GridDimensions");
      grid->InsertNextValue(31);
      grid->InsertNextValue(31);
      frame->GetFieldData()->AddArray(grid);
    }
    EXPECT_TRUE(Project(frame, [](vtkPointSetSurface*) {})->GetSurface()->GetUsesPointScales()) << kind;
  }
}

TEST(PointScales, BadScaleArraysAreErrors)
{
  auto cloud = MakePoints(GradedPlane(1.0));
  const auto n = static_cast<std::size_t>(cloud->GetNumberOfPoints());
  struct Case
  {
    const char* what;
    std::vector<double> values;
    int components;
    const char* message;
  };
  std::vector<double> zero(n, 0.1), negative(n, 0.1), nan(n, 0.1), tiny(n, 0.1);
  zero[7] = 0.0;
  negative[8] = -0.1;
  nan[9] = std::numeric_limits<double>::quiet_NaN();
  tiny[10] = 1e-200; // 1 / h^2 overflows
  const std::vector<Case> cases = {
    { "a zero", zero, 1, "the scale of point 7 must be a positive finite number" },
    { "a negative value", negative, 1, "the scale of point 8 must be a positive finite number" },
    { "a NaN", nan, 1, "the scale of point 9 must be a positive finite number" },
    { "a value whose inverse square overflows", tiny, 1, "the scale of point 10" },
    { "too few values", std::vector<double>(n - 1, 0.1), 1, "the scale array has 960 values for 961 points" },
    { "two components", std::vector<double>(n, 0.1), 2, "no one-component point array named \"Scale\"" },
  };
  for (const Case& c : cases)
  {
    vtkNew<ErrorObserver> log;
    auto filter = Project(WithScaleArray(cloud, c.values, c.components),
      [](vtkPointSetSurface* s) { s->SetPointScalesToFromArray(); }, log);
    EXPECT_TRUE(log->HasError(c.message)) << c.what << ": " << (log->Errors.empty() ? "no error" : log->Errors[0]);
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0) << c.what;
  }
  vtkNew<ErrorObserver> log;
  Project(cloud, [](vtkPointSetSurface* s) {
    s->SetPointScalesToFromArray();
    s->SetScaleArrayName("Radius");
  }, log);
  EXPECT_TRUE(log->HasError("no one-component point array named \"Radius\""));
}

TEST(PointScales, ViewpointAtACloudPointIsAnError)
{
  auto cloud = MakePoints(GradedPlane(1.0));
  double x[3];
  cloud->GetPoint(17, x);
  vtkNew<vtkPointSetSurfaceProjection> projection;
  vtkNew<ErrorObserver> log;
  log->Attach(projection);
  projection->SetInputData(cloud);
  projection->SetViewpointModeToGiven();
  projection->SetViewpoint(x);
  projection->Update();
  EXPECT_TRUE(log->HasError("is cloud point 17")) << (log->Errors.empty() ? "no error" : log->Errors[0]);
  EXPECT_EQ(projection->GetOutput()->GetNumberOfPoints(), 0);
  // A hair away it is a viewpoint like any other.
  log->Clear();
  projection->SetViewpoint(x[0], x[1], x[2] + 1e-6);
  projection->Update();
  EXPECT_FALSE(log->HasError());
  EXPECT_EQ(projection->GetOutput()->GetNumberOfPoints(), cloud->GetNumberOfPoints());
}

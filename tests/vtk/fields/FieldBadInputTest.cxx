// SPDX-License-Identifier: BSD-3-Clause
// Bad input for vtkPointSetSurfaceFieldSampler and vtkPointSetSurfaceImplicitFunction: every case
// must end in a clear error (or, for skipped points, a warning), never in a crash, and no output
// array may contain a NaN or an infinity.

#include "FieldTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceFieldSampler.h"
#include "vtkPointSetSurfaceImplicitFunction.h"

#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <limits>

using namespace pss_field_test;

namespace
{

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A sampler on @p cloud with h = 1 in 2D, its errors collected by @p observer.
vtkSmartPointer<vtkPointSetSurfaceFieldSampler> MakeSampler(vtkPolyData* cloud, ErrorObserver* observer)
{
  auto sampler = vtkSmartPointer<vtkPointSetSurfaceFieldSampler>::New();
  sampler->GetSurface()->AutomaticScaleOff();
  sampler->GetSurface()->SetScaleFactor(1.0);
  sampler->SetSourceData(cloud);
  observer->Watch(sampler);
  observer->Watch(sampler->GetExecutive());
  return sampler;
}

/// Runs the pipeline; returns the executive's verdict (0 on failure).
int RunPipeline(vtkAlgorithm* algorithm)
{
  return algorithm->GetExecutive()->Update();
}

vtkSmartPointer<vtkPolyData> Points(const std::vector<std::array<double, 3>>& pts)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : pts)
  {
    points->InsertNextPoint(p.data());
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  return data;
}

/// Sets AbortExecute on the first progress report above 0.
class AbortOnProgress : public vtkCommand
{
public:
  static AbortOnProgress* New() { return new AbortOnProgress; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    const double progress = callData ? *static_cast<double*>(callData) : 0.0;
    if (progress > 0.0 && progress < 1.0)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      ++this->Aborted;
    }
  }
  int Aborted = 0;
};

} // namespace

TEST(FieldBadInput, EmptyCloud)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<ErrorObserver> observer;
  // Probe mode.
  auto sampler = MakeSampler(empty, observer);
  sampler->SetInputData(Points({ { 0, 0, 0 } }));
  EXPECT_EQ(RunPipeline(sampler), 0);
  EXPECT_TRUE(observer->ErrorContains("empty")) << observer->AllErrors();
  EXPECT_EQ(sampler->GetOutput()->GetPointData()->GetArray("ImplicitG"), nullptr);

  // Grid mode.
  observer->Clear();
  auto grid = MakeSampler(empty, observer);
  grid->GenerateSamplingGridOn();
  EXPECT_EQ(RunPipeline(grid), 0);
  EXPECT_TRUE(observer->ErrorContains("empty")) << observer->AllErrors();

  // Implicit function: 0 everywhere and one error, not one per evaluation.
  vtkNew<vtkPointSetSurfaceImplicitFunction> function;
  vtkNew<ErrorObserver> fobserver;
  fobserver->Watch(function);
  function->SetInputData(empty);
  double x[3] = { 0.5, 0.5, 0.0 }, grad[3];
  for (int k = 0; k < 10; ++k)
  {
    EXPECT_EQ(function->EvaluateFunction(x), 0.0);
  }
  function->EvaluateGradient(x, grad);
  EXPECT_EQ(grad[0], 0.0);
  EXPECT_EQ(fobserver->Errors.size(), 1u) << fobserver->AllErrors();
  EXPECT_TRUE(fobserver->ErrorContains("empty")) << fobserver->AllErrors();
  EXPECT_FALSE(function->Initialize());

  // ... and without any cloud.
  vtkNew<vtkPointSetSurfaceImplicitFunction> none;
  vtkNew<ErrorObserver> nobserver;
  nobserver->Watch(none);
  EXPECT_EQ(none->EvaluateFunction(x), 0.0);
  EXPECT_TRUE(nobserver->ErrorContains("no point cloud")) << nobserver->AllErrors();
}

TEST(FieldBadInput, NonFiniteSamplePoints)
{
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(5.0, 0.1);
  vtkNew<ErrorObserver> observer;
  auto sampler = MakeSampler(cloud, observer);
  sampler->ComputeDomainLabelsOn();
  sampler->SetInputData(Points({ { 0.2, 0.3, 0 }, { kNaN, 0, 0 }, { kInf, 1, 0 }, { 0, -kInf, 0 }, { 0.5, 0, kNaN },
    { -0.2, -0.3, 0 } }));
  ASSERT_EQ(RunPipeline(sampler), 1) << observer->AllErrors();
  EXPECT_TRUE(observer->WarningContains("NaN or infinite")) << "a warning names the bad samples";
  vtkDataSet* out = sampler->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 6);
  EXPECT_EQ(CountNonFinite(out), 0);
  vtkDataArray* valid = out->GetPointData()->GetArray("Valid");
  vtkDataArray* stability = out->GetPointData()->GetArray("Stability");
  vtkDataArray* type = out->GetPointData()->GetArray("ExtremumType");
  vtkDataArray* label = out->GetPointData()->GetArray("DomainLabel");
  vtkDataArray* normal = out->GetPointData()->GetArray("Normal");
  ASSERT_TRUE(valid && stability && type && label && normal);
  for (vtkIdType i = 0; i < 6; ++i)
  {
    const bool good = i == 0 || i == 5;
    EXPECT_EQ(valid->GetTuple1(i), good ? 1.0 : 0.0) << i;
    if (!good)
    {
      EXPECT_EQ(stability->GetTuple1(i), 0.0);
      EXPECT_EQ(type->GetTuple1(i), 0.0);
      EXPECT_EQ(label->GetTuple1(i), 2.0) << "Undefined";
      EXPECT_EQ(normal->GetTuple3(i)[0], 0.0);
    }
    else
    {
      // 0.3 h from the line, inside every domain: a well-defined normal (y-axis), in the domain.
      EXPECT_GT(stability->GetTuple1(i), 0.9);
      EXPECT_NEAR(std::abs(normal->GetTuple3(i)[1]), 1.0, 1e-9);
      EXPECT_EQ(label->GetTuple1(i), 0.0) << "InDomain";
    }
  }

  // The implicit function at such points: 0, and a zero gradient.
  vtkNew<vtkPointSetSurfaceImplicitFunction> function;
  function->GetSurface()->AutomaticScaleOff();
  function->SetInputData(cloud);
  double bad[3] = { kNaN, 0.0, 0.0 }, grad[3] = { 1, 1, 1 };
  EXPECT_EQ(function->EvaluateFunction(bad), 0.0);
  function->EvaluateGradient(bad, grad);
  EXPECT_TRUE(grad[0] == 0.0 && grad[1] == 0.0 && grad[2] == 0.0);
}

TEST(FieldBadInput, NonFiniteCloudPointsAreSkipped)
{
  // Skipping a point must leave exactly the surface of the remaining points.
  vtkSmartPointer<vtkPolyData> clean = LineCloud(5.0, 0.1);
  vtkSmartPointer<vtkPolyData> dirty = LineCloud(5.0, 0.1);
  dirty->GetPoints()->InsertNextPoint(kNaN, 0.0, 0.0);
  dirty->GetPoints()->InsertNextPoint(0.0, kInf, 0.0);
  dirty->GetPoints()->InsertNextPoint(1.0, 1.0, -kInf);
  vtkSmartPointer<vtkPolyData> probe = Points({ { 0.2, 0.3, 0 }, { 1.0, -0.6, 0 }, { -2.0, 1.5, 0 } });

  vtkNew<ErrorObserver> observer;
  auto a = MakeSampler(clean, observer);
  a->SetInputData(probe);
  ASSERT_EQ(RunPipeline(a), 1);
  auto b = MakeSampler(dirty, observer);
  b->SetInputData(probe);
  ASSERT_EQ(RunPipeline(b), 1) << observer->AllErrors();
  EXPECT_TRUE(observer->WarningContains("3 cloud point(s)")) << "the skipped points are counted";
  EXPECT_EQ(CountNonFinite(b->GetOutput()), 0);
  for (const char* name : { "ImplicitG", "Energy", "Delta", "Stability" })
  {
    vtkDataArray* x = a->GetOutput()->GetPointData()->GetArray(name);
    vtkDataArray* y = b->GetOutput()->GetPointData()->GetArray(name);
    for (vtkIdType i = 0; i < 3; ++i)
    {
      EXPECT_EQ(x->GetTuple1(i), y->GetTuple1(i)) << name << " " << i;
    }
  }
}

TEST(FieldBadInput, AbsurdOrEmptyGrids)
{
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(5.0, 0.1);
  vtkNew<ErrorObserver> observer;
  const int cases[][3] = { { 0, 10, 1 }, { 10, -3, 1 }, { 10, 10, 0 }, { 100000, 100000, 1000 }, { 2000, 2000, 1000 },
    { 1 << 30, 1 << 30, 1 << 30 } };
  for (const auto& d : cases)
  {
    observer->Clear();
    auto sampler = MakeSampler(cloud, observer);
    sampler->GenerateSamplingGridOn();
    sampler->SetSampleDimensions(d[0], d[1], d[2]);
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(RunPipeline(sampler), 0) << d[0] << " x " << d[1] << " x " << d[2];
    // Rejected before any allocation or sampling: well under a second.
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
    EXPECT_TRUE(observer->ErrorContains("SampleDimensions")) << observer->AllErrors();
    EXPECT_EQ(sampler->GetOutput()->GetNumberOfPoints(), 0);
  }

  // The smallest valid grid: one sample, at the middle of the cloud.
  observer->Clear();
  auto one = MakeSampler(cloud, observer);
  one->GenerateSamplingGridOn();
  one->SetSampleDimensions(1, 1, 1);
  ASSERT_EQ(RunPipeline(one), 1) << observer->AllErrors();
  vtkImageData* image = vtkImageData::SafeDownCast(one->GetOutput());
  ASSERT_NE(image, nullptr);
  ASSERT_EQ(image->GetNumberOfPoints(), 1);
  EXPECT_NEAR(image->GetPoint(0)[0], 0.0, 1e-12);
  EXPECT_EQ(CountNonFinite(image), 0);

  // A flat axis with more than one sample and no margin has no extent to span.
  observer->Clear();
  auto flat = MakeSampler(cloud, observer);
  flat->GenerateSamplingGridOn();
  flat->SetSamplingMargin(0.0);
  flat->SetSampleDimensions(11, 11, 1);
  EXPECT_EQ(RunPipeline(flat), 0);
  EXPECT_TRUE(observer->ErrorContains("degenerate")) << observer->AllErrors();

  // No grid and no input 0.
  observer->Clear();
  auto nothing = MakeSampler(cloud, observer);
  EXPECT_EQ(RunPipeline(nothing), 0);
  EXPECT_TRUE(observer->ErrorContains("input 0")) << observer->AllErrors();
}

TEST(FieldBadInput, NonPositiveScale)
{
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(5.0, 0.1);
  for (const double h : { 0.0, -1.0, kNaN })
  {
    vtkNew<ErrorObserver> observer;
    auto sampler = MakeSampler(cloud, observer);
    sampler->GetSurface()->SetScaleFactor(h);
    sampler->GenerateSamplingGridOn();
    sampler->SetSampleDimensions(21, 21, 1);
    EXPECT_EQ(RunPipeline(sampler), 0) << "h = " << h;
    EXPECT_TRUE(observer->ErrorContains("cannot define the surface")) << observer->AllErrors();
    EXPECT_EQ(CountNonFinite(sampler->GetOutput()), 0);

    vtkNew<vtkPointSetSurfaceImplicitFunction> function;
    vtkNew<ErrorObserver> fobserver;
    fobserver->Watch(function);
    function->GetSurface()->AutomaticScaleOff();
    function->GetSurface()->SetScaleFactor(h);
    function->SetInputData(cloud);
    double x[3] = { 0.1, 0.2, 0.0 };
    EXPECT_EQ(function->EvaluateFunction(x), 0.0);
    EXPECT_EQ(fobserver->Errors.size(), 1u) << fobserver->AllErrors();
    // Fixing the scale is a modification: the next evaluation prepares again and succeeds.
    function->GetSurface()->SetScaleFactor(1.0);
    EXPECT_TRUE(std::isfinite(function->EvaluateFunction(x)));
    EXPECT_NE(function->EvaluateFunction(x), 0.0);
    EXPECT_EQ(fobserver->Errors.size(), 1u);
  }
}

TEST(FieldBadInput, BadReferenceDirection)
{
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(5.0, 0.1);
  vtkNew<ErrorObserver> observer;
  auto sampler = MakeSampler(cloud, observer);
  sampler->SetInputData(Points({ { 0.2, 0.3, 0 } }));
  sampler->SetOrientationModeToAlongDirection();
  sampler->SetReferenceDirection(0.0, 0.0, 0.0);
  EXPECT_EQ(RunPipeline(sampler), 0);
  EXPECT_TRUE(observer->ErrorContains("ReferenceDirection")) << observer->AllErrors();

  // A valid direction orients n along it: n = +y at 0.3 h above and below the line.
  observer->Clear();
  sampler->SetReferenceDirection(0.0, 2.0, 0.0);
  sampler->SetInputData(Points({ { 0.2, 0.3, 0 }, { 0.2, -0.3, 0 } }));
  ASSERT_EQ(RunPipeline(sampler), 1) << observer->AllErrors();
  vtkDataArray* normal = sampler->GetOutput()->GetPointData()->GetArray("Normal");
  EXPECT_NEAR(normal->GetTuple3(0)[1], 1.0, 1e-9);
  EXPECT_NEAR(normal->GetTuple3(1)[1], 1.0, 1e-9);
  // ... so g changes sign through the line (the line is its zero set).
  vtkDataArray* g = sampler->GetOutput()->GetPointData()->GetArray("ImplicitG");
  EXPECT_LT(g->GetTuple1(1), 0.0);
  EXPECT_GT(g->GetTuple1(0), 0.0);
}

TEST(FieldBadInput, AbortLeavesAnEmptyOutput)
{
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(5.0, 0.1);
  vtkNew<ErrorObserver> observer;
  auto sampler = MakeSampler(cloud, observer);
  sampler->GenerateSamplingGridOn();
  sampler->SetSampleDimensions(201, 201, 1);
  // The executive clears AbortExecute when an update starts, so abort from the first progress
  // report of the sampling loop, as a GUI's cancel button would.
  vtkNew<AbortOnProgress> abort;
  sampler->AddObserver(vtkCommand::ProgressEvent, abort);
  RunPipeline(sampler);
  EXPECT_GT(abort->Aborted, 0);
  EXPECT_EQ(sampler->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_TRUE(observer->Errors.empty()) << observer->AllErrors();
}

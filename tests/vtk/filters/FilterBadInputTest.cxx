// SPDX-License-Identifier: BSD-3-Clause
/**
 * Bad input for the projection filter, the domain classifier, the energy glyphs and the cloud
 * source: every case ends in a clear error (observed, not printed) or in flagged output, never in
 * a crash or in an unflagged NaN.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceDomainClassifier.h"
#include "vtkPointSetSurfaceEnergyGlyphs.h"
#include "vtkPointSetSurfaceProjection.h"

#include "vtkCellData.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

using namespace pss_test;

namespace
{

const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

// The three filters that take a cloud, each with its own observer.
struct Filters
{
  vtkNew<vtkPointSetSurfaceProjection> projection;
  vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  vtkNew<ErrorObserver> projectionLog;
  vtkNew<ErrorObserver> classifierLog;
  vtkNew<ErrorObserver> glyphsLog;

  Filters()
  {
    projectionLog->Attach(projection);
    classifierLog->Attach(classifier);
    glyphsLog->Attach(glyphs);
  }

  void SetCloud(vtkDataObject* cloud)
  {
    projection->SetInputData(0, cloud);
    classifier->SetInputData(0, cloud);
    glyphs->SetInputData(0, cloud);
  }

  void SetStarts(vtkDataObject* starts)
  {
    projection->SetStartPointsData(starts);
    classifier->SetStartPointsData(starts);
    glyphs->SetSamplePointsData(starts);
  }

  // Applies @p f to the three surfaces.
  template <class F>
  void Surfaces(F f)
  {
    f(projection->GetSurface());
    f(classifier->GetSurface());
    f(glyphs->GetSurface());
  }

  void Update()
  {
    projection->Update();
    classifier->Update();
    glyphs->Update();
  }

  // Each filter reported an error containing @p text, and left its outputs empty.
  void ExpectErrors(const std::string& text)
  {
    for (ErrorObserver* log : { projectionLog.Get(), classifierLog.Get(), glyphsLog.Get() })
    {
      EXPECT_TRUE(log->HasError(text)) << "expected an error with \"" << text << "\"; got "
                                       << (log->Errors.empty() ? std::string("none") : log->Errors.front());
      log->Clear();
    }
    EXPECT_EQ(projection->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_EQ(classifier->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_EQ(glyphs->GetOutput()->GetNumberOfPoints(), 0);
  }
};

std::vector<Point> LinePoints(int n, double spacing)
{
  std::vector<Point> points;
  for (int i = 0; i < n; ++i)
  {
    points.push_back({ (i - n / 2) * spacing, 0.0, 0.0 });
  }
  return points;
}

bool StopReasonIs(vtkPolyData* out, vtkIdType i, int reason)
{
  return static_cast<int>(Value(out, "StopReason", i)) == reason;
}

} // namespace

TEST(FilterBadInput, EmptyCloud)
{
  Filters f;
  vtkNew<vtkPolyData> empty;
  f.SetCloud(empty);
  f.Update();
  f.ExpectErrors("empty");

  // An empty set of start points on a good cloud: empty outputs, no error.
  Filters g;
  g.SetCloud(MakePoints(LinePoints(50, 0.1)));
  g.SetStarts(MakePoints({}));
  g.Update();
  for (ErrorObserver* log : { g.projectionLog.Get(), g.classifierLog.Get(), g.glyphsLog.Get() })
  {
    EXPECT_TRUE(log->Errors.empty());
  }
  EXPECT_EQ(g.projection->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(g.classifier->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(g.glyphs->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(FilterBadInput, NonFiniteCoordinatesAreSkippedAndFlagged)
{
  std::vector<Point> cloud = LinePoints(200, 0.05);
  cloud.push_back({ NaN, 0.0, 0.0 });
  cloud.push_back({ 0.0, Inf, 0.0 });
  cloud.push_back({ 1.0, 0.0, -Inf });
  Filters f;
  f.SetCloud(MakePoints(cloud));
  f.Surfaces([](vtkPointSetSurface* s) {
    s->AutomaticScaleOff();
    s->SetScaleFactor(0.25);
    s->SetDimension(2);
  });
  // No start points: the cloud itself is projected, its three bad points included.
  f.glyphs->SetResolution(8);
  f.Update();
  EXPECT_TRUE(f.projectionLog->Errors.empty());
  EXPECT_EQ(f.projection->GetSurface()->GetNumberOfSkippedPoints(), 3);
  EXPECT_TRUE(f.projectionLog->HasWarning("left out of the surface"));
  EXPECT_TRUE(f.projectionLog->HasWarning("3 start point(s)"));
  EXPECT_TRUE(f.glyphsLog->HasWarning("3 sample point(s)"));

  vtkPolyData* out = f.projection->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 203);
  for (vtkIdType i = 0; i < 200; ++i)
  {
    EXPECT_EQ(Value(out, "StopReason", i), 0.0) << i;
  }
  for (vtkIdType i = 200; i < 203; ++i)
  {
    EXPECT_EQ(Value(out, "StopReason", i), 4.0) << i;
    EXPECT_EQ(Value(out, "Converged", i), 0.0);
    EXPECT_EQ(Value(out, "Displacement", i, 0), 0.0); // flagged, not NaN
  }
  EXPECT_EQ(CountUnflaggedNonFinite(out, [&](vtkIdType i) { return StopReasonIs(out, i, 4); }), 0);

  vtkPolyData* labelled = f.classifier->GetOutput();
  ASSERT_EQ(labelled->GetNumberOfPoints(), 203);
  for (vtkIdType i = 200; i < 203; ++i)
  {
    EXPECT_EQ(Value(labelled, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::UNDEFINED);
    EXPECT_EQ(Value(labelled, "StartStability", i), 0.0);
  }
  EXPECT_EQ(CountUnflaggedNonFinite(labelled,
              [&](vtkIdType i) {
                const int label = static_cast<int>(Value(labelled, "DomainLabel", i));
                return label == vtkPointSetSurfaceDomainClassifier::UNDEFINED ||
                  label == vtkPointSetSurfaceDomainClassifier::NOT_CONVERGED;
              }),
    0);

  // Glyphs: 200 finite samples of 8 directions, all finite.
  vtkPolyData* glyphs = f.glyphs->GetOutput();
  ASSERT_EQ(glyphs->GetNumberOfPoints(), 200 * 8);
  EXPECT_EQ(CountUnflaggedNonFinite(glyphs, [](vtkIdType) { return false; }), 0);
  EXPECT_EQ(f.glyphs->GetOutput(1)->GetNumberOfLines(), 200);

  // A cloud of nothing but non-finite points is an error.
  Filters g;
  g.SetCloud(MakePoints({ { NaN, 0, 0 }, { Inf, 1, 2 } }));
  g.Update();
  g.ExpectErrors("no point with finite coordinates");
}

TEST(FilterBadInput, AllDuplicatePoints)
{
  const std::vector<Point> cloud(50, Point{ 1.0, 2.0, 0.0 });
  Filters f;
  f.SetCloud(MakePoints(cloud));
  f.SetStarts(MakePoints({ { 1.0, 2.0, 0.0 }, { 1.5, 2.5, 0.0 } }));
  f.Update();
  // Automatic scale: every k-th neighbour distance is 0.
  f.ExpectErrors("duplicates");

  // With an explicit h every weighted covariance is 0: n is undefined everywhere (flagged).
  f.Surfaces([](vtkPointSetSurface* s) {
    s->AutomaticScaleOff();
    s->SetScaleFactor(1.0);
  });
  f.glyphs->SetResolution(8);
  f.Update();
  vtkPolyData* out = f.projection->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 2);
  vtkPolyData* labelled = f.classifier->GetOutput();
  for (vtkIdType i = 0; i < 2; ++i)
  {
    EXPECT_EQ(Value(out, "StopReason", i), 2.0);
    EXPECT_EQ(Value(out, "Stability", i), 0.0);
    EXPECT_EQ(Value(labelled, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::UNDEFINED);
  }
  EXPECT_EQ(CountUnflaggedNonFinite(out, [](vtkIdType) { return false; }), 0);
  EXPECT_EQ(CountUnflaggedNonFinite(labelled,
              [&](vtkIdType i) { return Value(labelled, "DomainLabel", i) >= 2.0; }),
    0);
  // Glyphs: finite energies; n undefined, so stability 0 where a segment is drawn at all.
  EXPECT_EQ(CountUnflaggedNonFinite(f.glyphs->GetOutput(), [](vtkIdType) { return false; }), 0);
  vtkPolyData* fits = f.glyphs->GetOutput(1);
  for (vtkIdType c = 0; c < fits->GetNumberOfCells(); ++c)
  {
    EXPECT_EQ(fits->GetCellData()->GetArray("Stability")->GetTuple1(c), 0.0);
  }
}

TEST(FilterBadInput, CollinearPointsIn3DHaveNoNormal)
{
  // Points on the x axis, Dimension 3: the centre-of-mass covariance has rank 1, so the smallest
  // eigenvalue is double and n_COM undefined (StopReason 2, DomainLabel Undefined).
  Filters f;
  f.SetCloud(MakePoints(LinePoints(100, 0.05)));
  f.SetStarts(MakePoints({ { 0.1, 0.3, 0.2 }, { -0.4, 0.0, 0.5 }, { 0.2, 0.0, 0.0 } }));
  f.Surfaces([](vtkPointSetSurface* s) {
    s->SetVariantToCenterOfMass();
    s->SetDimension(3);
    s->AutomaticScaleOff();
    s->SetScaleFactor(0.3);
  });
  f.glyphs->SetResolution(8);
  f.Update();
  EXPECT_TRUE(f.projectionLog->Errors.empty());
  vtkPolyData* out = f.projection->GetOutput();
  vtkPolyData* labelled = f.classifier->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < 3; ++i)
  {
    EXPECT_EQ(Value(out, "StopReason", i), 2.0) << i;
    EXPECT_EQ(Value(out, "Converged", i), 0.0);
    EXPECT_EQ(Value(labelled, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::UNDEFINED) << i;
    EXPECT_TRUE(std::isnan(Value(labelled, "DistanceToCloud", i))); // no fixed point: NaN, flagged
  }
  EXPECT_EQ(CountUnflaggedNonFinite(out, [](vtkIdType) { return false; }), 0);
  EXPECT_EQ(CountUnflaggedNonFinite(f.glyphs->GetOutput(), [](vtkIdType) { return false; }), 0);
}

TEST(FilterBadInput, NonPositiveScale)
{
  for (double h : { 0.0, -1.0, NaN })
  {
    Filters f;
    f.SetCloud(MakePoints(LinePoints(50, 0.1)));
    f.Surfaces([h](vtkPointSetSurface* s) {
      s->AutomaticScaleOff();
      s->SetScaleFactor(h);
    });
    f.Update();
    f.ExpectErrors("invalid surface parameters");
  }
}

TEST(FilterBadInput, LargeCoordinatesSmallScale)
{
  // A planar grid through c = (1e6, 1e6, 1e6) with normal (1, 1, 1)/sqrt(3) and h = 1e-3: the core
  // works relative to the query point, so the projection keeps its accuracy.
  const double h = 1e-3;
  const Point c = { 1e6, 1e6, 1e6 };
  const Point u = { 1.0 / std::sqrt(2.0), -1.0 / std::sqrt(2.0), 0.0 };
  const Point v = { 1.0 / std::sqrt(6.0), 1.0 / std::sqrt(6.0), -2.0 / std::sqrt(6.0) };
  const Point n = { 1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0) };
  auto at = [&](double a, double b, double t) {
    return Point{ c[0] + a * u[0] + b * v[0] + t * n[0], c[1] + a * u[1] + b * v[1] + t * n[1],
      c[2] + a * u[2] + b * v[2] + t * n[2] };
  };
  std::vector<Point> cloud;
  for (int i = -12; i <= 12; ++i)
  {
    for (int j = -12; j <= 12; ++j)
    {
      cloud.push_back(at(0.3 * h * i, 0.3 * h * j, 0.0));
    }
  }
  std::vector<Point> starts;
  std::vector<Point> feet;
  for (int k = 0; k < 6; ++k)
  {
    const double a = (0.15 * k - 0.4) * h;
    const double b = (0.3 - 0.1 * k) * h;
    starts.push_back(at(a, b, (k % 2 ? -1.0 : 1.0) * (0.1 + 0.08 * k) * h));
    feet.push_back(at(a, b, 0.0));
  }
  for (int variant : { vtkPointSetSurface::CENTER_OF_MASS, vtkPointSetSurface::LEVIN_MLS })
  {
    Filters f;
    f.SetCloud(MakePoints(cloud));
    f.SetStarts(MakePoints(starts));
    f.Surfaces([&](vtkPointSetSurface* s) {
      s->SetVariant(variant);
      s->AutomaticScaleOff();
      s->SetScaleFactor(h);
    });
    f.projection->Update();
    f.classifier->Update();
    EXPECT_TRUE(f.projectionLog->Errors.empty());
    EXPECT_EQ(f.projection->GetSurface()->GetEffectiveDimension(), 3);
    vtkPolyData* out = f.projection->GetOutput();
    vtkPolyData* labelled = f.classifier->GetOutput();
    double worstPlane = 0.0;
    double worstFoot = 0.0;
    double worstNormal = 0.0;
    for (vtkIdType i = 0; i < 6; ++i)
    {
      ASSERT_EQ(Value(out, "StopReason", i), 0.0) << i;
      const Point e = Coordinates(out, i);
      worstPlane = std::max(worstPlane, std::abs(Dot(Sub(e, c), n)) / h);
      worstFoot = std::max(worstFoot, Norm(Sub(e, feet[static_cast<std::size_t>(i)])) / h);
      worstNormal = std::max(worstNormal,
        1.0 - std::abs(Dot({ Value(out, "Normal", i, 0), Value(out, "Normal", i, 1), Value(out, "Normal", i, 2) }, n)));
      EXPECT_EQ(Value(labelled, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::IN_DOMAIN) << i;
    }
    std::printf("[measured] 1e6 offset, h = 1e-3, %s: max distance to plane %.2e h, max distance to the "
                "foot %.2e h, max 1 - |n.n_true| %.2e\n",
      variant == vtkPointSetSurface::LEVIN_MLS ? "LevinMLS" : "CenterOfMass", worstPlane, worstFoot, worstNormal);
    // Coordinates of 1e6 carry 1.2e-10 of rounding (1.2e-7 h); the grid is symmetric enough that
    // the fixed point is the foot of the start point: 1e-3 h is the brief's bound for both.
    EXPECT_LT(worstPlane, 1e-3);
    EXPECT_LT(worstFoot, 1e-3);
    EXPECT_LT(worstNormal, 1e-6);
  }
}

TEST(FilterBadInput, SourceRejectsAbsurdSettings)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  vtkNew<ErrorObserver> log;
  log->Attach(source);

  // More points than the core generates (1e8): an error, not an attempt to allocate 24 TB.
  source->SetNumberOfPoints(static_cast<vtkIdType>(1e12));
  source->Update();
  EXPECT_TRUE(log->HasError("more than 1e8 points"));
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
  log->Clear();

  // Negative counts are clamped to 0: an empty cloud, no error.
  source->SetNumberOfPoints(-5);
  EXPECT_EQ(source->GetNumberOfPoints(), 0);
  source->Update();
  EXPECT_TRUE(log->Errors.empty());
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);

  source->SetNumberOfPoints(100);
  for (double size : { 0.0, -3.0, NaN, Inf })
  {
    source->SetSize(size);
    source->Update();
    EXPECT_TRUE(log->HasError("size must be a positive finite number")) << size;
    EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
    log->Clear();
  }
  source->SetSize(10.0);
  source->SetNoise(NaN);
  source->Update();
  EXPECT_TRUE(log->HasError("noise")) << "NaN noise";
  log->Clear();
  source->SetNoise(0.0);
  source->SetSize(1e299); // fine as a number, but the distances overflow
  source->Update();
  EXPECT_TRUE(log->HasError("beyond double precision"));
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
  log->Clear();

  // Clamped settings stay in range, and the source recovers.
  source->SetDimension(7);
  EXPECT_EQ(source->GetDimension(), 3);
  source->SetCornerAngle(200.0);
  EXPECT_LT(source->GetCornerAngle(), 180.0);
  source->SetScene(42);
  EXPECT_EQ(source->GetScene(), vtkPointSetSurfaceCloudSource::DEPTH_CAMERA);
  source->SetSceneToTwoSheets();
  source->SetSize(10.0);
  source->Update();
  EXPECT_TRUE(log->Errors.empty());
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 100);
}

TEST(FilterBadInput, SingleStartPointAndSingleCloudPoint)
{
  // One item of work: vtkSMPTools::For runs it inline on the calling thread (a path of its own).
  Filters f;
  f.SetCloud(MakePoints(LinePoints(60, 0.05)));
  f.SetStarts(MakePoints({ { 0.1, 0.2, 0.0 } }));
  f.Surfaces([](vtkPointSetSurface* s) {
    s->AutomaticScaleOff();
    s->SetScaleFactor(0.25);
  });
  f.glyphs->SetResolution(8);
  f.Update();
  EXPECT_TRUE(f.projectionLog->Errors.empty());
  ASSERT_EQ(f.projection->GetOutput()->GetNumberOfPoints(), 1);
  EXPECT_EQ(Value(f.projection->GetOutput(), "StopReason", 0), 0.0);
  EXPECT_NEAR(Coordinates(f.projection->GetOutput(), 0)[1], 0.0, 1e-6 * 0.25); // onto the line y = 0
  ASSERT_EQ(f.classifier->GetOutput()->GetNumberOfPoints(), 1);
  EXPECT_EQ(Value(f.classifier->GetOutput(), "DomainLabel", 0), vtkPointSetSurfaceDomainClassifier::IN_DOMAIN);
  EXPECT_EQ(f.glyphs->GetOutput()->GetNumberOfLines(), 1);

  // A one-point source, and a one-point cloud (n undefined: flagged, not a crash).
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetNumberOfPoints(1);
  source->Update();
  ASSERT_EQ(source->GetOutput()->GetNumberOfPoints(), 1);
  Filters g;
  g.SetCloud(source->GetOutput());
  g.Surfaces([](vtkPointSetSurface* s) {
    s->AutomaticScaleOff();
    s->SetScaleFactor(1.0);
  });
  g.glyphs->SetResolution(8);
  g.Update();
  ASSERT_EQ(g.projection->GetOutput()->GetNumberOfPoints(), 1);
  EXPECT_EQ(Value(g.projection->GetOutput(), "StopReason", 0), 2.0);
  EXPECT_EQ(Value(g.classifier->GetOutput(), "DomainLabel", 0), vtkPointSetSurfaceDomainClassifier::UNDEFINED);
  EXPECT_EQ(CountUnflaggedNonFinite(g.glyphs->GetOutput(), [](vtkIdType) { return false; }), 0);
}

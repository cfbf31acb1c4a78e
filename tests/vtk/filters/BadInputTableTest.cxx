// SPDX-License-Identifier: BSD-3-Clause
/**
 * The rows of the bad-input table (docs/bad-input.md) that the other bad-input suites
 * do not already pin down: one point, duplicated points, collinear and coplanar points in 3D, h
 * much larger than the cloud, start points 1000 h away, a grid of 10^10 samples and datasets
 * without points. Each case states the exact outcome per variant (StopReason, DomainLabel, where
 * the point ends), so a change of behaviour fails here and the table must be updated with it.
 *
 * Clouds: a line of 101 points at spacing 0.05 along x (2D), a 21 x 21 grid at spacing 0.05 in
 * z = 0 (3D), h = 0.25 unless said otherwise.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceDomainClassifier.h"
#include "vtkPointSetSurfaceEnergyGlyphs.h"
#include "vtkPointSetSurfaceFieldSampler.h"
#include "vtkPointSetSurfaceImplicitFunction.h"
#include "vtkPointSetSurfaceProjection.h"

#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

using namespace pss_test;

namespace
{

constexpr double kH = 0.25;
const char* const kVariantNames[] = { "LevinMLS", "NormalizedMLS", "CenterOfMass", "Integral", "Delta" };

std::vector<Point> Line()
{
  std::vector<Point> p;
  for (int i = 0; i < 101; ++i)
  {
    p.push_back({ (i - 50) * 0.05, 0.0, 0.0 });
  }
  return p;
}

std::vector<Point> Plane()
{
  std::vector<Point> p;
  for (int i = 0; i < 21; ++i)
  {
    for (int j = 0; j < 21; ++j)
    {
      p.push_back({ (i - 10) * 0.05, (j - 10) * 0.05, 0.0 });
    }
  }
  return p;
}

/// What one start point must become: StopReason, DomainLabel, and how far its end point may lie
/// from the surface the cloud samples (the line y = 0 or the plane z = 0; < 0: not checked), or,
/// with stays, from the start itself.
struct Outcome
{
  int reason;
  int label;
  double offSurface = -1.0; // bound on |y| (2D) or |z| (3D) at the end point
  bool stays = false;       // the end point is the start point (to 1e-9 h)
};

/// Classifies @p starts on @p cloud with every variant and checks each outcome of @p expected
/// (one row per variant, one entry per start), and that no value is a NaN without a flag.
void ExpectOutcomes(const std::vector<Point>& cloud, const std::vector<Point>& starts, double h, int dimension,
  const std::vector<std::vector<Outcome>>& expected)
{
  ASSERT_EQ(expected.size(), 5u);
  for (int variant = 0; variant < 5; ++variant)
  {
    SCOPED_TRACE(kVariantNames[variant]);
    vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
    vtkNew<ErrorObserver> log;
    log->Attach(classifier);
    classifier->SetInputData(MakePoints(cloud));
    classifier->SetStartPointsData(MakePoints(starts));
    classifier->GetSurface()->SetVariant(variant);
    classifier->GetSurface()->AutomaticScaleOff();
    classifier->GetSurface()->SetScaleFactor(h);
    classifier->GetSurface()->SetDimension(dimension);
    classifier->Update();
    EXPECT_TRUE(log->Errors.empty());
    vtkPolyData* out = classifier->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), static_cast<vtkIdType>(starts.size()));
    ASSERT_EQ(expected[variant].size(), starts.size());
    for (std::size_t k = 0; k < starts.size(); ++k)
    {
      const vtkIdType i = static_cast<vtkIdType>(k);
      const Outcome& o = expected[variant][k];
      EXPECT_EQ(Value(out, "StopReason", i), o.reason) << "start " << k;
      EXPECT_EQ(Value(out, "DomainLabel", i), o.label) << "start " << k;
      const Point end = Coordinates(out, i);
      if (o.offSurface >= 0.0)
      {
        EXPECT_LE(std::abs(end[dimension == 2 ? 1 : 2]), o.offSurface) << "start " << k;
      }
      if (o.stays)
      {
        EXPECT_LE(Norm(Sub(end, starts[k])), 1e-9 * h) << "start " << k;
      }
    }
    // NaN only where the label says there is no fixed point (the evidence of labels 2 and 3).
    EXPECT_EQ(CountUnflaggedNonFinite(out, [&](vtkIdType i) { return Value(out, "DomainLabel", i) >= 2.0; }), 0);
  }
}

// Shorthands: converged onto the surface; converged without moving (a spurious fixed point);
// n undefined at the start.
const Outcome OnSurface{ 0, 0, 1e-9 };
const Outcome StaysSpurious{ 0, 1, -1.0, true };
const Outcome StaysInDomain{ 0, 0, -1.0, true };
const Outcome Undefined{ 2, 2, -1.0, true };

/// Runs @p algorithm; 0 when the update failed.
int Update(vtkAlgorithm* algorithm)
{
  return algorithm->GetExecutive()->Update();
}

} // namespace

// One point: the automatic h needs 11 distinct points and fails with a message; with an explicit
// h, n is undefined everywhere except for Levin's and the normalized MLS n in 2D, which is defined
// off the point (normal to x - p) and makes every such start a fixed point.
TEST(BadInputTable, OnePoint)
{
  {
    vtkNew<vtkPointSetSurfaceProjection> projection;
    vtkNew<ErrorObserver> log;
    log->Attach(projection);
    projection->SetInputData(MakePoints({ { 1.0, 2.0, 0.0 } }));
    projection->Update();
    EXPECT_TRUE(log->HasError("the automatic scale is 0")) << (log->Errors.empty() ? "" : log->Errors.front());
    EXPECT_EQ(projection->GetOutput()->GetNumberOfPoints(), 0);
  }
  const std::vector<Point> starts2D = { { 1.1, 2.2, 0.0 }, { 1.0, 2.0, 0.0 } };
  ExpectOutcomes({ { 1.0, 2.0, 0.0 } }, starts2D, 1.0, 2,
    { { StaysInDomain, Undefined }, { StaysInDomain, Undefined }, { Undefined, Undefined },
      { { 2, 2 }, Undefined }, { { 2, 2 }, Undefined } });
  const std::vector<Point> starts3D = { { 1.1, 2.2, 3.0 }, { 1.0, 2.0, 3.0 } };
  ExpectOutcomes({ { 1.0, 2.0, 3.0 } }, starts3D, 1.0, 3,
    { { Undefined, Undefined }, { Undefined, Undefined }, { Undefined, Undefined }, { { 2, 2 }, Undefined },
      { { 2, 2 }, Undefined } });

  // The field quantities: delta is the squared distance to the point, n undefined (3D): zeros,
  // flagged by Stability 0, never NaN. The implicit function agrees.
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  sampler->SetSourceData(MakePoints({ { 1.0, 2.0, 3.0 } }));
  sampler->SetInputData(MakePoints({ { 1.5, 2.0, 3.0 }, { 1.0, 2.0, 3.0 } }));
  sampler->GetSurface()->AutomaticScaleOff();
  sampler->GetSurface()->SetScaleFactor(1.0);
  sampler->GetSurface()->SetVariantToCenterOfMass();
  ASSERT_EQ(Update(sampler), 1);
  vtkPolyData* field = vtkPolyData::SafeDownCast(sampler->GetOutput());
  ASSERT_NE(field, nullptr);
  EXPECT_NEAR(Value(field, "Delta", 0), 0.25, 1e-15);
  EXPECT_EQ(Value(field, "Delta", 1), 0.0);
  for (vtkIdType i = 0; i < 2; ++i)
  {
    EXPECT_EQ(Value(field, "Stability", i), 0.0);
    EXPECT_EQ(Value(field, "Valid", i), 1.0);
    EXPECT_EQ(Value(field, "ImplicitG", i), 0.0);
  }
  EXPECT_EQ(CountUnflaggedNonFinite(field, [](vtkIdType) { return false; }), 0);
  vtkNew<vtkPointSetSurfaceImplicitFunction> function;
  function->SetInputData(MakePoints({ { 1.0, 2.0, 3.0 } }));
  function->GetSurface()->AutomaticScaleOff();
  function->GetSurface()->SetScaleFactor(1.0);
  function->GetSurface()->SetVariantToCenterOfMass();
  double x[3] = { 1.5, 2.0, 3.0 };
  EXPECT_EQ(function->EvaluateFunction(x), 0.0);
  function->SetOutputQuantityToDelta();
  EXPECT_NEAR(function->EvaluateFunction(x), 0.25, 1e-15);

  // Energy glyphs of a one-point cloud: finite, and no best-fit segment where n is undefined.
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  glyphs->SetInputData(MakePoints({ { 1.0, 2.0, 3.0 } }));
  glyphs->SetSamplePointsData(MakePoints({ { 1.5, 2.0, 3.0 } }));
  glyphs->GetSurface()->AutomaticScaleOff();
  glyphs->GetSurface()->SetScaleFactor(1.0);
  glyphs->SetResolution(8);
  ASSERT_EQ(Update(glyphs), 1);
  EXPECT_GT(glyphs->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(CountUnflaggedNonFinite(glyphs->GetOutput(), [](vtkIdType) { return false; }), 0);
}

// Every point twice: the weights of each position add up, so normalized quantities do not change
// and the projections land where they land on the clean cloud (to the projection tolerance,
// 1e-6 h: n_I is refined to 1e-9 rad, not to the last bit), with the same
// StopReason and label.
TEST(BadInputTable, DuplicatedPoints)
{
  const std::vector<Point> clean = Line();
  std::vector<Point> doubled = clean;
  doubled.insert(doubled.end(), clean.begin(), clean.end());
  const std::vector<Point> starts = { { 0.3, 0.1, 0.0 }, { -1.0, -0.2, 0.0 }, { 0.3, 0.2, 0.0 } };
  for (int variant = 0; variant < 5; ++variant)
  {
    SCOPED_TRACE(kVariantNames[variant]);
    vtkSmartPointer<vtkPolyData> outputs[2];
    for (int k = 0; k < 2; ++k)
    {
      vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
      classifier->SetInputData(MakePoints(k == 0 ? clean : doubled));
      classifier->SetStartPointsData(MakePoints(starts));
      classifier->GetSurface()->SetVariant(variant);
      classifier->GetSurface()->AutomaticScaleOff();
      classifier->GetSurface()->SetScaleFactor(kH);
      classifier->Update();
      outputs[k] = classifier->GetOutput();
    }
    for (vtkIdType i = 0; i < 3; ++i)
    {
      EXPECT_EQ(Value(outputs[0], "StopReason", i), Value(outputs[1], "StopReason", i)) << i;
      EXPECT_EQ(Value(outputs[0], "DomainLabel", i), Value(outputs[1], "DomainLabel", i)) << i;
      EXPECT_LE(Norm(Sub(Coordinates(outputs[0], i), Coordinates(outputs[1], i))), 1e-6 * kH) << i; // the projection tolerance
    }
    // The starts 0.4 h and 0.8 h off the line: the first projects onto it for every variant.
    EXPECT_EQ(Value(outputs[1], "StopReason", 0), 0.0);
    EXPECT_LE(std::abs(Coordinates(outputs[1], 0)[1]), 1e-9);
  }
}

// Collinear points in 3D: the centre-of-mass covariance has rank 1 and n_I no unique minimum, so
// n is undefined (StopReason 2). Levin's C(x) about x has rank 2 off the line, so his n (and the
// normalized MLS n) is defined there, normal to the plane through the line and x, and x is
// already an extremum along it: a fixed point where it started. On the line, every n is undefined.
// Coplanar points in 3D are an ordinary surface: every variant projects onto the plane.
TEST(BadInputTable, CollinearAndCoplanarIn3D)
{
  const std::vector<Point> offLine = { { 0.3, 0.2, 0.1 }, { -0.4, 0.0, 0.05 }, { 0.2, 0.0, 0.0 } };
  ExpectOutcomes(Line(), offLine, kH, 3,
    { { StaysInDomain, StaysInDomain, Undefined }, { StaysInDomain, StaysInDomain, Undefined },
      { Undefined, Undefined, Undefined }, { { 2, 2 }, { 2, 2 }, Undefined }, { { 2, 2 }, { 2, 2 }, Undefined } });
  const std::vector<Point> offPlane = { { 0.1, 0.2, 0.02 }, { -0.2, 0.1, -0.05 } };
  const std::vector<Outcome> onPlane = { OnSurface, OnSurface };
  ExpectOutcomes(Plane(), offPlane, kH, 3, { onPlane, onPlane, onPlane, onPlane, onPlane });
}

// h 2000 times the cloud's extent: every weight is about 1, the cloud acts as one weighted
// cluster. The plane-fitting variants see its total-least-squares line (plane) and converge onto
// it (the centre of mass exactly: its plane is the regression plane through the centroid);
// n_I's stability decays like (extent / h)^2 and falls below MinimumStability (1e-5): StopReason 2.
TEST(BadInputTable, ScaleLargerThanTheCloud)
{
  const double h = 1e4;
  const Outcome Near{ 0, 0, 0.2 };
  const std::vector<Point> starts2D = { { 0.3, 0.2, 0.0 }, { -1.0, -0.5, 0.0 }, { 2.0, 5.0, 0.0 } };
  ExpectOutcomes(Line(), starts2D, h, 2,
    { { Near, Near, Near }, { Near, Near, Near }, { OnSurface, OnSurface, OnSurface },
      { Undefined, Undefined, Undefined }, { Undefined, Undefined, Undefined } });
  const std::vector<Point> starts3D = { { 0.3, 0.2, 0.1 }, { -0.4, 0.1, -0.5 } };
  ExpectOutcomes(Plane(), starts3D, h, 3,
    { { Near, Near }, { Near, Near }, { OnSurface, OnSurface }, { Undefined, Undefined }, { Undefined, Undefined } });
}

// Start points 1000 h away (and one 100 h away): no NaN, and per variant
// - LevinMLS, NormalizedMLS: beyond a few h only the nearest cloud point carries weight, n is
//   normal to x - p and x is an extremum along it: a fixed point where it started, labelled
//   Spurious (the paper's point about these definitions); above the middle of a symmetric plane
//   the two tangent directions tie: n undefined;
// - CenterOfMass: along the cloud's normal it comes back onto the cloud; off its ends the
//   weighted covariance collapses onto one point: n undefined;
// - Integral, Delta: n_I's stability (about 2 (h/d)^2) is below 1e-5 beyond ~450 h: n undefined;
//   from 100 h they come back onto the cloud.
TEST(BadInputTable, StartPoints1000hAway)
{
  const double far = 1000.0 * kH;
  const std::vector<Point> starts2D = { { 0.0, far, 0.0 }, { far, 0.0, 0.0 }, { 0.7 * far, 0.7 * far, 0.0 },
    { 0.0, 100.0 * kH, 0.0 } };
  const std::vector<Outcome> mls2D = { StaysSpurious, StaysSpurious, StaysSpurious, StaysSpurious };
  const std::vector<Outcome> integral2D = { Undefined, Undefined, Undefined, OnSurface };
  ExpectOutcomes(Line(), starts2D, kH, 2,
    { mls2D, mls2D, { OnSurface, Undefined, Undefined, OnSurface }, integral2D, integral2D });

  const std::vector<Point> starts3D = { { 0.0, 0.0, far }, { far, 0.0, 0.1 }, { 0.7 * far, 0.0, 0.7 * far } };
  const std::vector<Outcome> mls3D = { Undefined, StaysSpurious, StaysSpurious };
  const std::vector<Outcome> undefined3D = { Undefined, Undefined, Undefined };
  ExpectOutcomes(Plane(), starts3D, kH, 3,
    { mls3D, mls3D, { OnSurface, Undefined, Undefined }, undefined3D, undefined3D });

  // The field sampler there: every quantity finite (Levin's energy underflows to 0, never NaN).
  for (int variant = 0; variant < 5; ++variant)
  {
    vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
    sampler->SetSourceData(MakePoints(Line()));
    sampler->SetInputData(MakePoints(starts2D));
    sampler->GetSurface()->SetVariant(variant);
    sampler->GetSurface()->AutomaticScaleOff();
    sampler->GetSurface()->SetScaleFactor(kH);
    ASSERT_EQ(Update(sampler), 1);
    vtkPolyData* field = vtkPolyData::SafeDownCast(sampler->GetOutput());
    EXPECT_EQ(CountUnflaggedNonFinite(field, [](vtkIdType) { return false; }), 0) << kVariantNames[variant];
    EXPECT_EQ(Value(field, "Valid", 0), 1.0);
  }
}

// A grid of 10^10 samples (80 GB of arrays) is refused before any allocation, and so is a grid
// with a zero dimension; the sampler says which setting is wrong.
TEST(BadInputTable, TenBillionSampleGrid)
{
  for (const int nx : { 100000, 0 })
  {
    vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
    vtkNew<ErrorObserver> log;
    log->Attach(sampler);
    sampler->SetSourceData(MakePoints(Line()));
    sampler->GenerateSamplingGridOn();
    sampler->SetSampleDimensions(nx, nx == 0 ? 0 : 100000, 1);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(Update(sampler), 0);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_TRUE(log->HasError("SampleDimensions")) << nx;
    EXPECT_EQ(sampler->GetOutput()->GetNumberOfPoints(), 0);
  }
}

// The filters read nothing but point coordinates, so the only array that can be missing is the
// points themselves: a cloud without a vtkPoints fails like an empty cloud; start points, samples
// or a probe dataset without one give an empty output and no error.
TEST(BadInputTable, DatasetsWithoutPoints)
{
  vtkNew<vtkPolyData> noPoints; // GetPoints() == nullptr
  {
    vtkNew<vtkPointSetSurfaceProjection> projection;
    vtkNew<ErrorObserver> log;
    log->Attach(projection);
    projection->SetInputData(noPoints);
    EXPECT_EQ(Update(projection), 0);
    EXPECT_TRUE(log->HasError("empty"));
  }
  {
    vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
    vtkNew<ErrorObserver> log;
    log->Attach(classifier);
    classifier->SetInputData(MakePoints(Line()));
    classifier->SetStartPointsData(noPoints);
    EXPECT_EQ(Update(classifier), 1);
    EXPECT_TRUE(log->Errors.empty());
    EXPECT_EQ(classifier->GetOutput()->GetNumberOfPoints(), 0);
  }
  {
    vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
    vtkNew<ErrorObserver> log;
    log->Attach(glyphs);
    glyphs->SetInputData(MakePoints(Line()));
    glyphs->SetSamplePointsData(noPoints);
    EXPECT_EQ(Update(glyphs), 1);
    EXPECT_TRUE(log->Errors.empty());
    EXPECT_EQ(glyphs->GetOutput()->GetNumberOfPoints(), 0);
  }
  {
    vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
    vtkNew<ErrorObserver> log;
    log->Attach(sampler);
    sampler->SetSourceData(MakePoints(Line()));
    sampler->SetInputData(noPoints);
    EXPECT_EQ(Update(sampler), 1);
    EXPECT_TRUE(log->Errors.empty());
    EXPECT_EQ(sampler->GetOutput()->GetNumberOfPoints(), 0);

    vtkNew<vtkPointSetSurfaceFieldSampler> noCloud;
    vtkNew<ErrorObserver> noCloudLog;
    noCloudLog->Attach(noCloud);
    noCloud->SetSourceData(noPoints);
    noCloud->GenerateSamplingGridOn();
    EXPECT_EQ(Update(noCloud), 0);
    EXPECT_TRUE(noCloudLog->HasError("empty"));
  }
  {
    vtkNew<vtkPointSetSurfaceImplicitFunction> function;
    vtkNew<ErrorObserver> log;
    function->AddObserver(vtkCommand::ErrorEvent, log);
    function->SetInputData(noPoints);
    double x[3] = { 0.0, 0.0, 0.0 };
    EXPECT_EQ(function->EvaluateFunction(x), 0.0);
    EXPECT_TRUE(log->HasError("empty"));
  }
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * The domain of Levin's MLS surface is narrow, the centre-of-mass one's is not (Secs. 4 and 5).
 *
 * Cloud: a dense straight line y = 0 in 2D, h = 1. At height y above an (infinite, uniform) line,
 * Levin's covariance about x has vertical entry ~ y^2 and horizontal entry ~ h^2 / 2 (both times
 * the same Gaussian integral), so n_MLS is the line's normal exactly when y < h / sqrt(2) and
 * parallel to the line above: start points below h/sqrt(2) project onto the line (InDomain), start
 * points at 3h..5h move along the line and never reach it (not InDomain). n_COM is the normal of
 * the weighted total-least-squares line, which is the line itself at any height: every start
 * point is InDomain.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceDomainClassifier.h"
#include "vtkPointSetSurfaceProjection.h"

#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

using namespace pss_test;

namespace
{

constexpr double H = 1.0;

std::vector<Point> VerticalStartLine(const std::vector<double>& heights)
{
  std::vector<Point> starts;
  for (double y : heights)
  {
    starts.push_back({ 0.3, y * H, 0.0 });
  }
  return starts;
}

// A dense line: 4000 points on [-20, 20] (40 per h), noise-free.
void SetUpLine(vtkPointSetSurfaceCloudSource* source)
{
  source->SetSceneToLine();
  source->SetDimension(2);
  source->SetNumberOfPoints(4000);
  source->SetSize(40.0);
  source->SetSeed(5);
}

void Configure(vtkPointSetSurfaceProjection* filter, vtkPointSetSurfaceCloudSource* source, vtkPolyData* starts,
  int variant)
{
  filter->SetInputConnection(0, source->GetOutputPort());
  filter->SetStartPointsData(starts);
  filter->GetSurface()->SetVariant(variant);
  filter->GetSurface()->AutomaticScaleOff();
  filter->GetSurface()->SetScaleFactor(H);
}

// The evidence arrays justify every label (see the classifier's class description).
void CheckLabelsJustified(vtkPolyData* out, double maxDistance, double maxAngle)
{
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const int label = static_cast<int>(Value(out, "DomainLabel", i));
    const int reason = static_cast<int>(Value(out, "StopReason", i));
    const double distance = Value(out, "DistanceToCloud", i);
    const double angle = Value(out, "NormalAngle", i);
    switch (label)
    {
      case vtkPointSetSurfaceDomainClassifier::IN_DOMAIN:
        EXPECT_EQ(reason, 0);
        EXPECT_LE(distance, maxDistance * H);
        EXPECT_LE(angle, maxAngle);
        break;
      case vtkPointSetSurfaceDomainClassifier::SPURIOUS:
        EXPECT_EQ(reason, 0);
        EXPECT_TRUE(distance > maxDistance * H || angle > maxAngle) << "spurious point " << i;
        break;
      case vtkPointSetSurfaceDomainClassifier::UNDEFINED:
        EXPECT_TRUE(reason == 2 || reason == 4);
        EXPECT_TRUE(std::isnan(distance) && std::isnan(angle));
        break;
      case vtkPointSetSurfaceDomainClassifier::NOT_CONVERGED:
        EXPECT_TRUE(reason == 1 || reason == 3);
        EXPECT_TRUE(std::isnan(distance) && std::isnan(angle));
        break;
      default:
        ADD_FAILURE() << "unknown label " << label;
    }
    // The stabilities are in [0, 1], angles in [0, 90] where defined.
    EXPECT_GE(Value(out, "StartStability", i), 0.0);
    EXPECT_LE(Value(out, "StartStability", i), 1.0);
    if (!std::isnan(angle))
    {
      EXPECT_GE(angle, 0.0);
      EXPECT_LE(angle, 90.0);
      EXPECT_GE(Value(out, "StartAngle", i), 0.0);
      EXPECT_LE(Value(out, "StartAngle", i), 90.0);
    }
  }
}

} // namespace

TEST(FilterDomainClassifier, LevinDomainIsNarrowCenterOfMassIsNot)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  SetUpLine(source);
  // h / sqrt(2) = 0.707 h is the analytic edge of Levin's domain above a line.
  const std::vector<double> near = { 0.05, 0.15, 0.3, 0.45, 0.6 };
  const std::vector<double> far = { 3.0, 3.5, 4.0, 4.5, 5.0 };
  std::vector<double> heights = near;
  heights.insert(heights.end(), far.begin(), far.end());
  auto starts = MakePoints(VerticalStartLine(heights));

  vtkNew<vtkPointSetSurfaceDomainClassifier> levin;
  vtkNew<ErrorObserver> observer;
  observer->Attach(levin);
  Configure(levin, source, starts, vtkPointSetSurface::LEVIN_MLS);
  levin->Update();
  ASSERT_TRUE(observer->Errors.empty());
  vtkPolyData* out = levin->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), static_cast<vtkIdType>(heights.size()));
  std::printf("[measured] LevinMLS above a line (h = 1): height label reason distance normalAngle startAngle "
              "startStability\n");
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    std::printf("[measured]   %.2f  %d  %d  %.4g  %.4g  %.4g  %.4f\n", heights[i], int(Value(out, "DomainLabel", i)),
      int(Value(out, "StopReason", i)), Value(out, "DistanceToCloud", i), Value(out, "NormalAngle", i),
      Value(out, "StartAngle", i), Value(out, "StartStability", i));
  }
  for (std::size_t i = 0; i < near.size(); ++i)
  {
    EXPECT_EQ(Value(out, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::IN_DOMAIN) << "height " << near[i];
    // Projected onto the line: the nearest cloud point is within the spacing (40 points per h, so
    // gaps above 0.25 h are vanishingly unlikely), and on the line n is its normal (all weighted
    // points have y = 0: exactly).
    EXPECT_LT(Value(out, "DistanceToCloud", i), 0.25 * H);
    EXPECT_LT(Value(out, "NormalAngle", i), 1e-6);
    // At the start, n is the normal tilted by the random sampling's off-diagonal covariance over
    // the eigenvalue gap, which closes towards h/sqrt(2): measured 7.3 degrees at 0.6 h
    // (stability 0.18). 15 degrees keeps it well inside the 30-degree threshold.
    EXPECT_LT(Value(out, "StartAngle", i), 15.0);
  }
  for (std::size_t i = near.size(); i < heights.size(); ++i)
  {
    EXPECT_NE(Value(out, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::IN_DOMAIN) << "height " << heights[i];
    // n_MLS is (nearly) parallel to the line up there, and well defined: vertical entry y^2 >= 9,
    // horizontal h^2 / 2, stability (9 - 0.5) / (9 + 0.5) = 0.89 at 3h, the sampling aside.
    EXPECT_GT(Value(out, "StartStability", i), 0.8);
  }
  CheckLabelsJustified(out, levin->GetMaxDistance(), levin->GetMaxNormalAngle());

  // The same start points with the centre-of-mass definition: all in its domain.
  vtkNew<vtkPointSetSurfaceDomainClassifier> com;
  Configure(com, source, starts, vtkPointSetSurface::CENTER_OF_MASS);
  com->Update();
  vtkPolyData* comOut = com->GetOutput();
  double worstDistance = 0.0;
  double worstAngle = 0.0;
  for (vtkIdType i = 0; i < comOut->GetNumberOfPoints(); ++i)
  {
    EXPECT_EQ(Value(comOut, "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::IN_DOMAIN)
      << "height " << heights[i];
    worstDistance = std::max(worstDistance, Value(comOut, "DistanceToCloud", i));
    worstAngle = std::max(worstAngle, Value(comOut, "NormalAngle", i));
    // The fixed point is the foot of the start point on the line (n_COM is exactly vertical for a
    // noise-free line, and the normalized energy's minimum along it is y = 0).
    EXPECT_NEAR(Coordinates(comOut, i)[1], 0.0, 1e-6 * H);
    EXPECT_NEAR(Coordinates(comOut, i)[0], 0.3, 1e-9 * H);
  }
  std::printf("[measured] CenterOfMass: all InDomain, max DistanceToCloud %.4g h, max NormalAngle %.3g deg\n",
    worstDistance, worstAngle);
  CheckLabelsJustified(comOut, com->GetMaxDistance(), com->GetMaxNormalAngle());
}

TEST(FilterDomainClassifier, ProjectionArraysIdenticalToProjectionFilter)
{
  // The classifier projects each point once, through the same hook: its projection arrays must be
  // bit-identical to the projection filter's with the same settings.
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  SetUpLine(source);
  auto starts = MakePoints(VerticalStartLine({ 0.2, 0.7, 1.5, 3.0, 6.0 }));
  for (int variant : { vtkPointSetSurface::LEVIN_MLS, vtkPointSetSurface::NORMALIZED_MLS,
         vtkPointSetSurface::CENTER_OF_MASS })
  {
    vtkNew<vtkPointSetSurfaceProjection> projection;
    vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
    Configure(projection, source, starts, variant);
    Configure(classifier, source, starts, variant);
    projection->GenerateProjectionLinesOn();
    classifier->GenerateProjectionLinesOn();
    projection->Update();
    classifier->Update();
    vtkPolyData* a = projection->GetOutput();
    vtkPolyData* b = classifier->GetOutput();
    ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
    for (const char* name :
      { "Normal", "Energy", "Displacement", "Iterations", "Converged", "Stability", "ExtremumType", "StopReason" })
    {
      for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
      {
        for (int c = 0; c < PointArray(a, name)->GetNumberOfComponents(); ++c)
        {
          EXPECT_EQ(Value(a, name, i, c), Value(b, name, i, c)) << name << " variant " << variant;
        }
      }
    }
    for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
    {
      EXPECT_EQ(Coordinates(a, i), Coordinates(b, i));
    }
    EXPECT_EQ(projection->GetOutput(1)->GetNumberOfLines(), classifier->GetOutput(1)->GetNumberOfLines());
    // Converged points are labelled InDomain or Spurious, the others Undefined or NotConverged.
    for (vtkIdType i = 0; i < b->GetNumberOfPoints(); ++i)
    {
      const bool converged = Value(b, "Converged", i) == 1.0;
      const int label = static_cast<int>(Value(b, "DomainLabel", i));
      EXPECT_EQ(converged, label <= vtkPointSetSurfaceDomainClassifier::SPURIOUS);
    }
  }
}

TEST(FilterDomainClassifier, ThresholdsAndPrintSelf)
{
  vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
  EXPECT_EQ(classifier->GetMaxDistance(), 1.0);
  EXPECT_EQ(classifier->GetMaxNormalAngle(), 30.0);
  classifier->SetMaxNormalAngle(120.0);
  EXPECT_EQ(classifier->GetMaxNormalAngle(), 90.0);
  classifier->SetMaxDistance(-1.0);
  EXPECT_GT(classifier->GetMaxDistance(), 0.0);

  // A tighter angle threshold turns Levin's near-threshold fixed points Spurious, never the reverse.
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  SetUpLine(source);
  auto starts = MakePoints(VerticalStartLine({ 0.1, 0.3, 0.5 }));
  Configure(classifier, source, starts, vtkPointSetSurface::LEVIN_MLS);
  classifier->SetMaxDistance(1.0);
  classifier->SetMaxNormalAngle(0.0); // every fixed point with n not exactly the cloud's normal is Spurious
  classifier->Update();
  CheckLabelsJustified(classifier->GetOutput(), 1.0, 0.0);
  classifier->SetMaxNormalAngle(30.0);
  classifier->SetMaxDistance(1e-6); // closer than 1e-6 h to a cloud point: almost never
  classifier->Update();
  CheckLabelsJustified(classifier->GetOutput(), 1e-6, 30.0);
  for (vtkIdType i = 0; i < 3; ++i)
  {
    EXPECT_EQ(Value(classifier->GetOutput(), "DomainLabel", i), vtkPointSetSurfaceDomainClassifier::SPURIOUS);
  }

  std::ostringstream print;
  classifier->Print(print);
  for (const char* key : { "MaxDistance", "MaxNormalAngle", "Procedure", "Surface", "Variant: 0" })
  {
    EXPECT_NE(print.str().find(key), std::string::npos) << key;
  }
}

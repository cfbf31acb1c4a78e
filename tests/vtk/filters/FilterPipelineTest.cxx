// SPDX-License-Identifier: BSD-3-Clause
/**
 * Pipelines of the cloud source and the projection filter, checked against the analytic shapes:
 * - the source's clouds lie on their shapes (DistanceToShape 0 without noise, its RMS = Noise
 *   with noise) and repeat with the seed;
 * - source -> projection -> vtkXMLPolyDataWriter -> vtkXMLPolyDataReader keeps every array and
 *   value, and a noise-free circle of radius R projects onto radius R (Sec. 5: the centre-of-mass
 *   surface of a smooth curve);
 * - on a straight line (2D) and a plane (3D) the projection moves start points straight onto the
 *   shape: Displacement = end - start, Normal = the shape's normal, point data passed through,
 *   one projection line per valid start point;
 * - the integral definition's filter projects a scattered start set on the exact path (bitwise
 *   DeltaLatticeSpacing 0's output) and a dense one with the lattice.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceProjection.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

using namespace pss_test;

TEST(FilterCloudSource, ScenesLieOnTheirShapes)
{
  for (int scene = vtkPointSetSurfaceCloudSource::LINE; scene <= vtkPointSetSurfaceCloudSource::TWO_SHEETS; ++scene)
  {
    for (int dimension : { 2, 3 })
    {
      vtkNew<vtkPointSetSurfaceCloudSource> source;
      source->SetScene(scene);
      source->SetDimension(dimension);
      source->SetNumberOfPoints(300);
      source->SetSize(10.0);
      source->SetSheetGap(2.0);
      source->SetCornerAngle(45.0);
      source->Update();
      vtkPolyData* out = source->GetOutput();
      ASSERT_EQ(out->GetNumberOfPoints(), 300) << source->GetSceneAsString();
      ASSERT_EQ(out->GetNumberOfVerts(), 300);
      double worst = 0.0;
      double zMax = 0.0;
      for (vtkIdType i = 0; i < 300; ++i)
      {
        worst = std::max(worst, std::abs(Value(out, "DistanceToShape", i)));
        zMax = std::max(zMax, std::abs(Coordinates(out, i)[2]));
      }
      // Noise-free points are on the shape up to the rounding of cos/sin times Size/2 (~1e-15).
      EXPECT_LT(worst, 1e-12) << source->GetSceneAsString() << " " << dimension << "D";
      if (dimension == 2)
      {
        EXPECT_EQ(zMax, 0.0) << "2D clouds lie in the xy-plane";
      }
    }
  }
}

TEST(FilterCloudSource, NoiseAndSeed)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToPlane();
  source->SetDimension(3);
  source->SetNumberOfPoints(4000);
  source->SetSize(1000.0); // large next to the noise: the edges do not bias the distances
  source->SetNoise(0.5);
  source->SetSeed(7);
  source->Update();
  vtkNew<vtkPolyData> first;
  first->DeepCopy(source->GetOutput());
  double sum2 = 0.0;
  for (vtkIdType i = 0; i < 4000; ++i)
  {
    const double d = Value(first, "DistanceToShape", i);
    const Point p = Coordinates(first, i);
    // Above the square the distance to it is |z| (the noise pushes a few edge points beyond it).
    if (std::abs(p[0]) <= 500.0 && std::abs(p[1]) <= 500.0)
    {
      EXPECT_NEAR(d, std::abs(p[2]), 1e-12);
    }
    else
    {
      EXPECT_GT(d, std::abs(p[2]));
    }
    sum2 += d * d;
  }
  const double rms = std::sqrt(sum2 / 4000.0);
  std::printf("[measured] plane noise 0.5: RMS DistanceToShape = %.4f\n", rms);
  // RMS of N(0, 0.5^2) over 4000 samples: relative standard error 1/sqrt(2 * 4000) = 1.1%; 5% is 4.5 sigma.
  EXPECT_NEAR(rms, 0.5, 0.025);

  // Same seed, same cloud; another seed, another cloud.
  source->Modified();
  source->Update();
  EXPECT_EQ(Coordinates(source->GetOutput(), 123), Coordinates(first, 123));
  source->SetSeed(8);
  source->Update();
  EXPECT_NE(Coordinates(source->GetOutput(), 123), Coordinates(first, 123));

  std::ostringstream print;
  source->Print(print);
  for (const char* key : { "Scene: plane", "NumberOfPoints: 4000", "Noise: 0.5", "Seed: 8", "SheetGap" })
  {
    EXPECT_NE(print.str().find(key), std::string::npos) << key;
  }
}

TEST(FilterPipeline, CircleProjectionSurvivesXMLRoundTrip)
{
  const double radius = 50.0;
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToCircle();
  source->SetDimension(2);
  source->SetNumberOfPoints(400);
  source->SetSize(2.0 * radius);
  source->SetSeed(3);

  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputConnection(source->GetOutputPort());
  projection->GetSurface()->SetVariantToCenterOfMass();
  projection->GenerateProjectionLinesOn();

  const std::string file = std::string(PSS_BINARY_DIR) + "/FilterPipelineCircleRoundTrip.vtp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(projection->GetOutputPort(0));
  writer->SetFileName(file.c_str());
  writer->SetDataModeToBinary(); // binary keeps doubles bit for bit
  ASSERT_EQ(writer->Write(), 1);

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  std::remove(file.c_str());

  vtkPolyData* original = projection->GetOutput(0);
  vtkPolyData* copy = reader->GetOutput();
  const vtkIdType n = original->GetNumberOfPoints();
  ASSERT_EQ(n, 400);
  ASSERT_EQ(copy->GetNumberOfPoints(), n);
  EXPECT_EQ(copy->GetNumberOfVerts(), n);
  const char* expected[] = { "DistanceToShape", "Normal", "Energy", "Displacement", "Iterations", "Converged",
    "Stability", "ExtremumType", "StopReason" };
  for (const char* name : expected)
  {
    vtkDataArray* a = original->GetPointData()->GetArray(name);
    vtkDataArray* b = copy->GetPointData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    ASSERT_NE(b, nullptr) << name;
    ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents()) << name;
    ASSERT_EQ(a->GetDataType(), b->GetDataType()) << name;
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int c = 0; c < a->GetNumberOfComponents(); ++c)
      {
        ASSERT_EQ(a->GetComponent(i, c), b->GetComponent(i, c)) << name << " at " << i; // bit for bit
      }
    }
  }
  EXPECT_EQ(original->GetPointData()->GetNumberOfArrays(), copy->GetPointData()->GetNumberOfArrays());
  for (vtkIdType i = 0; i < n; ++i)
  {
    ASSERT_EQ(Coordinates(original, i), Coordinates(copy, i)) << i; // double points, bit for bit
  }
  ASSERT_NE(copy->GetPointData()->GetNormals(), nullptr);
  EXPECT_STREQ(copy->GetPointData()->GetNormals()->GetName(), "Normal");

  // The analytic circle, read back from the file.
  const double h = projection->GetEffectiveScale();
  ASSERT_GT(h, 0.0);
  double worstRadius = 0.0;
  double worstNormal = 0.0;
  double worstDisplacement = 0.0;
  vtkPolyData* cloud = source->GetOutput();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const Point p = Coordinates(copy, i);
    ASSERT_EQ(Value(copy, "Converged", i), 1.0) << i;
    ASSERT_EQ(Value(copy, "StopReason", i), 0.0) << i;
    worstRadius = std::max(worstRadius, std::abs(Norm(p) - radius) / h);
    const Point nrm = { Value(copy, "Normal", i, 0), Value(copy, "Normal", i, 1), Value(copy, "Normal", i, 2) };
    // Oriented away from the centroid (the centre of the circle): the outward radial direction.
    worstNormal = std::max(worstNormal, 1.0 - Dot(nrm, p) / Norm(p));
    const Point d = { Value(copy, "Displacement", i, 0), Value(copy, "Displacement", i, 1),
      Value(copy, "Displacement", i, 2) };
    const Point moved = Sub(p, Coordinates(cloud, i));
    worstDisplacement = std::max(worstDisplacement, Norm(Sub(d, moved)));
    // The start points are on the circle: DistanceToShape, passed through, is rounding only.
    EXPECT_LT(Value(copy, "DistanceToShape", i), 1e-12);
  }
  std::printf("[measured] circle R = %.0f, h = %.4f: max ||f(x)| - R| = %.5f h, max 1 - n.r = %.2e, "
              "max |Displacement - (end - start)| = %.1e\n",
    radius, h, worstRadius, worstNormal, worstDisplacement);
  // The centre-of-mass curve of a circle sits inside it by about h^2 / (4 R) (the weighted mean of
  // R cos(phi) over an arc of angular spread h / (sqrt(2) R)): 0.02 h here; 0.05 h is the bound.
  EXPECT_LT(worstRadius, 0.05);
  // n is radial to the same order (h / R ~ 0.08 at worst for an uneven sampling): cos 10 deg.
  EXPECT_LT(worstNormal, 1.0 - std::cos(10.0 * M_PI / 180.0));
  // Displacement is end - start, computed from the same doubles: only rounding of the subtraction.
  EXPECT_LT(worstDisplacement, 1e-12);

  // Output 1: one segment per start point (all valid here), from start to end.
  vtkPolyData* lines = projection->GetOutput(1);
  EXPECT_EQ(lines->GetNumberOfLines(), n);
}

namespace
{

// Start points above a shape lying in y = 0 (2D) or z = 0 (3D), with a tag array to pass through.
vtkSmartPointer<vtkPolyData> StartPoints(const std::vector<Point>& coordinates)
{
  auto starts = MakePoints(coordinates);
  vtkNew<vtkIntArray> tag;
  tag->SetName("Tag");
  for (std::size_t i = 0; i < coordinates.size(); ++i)
  {
    tag->InsertNextValue(static_cast<int>(7 * i + 1));
  }
  starts->GetPointData()->AddArray(tag);
  return starts;
}

// Runs a projection of @p starts onto the noise-free @p scene and checks the analytic outcome:
// the end point is the start point dropped orthogonally onto the shape (axis @p up is the normal).
void CheckStraightProjection(int scene, int dimension, double size, int count, double h, int up,
  const std::vector<Point>& coordinates, int invalidIndex)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetScene(scene);
  source->SetDimension(dimension);
  source->SetNumberOfPoints(count);
  source->SetSize(size);
  auto starts = StartPoints(coordinates);

  vtkNew<vtkPointSetSurfaceProjection> projection;
  vtkNew<ErrorObserver> observer;
  observer->Attach(projection);
  projection->SetInputConnection(0, source->GetOutputPort());
  projection->SetStartPointsData(starts);
  projection->GetSurface()->SetVariantToCenterOfMass();
  projection->GetSurface()->AutomaticScaleOff();
  projection->GetSurface()->SetScaleFactor(h);
  projection->GetSurface()->SetDimension(dimension);
  projection->GenerateProjectionLinesOn();
  projection->Update();
  EXPECT_TRUE(observer->Errors.empty());

  vtkPolyData* out = projection->GetOutput(0);
  const vtkIdType n = static_cast<vtkIdType>(coordinates.size());
  ASSERT_EQ(out->GetNumberOfPoints(), n);
  double worstEnd = 0.0;
  double worstNormal = 0.0;
  double worstDisplacement = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    EXPECT_EQ(Value(out, "Tag", i), 7.0 * i + 1) << "start point data passed through";
    if (i == invalidIndex)
    {
      EXPECT_EQ(Value(out, "StopReason", i), 4.0);
      continue;
    }
    ASSERT_EQ(Value(out, "StopReason", i), 0.0) << i;
    ASSERT_EQ(Value(out, "ExtremumType", i), 1.0) << i;
    const Point s = coordinates[static_cast<std::size_t>(i)];
    const Point e = Coordinates(out, i);
    Point expectedEnd = s;
    expectedEnd[up] = 0.0;
    worstEnd = std::max(worstEnd, Norm(Sub(e, expectedEnd)) / h);
    const Point d = { Value(out, "Displacement", i, 0), Value(out, "Displacement", i, 1),
      Value(out, "Displacement", i, 2) };
    worstDisplacement = std::max(worstDisplacement, Norm(Sub(d, Sub(e, s))));
    // The analytic normal is the axis `up` (unoriented on the shape itself: +-).
    worstNormal = std::max(worstNormal, 1.0 - std::abs(Value(out, "Normal", i, up)));
  }
  std::printf("[measured] %dD %s: max |f(x) - x_on_shape| = %.2e h, max 1 - |n.up| = %.2e, "
              "max |Displacement - (end - start)| = %.2e\n",
    dimension, dimension == 2 ? "line" : "plane", worstEnd, worstNormal, worstDisplacement);
  // A noise-free straight shape: every weighted neighbour lies in the shape, so n_COM is the
  // shape's normal to rounding and the energy minimum along it is on the shape; the line search
  // stops at 1e-12 h and the iteration at a step below Tolerance = 1e-6 h.
  EXPECT_LT(worstEnd, 1e-6);
  EXPECT_LT(worstNormal, 1e-12);
  EXPECT_LT(worstDisplacement, 1e-12); // same doubles subtracted: rounding only

  // Output 1: one segment per valid start point, from its start to its end.
  vtkPolyData* lines = projection->GetOutput(1);
  const vtkIdType valid = invalidIndex >= 0 ? n - 1 : n;
  ASSERT_EQ(lines->GetNumberOfLines(), valid);
  vtkDataArray* startIds = lines->GetCellData()->GetArray("StartPointId");
  ASSERT_NE(startIds, nullptr);
  vtkIdType cell = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (i == invalidIndex)
    {
      continue;
    }
    EXPECT_EQ(startIds->GetComponent(cell, 0), static_cast<double>(i));
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    lines->GetLines()->GetCellAtId(cell, npts, pts);
    ASSERT_EQ(npts, 2);
    EXPECT_EQ(Coordinates(lines, pts[0]), coordinates[static_cast<std::size_t>(i)]);
    EXPECT_EQ(Coordinates(lines, pts[1]), Coordinates(out, i));
    ++cell;
  }
  if (invalidIndex >= 0)
  {
    EXPECT_TRUE(observer->HasWarning("NaN or infinite")) << "the invalid start point is reported";
  }
}

} // namespace

TEST(FilterProjection, LineCloudExplicitStartPoints2D)
{
  const double h = 0.25;
  std::vector<Point> starts;
  for (int k = 0; k < 12; ++k)
  {
    // Heights from 0.1 h to 4.5 h on both sides, x well inside the segment [-10, 10].
    const double y = (k % 2 ? -1.0 : 1.0) * (0.1 + 0.4 * k) * h;
    starts.push_back({ -4.0 + 0.7 * k, y, 0.0 });
  }
  starts.push_back({ std::nan(""), 1.0, 0.0 }); // flagged and skipped by the projection lines
  CheckStraightProjection(vtkPointSetSurfaceCloudSource::LINE, 2, 20.0, 800, h, 1, starts,
    static_cast<int>(starts.size()) - 1);
}

TEST(FilterProjection, PlaneCloudExplicitStartPoints3D)
{
  const double h = 0.5;
  std::vector<Point> starts;
  for (int k = 0; k < 8; ++k)
  {
    starts.push_back({ -1.5 + 0.4 * k, 1.0 - 0.3 * k, (k % 2 ? -1.0 : 1.0) * (0.2 + 0.3 * k) * h });
  }
  CheckStraightProjection(vtkPointSetSurfaceCloudSource::PLANE, 3, 10.0, 3000, h, 2, starts, -1);
}

// The rule on the whole start set (pss::latticeServes): 64 starts 8 h apart, one per lattice
// brick, take the exact path; 64 starts inside one brick take the lattice.
TEST(FilterPipeline, ScatteredStartsOfTheIntegralDefinitionTakeTheExactPath)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToPlane();
  source->SetDimension(3);
  source->SetSize(80.0);
  source->SetNumberOfPoints(25600); // spacing h / 2
  source->SetNoise(0.02);
  source->Update();
  std::vector<Point> scattered, dense;
  for (int k = 0; k < 64; ++k)
  {
    scattered.push_back({ 8.0 * (k % 8) - 28.0, 8.0 * (k / 8) - 28.0, 0.4 });
    dense.push_back({ 0.5 + 0.4 * (k % 8), 0.5 + 0.4 * (k / 8), 0.4 });
  }
  auto project = [&](const std::vector<Point>& starts, double spacing) {
    vtkNew<vtkPointSetSurfaceProjection> projection;
    projection->GetSurface()->SetVariantToIntegral();
    projection->GetSurface()->AutomaticScaleOff();
    projection->GetSurface()->SetScaleFactor(1.0);
    projection->GetSurface()->SetDeltaLatticeSpacing(spacing);
    projection->SetInputConnection(0, source->GetOutputPort());
    projection->SetStartPointsData(MakePoints(starts));
    projection->Update();
    std::vector<double> out;
    vtkPolyData* pd = projection->GetOutput();
    for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    {
      double x[3];
      pd->GetPoint(i, x);
      out.insert(out.end(), x, x + 3);
    }
    return out;
  };
  const std::vector<double> scatteredExact = project(scattered, 0.0);
  ASSERT_EQ(scatteredExact.size(), 3 * scattered.size());
  EXPECT_EQ(project(scattered, 0.5), scatteredExact);
  EXPECT_NE(project(dense, 0.5), project(dense, 0.0));
}

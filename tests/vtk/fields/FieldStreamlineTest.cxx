// SPDX-License-Identifier: BSD-3-Clause
// vtkPointSetSurfaceFieldSampler -> vtkStreamTracer on the oriented `Normal`: the streamlines of
// the unoriented direction field n above a dense straight line (Fig. 5 and Fig. 9 of the paper).
//
// Analytic truths for a straight, uniformly sampled line along x through the origin (2D, h = 1,
// spacing 0.1 h, half-length 12 h, so within the sampled window |x| <= 5 h the nearest end is 7 h
// away and its influence is below exp(-49)):
// - CenterOfMass: n = y-axis everywhere (the weighted centre of mass lies on the line and the
//   weighted covariance about it is purely along x), so every streamline is a vertical segment.
// - LevinMLS: C(x) = sum theta (p - x)(p - x)^T has tangent moment ~ h^2/2 and normal moment y^2,
//   with no off-diagonal term (the line is symmetric about x), so n = y-axis for |y| < h/sqrt(2)
//   and n = x-axis above it: streamlines seeded in the tangent region are horizontal lines that
//   run until they leave the grid. At |y| = h/sqrt(2) the two eigenvalues cross and n turns by
//   90 degrees within less than one grid cell: the only singularity of n in the window.
// With AWAY_FROM_CENTROID (centroid = origin) the orientation seams are x = 0 in Levin's tangent
// region and y = 0 (on the cloud) in the normal region; streamlines run away from both. With
// PROPAGATE the seams lie only on the singular height.

#include "FieldTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceFieldSampler.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkStreamTracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <sstream>

using namespace pss_field_test;

namespace
{

constexpr double kH = 1.0;
constexpr double kGrid = 0.1 * kH;                    // spacing of the sampling grid
constexpr double kXMax = 5.0 * kH, kYMax = 3.0 * kH; // the grid spans [-5, 5] x [-3, 3]
const double kSingularHeight = kH / std::sqrt(2.0);

struct Streamline
{
  std::vector<std::array<double, 3>> points;
  int reason = -1;
  double length = 0.0;
  int seed = -1;
};

vtkSmartPointer<vtkImageData> MakeGrid()
{
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(static_cast<int>(std::lround(2 * kXMax / kGrid)) + 1,
    static_cast<int>(std::lround(2 * kYMax / kGrid)) + 1, 1);
  grid->SetOrigin(-kXMax, -kYMax, 0.0);
  grid->SetSpacing(kGrid, kGrid, kGrid);
  return grid;
}

void Configure(vtkPointSetSurface* surface, int variant)
{
  surface->SetVariant(variant);
  surface->AutomaticScaleOff();
  surface->SetScaleFactor(kH);
  surface->SetDimension(vtkPointSetSurface::DIMENSION_2D);
}

std::vector<Streamline> Trace(vtkDataSet* field, const std::vector<std::array<double, 2>>& seeds)
{
  vtkNew<vtkPoints> seedPoints;
  for (const auto& s : seeds)
  {
    seedPoints->InsertNextPoint(s[0], s[1], 0.0);
  }
  vtkNew<vtkPolyData> seedData;
  seedData->SetPoints(seedPoints);

  vtkNew<vtkStreamTracer> tracer;
  tracer->SetInputData(field);
  tracer->SetSourceData(seedData);
  tracer->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Normal");
  tracer->SetIntegratorTypeToRungeKutta4();
  tracer->SetIntegrationStepUnit(vtkStreamTracer::CELL_LENGTH_UNIT);
  tracer->SetInitialIntegrationStep(0.2);
  tracer->SetMaximumPropagation(40.0 * kH);
  tracer->SetMaximumNumberOfSteps(20000);
  tracer->SetIntegrationDirectionToForward();
  tracer->SetComputeVorticity(false);
  tracer->Update();

  vtkPolyData* lines = tracer->GetOutput();
  vtkDataArray* reasons = lines->GetCellData()->GetArray("ReasonForTermination");
  vtkDataArray* seedIds = lines->GetCellData()->GetArray("SeedIds");
  std::vector<Streamline> out;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < lines->GetNumberOfCells(); ++c)
  {
    lines->GetCellPoints(c, ids);
    Streamline s;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      std::array<double, 3> p;
      lines->GetPoint(ids->GetId(k), p.data());
      if (!s.points.empty())
      {
        const auto& q = s.points.back();
        s.length += std::hypot(p[0] - q[0], p[1] - q[1]);
      }
      s.points.push_back(p);
    }
    s.reason = reasons ? static_cast<int>(reasons->GetTuple1(c)) : -1;
    s.seed = seedIds ? static_cast<int>(seedIds->GetTuple1(c)) : -1;
    out.push_back(s);
  }
  return out;
}

/// The exact n at @p pts (a probe run of the sampler, independent of the grid's interpolation).
vtkSmartPointer<vtkDataSet> ExactDirections(vtkPolyData* cloud, int variant, const std::vector<std::array<double, 3>>& pts)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : pts)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkPolyData> probe;
  probe->SetPoints(points);
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  Configure(sampler->GetSurface(), variant);
  sampler->SetInputData(probe);
  sampler->SetSourceData(cloud);
  sampler->Update();
  return sampler->GetOutput();
}

/**
 * True inside the row of grid cells (k, k + 1) * spacing (in |y|) that contains h/sqrt(2), by more
 * than 1e-3 h from its edges: closer to an edge the blend weight of the other row of samples is
 * below 1%, and a streamline that settles onto the row's edge (as Levin's do after turning) is
 * checked there.
 */
bool InSingularRow(double y)
{
  const double lower = std::floor(kSingularHeight / kGrid) * kGrid;
  const double eps = 1e-3 * kH;
  return std::abs(y) > lower + eps && std::abs(y) < lower + kGrid - eps;
}

/// The first grid row above the singular height: every sample there has n = x-axis.
double FirstTangentRow()
{
  return std::ceil(kSingularHeight / kGrid) * kGrid;
}

struct Agreement
{
  double minAbsCos = 1.0;
  int checked = 0;
  int excluded = 0;
};

/**
 * |cos| between the streamline's tangent (central difference of its points) and the exact n at
 * each interior point. Excluded: for LevinMLS, points inside the row of grid cells that contains
 * the singular height |y| = h/sqrt(2) (0.7 h < |y| < 0.8 h here, see InSingularRow). n turns by 90 degrees at that
 * height, so the corner samples of those cells disagree by 90 degrees and the tracer follows
 * their bilinear blend, not n. Everywhere else a cell's corners agree with n inside it.
 */
Agreement CheckTangents(vtkPolyData* cloud, int variant, const Streamline& s)
{
  Agreement a;
  if (s.points.size() < 3)
  {
    return a;
  }
  vtkSmartPointer<vtkDataSet> exact = ExactDirections(cloud, variant, s.points);
  vtkDataArray* normal = exact->GetPointData()->GetArray("Normal");
  for (std::size_t k = 1; k + 1 < s.points.size(); ++k)
  {
    const double y = s.points[k][1];
    if (variant == vtkPointSetSurface::LEVIN_MLS && InSingularRow(y))
    {
      ++a.excluded;
      continue;
    }
    const double tx = s.points[k + 1][0] - s.points[k - 1][0];
    const double ty = s.points[k + 1][1] - s.points[k - 1][1];
    const double tn = std::hypot(tx, ty);
    if (tn == 0.0)
    {
      continue;
    }
    double n[3];
    normal->GetTuple(static_cast<vtkIdType>(k), n);
    const double c = std::abs(tx * n[0] + ty * n[1]) / (tn * std::hypot(n[0], n[1]));
    a.minAbsCos = std::min(a.minAbsCos, c);
    ++a.checked;
  }
  return a;
}

bool OnGridBoundary(const std::array<double, 3>& p)
{
  // The last point of a streamline that left the grid lies within one step (0.2 cells) of the
  // boundary; 1.5 cells is a generous margin that still tells a boundary exit from an early stop.
  const double tol = 1.5 * kGrid;
  return std::abs(p[0]) > kXMax - tol || std::abs(p[1]) > kYMax - tol;
}

const char* ModeName(int mode)
{
  return mode == vtkPointSetSurfaceFieldSampler::PROPAGATE ? "Propagate" : "AwayFromCentroid";
}

} // namespace

class FieldStreamlines : public ::testing::TestWithParam<std::tuple<int, int>>
{
};

TEST_P(FieldStreamlines, FollowOrientedNormalToTheGridBoundary)
{
  const int variant = std::get<0>(GetParam());
  const int mode = std::get<1>(GetParam());
  const bool levin = variant == vtkPointSetSurface::LEVIN_MLS;
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(12.0 * kH, 0.1 * kH);
  vtkSmartPointer<vtkImageData> grid = MakeGrid();

  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  Configure(sampler->GetSurface(), variant);
  sampler->SetOrientationMode(mode);
  sampler->SetInputData(grid);
  sampler->SetSourceData(cloud);
  sampler->Update();
  vtkDataSet* field = sampler->GetOutput();
  ASSERT_EQ(field->GetNumberOfPoints(), grid->GetNumberOfPoints());
  vtkDataArray* normal = field->GetPointData()->GetArray("Normal");
  ASSERT_NE(normal, nullptr);
  ASSERT_EQ(field->GetPointData()->GetVectors(), normal);

  if (mode == vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID)
  {
    // The rule itself: n . (x - centroid) >= 0 at every sample (centroid = origin).
    int violations = 0;
    for (vtkIdType i = 0; i < field->GetNumberOfPoints(); ++i)
    {
      double x[3], n[3];
      field->GetPoint(i, x);
      normal->GetTuple(i, n);
      violations += n[0] * x[0] + n[1] * x[1] < 0.0 ? 1 : 0;
    }
    EXPECT_EQ(violations, 0);
  }

  // Seeds: Levin's tangent region above and below the line (|y| = 1.2 .. 2 h > h/sqrt(2)), its
  // normal region near the line (|y| = 0.3, 0.4 h), and further out for CenterOfMass.
  const std::vector<std::array<double, 2>> seeds = { { 0.5, 1.5 }, { -0.5, 2.0 }, { 0.8, -1.2 }, { 1.2, 0.3 },
    { -2.0, -0.4 }, { 3.0, -2.0 } };
  const std::vector<Streamline> lines = Trace(field, seeds);
  ASSERT_EQ(lines.size(), seeds.size());

  // The tracer writes single-precision points: rounding accumulates to ~1e-5 h over the ~150
  // steps of a streamline, so straightness is checked to 1e-4 h.
  const double straight = 1e-4 * kH;
  double worstCos = 1.0;
  for (const Streamline& s : lines)
  {
    ASSERT_GE(s.seed, 0);
    const auto& seed = seeds[static_cast<std::size_t>(s.seed)];
    std::ostringstream where;
    where << "seed (" << seed[0] << ", " << seed[1] << ") variant " << variant << " mode " << ModeName(mode);
    SCOPED_TRACE(where.str());
    const Agreement a = CheckTangents(cloud, variant, s);
    worstCos = std::min(worstCos, a.minAbsCos);
    const auto& end = s.points.back();
    std::cout << "[ stream   ] " << (levin ? "levin" : "com") << " " << ModeName(mode) << " seed (" << seed[0]
              << ", " << seed[1] << "): " << s.points.size() << " points, length " << s.length << " h, end ("
              << end[0] << ", " << end[1] << "), reason " << s.reason << ", min |cos| " << a.minAbsCos << " over "
              << a.checked << " points (" << a.excluded << " excluded)\n";

    // Tangent = n: the tracer integrates the sampled, oriented n; only interpolation between grid
    // samples separates the two, O(spacing^2 |d^2 n|) ~ 1e-3 where n is smooth, so 0.99 is loose.
    EXPECT_GT(a.checked, 10);
    EXPECT_GT(a.minAbsCos, 0.99);

    // Not cut short: every streamline leaves the grid (no zero-velocity stop at an orientation
    // seam, no STAGNATION where n is parallel to the cloud).
    EXPECT_EQ(s.reason, vtkStreamTracer::OUT_OF_DOMAIN);
    EXPECT_TRUE(OnGridBoundary(end)) << "ends at (" << end[0] << ", " << end[1] << ")";

    const bool tangentSeed = std::abs(seed[1]) > kSingularHeight;
    if (levin && tangentSeed)
    {
      // Levin's tangent region: a horizontal line (n = x-axis exactly, see the file comment) that
      // runs to x = +-5 h: at least 5 h - |x0| long (2 h to 4.5 h from these seeds).
      EXPECT_NEAR(end[1], seed[1], straight);
      EXPECT_NEAR(std::abs(end[0]), kXMax, 1.5 * kGrid);
      EXPECT_GT(s.length, kXMax - std::abs(seed[0]) - 1.5 * kGrid);
      if (mode == vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID)
      {
        EXPECT_GT(end[0] * seed[0], 0.0) << "runs away from the seam x = 0";
        EXPECT_NEAR(s.length, kXMax - std::abs(seed[0]), 1.5 * kGrid);
      }
    }
    if (!levin)
    {
      // CenterOfMass: a vertical segment to y = +-3 h (n = y-axis exactly at every sample).
      EXPECT_NEAR(end[0], seed[0], straight);
      EXPECT_NEAR(std::abs(end[1]), kYMax, 1.5 * kGrid);
      if (mode == vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID)
      {
        EXPECT_GT(end[1] * seed[1], 0.0) << "runs away from the cloud";
        EXPECT_NEAR(s.length, kYMax - std::abs(seed[1]), 1.5 * kGrid);
      }
    }
    if (levin && !tangentSeed && mode == vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID)
    {
      // Levin's normal region: away from the cloud up to the singular height, through the blended
      // row of cells (whose vertical velocity vanishes only at its top edge) onto the first row of
      // tangent samples, then along the cloud, away from x = 0, to the side of the grid.
      EXPECT_GT(end[0] * seed[0], 0.0);
      EXPECT_GT(end[1] * seed[1], 0.0);
      EXPECT_NEAR(std::abs(end[0]), kXMax, 1.5 * kGrid);
      EXPECT_NEAR(std::abs(end[1]), FirstTangentRow(), 1e-3 * kH);
    }
  }
  std::cout << "[ stream   ] " << (levin ? "levin" : "com") << " " << ModeName(mode) << ": min |cos| over all "
            << worstCos << "\n";
}

INSTANTIATE_TEST_SUITE_P(LineCloud, FieldStreamlines,
  ::testing::Combine(::testing::Values(static_cast<int>(vtkPointSetSurface::LEVIN_MLS),
                       static_cast<int>(vtkPointSetSurface::CENTER_OF_MASS)),
    ::testing::Values(static_cast<int>(vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID),
      static_cast<int>(vtkPointSetSurfaceFieldSampler::PROPAGATE))),
  [](const ::testing::TestParamInfo<std::tuple<int, int>>& info) {
    const int variant = std::get<0>(info.param);
    const int mode = std::get<1>(info.param);
    return std::string(variant == vtkPointSetSurface::LEVIN_MLS ? "LevinMLS" : "CenterOfMass") + "_" +
      ModeName(mode);
  });

// Levin's tangent field around a circle (the situation of Fig. 9, where n_MLS turns parallel to a
// curved cloud): outside |r - R| ~ h/sqrt(2), n is exactly tangent by symmetry, so the streamlines
// of the line field are the circles r = const. A point-wise rule cannot orient it (n . (x - c) is 0
// there, the sign is left to rounding); PROPAGATE orients the whole annulus one way, so a
// streamline seeded 1.5 h outside the circle goes round and round until its length budget ends.
TEST(FieldStreamlinesCircle, PropagateOrientsLevinsTangentFieldAroundACurvedCloud)
{
  const double R = 5.0 * kH, r0 = R + 1.5 * kH, budget = 60.0 * kH; // ~1.5 turns of 2 pi r0 = 40.8 h
  vtkSmartPointer<vtkPolyData> cloud = CircleCloud(R, 0.1 * kH);
  double lengthByMode[2] = { 0.0, 0.0 };
  for (const int mode : { vtkPointSetSurfaceFieldSampler::PROPAGATE, vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID })
  {
    vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
    Configure(sampler->GetSurface(), vtkPointSetSurface::LEVIN_MLS);
    sampler->SetOrientationMode(mode);
    sampler->GenerateSamplingGridOn();
    sampler->SetSampleDimensions(81, 81, 1); // [-8 h, 8 h]^2, spacing 0.2 h
    sampler->SetSourceData(cloud);
    sampler->Update();

    vtkNew<vtkPoints> seedPoints;
    seedPoints->InsertNextPoint(r0, 0.0, 0.0);
    vtkNew<vtkPolyData> seeds;
    seeds->SetPoints(seedPoints);
    vtkNew<vtkStreamTracer> tracer;
    tracer->SetInputConnection(sampler->GetOutputPort());
    tracer->SetSourceData(seeds);
    tracer->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Normal");
    tracer->SetIntegratorTypeToRungeKutta4();
    tracer->SetIntegrationStepUnit(vtkStreamTracer::CELL_LENGTH_UNIT);
    tracer->SetInitialIntegrationStep(0.2);
    tracer->SetMaximumPropagation(budget);
    tracer->SetMaximumNumberOfSteps(100000);
    tracer->SetIntegrationDirectionToForward();
    tracer->Update();
    vtkPolyData* line = tracer->GetOutput();
    ASSERT_EQ(line->GetNumberOfCells(), 1);
    const int reason = static_cast<int>(line->GetCellData()->GetArray("ReasonForTermination")->GetTuple1(0));
    double length = 0.0, maxRadialError = 0.0, turned = 0.0;
    double previous[3];
    line->GetPoint(0, previous);
    for (vtkIdType k = 1; k < line->GetNumberOfPoints(); ++k)
    {
      double p[3];
      line->GetPoint(k, p);
      length += std::hypot(p[0] - previous[0], p[1] - previous[1]);
      turned += std::remainder(std::atan2(p[1], p[0]) - std::atan2(previous[1], previous[0]), 2.0 * kPi);
      maxRadialError = std::max(maxRadialError, std::abs(std::hypot(p[0], p[1]) - r0));
      std::copy(p, p + 3, previous);
    }
    lengthByMode[mode == vtkPointSetSurfaceFieldSampler::PROPAGATE ? 0 : 1] = length;
    std::cout << "[ circle   ] levin " << ModeName(mode) << ": length " << length << " h, turned "
              << turned / (2.0 * kPi) << " turns, max |r - r0| " << maxRadialError << " h, reason " << reason << "\n";
    if (mode == vtkPointSetSurfaceFieldSampler::PROPAGATE)
    {
      // The whole budget, spent going round one way (no reversal: |turned| = length / r0).
      EXPECT_EQ(reason, vtkStreamTracer::OUT_OF_LENGTH);
      EXPECT_NEAR(length, budget, 0.2 * kH);
      EXPECT_NEAR(std::abs(turned) * r0, length, 0.05 * length);
      // On the circle r = r0. Bilinear interpolation reproduces the linear part of the tangent
      // field (-y, x) / r exactly; the curvature of 1 / r leaves a direction error of about
      // (spacing / r0)^2 / 8 ~ 1e-4 rad. Even if that error were systematic, 60 h of travel would
      // drift by 6e-3 h: 0.01 h bounds it.
      EXPECT_LT(maxRadialError, 0.01 * kH);
    }
  }
  // For the record: the point-wise rule is undecided on the tangent field (see the class doc).
  std::cout << "[ circle   ] length with PROPAGATE " << lengthByMode[0] << " h, with AWAY_FROM_CENTROID "
            << lengthByMode[1] << " h\n";
}

// PROPAGATE over the cells of an arbitrary dataset (here a poly-line, not a structured grid):
// along a segment at height 1.5 h above the line, Levin's n is the x-axis at every sample. The
// point-wise rule flips it at x = 0 (it points away from the centroid); propagation along the
// poly-line's consecutive points makes all samples agree.
TEST(FieldSamplerPropagate, OrientsAlongThePointsOfAPolyLine)
{
  vtkSmartPointer<vtkPolyData> cloud = LineCloud(12.0 * kH, 0.1 * kH);
  vtkNew<vtkPoints> points;
  const int n = 81;
  for (int i = 0; i < n; ++i)
  {
    points->InsertNextPoint(-4.0 * kH + 8.0 * kH * i / (n - 1), 1.5 * kH, 0.0);
  }
  vtkNew<vtkCellArray> cells;
  cells->InsertNextCell(n);
  for (int i = 0; i < n; ++i)
  {
    cells->InsertCellPoint(i);
  }
  vtkNew<vtkPolyData> polyline;
  polyline->SetPoints(points);
  polyline->SetLines(cells);

  for (const int mode : { vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID, vtkPointSetSurfaceFieldSampler::PROPAGATE })
  {
    vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
    Configure(sampler->GetSurface(), vtkPointSetSurface::LEVIN_MLS);
    sampler->SetOrientationMode(mode);
    sampler->SetInputData(polyline);
    sampler->SetSourceData(cloud);
    sampler->Update();
    vtkDataSet* out = sampler->GetOutput();
    ASSERT_TRUE(vtkPolyData::SafeDownCast(out));
    EXPECT_EQ(vtkPolyData::SafeDownCast(out)->GetNumberOfLines(), 1) << "the input's structure is kept";
    vtkDataArray* normal = out->GetPointData()->GetArray("Normal");
    int flips = 0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      EXPECT_NEAR(std::abs(normal->GetTuple3(i)[0]), 1.0, 1e-9) << "tangent at 1.5 h";
      if (i > 0)
      {
        flips += normal->GetTuple3(i)[0] * normal->GetTuple3(i - 1)[0] < 0.0 ? 1 : 0;
      }
    }
    // The point-wise rule: exactly one flip (at x = 0); propagation: none.
    EXPECT_EQ(flips, mode == vtkPointSetSurfaceFieldSampler::PROPAGATE ? 0 : 1);
    EXPECT_EQ(CountNonFinite(out), 0);
  }
}

// SPDX-License-Identifier: BSD-3-Clause
// The mesh with a scale per point (PointIndex::setScales, estimateLocalScales) on shapes whose
// sampling density varies tenfold: a plane graded along one axis, a sphere dense at one pole and
// sparse at the other. The surface must stay whole, where one h would tear its sparse part.
#include "TestClouds.h"

#include "pss/Domain.h"
#include "pss/SurfaceMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

namespace
{
using namespace pss;
using namespace pss_test;

double medianScale(const PointIndex& index)
{
  std::vector<double> h(index.size());
  for (std::size_t i = 0; i < h.size(); ++i)
  {
    h[i] = index.scale(i);
  }
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
  return h[h.size() / 2];
}

SurfaceMesh meshWithScales(PointIndex& index, double multiplier, const MeshOptions& options = {}, int threads = 0)
{
  index.setScales(estimateLocalScales(index, 10, multiplier));
  auto surface = makeSurface(Variant::CenterOfMass, index, params(medianScale(index)));
  return extractSurfaceMesh(*surface, options, threads);
}

// Edges used by one triangle only, as (vertex, vertex) pairs.
std::vector<std::pair<std::uint32_t, std::uint32_t>> boundaryEdges(const SurfaceMesh& mesh)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& [edge, count] : uses)
  {
    if (count == 1)
    {
      out.push_back(edge);
    }
  }
  return out;
}

} // namespace

// The plane z = 0, spacing 0.2 at x = 0 growing to 2 at x = 60, |y| <= 30: one piece, every
// boundary edge at the patch's own border (within two local scales of it), every vertex within
// 0.05 local h of the plane.
TEST(AdaptiveMesh, TenfoldGradedPlaneIsOnePieceOnThePlane)
{
  const double length = 60.0;
  PointIndex index(gradedPlane(0.2, 10.0, length), 3);
  const SurfaceMesh mesh = meshWithScales(index, 1.0);
  const MeshStatistics& st = mesh.statistics;
  std::cout << "points " << index.size() << ", h_i " << index.minScale() << " to " << index.maxScale()
            << ", triangles " << mesh.triangles.size() << ", pieces " << st.components << ", boundary "
            << st.boundaryEdges << "\n";
  EXPECT_EQ(st.components, 1u);
  EXPECT_EQ(st.nonManifoldEdges, 0u);
  ASSERT_GT(mesh.triangles.size(), 1000u);
  double worst = 0.0;
  for (const Vec3& p : mesh.points)
  {
    const double h = index.scale(index.nearest(p).first);
    worst = std::max(worst, std::abs(p.z()) / h);
  }
  EXPECT_LT(worst, 0.05) << "the largest |z| / local h";
  std::size_t inside = 0;
  for (const auto& [a, b] : boundaryEdges(mesh))
  {
    const Vec3 m = 0.5 * (mesh.points[a] + mesh.points[b]);
    const double h = index.scale(index.nearest(m).first);
    const double toBorder = std::min({ m.x(), length - m.x(), 0.5 * length - std::abs(m.y()) });
    inside += toBorder > 2.0 * h ? 1 : 0;
  }
  EXPECT_EQ(inside, 0u) << "boundary edges inside the patch";
  EXPECT_EQ(st.boundaryEdges, boundaryEdges(mesh).size());
  // The cells follow h_i: several sizes, meeting at hanging corners (a crack or a T-junction where
  // they meet would be a boundary edge inside the patch).
  std::cout << "cell levels " << st.cellLevels << ", band cells " << st.bandCells << ", hanging corners "
            << st.hangingVertices << "\n";
  EXPECT_GE(st.cellLevels, 3u);
  EXPECT_GT(st.hangingVertices, 100u);
  // The same bytes on one thread and on two.
  const SurfaceMesh single = meshWithScales(index, 1.0, {}, 1);
  const SurfaceMesh dual = meshWithScales(index, 1.0, {}, 2);
  ASSERT_EQ(single.points.size(), dual.points.size());
  EXPECT_TRUE(std::equal(single.points.begin(), single.points.end(), dual.points.begin()));
  EXPECT_EQ(single.triangles, dual.triangles);
  // One grid when asked: more cells, no hanging corner.
  MeshOptions regular;
  regular.adaptiveCells = false;
  const MeshStatistics one = meshWithScales(index, 1.0, regular).statistics;
  EXPECT_EQ(one.cellLevels, 1u);
  EXPECT_EQ(one.hangingVertices, 0u);
  EXPECT_GT(one.bandCells, st.bandCells);
}

// The same in 2D: a circle of radius 20 whose spacing grows tenfold from one side to the other
// is one closed polyline on the circle, with cells of several sizes (a quadtree).
TEST(AdaptiveMesh, TenfoldGradedCircleIsOneClosedCurve)
{
  const double radius = 20.0;
  std::vector<Vec3> pts;
  // Spacing 0.04 at angle 0 growing smoothly to 0.4 at angle pi and back.
  for (double angle = 0.0; angle < 2.0 * kPi; angle += 0.002 * std::pow(10.0, 0.5 * (1.0 - std::cos(angle))))
  {
    pts.emplace_back(radius * std::cos(angle), radius * std::sin(angle), 0.0);
  }
  PointIndex index(pts, 2);
  const SurfaceMesh mesh = meshWithScales(index, 1.0);
  const MeshStatistics& st = mesh.statistics;
  std::cout << "points " << index.size() << ", segments " << mesh.segments.size() << ", cell levels "
            << st.cellLevels << ", hanging corners " << st.hangingVertices << "\n";
  EXPECT_GE(st.cellLevels, 2u);
  EXPECT_GT(st.hangingVertices, 0u);
  EXPECT_EQ(st.components, 1u);
  EXPECT_EQ(st.boundaryEdges, 0u) << "polyline ends";
  EXPECT_EQ(st.nonManifoldEdges, 0u);
  ASSERT_GT(mesh.segments.size(), 50u);
  double worst = 0.0;
  for (const Vec3& p : mesh.points)
  {
    const double h = index.scale(index.nearest(p).first);
    worst = std::max(worst, std::abs(p.norm() - radius) / (h * h / radius));
  }
  EXPECT_LT(worst, 1.5) << "the largest |r - R| / (h^2 / R)";
}

// A sphere of radius 20 whose sampling density falls tenfold from the south pole to the north
// pole (a regular Fibonacci lattice, thinned deterministically): one closed piece, Euler
// characteristic 2, as close to the sphere as the local scale allows.
TEST(AdaptiveMesh, SphereDenseOnOneSideIsOneClosedPiece)
{
  const double radius = 20.0;
  const int lattice = 60000;
  std::vector<Vec3> pts;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  double kept = 0.0;
  for (int i = 0; i < lattice; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / lattice;
    const double r = std::sqrt(1.0 - z * z);
    // Keep a share 10^(-(1 + z) / 2) of the lattice: 1 at the south pole, 0.1 at the north.
    kept += std::pow(10.0, -0.5 * (1.0 + z));
    if (kept >= 1.0)
    {
      kept -= 1.0;
      pts.emplace_back(radius * r * std::cos(golden * i), radius * r * std::sin(golden * i), radius * z);
    }
  }
  PointIndex index(pts, 3);
  const SurfaceMesh mesh = meshWithScales(index, 1.0);
  const MeshStatistics& st = mesh.statistics;
  std::cout << "points " << index.size() << ", h_i " << index.minScale() << " to " << index.maxScale()
            << ", triangles " << mesh.triangles.size() << ", pieces " << st.components << ", boundary "
            << st.boundaryEdges << ", euler " << st.eulerCharacteristic << "\n";
  EXPECT_GT(index.maxScale() / index.minScale(), 2.5) << "the density varies tenfold";
  EXPECT_EQ(st.components, 1u);
  EXPECT_EQ(st.boundaryEdges, 0u);
  EXPECT_EQ(st.nonManifoldEdges, 0u);
  EXPECT_EQ(st.eulerCharacteristic, 2);
  EXPECT_GE(st.cellLevels, 2u);
  EXPECT_GT(st.hangingVertices, 0u);
  // The centre-of-mass surface of a sphere lies inside it by about h^2 / (2 R) to h^2 / R (the
  // weighted centroid of a curved neighbourhood); with a scale per point, by the local one's.
  double worst = 0.0;
  for (const Vec3& p : mesh.points)
  {
    const double h = index.scale(index.nearest(p).first);
    worst = std::max(worst, std::abs(p.norm() - radius) / (h * h / radius));
  }
  std::cout << "largest |r - R| / (h^2 / R): " << worst << "\n";
  EXPECT_LT(worst, 1.5);
}

// The mesher's border test (DomainThresholds::maxBorderOffset), against its analytic values: on a
// dense half-plane the neighbours' centroid trails a point of the border line by h / sqrt(pi)
// along the plane and sits over an inner point; a mesh of a sampled square stops at its edge
// with the test, and runs on for about MaxDistance without it.
TEST(AdaptiveMesh, BorderTestStopsTheMeshAtTheCloudsEdge)
{
  const double h = 1.0;
  std::vector<Vec3> half;
  for (double x = 0.0; x <= 8.0; x += 0.05)
  {
    for (double y = -8.0; y <= 8.0; y += 0.05)
    {
      half.emplace_back(x, y, 0.0);
    }
  }
  const PointIndex halfIndex(half, 3);
  auto halfPlane = makeSurface(Variant::CenterOfMass, halfIndex, params(h));
  DomainThresholds thresholds;
  thresholds.maxBorderOffset = 0.6;
  Workspace ws;
  const DomainEvidence atBorder = classifyStart(*halfPlane, Vec3(0.0, 0.0, 0.1), ProjectionOptions{}, thresholds, ws);
  // h / sqrt(pi) for the continuous half-plane; the samples on the border line itself add half a
  // column's weight at offset 0 (Euler-Maclaurin): (h / sqrt(pi)) / (1 + s / (h sqrt(pi))).
  const double s = 0.05;
  EXPECT_NEAR(atBorder.borderOffset, (h / std::sqrt(kPi)) / (1.0 + s / (h * std::sqrt(kPi))), 2e-3);
  EXPECT_EQ(atBorder.label, DomainLabel::InDomain);
  const DomainEvidence inside = classifyStart(*halfPlane, Vec3(4.0, 0.0, 0.1), ProjectionOptions{}, thresholds, ws);
  EXPECT_LT(inside.borderOffset, 1e-5) << "the centroid over the point, up to the sums' rounding";
  const DomainEvidence past = classifyStart(*halfPlane, Vec3(-0.3, 0.0, 0.1), ProjectionOptions{}, thresholds, ws);
  EXPECT_GT(past.borderOffset, 0.6);
  EXPECT_EQ(past.label, DomainLabel::Spurious);

  // A square of side 10 sampled every 0.25 h: how far past its edge do the vertices reach?
  const PointIndex square(planeCloud(5.0, 0.25), 3);
  auto surface = makeSurface(Variant::CenterOfMass, square, params(h));
  auto overhang = [&](double maxBorderOffset) {
    MeshOptions options;
    options.domain.maxBorderOffset = maxBorderOffset;
    const SurfaceMesh mesh = extractSurfaceMesh(*surface, options, 0);
    double worst = -1e9;
    for (const Vec3& p : mesh.points)
    {
      worst = std::max(worst, std::max(std::abs(p.x()), std::abs(p.y())) - 5.0);
    }
    return worst;
  };
  const double without = overhang(0.0), with = overhang(0.6);
  std::cout << "overhang past the square's edge: " << without << " h without the border test, " << with
            << " h with it\n";
  EXPECT_GT(without, 0.5 * h);
  EXPECT_LT(with, 0.2 * h);
}

// The trim (MeshOptions::trimDistance) on a plane sampled with three unsampled discs: a notch (a
// half disc of 4 spacings in radius) cut into the patch's edge, a wide round gap inside (4.5) and
// a narrow one (3). Without the trim the mesh covers all three (each vertex is within MaxDistance
// of a point, the triangles between them are not). With it the notch and the patch's outline are
// cut back to trimDistance local spacings from the cloud (to within 0.3 spacing: the cut is linear
// along edges of at most half a spacing); the wide gap, whose centre lies more than 3.1 spacings
// from the data, is cut open as well, while the narrow one stays covered: an enclosed region is
// cut only where it reaches that far. The plane is not moved.
TEST(AdaptiveMesh, TrimCutsTheMeshBackFromItsBorder)
{
  const double half = 20.0;
  struct Gap
  {
    Vec3 centre;
    double radius; // in spacings
  };
  const Gap notch{ Vec3(half, 0.0, 0.0), 4.0 };
  const Gap wide{ Vec3(6.0, 0.0, 0.0), 4.5 };
  const Gap narrow{ Vec3(-8.0, 0.0, 0.0), 3.0 };
  auto inside = [](const Gap& g, const Vec3& x, double margin) {
    return std::hypot(x.x() - g.centre.x(), x.y() - g.centre.y()) < g.radius + margin;
  };
  std::vector<Vec3> pts;
  for (int i = -20; i <= 20; ++i)
  {
    for (int j = -20; j <= 20; ++j)
    {
      const Vec3 p(i, j, 0.0);
      if (!inside(notch, p, 0.0) && !inside(wide, p, 0.0) && !inside(narrow, p, 0.0))
      {
        pts.push_back(p);
      }
    }
  }
  PointIndex index(pts, 3);
  MeshOptions options;
  options.domain.maxDistance = 1.0; // about four spacings: the vertex test alone covers the gaps
  options.domain.maxBorderOffset = 0.0; // no border criterion: the mesh runs on past the outline and over the notch
  const SurfaceMesh bridged = meshWithScales(index, 2.0, options);
  options.trimDistance = 2.5;
  const SurfaceMesh trimmed = meshWithScales(index, 2.0, options);
  const std::vector<double> spacing = estimateLocalSpacings(index, 12, 1);

  // The largest distance to the cloud, in the nearest point's spacing, over a barycentric grid
  // of every triangle outside the narrow gap (with a margin of one spacing).
  auto farthest = [&](const SurfaceMesh& mesh, bool inNarrow = false) {
    double worst = 0.0;
    for (const auto& t : mesh.triangles)
    {
      for (int a = 0; a <= 8; ++a)
      {
        for (int b = 0; a + b <= 8; ++b)
        {
          const Vec3 x = (a * mesh.points[t[0]] + b * mesh.points[t[1]] + (8 - a - b) * mesh.points[t[2]]) / 8.0;
          if (inside(narrow, x, 1.0) == inNarrow)
          {
            const auto [j, d2] = index.nearest(x);
            worst = std::max(worst, std::sqrt(d2) / spacing[j]);
          }
        }
      }
    }
    return worst;
  };
  // Whether a triangle of the mesh covers (x, y) (seen along z).
  auto covers = [](const SurfaceMesh& mesh, double x, double y) {
    for (const auto& t : mesh.triangles)
    {
      const Vec3 p = mesh.points[t[0]], q = mesh.points[t[1]], r = mesh.points[t[2]];
      const double d = (q.x() - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (q.y() - p.y());
      const double u = ((x - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (y - p.y())) / d;
      const double v = ((q.x() - p.x()) * (y - p.y()) - (x - p.x()) * (q.y() - p.y())) / d;
      if (u >= 0.0 && v >= 0.0 && u + v <= 1.0)
      {
        return true;
      }
    }
    return false;
  };
  const double before = farthest(bridged);
  const double after = farthest(trimmed);
  const double narrowGap = farthest(trimmed, true);
  std::cout << "h_i " << index.minScale() << " to " << index.maxScale() << "; farthest outside the narrow gap: bridged "
            << before << " spacings, trimmed " << after << " spacings; in the narrow gap " << narrowGap
            << " spacings; trimmed triangles "
            << trimmed.statistics.trimmedSimplices << ", boundary edges " << bridged.statistics.boundaryEdges << " -> "
            << trimmed.statistics.boundaryEdges << "\n";
  ASSERT_GT(before, 3.0) << "the untrimmed mesh must run far from the cloud for this test to mean anything";
  for (const Gap* g : { &notch, &wide, &narrow })
  {
    ASSERT_TRUE(covers(bridged, g->centre.x() - 1.0, 0.0)) << "the untrimmed mesh must cover each gap";
  }
  EXPECT_LE(after, 2.5 + 0.3);
  EXPECT_FALSE(covers(trimmed, half - 1.0, 0.0)) << "the notch, 3 spacings from the cloud, is cut open";
  EXPECT_FALSE(covers(trimmed, wide.centre.x(), 0.0)) << "the wide gap is cut open";
  EXPECT_TRUE(covers(trimmed, narrow.centre.x(), 0.0)) << "the narrow gap stays covered";
  EXPECT_GT(narrowGap, 2.5) << "the narrow gap must reach past the trim distance for this test to mean anything";
  EXPECT_GT(trimmed.statistics.trimmedSimplices, 0u);
  EXPECT_EQ(trimmed.statistics.components, 1u);
  EXPECT_EQ(trimmed.statistics.nonManifoldEdges, 0u);
  // Boundary edges only at the patch's outline (the notch included) and around the wide gap.
  for (const auto& [a, b] : boundaryEdges(trimmed))
  {
    for (const std::uint32_t v : { a, b })
    {
      const Vec3& p = trimmed.points[v];
      const bool atBorder = std::max(std::abs(p.x()), std::abs(p.y())) > half - 3.0;
      EXPECT_TRUE(inside(notch, p, 3.0) || inside(wide, p, 0.0) || atBorder) << "boundary vertex at " << p.transpose();
    }
  }
  for (const Vec3& p : trimmed.points)
  {
    EXPECT_LT(std::abs(p.z()), 1e-9) << "the trim moves no vertex off the plane";
  }
  for (const double bad : { -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity() })
  {
    options.trimDistance = bad;
    EXPECT_THROW(meshWithScales(index, 3.0, options), std::invalid_argument) << bad;
  }
}

// Coincident points have no spacing of their own (their 12th neighbour is at distance 0, and so
// is the median around them): the trim must not take every sample near them for far. A plane
// sampled every 0.5 h with one point repeated 16 times is not cut anywhere.
TEST(AdaptiveMesh, TrimIgnoresCoincidentPoints)
{
  std::vector<Vec3> pts = planeCloud(10.0, 0.5);
  pts.insert(pts.end(), 15, Vec3(0.5, 0.5, 0.0));
  const PointIndex index(pts, 3);
  auto surface = makeSurface(Variant::CenterOfMass, index, params(1.0));
  MeshOptions options;
  options.trimDistance = 2.5;
  const SurfaceMesh mesh = extractSurfaceMesh(*surface, options, 0);
  EXPECT_EQ(mesh.statistics.trimmedSimplices, 0u);
  EXPECT_EQ(mesh.statistics.components, 1u);
  for (const auto& [a, b] : boundaryEdges(mesh))
  {
    EXPECT_GT(std::hypot(mesh.points[a].x(), mesh.points[a].y()), 5.0) << "boundary vertex near the duplicates";
  }
}

// The octree is refused like the grid: counted level by level, before its cells are allocated.
TEST(AdaptiveMesh, AbsurdBandsAreRefusedBeforeAllocating)
{
  PointIndex index(gradedPlane(0.2, 10.0, 60.0), 3);
  index.setScales(estimateLocalScales(index, 10, 1.0));
  auto surface = makeSurface(Variant::CenterOfMass, index, params(medianScale(index)));
  auto refused = [&](const MeshOptions& o, const std::string& text) {
    try
    {
      SurfaceMesher mesher(*surface, o);
      ADD_FAILURE() << "accepted; expected: " << text;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  MeshOptions o;
  o.maxBandCells = 100;
  refused(o, "the limit is 100");
  o = {};
  o.cellSize = 1e-3; // about 10^10 cells at the finest level
  refused(o, "more than");
}

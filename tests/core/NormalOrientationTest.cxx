// SPDX-License-Identifier: BSD-3-Clause
// pss::orientNormals on shapes whose outward normal is known: a sphere with half its normals
// flipped, a torus (where "away from the centroid" points inward on the inner ring), two spheres
// apart (two pieces, each from its own seed), and the viewpoint rule.
#include "TestClouds.h"

#include "pss/NormalOrientation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace
{
using namespace pss;
using namespace pss_test;

// Fibonacci points on a sphere of @p radius about @p centre.
std::vector<Vec3> spherePoints(int count, double radius, const Vec3& centre)
{
  std::vector<Vec3> pts;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / count;
    const double r = std::sqrt(1.0 - z * z);
    pts.push_back(centre + radius * Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z));
  }
  return pts;
}

// Outward normals of the indexed points of a sphere about @p centre, the sign of each chosen by
// @p sign(point).
template <class Sign>
std::vector<Vec3> sphereNormals(const PointIndex& index, const Vec3& centre, Sign sign)
{
  std::vector<Vec3> n(index.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    n[i] = (index.point(i) - centre).normalized() * sign(index.point(i));
  }
  return n;
}

} // namespace

TEST(NormalOrientation, FlippedHalfOfASphereIsRepaired)
{
  PointIndex index(spherePoints(4000, 10.0, Vec3::Zero()), 3);
  auto flippedHalf = [](const Vec3& p) { return p.x() < 0.0 ? -1.0 : 1.0; };
  for (const int threads : { 1, 2 })
  {
    std::vector<Vec3> n = sphereNormals(index, Vec3::Zero(), flippedHalf);
    const std::size_t flips = orientNormals(index, n, std::nullopt, 10, threads);
    std::size_t outward = 0;
    for (std::size_t i = 0; i < n.size(); ++i)
    {
      outward += n[i].dot(index.point(i)) > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(outward, n.size()) << threads << " thread(s)";
    EXPECT_GT(flips, 1500u);
    EXPECT_LT(flips, 2500u);
  }
}

TEST(NormalOrientation, TorusIsOrientedOutwardWhereTheCentroidRuleIsNot)
{
  // Major radius 10, minor 3, about the z axis; each normal given a random sign.
  const double major = 10.0, minor = 3.0;
  std::vector<Vec3> pts, truth;
  for (int i = 0; i < 160; ++i)
  {
    for (int j = 0; j < 50; ++j)
    {
      const double u = 2.0 * kPi * (i + 0.5 * (j % 2)) / 160.0, v = 2.0 * kPi * j / 50.0;
      const Vec3 axis(std::cos(u), std::sin(u), 0.0);
      const Vec3 out = std::cos(v) * axis + std::sin(v) * Vec3::UnitZ();
      pts.push_back(major * axis + minor * out);
      truth.push_back(out);
    }
  }
  PointIndex index(pts, 3);
  std::mt19937 rng(3);
  std::vector<Vec3> n(index.size()), centroidRule(index.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    const Vec3& t = truth[index.originalId(i)];
    n[i] = (rng() % 2 ? 1.0 : -1.0) * t;
    centroidRule[i] = t.dot(index.point(i)) < 0.0 ? Vec3(-t) : t;
  }
  orientNormals(index, n, std::nullopt);
  std::size_t outward = 0, centroidOutward = 0;
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    outward += n[i].dot(truth[index.originalId(i)]) > 0.0 ? 1 : 0;
    centroidOutward += centroidRule[i].dot(truth[index.originalId(i)]) > 0.0 ? 1 : 0;
  }
  EXPECT_EQ(outward, index.size());
  EXPECT_LT(centroidOutward, index.size() * 3 / 4) << "the inner ring faces the centroid";
}

TEST(NormalOrientation, EachPieceFromItsOwnSeedAndTheViewpointRule)
{
  const Vec3 a(0.0, 0.0, 0.0), b(50.0, 0.0, -5.0);
  std::vector<Vec3> pts = spherePoints(2000, 5.0, a);
  for (const Vec3& p : spherePoints(2000, 8.0, b))
  {
    pts.push_back(p);
  }
  PointIndex index(pts, 3);
  auto centreOf = [&](const Vec3& p) { return (p - a).norm() < 20.0 ? a : b; };
  std::vector<Vec3> n(index.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    const Vec3& p = index.point(i);
    n[i] = (p - centreOf(p)).normalized() * (p.y() > 0.0 ? -1.0 : 1.0);
  }
  std::vector<Vec3> fromViewpoint = n;
  orientNormals(index, n, std::nullopt);
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    ASSERT_GT(n[i].dot(index.point(i) - centreOf(index.point(i))), 0.0) << "point " << i;
  }
  // Toward a viewpoint: point by point, every normal faces it.
  const Vec3 viewpoint(20.0, 0.0, 100.0);
  orientNormals(index, fromViewpoint, viewpoint);
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    ASSERT_GE(fromViewpoint[i].dot(viewpoint - index.point(i)), 0.0);
  }
  std::vector<Vec3> wrong(3);
  EXPECT_THROW(orientNormals(index, wrong, std::nullopt), std::invalid_argument);
}

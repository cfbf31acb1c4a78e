// SPDX-License-Identifier: BSD-3-Clause
// projectAll's results must not depend on the number of threads (Parallel.h / ExtremalSurface.h).

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>

using namespace pss;
using namespace pss_test;

namespace
{

/// A noisy sine curve y = 0.8h sin(x / 2h) + U(-0.1h, 0.1h), x in [-8h, 8h] at spacing 0.1h.
std::vector<Vec3> noisyCurve(double h, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.1 * h, 0.1 * h);
  std::vector<Vec3> pts = lineCloud(8 * h, 0.1 * h);
  for (Vec3& p : pts)
  {
    p.y() = 0.8 * h * std::sin(p.x() / (2 * h)) + noise(rng);
  }
  return pts;
}

} // namespace

// Truth: each start is computed independently and identically, so 1 and 2 threads must give the
// same bits; 1e-12 relative is the brief's bound (any real difference would be far larger).
TEST(Determinism, ProjectAllIndependentOfThreadCount)
{
  const double h = 0.5;
  const std::vector<Vec3> cloud = noisyCurve(h, 3u);
  PointIndex index(cloud, 2);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> ux(-6 * h, 6 * h);
  std::uniform_real_distribution<double> uy(-1.0 * h, 1.0 * h);
  std::vector<Vec3> starts;
  for (int i = 0; i < 200; ++i)
  {
    const double x = ux(rng);
    starts.emplace_back(x, 0.8 * h * std::sin(x / (2 * h)) + uy(rng), 0.0);
  }
  for (Variant v : allVariants())
  {
    auto s = makeSurface(v, index, params(h));
    for (Procedure proc : { Procedure::Extremal, Procedure::Plane })
    {
      SCOPED_TRACE(std::string(variantName(v)) + (proc == Procedure::Plane ? " plane" : " extremal"));
      ProjectionOptions opt;
      opt.procedure = proc;
      const std::vector<ProjectionResult> one = projectAll(*s, starts, opt, 1);
      const std::vector<ProjectionResult> two = projectAll(*s, starts, opt, 2);
      ASSERT_EQ(one.size(), starts.size());
      ASSERT_EQ(two.size(), starts.size());
      int converged = 0;
      for (std::size_t i = 0; i < starts.size(); ++i)
      {
        EXPECT_LE((one[i].point - two[i].point).norm(), 1e-12 * (1 + one[i].point.norm())) << "start " << i;
        EXPECT_EQ(one[i].iterations, two[i].iterations) << "start " << i;
        EXPECT_EQ(one[i].reason, two[i].reason) << "start " << i;
        EXPECT_EQ(one[i].type, two[i].type) << "start " << i;
        converged += one[i].reason == StopReason::Converged ? 1 : 0;
      }
      // Not the point of this test, but a suite where nothing converges would prove nothing.
      EXPECT_GT(converged, 100);
    }
  }
}

// Truth: parallelFor visits each index exactly once for any thread count (its contract).
TEST(Determinism, ParallelForVisitsEachIndexOnce)
{
  for (int threads : { 1, 2, 3, 0 })
  {
    for (std::size_t n : { std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(1000) })
    {
      std::vector<std::atomic<int>> hits(n);
      for (auto& h : hits)
      {
        h = 0;
      }
      parallelFor(n, threads, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i)
        {
          ++hits[i];
        }
      });
      for (std::size_t i = 0; i < n; ++i)
      {
        EXPECT_EQ(hits[i].load(), 1) << "n " << n << " threads " << threads << " index " << i;
      }
    }
  }
  EXPECT_EQ(resolveThreadCount(3), 3);
  EXPECT_GE(resolveThreadCount(0), 1);
}

// Truth: a projection does not depend on what the thread computed before. A start 1e300 from the
// cloud (its squared distance overflows) used to leave the thread's candidate cache claiming a
// ball it did not hold, and the next start on that thread then stopped with NoExtremum instead of
// converging (found by tests/fuzz/FuzzCore.cxx as a 1- vs 2-thread difference).
TEST(Determinism, OverflowingStartDoesNotChangeTheNextProjection)
{
  const std::vector<Vec3> cloud = { Vec3(0.0, 1e300, 0.0), Vec3(-3.9322159026487844, 1e300, 0.0),
    Vec3(-3.3834143897249822, 1e300, 0.0) };
  PointIndex index(cloud, 2);
  auto s = makeSurface(Variant::Delta, index, params(1.0));
  ProjectionOptions opt;
  opt.seekMaxima = true;
  opt.maxIterations = 2;
  const Vec3 start(-3.3834143897249822, 1e300, 0.0);
  const ProjectionResult alone = projectAll(*s, { start }, opt, 1).front(); // after nothing else
  const std::vector<ProjectionResult> after = projectAll(*s, { Vec3(0.0, 0.0, 0.0), start }, opt, 1);
  EXPECT_EQ(after[0].reason, StopReason::UndefinedDirection); // 1e300 away: n undefined, flagged
  EXPECT_EQ(after[1].reason, alone.reason);
  EXPECT_EQ(after[1].iterations, alone.iterations);
  EXPECT_EQ(std::memcmp(after[1].point.data(), alone.point.data(), 3 * sizeof(double)), 0);
}

// pss::CloudNormals fills its table from whichever thread asks first; every thread must get the
// uncached value, bit for bit, and on a plane that is the plane's normal.
TEST(Determinism, CloudNormalsSharedByThreadsAreTheUncachedOnes)
{
  Workspace ws;
  const std::vector<Vec3> cloud = planeCloud(4.0, 0.25);
  PointIndex index(cloud, 3);
  const auto surface = makeSurface(Variant::CenterOfMass, index, params(0.5));
  const CloudNormals normals(*surface);
  const std::size_t n = index.size();
  std::vector<Direction> got(2 * n);
  // Each point asked for twice, from the two ends of the range, so the two threads race for it.
  parallelFor(2 * n, 2, [&](std::size_t begin, std::size_t end, Workspace& worker) {
    for (std::size_t k = begin; k < end; ++k)
    {
      got[k] = normals.at(k < n ? k : 2 * n - 1 - k, worker);
    }
  });
  for (std::size_t k = 0; k < 2 * n; ++k)
  {
    const std::size_t i = k < n ? k : 2 * n - 1 - k;
    const Direction truth = cloudNormalAt(*surface, i, ws);
    ASSERT_TRUE(got[k].defined) << i;
    ASSERT_EQ(0, std::memcmp(got[k].n.data(), truth.n.data(), sizeof(double) * 3)) << i;
    ASSERT_EQ(got[k].stability, truth.stability) << i;
    ASSERT_GT(std::abs(got[k].n.z()), 1.0 - 1e-12) << i;
  }
}

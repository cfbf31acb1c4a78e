// SPDX-License-Identifier: BSD-3-Clause
// projectAll's results, and the index they run on, must not depend on the number of threads
// (Parallel.h / ExtremalSurface.h / PointIndex.h), nor on which thread computed the delta lattice's
// shared nodes (DeltaLattice.h).

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

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

/// @p n uniform random points in a 100-unit cube, with what the index must get right whatever the
/// chunking: every 101st point has a NaN or infinite coordinate, every 53rd repeats an earlier
/// point exactly, and a few sit at +0 and -0 (zeros of either sign compare equal).
std::vector<Vec3> messyCloud(std::size_t n, unsigned seed)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::vector<Vec3> pts(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    pts[i] = Vec3(u(rng), u(rng), u(rng));
    if (i % 101 == 7)
    {
      pts[i][static_cast<int>(i % 3)] = (i % 2) ? nan : -inf;
    }
    else if (i % 53 == 11)
    {
      pts[i] = pts[i / 2];
    }
    else if (i % 997 == 5)
    {
      pts[i] = Vec3((i % 2) ? 0.0 : -0.0, pts[i].y(), -0.0);
    }
  }
  return pts;
}

/// Same bits (memcmp, so -0 differs from +0 and NaNs compare equal to themselves).
template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameBits(const Vec3& a, const Vec3& b)
{
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

bool sameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

/// Everything a PointIndex exposes of its construction, and the answers of its tree to queries.
void expectSameIndex(const PointIndex& a, const PointIndex& b)
{
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a.skippedCount(), b.skippedCount());
  EXPECT_TRUE(sameBits(a.points(), b.points()));
  std::vector<std::uint32_t> idsA, idsB;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    idsA.push_back(static_cast<std::uint32_t>(a.originalId(i)));
  }
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    idsB.push_back(static_cast<std::uint32_t>(b.originalId(i)));
  }
  EXPECT_EQ(idsA, idsB);
  // The visiting order is the same whichever thread count computes it.
  const PointIndex::VisitingOrder orderA = a.visitingOrder(1);
  const PointIndex::VisitingOrder orderB = b.visitingOrder(2);
  EXPECT_EQ(orderA.positions, orderB.positions);
  EXPECT_EQ(orderA.ids, orderB.ids);
  EXPECT_TRUE(sameBits(a.centroid(), b.centroid()));
  EXPECT_TRUE(sameBits(a.boundsMin(), b.boundsMin()));
  EXPECT_TRUE(sameBits(a.boundsMax(), b.boundsMax()));
  // The tree itself: the same queries find the same indices at the same distances.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-60.0, 60.0);
  std::vector<std::pair<std::uint32_t, double>> foundA, foundB;
  PointIndex::LeafRanges leavesA, leavesB;
  for (int q = 0; q < 200; ++q)
  {
    const Vec3 x(u(rng), u(rng), u(rng));
    a.kNearest(x, 12, foundA);
    b.kNearest(x, 12, foundB);
    EXPECT_EQ(foundA, foundB);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> rangesA, rangesB;
    a.forEachLeafInBall(x, 25.0, leavesA, [&](std::uint32_t lo, std::uint32_t hi) { rangesA.emplace_back(lo, hi); });
    b.forEachLeafInBall(x, 25.0, leavesB, [&](std::uint32_t lo, std::uint32_t hi) { rangesB.emplace_back(lo, hi); });
    EXPECT_EQ(rangesA, rangesB);
  }
}

} // namespace

// Truth: the index is built from per-point loops, whose results do not depend on who computes
// them, and from per-chunk counts (the NaN filter, the radix sort's histograms) combined in chunk
// order, which give the serial result for any chunking; the centroid's sum stays serial. So 1, 2
// and 3 threads (1, 8 and 12 chunks) give the same bits. 300,000 points take the input-order
// build, 2^20 + 30,000 the Morton-sorted one (PointIndex.cxx's SortedBuildThreshold).
TEST(Determinism, PointIndexIndependentOfThreadCount)
{
  for (const std::size_t n : { std::size_t(300000), (std::size_t(1) << 20) + 30000 })
  {
    const std::vector<Vec3> cloud = messyCloud(n, static_cast<unsigned>(n));
    for (const int dimension : { 3, 2 })
    {
      if (n > 300000 && dimension == 2)
      {
        continue; // the sorted build is the same code in 2D; spare the sanitizer stages its time
      }
      SCOPED_TRACE("n " + std::to_string(n) + ", dimension " + std::to_string(dimension));
      const PointIndex one(cloud, dimension, 1);
      ASSERT_GT(one.skippedCount(), n / 200);
      const double h = estimateScale(one, 10, 1.0, 1);
      ASSERT_GT(h, 0.0);
      for (const int threads : { 2, 3 })
      {
        SCOPED_TRACE("threads " + std::to_string(threads));
        const PointIndex other(cloud, dimension, threads);
        expectSameIndex(one, other);
        EXPECT_TRUE(sameBits(h, estimateScale(other, 10, 1.0, threads)));
        EXPECT_TRUE(sameBits(h, estimateScale(one, 10, 1.0, threads)));
      }
      EXPECT_EQ(detectDimension(cloud, 1), 3);
      EXPECT_EQ(detectDimension(cloud, 3), 3);
    }
  }
}

// Truth: spatialOrder's radix sort places each chunk's keys of a digit value after those of the
// earlier chunks, which is where the serial pass places them; its keys are computed per point.
// So the order (a stable sort, ties by input index) is the same for every thread count.
TEST(Determinism, SpatialOrderIndependentOfThreadCount)
{
  const std::vector<Vec3> cloud = messyCloud(400000, 5u);
  const std::vector<std::uint32_t> one = spatialOrder(cloud, 1);
  ASSERT_EQ(one.size(), cloud.size());
  for (const int threads : { 2, 3, 0 })
  {
    EXPECT_TRUE(sameBits(one, spatialOrder(cloud, threads))) << "threads " << threads;
  }
  // Non-finite points last, in input order.
  std::vector<std::uint32_t> tail;
  for (std::uint32_t i = 0; i < cloud.size(); ++i)
  {
    if (!isFinite(cloud[i]))
    {
      tail.push_back(i);
    }
  }
  EXPECT_TRUE(std::equal(tail.begin(), tail.end(), one.end() - static_cast<std::ptrdiff_t>(tail.size())));
  // A flat cloud (2D detection) also detects the same on any thread count.
  std::vector<Vec3> flat(cloud);
  for (Vec3& p : flat)
  {
    p.z() = 1.5;
  }
  EXPECT_EQ(detectDimension(flat, 1), 2);
  EXPECT_EQ(detectDimension(flat, 2), 2);
}

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
  for (Variant v : paperVariants())
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

// Truth (ChunkQueue's contract): a worker takes its own contiguous part from the front, then
// chunks from the back of the part with the most left; every index is handed out exactly once.
TEST(Determinism, ChunkQueueKeepsPartsContiguousAndStealsFromTheBack)
{
  ChunkQueue queue(100, 2, 10);
  std::size_t begin = 0;
  std::size_t end = 0;
  ASSERT_TRUE(queue.take(0, begin, end));
  EXPECT_EQ(begin, 0u);
  EXPECT_EQ(end, 10u);
  std::vector<int> hits(100, 0);
  std::fill(hits.begin(), hits.begin() + 10, 1);
  std::vector<std::size_t> starts;
  while (queue.take(1, begin, end))
  {
    starts.push_back(begin);
    for (std::size_t i = begin; i < end; ++i)
    {
      ++hits[i];
    }
  }
  // Worker 1's own part 50..99 in order, then worker 0's rest stolen from its back.
  const std::vector<std::size_t> expected{ 50, 60, 70, 80, 90, 40, 30, 20, 10 };
  EXPECT_EQ(starts, expected);
  EXPECT_FALSE(queue.take(0, begin, end));
  EXPECT_TRUE(std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; }));
  // Uneven sizes: parts of 3 and 4 indices with chunks of 2, one worker taking everything.
  ChunkQueue small(7, 2, 2);
  std::vector<int> seen(7, 0);
  while (small.take(0, begin, end))
  {
    for (std::size_t i = begin; i < end; ++i)
    {
      ++seen[i];
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int h) { return h == 1; }));
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

namespace
{

// @p starts projected twice over on 2 threads, each thread running through the whole list in the
// same order (parallelFor's parts are contiguous), so the threads race for the same lattice
// nodes all along; each result must be the one-thread run's, bit for bit.
void expectRacingThreadsAgree(const SurfaceDefinition& surface, const std::vector<Vec3>& starts)
{
  ProjectionOptions options;
  const std::vector<ProjectionResult> one = projectAll(surface, starts, options, 1);
  const std::size_t n = starts.size();
  std::vector<ProjectionResult> got(2 * n);
  parallelFor(2 * n, 2, [&](std::size_t begin, std::size_t end, Workspace& worker) {
    for (std::size_t k = begin; k < end; ++k)
    {
      got[k] = project(surface, starts[k % n], options, worker);
    }
  });
  for (std::size_t k = 0; k < 2 * n; ++k)
  {
    const ProjectionResult& truth = one[k % n];
    ASSERT_EQ(0, std::memcmp(got[k].point.data(), truth.point.data(), sizeof(double) * 3)) << k;
    ASSERT_EQ(got[k].direction.stability, truth.direction.stability) << k;
    ASSERT_EQ(got[k].iterations, truth.iterations) << k;
    ASSERT_EQ(got[k].reason, truth.reason) << k;
  }
}

} // namespace

// The delta lattice's nodes are shared by the threads that read them (DeltaLattice.h): whichever
// thread computes a node, the others read the same bits, on a sphere patch where both threads
// need the same nodes at the same time.
TEST(Determinism, LatticeNodesSharedByThreadsChangeNoBit)
{
  const double h = 1.0;
  const std::vector<Vec3> cloud = sceneCloud(Scene::Sphere, 3, 3000, 14.0, 0.02);
  const PointIndex index(cloud, 3);
  // The cloud points within 3 h of its top, moved off the surface.
  double top = -1e300;
  for (const Vec3& p : cloud)
  {
    top = std::max(top, p.z());
  }
  std::vector<Vec3> starts;
  for (const Vec3& p : cloud)
  {
    if (p.z() > top - 3.0 * h)
    {
      starts.push_back(p + Vec3(0.1, -0.2, 0.3) * h);
    }
  }
  ASSERT_GE(starts.size(), 60u);
  SurfaceParameters p = params(h);
  p.deltaLattice = 0.5;
  expectRacingThreadsAgree(*makeSurface(Variant::Integral, index, p), starts);
}

// A run that needs more bricks than the shared table holds (LatticeCache::MaxBricks): the table
// forgets bricks that another thread may still be reading, and is asked for them again. A
// straight line 8,800 h long, starts 0.3 h off it every 2 h (over 2,000 bricks of starts alone):
// every end point on the line, the same bits on 1 and 2 threads.
TEST(Determinism, LatticeTableForgetsBricksUnderThreads)
{
  const double h = 1.0;
  const std::vector<Vec3> cloud = lineCloud(4400.0 * h, 0.5 * h);
  const PointIndex index(cloud, 2);
  std::vector<Vec3> starts;
  for (double x = -4390.0 * h; x <= 4390.0 * h; x += 2.0 * h)
  {
    starts.emplace_back(x, 0.3 * h, 0.0);
  }
  SurfaceParameters p = params(h);
  p.deltaLattice = 0.5;
  ASSERT_GT(latticeBrickKeys(starts, index, p).size(), LatticeCache::MaxBricks);
  const auto surface = makeSurface(Variant::Integral, index, p);
  const std::vector<ProjectionResult> two = projectAll(*surface, starts, ProjectionOptions(), 2);
  for (std::size_t i = 0; i < starts.size(); ++i)
  {
    ASSERT_EQ(two[i].reason, StopReason::Converged) << i;
    ASSERT_LT(std::abs(two[i].point.y()), 1e-3 * h) << i;
  }
  expectRacingThreadsAgree(*surface, starts);
}

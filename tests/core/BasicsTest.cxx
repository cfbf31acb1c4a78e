// SPDX-License-Identifier: BSD-3-Clause
// Input handling (PointIndex, factory, NaN starts), Gauss-Hermite exactness and seeking maxima.

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

using namespace pss;
using namespace pss_test;

// Truth: non-finite input points are dropped and counted, every kept point maps back to its
// input position (exact integer/coordinate bookkeeping, so exact equality).
TEST(PointIndex, SkipsNonFinitePointsAndMapsIds)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Vec3> input = { Vec3(0, 0, 0), Vec3(nan, 1, 2), Vec3(1, 2, 3), Vec3(4, inf, 0),
    Vec3(-inf, 0, 0), Vec3(5, 5, 5), Vec3(0, 0, nan) };
  PointIndex index(input, 3);
  EXPECT_EQ(index.size(), 3u);
  EXPECT_EQ(index.skippedCount(), 4u);
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    ids.push_back(index.originalId(i));
    EXPECT_TRUE(isFinite(index.point(i)));
    EXPECT_EQ(index.point(i), input[index.originalId(i)]);
  }
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<std::size_t>{ 0, 2, 5 }));
  // nearest() only sees the finite points: (1,2,3) is the nearest to (1,2,2.9).
  const auto nn = index.nearest(Vec3(1, 2, 2.9));
  EXPECT_EQ(index.originalId(nn.first), 2u);
  EXPECT_NEAR(nn.second, 0.01, 1e-12);
}

// Truth: visitingOrder() visits every indexed point once, in spatialOrder() of the index's points,
// and lists every input index exactly once: each visited point's own id, then the skipped
// non-finite ones, ascending.
TEST(PointIndex, VisitingOrderCoversEveryInputOnce)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec3> input;
  for (int i = 0; i < 500; ++i)
  {
    input.emplace_back(std::cos(0.37 * i) * i, std::sin(0.37 * i) * i, (i % 7 == 3) ? nan : 0.01 * i);
  }
  PointIndex index(input, 3);
  const PointIndex::VisitingOrder order = index.visitingOrder();
  EXPECT_EQ(order.positions, spatialOrder(index.points()));
  ASSERT_EQ(order.ids.size(), input.size());
  for (std::size_t k = 0; k < index.size(); ++k)
  {
    EXPECT_EQ(order.ids[k], index.originalId(order.positions[k]));
  }
  EXPECT_TRUE(std::is_sorted(order.ids.begin() + static_cast<std::ptrdiff_t>(index.size()), order.ids.end()));
  std::vector<std::uint32_t> sorted(order.ids);
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i)
  {
    EXPECT_EQ(sorted[i], i);
  }
}

// Truth: spatialOrder is a stable sort by Morton code. Its radix sort must give exactly what a
// comparison sort of (code, index) pairs gives, including ties (duplicates) and non-finite points
// (last); the codes are recomputed here from the definition (cells of a 2^21 grid, x in bit 0).
TEST(PointIndex, SpatialOrderIsTheStableMortonOrder)
{
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Vec3> points;
  for (int i = 0; i < 3000; ++i)
  {
    const double t = 0.001 * i * i;
    points.emplace_back(std::fmod(t, 17.0), std::fmod(3.0 * t, 5.0) - 2.0, std::fmod(7.0 * t, 11.0));
  }
  points.push_back(points[10]); // a duplicate: same code, input order decides
  points.emplace_back(inf, 0.0, 0.0);
  points.push_back(points[20]);
  Vec3 lo = Vec3::Constant(inf);
  Vec3 hi = -lo;
  for (const Vec3& p : points)
  {
    if (isFinite(p))
    {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  auto code = [&](const Vec3& p) {
    if (!isFinite(p))
    {
      return std::numeric_limits<std::uint64_t>::max();
    }
    std::uint64_t c = 0;
    const double cells = double((1u << 21) - 1);
    for (int d = 0; d < 3; ++d)
    {
      const double scale = cells / (hi[d] - lo[d]);
      const auto cell = static_cast<std::uint64_t>(std::min(cells, std::max(0.0, (p[d] - lo[d]) * scale)));
      for (int b = 0; b < 21; ++b)
      {
        c |= ((cell >> b) & 1u) << (3 * b + d);
      }
    }
    return c;
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    keyed.emplace_back(code(points[i]), static_cast<std::uint32_t>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  const std::vector<std::uint32_t> order = spatialOrder(points);
  ASSERT_EQ(order.size(), keyed.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    EXPECT_EQ(order[i], keyed[i].second) << "position " << i;
  }
}

// Truth: in 2D z is ignored (a z-offset query has the same nearest distance), other dimensions throw.
TEST(PointIndex, TwoDimensionalIgnoresZAndRejectsBadDimension)
{
  const std::vector<Vec3> input = { Vec3(0, 0, 0), Vec3(1, 0, 0) };
  PointIndex index(input, 2);
  EXPECT_EQ(index.dimension(), 2);
  EXPECT_NEAR(index.nearest(Vec3(0.25, 0.5, 7.0)).second, 0.25 * 0.25 + 0.25, 1e-12);
  EXPECT_THROW({ PointIndex bad(input, 4); }, std::invalid_argument);
  EXPECT_THROW({ PointIndex bad(input, 1); }, std::invalid_argument);
}

// Truth: the contract of makeSurface (empty index, h <= 0 or NaN are rejected) for every variant.
TEST(Factory, RejectsEmptyIndexAndBadScale)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PointIndex empty(std::vector<Vec3>{}, 3);
  PointIndex allNaN(std::vector<Vec3>{ Vec3(nan, 0, 0) }, 3);
  PointIndex good(lineCloud(1.0, 0.1), 2);
  for (Variant v : paperVariants())
  {
    SCOPED_TRACE(variantName(v));
    EXPECT_THROW(makeSurface(v, empty, params(1.0)), std::invalid_argument);
    EXPECT_THROW(makeSurface(v, allNaN, params(1.0)), std::invalid_argument);
    EXPECT_THROW(makeSurface(v, good, params(0.0)), std::invalid_argument);
    EXPECT_THROW(makeSurface(v, good, params(-1.0)), std::invalid_argument);
    EXPECT_THROW(makeSurface(v, good, params(nan)), std::invalid_argument);
    EXPECT_THROW(makeSurface(v, good, params(std::numeric_limits<double>::infinity())),
      std::invalid_argument);
    auto s = makeSurface(v, good, params(1.0));
    ASSERT_TRUE(s);
    EXPECT_EQ(s->variant(), v);
  }
}

// Truth: a start with a NaN/Inf coordinate cannot be projected; the contract says InvalidInput.
TEST(Projection, NonFiniteStartIsInvalidInput)
{
  Workspace ws;
  PointIndex index(lineCloud(3.0, 0.1), 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Variant v : paperVariants())
  {
    SCOPED_TRACE(variantName(v));
    auto s = makeSurface(v, index, params(1.0));
    for (const Vec3& start : { Vec3(nan, 0.5, 0), Vec3(0, std::numeric_limits<double>::infinity(), 0) })
    {
      for (Procedure proc : { Procedure::Extremal, Procedure::Plane })
      {
        ProjectionOptions opt;
        opt.procedure = proc;
        const ProjectionResult r = project(*s, start, opt, ws);
        EXPECT_EQ(r.reason, StopReason::InvalidInput);
        EXPECT_FALSE(r.converged);
      }
    }
  }
}

// Truth: int x^(2k) e^(-x^2) dx = Gamma(k + 1/2) exactly for 2k <= 2n - 1, odd moments vanish,
// weights sum to sqrt(pi). 1e-12 relative for n <= 12 and for degree <= 16 at any n; above that
// (n > 12, degree > 16) the moment is carried by outer weights as small as 1e-22, which the
// Golub-Welsch method (Quadrature.h) only gets to absolute, not relative, accuracy, so 1e-6.
TEST(Quadrature, GaussHermiteIsExactForPolynomials)
{
  for (int n = 1; n <= 32; ++n)
  {
    SCOPED_TRACE(n);
    const GaussHermiteRule rule = gaussHermite(n);
    ASSERT_EQ(rule.nodes.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(rule.weights.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
      EXPECT_NEAR(rule.nodes[i], -rule.nodes[n - 1 - i], 1e-12 * (1 + std::abs(rule.nodes[i])));
      if (i > 0)
      {
        EXPECT_LT(rule.nodes[i - 1], rule.nodes[i]);
      }
      EXPECT_GT(rule.weights[i], 0.0);
    }
    for (int degree = 0; degree <= 2 * n - 1; ++degree)
    {
      double sum = 0.0;
      for (int i = 0; i < n; ++i)
      {
        sum += rule.weights[i] * std::pow(rule.nodes[i], degree);
      }
      const double exact = degree % 2 == 1 ? 0.0 : std::tgamma(degree / 2 + 0.5);
      const double rel = (n <= 12 || degree <= 16) ? 1e-12 : 1e-6;
      EXPECT_NEAR(sum, exact, rel * std::max(1.0, std::tgamma(degree / 2 + 0.5)))
        << "degree " << degree;
    }
  }
  // Closed form for n = 2: nodes +-1/sqrt(2), weights sqrt(pi)/2; int x^2 e^{-x^2} = sqrt(pi)/2.
  const GaussHermiteRule two = gaussHermite(2);
  EXPECT_NEAR(two.nodes[1], 1.0 / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(two.weights[0], std::sqrt(kPi) / 2, 1e-14);
  EXPECT_THROW(gaussHermite(0), std::invalid_argument);
  EXPECT_THROW(gaussHermite(65), std::invalid_argument);
}

// Truth: when maxima are sought the projection may find a maximum or report that there is none,
// but it must never hand back a minimum (flat line, Levin, start 2h above: n is tangent there).
TEST(Projection, SeekingMaximaNeverReturnsMinimum)
{
  Workspace ws;
  const double h = 1.0;
  PointIndex index(lineCloud(12 * h, 0.1 * h), 2);
  auto s = makeSurface(Variant::LevinMLS, index, params(h));
  ProjectionOptions opt;
  opt.seekMaxima = true;
  for (const Vec3& start : { Vec3(0.0, 2 * h, 0), Vec3(0.37 * h, 2 * h, 0), Vec3(-1.3 * h, -2 * h, 0) })
  {
    const ProjectionResult r = project(*s, start, opt, ws);
    SCOPED_TRACE(stopReasonName(r.reason));
    EXPECT_NE(r.type, ExtremumType::Minimum) << "at " << r.point.transpose();
    EXPECT_TRUE(r.type == ExtremumType::Maximum || r.reason == StopReason::NoExtremum)
      << "type " << static_cast<int>(r.type) << " at " << r.point.transpose();
  }
}

// Truth: std::exp. The kernel's vectorized exponential must agree with it to one unit in the
// last place over the whole range the weights use, and keep its special values (0 -> 1 exactly,
// which makes the nearest neighbour's weight exactly 1; NaN stays NaN; far below: 0).
TEST(Kernel, VectorizedExpMatchesStdExp)
{
  std::vector<double> x;
  for (int i = 0; i <= 100000; ++i)
  {
    x.push_back(-708.0 * i / 100000.0);   // the whole range, evenly
    x.push_back(-9.0 * i / 100000.0);     // the range a cutoff of 3 h gives
    x.push_back(-1e-12 * i);              // near 0, where r is tiny
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  x.insert(x.end(), { 0.0, -0.0, nan, -inf, -708.5, -1e4, -707.999 });
  std::vector<double> out(x.size(), -1.0);
  expNonPositive(x.data(), out.data(), static_cast<Eigen::Index>(x.size()));
  double worstUlps = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    if (std::isnan(x[i]))
    {
      EXPECT_TRUE(std::isnan(out[i]));
    }
    else if (x[i] < -708.0)
    {
      EXPECT_EQ(out[i], 0.0) << "x = " << x[i];
    }
    else
    {
      const double truth = std::exp(x[i]);
      const double ulp = std::nextafter(truth, inf) - truth;
      worstUlps = std::max(worstUlps, std::abs(out[i] - truth) / ulp);
    }
  }
  EXPECT_LE(worstUlps, 1.0);
  EXPECT_EQ(out[x.size() - 7], 1.0);
  EXPECT_EQ(out[x.size() - 6], 1.0);
  // Odd lengths take the scalar tail: the same values.
  std::vector<double> tail(3);
  expNonPositive(x.data() + 1, tail.data(), 3);
  EXPECT_EQ(tail[0], out[1]);
  EXPECT_EQ(tail[2], out[3]);
}

// Truth: a matrix built from known eigenvalues and eigenvectors. Starting the decomposition from
// a nearby basis (as the plane procedure does from one iterate to the next) must find the same
// smallest eigenvector and the same stability as starting from scratch, in 3D and in 2D.
TEST(Kernel, EigenDirectionFromNearbyFrameMatchesTruth)
{
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 lambda(2e-4, 0.6, 1.3); // a flat, noisy patch: l0 << l1
  const Mat3 C = R * lambda.asDiagonal() * R.transpose();
  const double stability = (lambda[1] - lambda[0]) / (lambda[1] + lambda[0]);
  for (const double tilt : { 0.0, 1e-6, 1e-3, 0.05, 0.5 })
  {
    EigenFrame frame;
    frame.vectors = R * Eigen::AngleAxisd(tilt, Vec3(0.3, -1, 0.2).normalized()).toRotationMatrix();
    frame.valid = true;
    const Direction d = smallestEigenDirection(C, 3, 1e-5, &frame);
    ASSERT_TRUE(d.defined) << "tilt " << tilt;
    EXPECT_NEAR(std::abs(d.n.dot(R.col(0))), 1.0, 1e-14) << "tilt " << tilt;
    EXPECT_NEAR(d.stability, stability, 1e-12) << "tilt " << tilt;
    // The frame comes back orthonormal, smallest eigenvector first.
    EXPECT_LT((frame.vectors.transpose() * frame.vectors - Mat3::Identity()).norm(), 1e-14);
    EXPECT_NEAR(std::abs(frame.vectors.col(0).dot(R.col(0))), 1.0, 1e-14);
  }
  const Direction cold = smallestEigenDirection(C, 3, 1e-5);
  EXPECT_NEAR(std::abs(cold.n.dot(R.col(0))), 1.0, 1e-14);

  // 2D: only the xy block counts; the frame keeps z as its third axis.
  Mat3 C2 = Mat3::Zero();
  const double a = 0.4;
  const Eigen::Vector2d u(std::cos(a), std::sin(a));
  const Eigen::Vector2d v(-std::sin(a), std::cos(a));
  C2.topLeftCorner<2, 2>() = 1e-3 * u * u.transpose() + 0.9 * v * v.transpose();
  C2(2, 2) = 7.0; // ignored in 2D
  EigenFrame frame2;
  frame2.vectors.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(a + 0.01).toRotationMatrix();
  frame2.valid = true;
  const Direction d2 = smallestEigenDirection(C2, 2, 1e-5, &frame2);
  ASSERT_TRUE(d2.defined);
  EXPECT_NEAR(std::abs(d2.n.head<2>().dot(u)), 1.0, 1e-14);
  EXPECT_EQ(d2.n.z(), 0.0);
  EXPECT_NEAR(d2.stability, (0.9 - 1e-3) / (0.9 + 1e-3), 1e-12);

  // A rank-deficient matrix (a collinear neighbourhood in 3D) stays undefined from any start.
  EigenFrame frame3;
  frame3.vectors = R;
  frame3.valid = true;
  const Direction line = smallestEigenDirection(R.col(1) * R.col(1).transpose(), 3, 1e-5, &frame3);
  EXPECT_FALSE(line.defined);
}

// Truth: a neighbourhood is defined by the cloud alone, so gathering it from the focused subset
// of a prefetch (as e_I's quadrature nodes do) must give the same neighbours, in the same order,
// with the same weights and sums, bit for bit, as gathering it from a k-d tree fetch at the point.
TEST(Kernel, FocusedGatherMatchesPlainGatherBitwise)
{
  Workspace ws;
  const PointIndex index(randomBox(20000, 3, 20.0, 11), 3);
  SurfaceParameters params;
  params.h = 1.0;
  const Vec3 centre(10.0, 9.0, 11.0);
  const double reach = 1.5;
  std::mt19937 rng(5);
  std::vector<Vec3> queries;
  for (int i = 0; i < 40; ++i)
  {
    queries.push_back(centre + reach * std::uniform_real_distribution<double>(0.0, 1.0)(rng) * randomUnit(rng, 3));
  }
  // Plain gathers first, each from a fetch of its own (nothing is focused yet)...
  std::vector<Neighbourhood> plain(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i)
  {
    gatherNeighbourhood(index, params, queries[i], plain[i], ws);
  }
  // ...then the same queries after a wider prefetch and a focus on the region they lie in.
  prefetchNeighbourhoods(index, params, centre, 3.0 * reach, ws);
  focusNeighbourhoods(index, params, centre, reach, ws);
  for (std::size_t i = 0; i < queries.size(); ++i)
  {
    Neighbourhood nb;
    gatherNeighbourhood(index, params, queries[i], nb, ws);
    const Neighbourhood& ref = plain[i];
    ASSERT_EQ(nb.size(), ref.size()) << "query " << i;
    ASSERT_GT(nb.size(), 10);
    EXPECT_EQ(nb.minSqDist, ref.minSqDist);
    EXPECT_EQ(nb.weightSum, ref.weightSum);
    EXPECT_EQ(nb.moment, ref.moment);
    EXPECT_TRUE((nb.x() == ref.x()).all() && (nb.y() == ref.y()).all() && (nb.z() == ref.z()).all());
    EXPECT_TRUE((nb.w() == ref.w()).all());
  }
}

// SPDX-License-Identifier: BSD-3-Clause
// A scale per point (PointIndex::setScales): weights theta_i(y) = exp(-|y - p_i|^2 / h_i^2).
//
// Checked against truths that do not come from the code under test: neighbourhood sums against
// brute-force sums over the whole cloud, analytic derivatives against central differences (the
// reasoning of DerivativeTest.cxx: step 1e-4 h, cutoff 6), constant scales against the single-h
// path, and projections onto a plane and a sphere whose sampling density varies tenfold.

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>

using namespace pss;
using namespace pss_test;

namespace
{

// Scales that vary independently from point to point (not smoothly: the formulas must not care),
// in [0.5 h, 2 h].
std::vector<double> jitteredScales(std::size_t n, double h, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::vector<double> out(n);
  for (double& s : out)
  {
    s = u(rng) * h;
  }
  return out;
}

// Queries near a random box cloud: each a short hop from the last, so that the candidate caches
// are reused, with a jump now and then.
std::vector<Vec3> walk(const std::vector<Vec3>& pts, int count, double h, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  std::vector<Vec3> out;
  Vec3 x = pts[pick(rng)];
  for (int i = 0; i < count; ++i)
  {
    x = (i % 7 == 0) ? pts[pick(rng)] + 0.5 * h * randomUnit(rng, 3) : Vec3(x + 0.2 * h * randomUnit(rng, 3));
    out.push_back(x);
  }
  return out;
}

TEST(ScaledNeighbourhood, SumsEqualBruteForceOverTheWholeCloud)
{
  const double h = 1.0;
  const std::vector<Vec3> pts = randomBox(600, 3, 8.0, 5u);
  const std::vector<double> scales = jitteredScales(pts.size(), h, 6u);
  PointIndex index(pts, 3);
  index.setScales(scales);
  const SurfaceParameters p = params(h, 6.0); // neglected mass below 600 exp(-36): 1e-13
  Workspace ws;
  for (const Vec3& y : walk(pts, 200, h, 7u))
  {
    double sMin = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pts.size(); ++i)
    {
      sMin = std::min(sMin, (pts[i] - y).squaredNorm() / (scales[i] * scales[i]));
    }
    double w = 0.0, wh = 0.0;
    Vec3 moment = Vec3::Zero();
    for (std::size_t i = 0; i < pts.size(); ++i)
    {
      const double wi = std::exp(-((pts[i] - y).squaredNorm() / (scales[i] * scales[i]) - sMin));
      w += wi;
      wh += wi * scales[i];
      moment += wi * (pts[i] - y);
    }
    Neighbourhood nb;
    gatherNeighbourhood(index, p, y, nb, ws);
    ASSERT_TRUE(nb.scaled);
    EXPECT_NEAR(nb.logScale(), -sMin, 1e-12 * std::max(1.0, sMin));
    EXPECT_NEAR(nb.weightSum, w, 1e-12 * w);
    EXPECT_NEAR(nb.localScale, wh / w, 1e-12 * h);
    EXPECT_LT((nb.moment - moment).norm(), 1e-11 * w * h);
  }
}

TEST(ScaledNeighbourhood, FarQueriesSeeTheSameSumsAsBruteForce)
{
  // Far from the cloud the point of largest weight is not the nearest one: a point with a large
  // scale outweighs nearer points with small ones.
  std::vector<Vec3> pts = randomBox(300, 3, 4.0, 8u);
  std::vector<double> scales(pts.size(), 0.2);
  scales[17] = 3.0;
  PointIndex index(pts, 3);
  index.setScales(scales);
  Workspace ws;
  for (const Vec3& y : { Vec3(20.0, 2.0, 2.0), Vec3(-5.0, -5.0, 9.0), Vec3(2.0, 2.0, 2.5) })
  {
    double sMin = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pts.size(); ++i)
    {
      sMin = std::min(sMin, (pts[i] - y).squaredNorm() / (scales[i] * scales[i]));
    }
    double w = 0.0;
    for (std::size_t i = 0; i < pts.size(); ++i)
    {
      w += std::exp(-((pts[i] - y).squaredNorm() / (scales[i] * scales[i]) - sMin));
    }
    Neighbourhood nb;
    gatherNeighbourhood(index, params(1.0, 6.0), y, nb, ws);
    EXPECT_NEAR(nb.logScale(), -sMin, 1e-12 * std::max(1.0, sMin));
    EXPECT_NEAR(nb.weightSum, w, 1e-12 * w);
  }
}

TEST(ScaledNeighbourhood, BadScalesAreRefused)
{
  const std::vector<Vec3> pts = randomBox(50, 3, 4.0, 9u);
  PointIndex index(pts, 3);
  const auto refused = [&](std::vector<double> scales, const char* what) {
    EXPECT_THROW(index.setScales(scales), std::invalid_argument) << what;
    EXPECT_FALSE(index.hasScales()) << what;
  };
  refused(std::vector<double>(49, 1.0), "wrong length");
  std::vector<double> s(50, 1.0);
  s[3] = 0.0;
  refused(s, "zero");
  s[3] = -1.0;
  refused(s, "negative");
  s[3] = std::nan("");
  refused(s, "NaN");
  s[3] = std::numeric_limits<double>::infinity();
  refused(s, "infinite");
  s[3] = 1e-200;
  refused(s, "1 / h^2 overflows");
  EXPECT_NO_THROW(index.setScales(std::vector<double>(50, 1.0)));
  EXPECT_TRUE(index.hasScales());
  index.setScales({});
  EXPECT_FALSE(index.hasScales());
}

// Every definition's slope and (where it has one) curvature along a line, and delta's gradient
// and Hessian, against central differences, with jittered scales.
TEST(ScaledDerivatives, MatchCentralDifferences)
{
  const double h = 1.2;
  const std::vector<Vec3> pts = randomBox(150, 3, 4 * h, 42u);
  PointIndex index(pts, 3);
  index.setScales(jitteredScales(pts.size(), h, 43u));
  const double eps = 1e-4 * h;
  Workspace ws;
  std::mt19937 rng(44);
  const std::vector<Vec3> xs = walk(pts, 12, h, 45u);
  const auto close = [](double analytic, double numeric, double scale, const std::string& what) {
    EXPECT_NEAR(analytic, numeric, 1e-6 * std::max(std::abs(analytic), scale)) << what;
  };
  for (Variant v : paperVariants())
  {
    auto s = makeSurface(v, index, params(h, 6.0));
    for (const Vec3& x : xs)
    {
      const Vec3 a = randomUnit(rng, 3);
      const LineSample ls = s->lineSample(x, a, ws);
      const double ep = s->energy(x + eps * a, a, ws);
      const double em = s->energy(x - eps * a, a, ws);
      const double e0 = s->energy(x, a, ws);
      const std::string name = variantName(v);
      close(ls.trueValue(), e0, 0.0, name + " value");
      close(ls.trueSlope(), (ep - em) / (2 * eps), e0 / h, name + " slope");
      if (!std::isnan(ls.curvature) && v != Variant::Integral)
      {
        const double fd = (s->lineSample(x + eps * a, a, ws).trueSlope() - s->lineSample(x - eps * a, a, ws).trueSlope()) /
          (2 * eps);
        close(ls.curvature * std::exp(ls.logScale), fd, e0 / (h * h), name + " curvature");
      }
    }
  }
  DistanceField field(index, params(h, 6.0));
  for (const Vec3& x : xs)
  {
    const DeltaHessian hess = field.hessian(x, ws);
    for (int k = 0; k < 3; ++k)
    {
      const Vec3 e = Vec3::Unit(k);
      close(hess.gradient[k], (field.delta(x + eps * e, ws) - field.delta(x - eps * e, ws)) / (2 * eps),
        std::max(hess.gradient.norm(), hess.value / h), "d delta / dx" + std::to_string(k));
      const Vec3 column = (field.hessian(x + eps * e, ws).gradient - field.hessian(x - eps * e, ws).gradient) / (2 * eps);
      for (int j = 0; j < 3; ++j)
      {
        close(hess.hessian(j, k), column[j], std::max(2.0, hess.value / (h * h)), "Hessian entry");
      }
    }
    const Vec3 a = randomUnit(rng, 3);
    close(field.jet(x, a, ws).curvature, a.dot(hess.hessian * a), 2.0, "jet curvature against the Hessian");
  }
}

// With every h_i = h the per-point path computes the single scale's sums in another order of
// operations: every definition's energies, slopes and curvatures agree to rounding, and every
// definition's projections to 1e-12 h (the two whose n is the argmin of e_I over directions
// included: IntegralDirection polishes that minimum by the gradient, below what values resolve).
TEST(AdaptiveScale, ConstantScalesGiveTheSingleScaleProjections)
{
  const double h = 3.0;
  const std::vector<Vec3> pts = sceneCloud(Scene::Sphere, 3, 1500, 40.0, 0.3);
  PointIndex global(pts, 3);
  PointIndex scaled(pts, 3);
  scaled.setScales(std::vector<double>(pts.size(), h));
  std::mt19937 rng(12);
  std::vector<Vec3> starts;
  for (int i = 0; i < 25; ++i)
  {
    starts.push_back(pts[static_cast<std::size_t>(i) * 37] + 0.5 * h * randomUnit(rng, 3));
  }
  for (Variant v : paperVariants())
  {
    auto a = makeSurface(v, global, params(h));
    auto b = makeSurface(v, scaled, params(h));
    Workspace wa, wb;
    for (const Vec3& x : starts)
    {
      const Vec3 dir = randomUnit(rng, 3);
      const LineSample la = a->lineSample(x, dir, wa);
      const LineSample lb = b->lineSample(x, dir, wb);
      EXPECT_NEAR(lb.trueValue(), la.trueValue(), 1e-12 * std::abs(la.trueValue())) << variantName(v);
      EXPECT_NEAR(lb.trueSlope(), la.trueSlope(), 1e-11 * la.trueValue() / h) << variantName(v);
    }
    for (const Procedure procedure : { Procedure::Extremal, Procedure::Plane })
    {
      ProjectionOptions options;
      options.procedure = procedure;
      for (const Vec3& x : starts)
      {
        const ProjectionResult ra = project(*a, x, options, wa);
        const ProjectionResult rb = project(*b, x, options, wb);
        ASSERT_EQ(ra.reason, rb.reason) << variantName(v);
        EXPECT_LT((ra.point - rb.point).norm(), 1e-12 * h)
          << variantName(v) << " from " << x.transpose();
      }
    }
  }
}

// The plane z = 0 sampled with spacing growing tenfold along x (gradedPlane), the scales
// estimated from the data: every definition projects starts above and below the whole patch onto
// the plane, and the classifier finds them in the domain.
TEST(AdaptiveScale, PlaneWithTenfoldSpacingProjectsOntoThePlane)
{
  const double length = 60.0;
  const std::vector<Vec3> pts = gradedPlane(0.2, 10.0, length);
  PointIndex index(pts, 3);
  const std::vector<double> scales = estimateLocalScales(index);
  EXPECT_GT(scaleSpread(scales), 2.5) << "the spacing varies tenfold across the patch";
  const double typical = estimateScale(index);
  index.setScales(scales);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(0.1 * length, 0.9 * length), uy(-0.3 * length, 0.3 * length);
  std::vector<Vec3> starts;
  for (int i = 0; i < 60; ++i)
  {
    const Vec3 onPlane(ux(rng), uy(rng), 0.0);
    Workspace ws;
    const double hx = index.scale(index.nearest(onPlane).first);
    starts.push_back(onPlane + Vec3(0.0, 0.0, (i % 2 ? 0.4 : -0.4) * hx));
  }
  for (Variant v : paperVariants())
  {
    auto s = makeSurface(v, index, params(typical));
    Workspace ws;
    for (const Vec3& x : starts)
    {
      const DomainEvidence ev = classifyStart(*s, x, ProjectionOptions{}, DomainThresholds{}, ws);
      const double hx = index.scale(index.nearest(x).first);
      EXPECT_EQ(ev.label, DomainLabel::InDomain) << variantName(v) << " from " << x.transpose();
      EXPECT_LT(std::abs(ev.projection.point.z()), 1e-5 * hx) << variantName(v) << " from " << x.transpose();
      if (v == Variant::CenterOfMass)
      {
        // Only the centroid's covariance has the plane's normal as an eigenvector whatever the
        // weights (the others tilt where the density is uneven, and still land on the plane).
        EXPECT_LT((ev.projection.point - x).head<2>().norm(), 1e-5 * hx) << "not vertical from " << x.transpose();
      }
    }
  }
}

// A sphere sampled with density falling tenfold from one pole to the other: every definition
// projects jittered starts back onto it (the MLS surfaces of a sphere of radius R lie within
// about h^2 / R of it).
TEST(AdaptiveScale, SphereOfTenfoldDensityProjectsOntoTheSphere)
{
  const double radius = 20.0;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pts;
  while (pts.size() < 8000)
  {
    const Vec3 p = radius * randomUnit(rng, 3);
    // Density ratio 10 between the poles: accept with probability 10^(-(1 + z/R)/2).
    if (u(rng) < std::pow(10.0, -0.5 * (1.0 + p.z() / radius)))
    {
      pts.push_back(p);
    }
  }
  PointIndex index(pts, 3);
  index.setScales(estimateLocalScales(index));
  const double hMax = index.maxScale();
  EXPECT_GT(hMax / index.minScale(), 2.0);
  for (Variant v : paperVariants())
  {
    auto s = makeSurface(v, index, params(estimateScale(index)));
    Workspace ws;
    for (int i = 0; i < 40; ++i)
    {
      const Vec3 dir = randomUnit(rng, 3);
      const double hx = index.scale(index.nearest(radius * dir).first);
      const Vec3 start = (radius + (i % 2 ? 0.3 : -0.3) * hx) * dir;
      const ProjectionResult r = project(*s, start, ProjectionOptions{}, ws);
      ASSERT_EQ(r.reason, StopReason::Converged) << variantName(v) << " from " << start.transpose();
      EXPECT_LT(std::abs(r.point.norm() - radius), 0.1 * hx) << variantName(v) << " from " << start.transpose();
      EXPECT_GT(r.point.normalized().dot(dir), 1.0 - 1e-3) << "projected across the sphere";
    }
  }
}

TEST(AdaptiveScale, LocalScalesFollowTheSpacingAndTheirArguments)
{
  const std::vector<Vec3> even = planeCloud(10.0, 0.5);
  PointIndex index(even, 3);
  const std::vector<double> scales = estimateLocalScales(index);
  const double h = estimateScale(index);
  EXPECT_LT(scaleSpread(scales), 1.5) << "an even grid has nearly one scale";
  for (std::size_t i = 0; i < scales.size(); i += 97)
  {
    EXPECT_NEAR(scales[i], h, 0.35 * h) << "point " << i;
  }
  EXPECT_THROW(estimateLocalScales(index, 0), std::invalid_argument);
  EXPECT_THROW(estimateLocalScales(index, 10, 0.0), std::invalid_argument);
  EXPECT_THROW(estimateLocalScales(index, 10, -1.0), std::invalid_argument);
  EXPECT_THROW(estimateLocalScales(index, 10, 1.0, -1), std::invalid_argument);
  PointIndex tiny(std::vector<Vec3>(5, Vec3::Zero()), 3);
  EXPECT_THROW(estimateLocalScales(tiny), std::invalid_argument);
  EXPECT_THROW(estimateLocalScales(index, 10, 1.0, 2, 1, 0.0), std::invalid_argument);
  // Two threads give the same scales bit for bit.
  EXPECT_EQ(estimateLocalScales(index, 10, 1.0, 2, 1), estimateLocalScales(index, 10, 1.0, 2, 2));

  // A cluster of stray points far from the plane, too many for the median to smooth away (the
  // smoothing alone fixes a cluster of fewer than k / 2): their k-th neighbour is on the plane,
  // 30 units away, but their scale stops at maxRatio times the median.
  std::vector<Vec3> stray = even;
  for (int i = 0; i < 8; ++i)
  {
    stray.emplace_back(0.1 * (i % 4), 0.1 * (i / 4), 30.0);
  }
  PointIndex withStray(stray, 3);
  const std::vector<double> capped = estimateLocalScales(withStray);
  const std::vector<double> free = estimateLocalScales(withStray, 10, 1.0, 2, 1, std::numeric_limits<double>::infinity());
  std::vector<double> sorted(capped);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  for (std::size_t i = even.size(); i < stray.size(); ++i)
  {
    EXPECT_GT(free[i], 25.0) << "uncapped: the distance to the plane";
    EXPECT_DOUBLE_EQ(capped[i], 6.0 * median) << "stray point " << i;
  }
  EXPECT_EQ(capped[0], free[0]) << "the plane's own scales are below the cap";
}

} // namespace

// The automatic mode's decision on a cloud above pss::ScaleSpreadSampledAbove points: the spread
// measured on ScaleSpreadSamples points agrees with the spread of every point's scale. An even
// grid has spread 1 (its border is under a tenth of its points); two grids of spacings 1 and 3,
// each more than a tenth of the points, have spread 3.
TEST(AdaptiveScale, SpreadOfLargeCloudsIsMeasuredOnASample)
{
  auto patch = [](std::vector<Vec3>& pts, double x0, int side, double step) {
    for (int i = 0; i < side; ++i)
    {
      for (int j = 0; j < side; ++j)
      {
        pts.emplace_back(x0 + i * step, j * step, 0.0);
      }
    }
  };
  std::vector<Vec3> even;
  patch(even, 0.0, 520, 1.0); // 270,400 points
  ASSERT_GT(even.size(), ScaleSpreadSampledAbove);
  const PointIndex evenIndex(even, 3, 2);
  const double evenSpread = estimateScaleSpread(evenIndex, 10, 2, 2);
  EXPECT_NEAR(evenSpread, scaleSpread(estimateLocalScales(evenIndex, 10, 1.0, 2, 2)), 1e-12);
  EXPECT_NEAR(evenSpread, 1.0, 1e-9) << "an even grid has one scale";
  EXPECT_EQ(evenSpread, estimateScaleSpread(evenIndex, 10, 2, 1)) << "the same for every thread count";

  std::vector<Vec3> mixed;
  patch(mixed, 0.0, 400, 1.0);    // 160,000 points, spacing 1
  patch(mixed, 1000.0, 350, 3.0); // 122,500 points, spacing 3: the 90th percentile is here
  ASSERT_GT(mixed.size(), ScaleSpreadSampledAbove);
  const PointIndex mixedIndex(mixed, 3, 2);
  const double sampled = estimateScaleSpread(mixedIndex, 10, 2, 2);
  const double full = scaleSpread(estimateLocalScales(mixedIndex, 10, 1.0, 2, 2));
  std::cout << "spread of the two patches: every point " << full << ", sampled " << sampled << "\n";
  EXPECT_NEAR(full, 3.0, 0.05) << "the patches' spacings are 3 apart";
  EXPECT_NEAR(sampled, full, 0.01 * full);
  EXPECT_THROW(estimateScaleSpread(mixedIndex, 0), std::invalid_argument);
}

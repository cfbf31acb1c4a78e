// SPDX-License-Identifier: BSD-3-Clause
// Analytic derivatives against central differences on small random clouds.
//
// Central difference with step eps = 1e-4 h: truncation error eps^2/6 f''' ~ 1e-9 relative for
// functions varying on the scale h, rounding ~1e-16 / 1e-4 = 1e-12 relative; so 1e-6 relative is a
// real check of the formula. cutoff = 6 makes the neglected Gaussian mass exp(-36) ~ 2e-16, so a
// neighbour entering or leaving within the step cannot produce a visible jump.

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pss;
using namespace pss_test;

namespace
{

constexpr double kRelTol = 1e-6;

struct Cloud
{
  std::vector<Vec3> pts;
  int dim;
  double h;
};

Cloud makeCloud(int dim)
{
  const double h = dim == 2 ? 0.6 : 1.4;
  return { randomBox(dim == 2 ? 80 : 150, dim, 4 * h, dim == 2 ? 41u : 42u), dim, h };
}

/// Query points at distance 0.3h..2h from the nearest cloud point.
std::vector<Vec3> queries(const Cloud& c, int count, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, c.pts.size() - 1);
  std::uniform_real_distribution<double> dist(0.3, 2.0);
  std::vector<Vec3> out;
  while (static_cast<int>(out.size()) < count)
  {
    const Vec3 x = c.pts[pick(rng)] + dist(rng) * c.h * randomUnit(rng, c.dim);
    const double d = std::sqrt(bruteNearestSq(c.pts, x));
    if (d >= 0.3 * c.h && d <= 2.0 * c.h)
    {
      out.push_back(x);
    }
  }
  return out;
}

/// |analytic - numeric| <= 1e-6 * max(|analytic|, natural scale).
void expectClose(double analytic, double numeric, double scale, const std::string& what)
{
  EXPECT_NEAR(analytic, numeric, kRelTol * std::max(std::abs(analytic), scale))
    << what << ": analytic " << analytic << " vs central difference " << numeric;
}

void checkLineSlopes(int dim)
{
  Workspace ws;
  const Cloud c = makeCloud(dim);
  PointIndex index(c.pts, dim);
  const double eps = 1e-4 * c.h;
  for (Variant v : paperVariants())
  {
    auto s = makeSurface(v, index, params(c.h, 6.0));
    std::mt19937 rng(77);
    const int n = (dim == 3 && (v == Variant::Integral || v == Variant::Delta)) ? 10 : 25;
    for (const Vec3& x : queries(c, n, 55u))
    {
      const Vec3 a = randomUnit(rng, dim);
      const LineSample ls = s->lineSample(x, a, ws);
      const double ep = s->energy(x + eps * a, a, ws);
      const double em = s->energy(x - eps * a, a, ws);
      const double e0 = s->energy(x, a, ws);
      expectClose(ls.trueValue(), e0, 0.0, std::string(variantName(v)) + " value");
      expectClose(ls.trueSlope(), (ep - em) / (2 * eps), e0 / c.h,
        std::string(variantName(v)) + " slope dim " + std::to_string(dim));
    }
  }
}

void checkImplicitG(int dim)
{
  Workspace ws;
  const Cloud c = makeCloud(dim);
  PointIndex index(c.pts, dim);
  const double eps = 1e-4 * c.h;
  const Orientation orient = Orientation::awayFromCentroid(index);
  for (Variant v : paperVariants())
  {
    auto s = makeSurface(v, index, params(c.h, 6.0));
    const int n = (dim == 3 && (v == Variant::Integral || v == Variant::Delta)) ? 6 : 20;
    int tested = 0;
    for (const Vec3& x : queries(c, n, 66u))
    {
      const ImplicitSample is = evaluateImplicit(*s, x, orient, ws);
      if (!is.direction.defined)
      {
        continue;
      }
      ++tested;
      const Vec3 nn = is.direction.n;
      EXPECT_NEAR(nn.norm(), 1.0, 1e-12);
      const double e0 = s->energy(x, nn, ws);
      expectClose(is.energy, e0, 0.0, std::string(variantName(v)) + " energy");
      const double fd = (s->energy(x + eps * nn, nn, ws) - s->energy(x - eps * nn, nn, ws)) / (2 * eps);
      expectClose(is.g, fd, e0 / c.h, std::string(variantName(v)) + " g dim " + std::to_string(dim));
      // The second derivative along n (a central difference of the slope inside the core) must
      // agree with the second difference of the energy to the accuracy of two differences: 1e-3.
      const double fd2 = (s->energy(x + 10 * eps * nn, nn, ws) - 2 * e0 + s->energy(x - 10 * eps * nn, nn, ws)) /
        (100 * eps * eps);
      EXPECT_NEAR(is.curvature, fd2, 1e-3 * std::max(std::abs(fd2), e0 / (c.h * c.h)))
        << variantName(v) << " curvature";
      if (is.curvature > 1e-3 * e0 / (c.h * c.h))
      {
        EXPECT_EQ(is.type, ExtremumType::Minimum);
      }
      else if (is.curvature < -1e-3 * e0 / (c.h * c.h))
      {
        EXPECT_EQ(is.type, ExtremumType::Maximum);
      }
    }
    EXPECT_GE(tested, n / 2) << variantName(v) << ": too many undefined directions";
  }
}

void checkDistanceGradient(int dim)
{
  Workspace ws;
  const Cloud c = makeCloud(dim);
  PointIndex index(c.pts, dim);
  DistanceField field(index, params(c.h, 6.0));
  const double eps = 1e-4 * c.h;
  for (const Vec3& x : queries(c, 40, 88u))
  {
    const DeltaJet jet = field.jet(x, Vec3::UnitX(), ws);
    const Vec3 grad = jet.gradient;
    const double delta = jet.value;
    for (int k = 0; k < dim; ++k)
    {
      const Vec3 e = Vec3::Unit(k);
      const double fd = (field.delta(x + eps * e, ws) - field.delta(x - eps * e, ws)) / (2 * eps);
      expectClose(grad[k], fd, std::max(grad.norm(), delta / c.h), "d delta / dx" + std::to_string(k));
    }
    if (dim == 2)
    {
      EXPECT_EQ(grad.z(), 0.0);
    }
  }
}

// The second derivatives: delta's curvature along a direction (and its jet's value), and every definition's LineSample.curvature where it gives one, against central
// differences of the analytic first derivatives.
void checkSecondDerivatives(int dim)
{
  Workspace ws;
  const Cloud c = makeCloud(dim);
  PointIndex index(c.pts, dim);
  DistanceField field(index, params(c.h, 6.0));
  const double eps = 1e-4 * c.h;
  std::mt19937 rng(91);
  for (const Vec3& x : queries(c, 30, 99u))
  {
    const Vec3 a = randomUnit(rng, dim);
    const DeltaJet jet = field.jet(x, a, ws);
    const double delta = field.delta(x, ws);
    expectClose(jet.value, delta, 0.0, "jet value");
    const Vec3 gp = field.jet(x + eps * a, a, ws).gradient;
    const Vec3 gm = field.jet(x - eps * a, a, ws).gradient;
    expectClose(jet.curvature, a.dot(gp - gm) / (2 * eps), std::max(2.0, delta / (c.h * c.h)), "a^T H a of delta");
  }
  for (Variant v : paperVariants())
  {
    auto s = makeSurface(v, index, params(c.h, 6.0));
    const int n = (dim == 3 && v == Variant::Integral) ? 6 : 15;
    for (const Vec3& x : queries(c, n, 56u))
    {
      const Vec3 a = randomUnit(rng, dim);
      const LineSample ls = s->lineSample(x, a, ws);
      if (std::isnan(ls.curvature))
      {
        continue; // no closed form: the core differences the slope itself
      }
      const LineSample plus = s->lineSample(x + eps * a, a, ws);
      const LineSample minus = s->lineSample(x - eps * a, a, ws);
      const double fd = (plus.trueSlope() - minus.trueSlope()) / (2 * eps);
      const double curvature = ls.curvature * std::exp(ls.logScale);
      expectClose(curvature, fd, ls.trueValue() / (c.h * c.h),
        std::string(variantName(v)) + " line curvature dim " + std::to_string(dim));
    }
  }
}

} // namespace

// Truth: delta's curvature along a = derivative of a . grad delta along a (the gradient itself
// is checked above); the jet's value is delta; LineSample.curvature = derivative of the slope.
// 1e-6 relative.
TEST(Derivatives, SecondDerivativesMatchCentralDifference2D)
{
  checkSecondDerivatives(2);
}

// Truth: same in 3D.
TEST(Derivatives, SecondDerivativesMatchCentralDifference3D)
{
  checkSecondDerivatives(3);
}

// Truth: delta of a single point is |y - p|^2, whose Hessian is 2 I: curvature 2 along any a.
TEST(Derivatives, SinglePointDeltaCurvatureIsTwo)
{
  Workspace ws;
  const std::vector<Vec3> one{ Vec3(0.3, -0.2, 0.1) };
  PointIndex index(one, 3);
  DistanceField field(index, params(0.5, 3.0));
  std::mt19937 rng(5);
  for (int k = 0; k < 10; ++k)
  {
    const Vec3 y = one[0] + 3.0 * randomUnit(rng, 3);
    const DeltaJet jet = field.jet(y, randomUnit(rng, 3), ws);
    EXPECT_NEAR(jet.curvature, 2.0, 1e-12);
    EXPECT_NEAR(jet.value, (y - one[0]).squaredNorm(), 1e-12);
  }
}

// Truth: the tilt gradient and Hessian of e_I are the first and second derivatives of
// s -> e_I(x, tilted(frame, s)) at s = 0 (tilted() is the chart Newton steps in). Central and
// second differences with step 1e-3 rad: truncation ~1e-7 relative, rounding ~1e-10.
TEST(Derivatives, IntegralTiltHessianMatchesDifferences)
{
  Workspace ws;
  const Cloud c = makeCloud(3);
  PointIndex index(c.pts, 3);
  IntegralEnergy integral(index, params(c.h, 6.0));
  using D = IntegralEnergy::Derivatives;
  const double eps = 1e-3;
  std::mt19937 rng(17);
  for (const Vec3& x : queries(c, 5, 23u))
  {
    const IntegralEnergy::Frame f = integral.frameOf(randomUnit(rng, 3));
    const IntegralEnergy::PlaneIntegral at = integral.integrate(x, f, D::UpToSecond, ws);
    auto e = [&](double s1, double s2) {
      return integral.integrate(x, IntegralEnergy::tilted(f, Eigen::Vector2d(s1, s2)), D::None, ws).value;
    };
    const double e0 = e(0, 0);
    const double scale = at.value;
    expectClose(at.value, e0, 0.0, "value");
    expectClose(at.tilt.x(), (e(eps, 0) - e(-eps, 0)) / (2 * eps), scale, "tilt 1");
    expectClose(at.tilt.y(), (e(0, eps) - e(0, -eps)) / (2 * eps), scale, "tilt 2");
    const double tol = 1e-5 * std::max(at.tiltHessian.cwiseAbs().maxCoeff(), scale);
    EXPECT_NEAR(at.tiltHessian(0, 0), (e(eps, 0) - 2 * e0 + e(-eps, 0)) / (eps * eps), tol);
    EXPECT_NEAR(at.tiltHessian(1, 1), (e(0, eps) - 2 * e0 + e(0, -eps)) / (eps * eps), tol);
    const double mixed = (e(eps, eps) - e(eps, -eps) - e(-eps, eps) + e(-eps, -eps)) / (4 * eps * eps);
    EXPECT_NEAR(at.tiltHessian(0, 1), mixed, tol);
    EXPECT_NEAR(at.tiltHessian(1, 0), mixed, tol);
  }
}

// Truth: LineSample.slope = d/dt e(y + t a, a) (its definition); 1e-6 relative (see top).
TEST(Derivatives, LineSlopeMatchesCentralDifference2D)
{
  checkLineSlopes(2);
}

// Truth: same in 3D.
TEST(Derivatives, LineSlopeMatchesCentralDifference3D)
{
  checkLineSlopes(3);
}

// Truth: g = d/dt e(x + t n, n) at 0 with n = n(x) fixed (Eq. 2); 1e-6 relative.
TEST(Derivatives, ImplicitGMatchesCentralDifference2D)
{
  checkImplicitG(2);
}

// Truth: same in 3D.
TEST(Derivatives, ImplicitGMatchesCentralDifference3D)
{
  checkImplicitG(3);
}

// Truth: DistanceField gradient = partial derivatives of delta; 1e-6 relative.
TEST(Derivatives, DistanceGradientMatchesCentralDifference2D)
{
  checkDistanceGradient(2);
}

// Truth: same in 3D.
TEST(Derivatives, DistanceGradientMatchesCentralDifference3D)
{
  checkDistanceGradient(3);
}

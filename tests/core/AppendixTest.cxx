// SPDX-License-Identifier: BSD-3-Clause
// Paper, Appendix A: a single cloud point p, where theta_N(y, p) = 1 and delta(y) = |y - p|^2
// exactly, so every energy has a closed form and Gauss-Hermite (6 nodes, exact to degree 11)
// integrates the quartic delta^2 exactly.
//
// With x at distance k from p and (2D) the line through x with normal a parametrised by
// y = x + alpha b (b the unit tangent, v = b . (x - p)/k):
//   power 1:  e = int exp(-alpha^2/h^2)(alpha^2 + 2 k v alpha + k^2) = sqrt(pi) h (k^2 + h^2/2)
//   power 2:  e = int exp(-alpha^2/h^2)(alpha^2 + 2 k v alpha + k^2)^2
//               = sqrt(pi) h (3h^4/4 + k^2 h^2 (1 + 2 v^2) + k^4),   v^2 = 1 - (a . u)^2
// and (3D, plane with in-plane coordinates alpha, beta; int r^4 = 2 pi h^6, int r^2 = pi h^4):
//   power 1:  e = pi h^2 (h^2 + k^2)
//   power 2:  e = pi h^2 (2h^4 + 2k^2h^2 + k^4 + 2k^2h^2 (1 - (a . u)^2))
// where u = (x - p)/k. So power 1 is blind to a and power 2 is minimised by a = u.

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pss;
using namespace pss_test;

namespace
{

double closedForm(int dim, int power, double h, double k, double au)
{
  const double h2 = h * h;
  const double k2 = k * k;
  if (dim == 2)
  {
    const double c = std::sqrt(kPi) * h;
    return power == 1 ? c * (k2 + h2 / 2) : c * (0.75 * h2 * h2 + k2 * h2 * (1 + 2 * (1 - au * au)) + k2 * k2);
  }
  const double c = kPi * h2;
  return power == 1 ? c * (h2 + k2) : c * (2 * h2 * h2 + 2 * k2 * h2 + k2 * k2 + 2 * k2 * h2 * (1 - au * au));
}

/// d/dt of the closed form along a = u (k -> k + t).
double closedFormSlopeAlongU(int dim, int power, double h, double k)
{
  const double h2 = h * h;
  if (dim == 2)
  {
    const double c = std::sqrt(kPi) * h;
    return power == 1 ? c * 2 * k : c * (2 * k * h2 + 4 * k * k * k);
  }
  const double c = kPi * h2;
  return power == 1 ? c * 2 * k : c * (4 * k * h2 + 4 * k * k * k);
}

struct SinglePoint
{
  int dim;
  Vec3 p;
  Vec3 u; // unit vector from p to x
  double h;
  double k;
  Vec3 x() const { return p + k * u; }
};

std::vector<SinglePoint> configurations(int dim)
{
  std::vector<SinglePoint> out;
  const Vec3 up = dim == 2 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  out.push_back({ dim, Vec3::Zero(), up, 0.8, 1.3 * 0.8 }); // the appendix set-up: p = 0, x = (0, k)
  std::mt19937 rng(dim == 2 ? 21u : 31u);
  out.push_back({ dim, Vec3(1.5, -2.0, dim == 3 ? 0.7 : 0.0), randomUnit(rng, dim), 2.0, 0.45 * 2.0 });
  out.push_back({ dim, Vec3(-3.0, 0.25, 0.0), randomUnit(rng, dim), 0.5, 3.0 * 0.5 });
  return out;
}

void checkIntegralClosedForms(int dim)
{
  Workspace ws;
  for (const SinglePoint& c : configurations(dim))
  {
    PointIndex index(std::vector<Vec3>{ c.p }, dim);
    std::mt19937 rng(7);
    for (int power : { 1, 2 })
    {
      SurfaceParameters prm = params(c.h);
      prm.integrandPower = power;
      const SurfaceDefinition s(variantInfo(Variant::Integral), index, prm);
      SCOPED_TRACE("power " + std::to_string(power) + " h " + std::to_string(c.h) + " k/h " +
        std::to_string(c.k / c.h));
      double lo = 1e300, hi = -1e300;
      for (int i = 0; i < 40; ++i)
      {
        const Vec3 a = i == 0 ? c.u : randomUnit(rng, dim);
        const double e = s.energy(c.x(), a, ws);
        const double expected = closedForm(dim, power, c.h, c.k, a.dot(c.u));
        EXPECT_NEAR(e, expected, 1e-10 * expected) << "a = " << a.transpose();
        // lineSample's value must be the same energy (stored relative to exp(logScale)).
        EXPECT_NEAR(s.lineSample(c.x(), a, ws).trueValue(), expected, 1e-10 * expected);
        lo = std::min(lo, e);
        hi = std::max(hi, e);
      }
      if (power == 1)
      {
        // Appendix: integrating delta (not delta^2) cannot tell directions apart.
        EXPECT_LT((hi - lo) / lo, 1e-9);
        const Direction d = s.direction(c.x(), ws);
        EXPECT_FALSE(d.defined) << "n_I is not unique with power 1, stability " << d.stability;
        EXPECT_LT(d.stability, 1e-8);
      }
      else
      {
        EXPECT_GT((hi - lo) / lo, 1e-3);
        const Direction d = s.direction(c.x(), ws);
        EXPECT_TRUE(d.defined);
        // n_I = u (the gradient direction of the distance function), to search accuracy.
        const double tol = dim == 2 ? 1e-6 : 1e-5;
        EXPECT_GT(std::abs(d.n.dot(c.u)), 1 - tol * tol) << "n = " << d.n.transpose() << ", u = " << c.u.transpose();
        // Stability = (e_perp - e_min)/(e_perp + e_min) with e_perp at a . u = 0.
        const double eMin = closedForm(dim, 2, c.h, c.k, 1.0);
        const double ePerp = closedForm(dim, 2, c.h, c.k, 0.0);
        EXPECT_NEAR(d.stability, (ePerp - eMin) / (ePerp + eMin), 1e-6);
        // The tangent direction has strictly larger energy than the normal (paper: v^2 term).
        const Vec3 t = dim == 2 ? Vec3(-c.u.y(), c.u.x(), 0) : c.u.cross(std::abs(c.u.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)).normalized();
        EXPECT_LT(s.energy(c.x(), c.u, ws), s.energy(c.x(), t, ws));
      }
      // Slope along a = u: the closed form differentiated in k.
      const LineSample ls = s.lineSample(c.x(), c.u, ws);
      const double slope = closedFormSlopeAlongU(dim, power, c.h, c.k);
      EXPECT_NEAR(ls.trueSlope(), slope, 1e-9 * std::abs(slope));
    }
  }
}

} // namespace

// Truth: Appendix A closed forms in 2D (see file comment); 1e-10 relative = exact quadrature up to
// rounding; direction tolerance 1e-6 rad is golden-section accuracy on a quadratic minimum.
TEST(Appendix, IntegralEnergySinglePoint2D)
{
  checkIntegralClosedForms(2);
}

// Truth: the 3D closed forms; 1e-5 rad for the pattern search on the sphere.
TEST(Appendix, IntegralEnergySinglePoint3D)
{
  checkIntegralClosedForms(3);
}

// Truth: the definitions of the other energies for one point (theta_N = 1, q = a . (p - x)):
// Levin e = exp(-k^2/h^2) q^2, slope exp(-k^2/h^2)(2 q^3/h^2 - 2 q) (moving weight);
// normalized/COM e = q^2, slope -2q; delta e = k^2 for every a, slope 2 a . (x - p). Exact formulas,
// so 1e-12 relative (rounding only).
TEST(Appendix, OtherEnergiesSinglePoint)
{
  Workspace ws;
  for (int dim : { 2, 3 })
  {
    for (const SinglePoint& c : configurations(dim))
    {
      PointIndex index(std::vector<Vec3>{ c.p }, dim);
      std::mt19937 rng(9);
      for (Variant v : { Variant::LevinMLS, Variant::NormalizedMLS, Variant::CenterOfMass, Variant::Delta })
      {
        auto s = makeSurface(v, index, params(c.h));
        SCOPED_TRACE(std::string(variantName(v)) + " dim " + std::to_string(dim));
        for (int i = 0; i < 10; ++i)
        {
          const Vec3 a = randomUnit(rng, dim);
          const double q = a.dot(c.p - c.x());
          const double theta = std::exp(-c.k * c.k / (c.h * c.h));
          double e = 0, slope = 0;
          switch (v)
          {
            case Variant::LevinMLS:
              e = theta * q * q;
              slope = theta * (2 * q * q * q / (c.h * c.h) - 2 * q);
              break;
            case Variant::Delta:
              e = c.k * c.k;
              slope = 2 * a.dot(c.x() - c.p);
              break;
            default:
              e = q * q;
              slope = -2 * q;
              break;
          }
          const LineSample ls = s->lineSample(c.x(), a, ws);
          const double scale = v == Variant::LevinMLS ? theta * c.k * c.k : c.k * c.k;
          EXPECT_NEAR(s->energy(c.x(), a, ws), e, 1e-12 * scale);
          EXPECT_NEAR(ls.trueValue(), e, 1e-12 * scale);
          EXPECT_NEAR(ls.trueSlope(), slope, 1e-12 * scale / c.h * 10);
          EXPECT_NEAR(ls.nearestSqDist, c.k * c.k, 1e-12 * c.k * c.k);
        }
      }
    }
  }
}

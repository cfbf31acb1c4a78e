// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TestClouds.h
 * @brief Point clouds with known geometry (line, plane, circle arc, sphere cap, random box) and
 *        small helpers shared by the core test suites.
 *
 * Every sampling is a regular lattice in a coordinate where the surface is flat or uniformly
 * parametrised by arc length, so Gaussian-weighted sums over it equal their continuum integrals
 * to far better than any test tolerance (Poisson summation: relative error ~exp(-pi^2 h^2 / s^2)
 * for spacing s, i.e. ~1e-400 at s = 0.1 h).
 */
#pragma once

#include "pss/Core.h"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace pss_test
{

using pss::Vec3;

constexpr double kPi = 3.14159265358979323846;

/// The paper's five definitions, which need nothing but the points. APSS and RIMLS also need
/// normals: NormalFitTest.cxx tests them.
inline const std::array<pss::Variant, 5>& paperVariants()
{
  static const std::array<pss::Variant, 5> v = { pss::Variant::LevinMLS,
    pss::Variant::NormalizedMLS, pss::Variant::CenterOfMass, pss::Variant::Integral,
    pss::Variant::Delta };
  return v;
}

/// The plane z = 0 on a grid whose spacing grows from s0 at x = 0 to ratio * s0 at x = length
/// (rows and columns alike, each column's spacing that of its x), |y| <= length / 2.
inline std::vector<Vec3> gradedPlane(double s0, double ratio, double length)
{
  std::vector<double> xs{ 0.0 };
  const double growth = std::log(ratio) / length;
  while (xs.back() < length)
  {
    xs.push_back(xs.back() + s0 * std::exp(growth * xs.back()));
  }
  std::vector<Vec3> pts;
  for (const double x : xs)
  {
    const double s = s0 * std::exp(growth * x);
    for (double y = -0.5 * length; y <= 0.5 * length; y += s)
    {
      pts.emplace_back(x, y, 0.0);
    }
  }
  return pts;
}

/// Points (i * spacing, 0, 0) for |i * spacing| <= halfLength: a straight line along x.
inline std::vector<Vec3> lineCloud(double halfLength, double spacing)
{
  const long n = std::lround(halfLength / spacing);
  std::vector<Vec3> pts;
  pts.reserve(static_cast<std::size_t>(2 * n + 1));
  for (long i = -n; i <= n; ++i)
  {
    pts.emplace_back(static_cast<double>(i) * spacing, 0.0, 0.0);
  }
  return pts;
}

/// A square lattice (i s, j s, 0) with |i s|, |j s| <= halfWidth: the plane z = 0.
inline std::vector<Vec3> planeCloud(double halfWidth, double spacing)
{
  const long n = std::lround(halfWidth / spacing);
  std::vector<Vec3> pts;
  pts.reserve(static_cast<std::size_t>((2 * n + 1) * (2 * n + 1)));
  for (long i = -n; i <= n; ++i)
  {
    for (long j = -n; j <= n; ++j)
    {
      pts.emplace_back(static_cast<double>(i) * spacing, static_cast<double>(j) * spacing, 0.0);
    }
  }
  return pts;
}

/// Arc of the circle |p| = R in the xy-plane, centred on angle @p centreAngle, spanning
/// +-halfArcLength of arc length at (arc-length) spacing @p spacing.
inline std::vector<Vec3> circleArc(double R, double centreAngle, double halfArcLength, double spacing)
{
  const long n = std::lround(halfArcLength / spacing);
  const double dphi = spacing / R;
  std::vector<Vec3> pts;
  pts.reserve(static_cast<std::size_t>(2 * n + 1));
  for (long i = -n; i <= n; ++i)
  {
    const double phi = centreAngle + static_cast<double>(i) * dphi;
    pts.emplace_back(R * std::cos(phi), R * std::sin(phi), 0.0);
  }
  return pts;
}

/// Cap of the sphere |p| = R around the north pole (0, 0, R) with geodesic radius
/// R * capAngle: a square lattice of spacing @p spacing in (x, y), lifted to z = sqrt(R^2 - x^2 - y^2).
/// The area distortion is 1 + O(rho^2 / R^2), i.e. < 0.3% within 1 h of the pole when R = 20 h.
inline std::vector<Vec3> sphereCap(double R, double capAngle, double spacing)
{
  const double rhoMax = R * std::sin(capAngle);
  const long n = static_cast<long>(std::floor(rhoMax / spacing));
  std::vector<Vec3> pts;
  for (long i = -n; i <= n; ++i)
  {
    for (long j = -n; j <= n; ++j)
    {
      const double x = static_cast<double>(i) * spacing;
      const double y = static_cast<double>(j) * spacing;
      const double rho2 = x * x + y * y;
      if (rho2 <= rhoMax * rhoMax)
      {
        pts.emplace_back(x, y, std::sqrt(R * R - rho2));
      }
    }
  }
  return pts;
}

/// Points on a square lattice of spacing @p spacing over [0, length] x [-halfWidth, halfWidth] of the
/// half-plane through the y axis at @p angle degrees from the +x axis (in the xz-plane).
inline std::vector<Vec3> halfPlane(double angle, double length, double halfWidth, double spacing)
{
  std::vector<Vec3> pts;
  const double a = angle * kPi / 180.0;
  for (double s = spacing / 2; s <= length; s += spacing)
  {
    for (double y = -halfWidth; y <= halfWidth + 1e-9; y += spacing)
    {
      pts.emplace_back(s * std::cos(a), y, s * std::sin(a));
    }
  }
  return pts;
}

/// A synthetic cloud of SyntheticClouds.h's scenes, with the fields the tests vary.
inline std::vector<Vec3> sceneCloud(pss::Scene scene, int dimension, std::size_t count, double size, double noise,
  double gap = 10.0)
{
  pss::CloudSpec spec;
  spec.scene = scene;
  spec.dimension = dimension;
  spec.count = count;
  spec.size = size;
  spec.noise = noise;
  spec.gap = gap;
  return pss::generateCloud(spec);
}

/// @p n points uniform in [0, size]^dim (z = 0 in 2D), fixed seed.
inline std::vector<Vec3> randomBox(int n, int dim, double size, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, size);
  std::vector<Vec3> pts;
  pts.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    const double x = u(rng);
    const double y = u(rng);
    const double z = dim == 3 ? u(rng) : 0.0;
    pts.emplace_back(x, y, z);
  }
  return pts;
}

/// A uniformly distributed unit vector (z = 0 in 2D).
inline Vec3 randomUnit(std::mt19937& rng, int dim)
{
  std::normal_distribution<double> g(0.0, 1.0);
  Vec3 v;
  do
  {
    v = Vec3(g(rng), g(rng), dim == 3 ? g(rng) : 0.0);
  } while (v.norm() < 1e-3);
  return v.normalized();
}

/// Squared distance from @p x to the nearest of @p pts, by brute force (independent of the index).
inline double bruteNearestSq(const std::vector<Vec3>& pts, const Vec3& x)
{
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : pts)
  {
    best = std::min(best, (p - x).squaredNorm());
  }
  return best;
}

inline pss::SurfaceParameters params(double h, double cutoff = 3.0)
{
  pss::SurfaceParameters p;
  p.h = h;
  p.cutoff = cutoff;
  return p;
}

inline bool finite(double v) { return std::isfinite(v); }

} // namespace pss_test

// SPDX-License-Identifier: BSD-3-Clause
// n(x) above a dense straight line (2D) and a dense plane (3D), Sections 4 and 5 of the paper.
//
// Continuum theory for Levin's C(x) at height z above a flat, uniformly sampled cloud: the
// tangent second moment is int s^2 exp(-s^2/h^2) / int exp(-s^2/h^2) = h^2/2 per tangent axis and
// the normal one is z^2, so n_MLS is the normal for z < h/sqrt(2) and tangent above it (Fig. 5).
// The centre-of-mass and integral directions stay normal at every height (Sec. 5).

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace pss;
using namespace pss_test;

namespace
{

/// |n . normal| > 0.5 at height z above (offset, 0[, 0]).
bool isNormalAt(const SurfaceDefinition& s, double offset, double z)
{
  Workspace ws;
  const Vec3 x = s.dimension() == 2 ? Vec3(offset, z, 0) : Vec3(offset, 0, z);
  const Vec3 normal = s.dimension() == 2 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  return std::abs(s.direction(x, ws).n.dot(normal)) > 0.5;
}

/// Bisection on the height for the switch from normal (below) to tangent (above).
double flipHeight(const SurfaceDefinition& s, double offset, double lo, double hi)
{
  for (int it = 0; it < 40; ++it)
  {
    const double mid = 0.5 * (lo + hi);
    (isNormalAt(s, offset, mid) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void checkLevinFlip(const PointIndex& index, double h)
{
  Workspace ws;
  const int dim = index.dimension();
  const Vec3 normal = dim == 2 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  for (Variant v : { Variant::LevinMLS, Variant::NormalizedMLS })
  {
    auto s = makeSurface(v, index, params(h));
    for (double offset : { 0.0, 0.37 * h })
    {
      SCOPED_TRACE(std::string(variantName(v)) + " offset " + std::to_string(offset / h) + "h");
      // Clearly below (0.5h, 0.1h): normal; clearly above (0.9h, 1.5h): in the tangent space.
      for (double z : { 0.1 * h, 0.5 * h, -0.5 * h })
      {
        const Vec3 x = dim == 2 ? Vec3(offset, z, 0) : Vec3(offset, 0, z);
        const Direction d = s->direction(x, ws);
        EXPECT_TRUE(d.defined) << "z = " << z / h << "h";
        EXPECT_GT(std::abs(d.n.dot(normal)), 0.999) << "z = " << z / h << "h, n = " << d.n.transpose();
      }
      for (double z : { 0.9 * h, 1.5 * h, -0.9 * h })
      {
        const Vec3 x = dim == 2 ? Vec3(offset, z, 0) : Vec3(offset, 0, z);
        const Direction d = s->direction(x, ws);
        EXPECT_LT(std::abs(d.n.dot(normal)), 1e-3) << "z = " << z / h << "h, n = " << d.n.transpose();
        if (dim == 2)
        {
          // In 2D the tangent is unique (eigenvalues h^2/2 vs z^2), so n must be defined and unit.
          EXPECT_TRUE(d.defined) << "z = " << z / h << "h";
          EXPECT_NEAR(std::abs(d.n.x()), 1.0, 1e-6) << "z = " << z / h << "h";
        }
      }
      const double flip = flipHeight(*s, offset, 0.5 * h, 0.9 * h);
      std::cout << "[ flip     ] " << variantName(v) << " dim " << dim << " offset " << offset / h
                << "h: flip height " << flip / h << "h (theory " << 1 / std::sqrt(2.0) << "h)\n";
      EXPECT_NEAR(flip / (h / std::sqrt(2.0)), 1.0, 0.03);
    }
  }
}

void checkStaysNormal(const PointIndex& index, double h, Variant v, std::initializer_list<double> heights,
  std::initializer_list<double> offsets)
{
  Workspace ws;
  const int dim = index.dimension();
  const Vec3 normal = dim == 2 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  auto s = makeSurface(v, index, params(h));
  for (double offset : offsets)
  {
    for (double zh : heights)
    {
      const double z = zh * h;
      const Vec3 x = dim == 2 ? Vec3(offset * h, z, 0) : Vec3(offset * h, 0, z);
      const Direction d = s->direction(x, ws);
      // At 100h the analytic n_I stability is 1.5 h^2/z^2 = 1.5e-4, next to the default
      // minStability 1e-4, so 'defined' is only required up to 10h (stability >= 1.5e-2 there).
      if (std::abs(zh) <= 10)
      {
        EXPECT_TRUE(d.defined) << variantName(v) << " z = " << zh << "h offset " << offset << "h";
      }
      EXPECT_GE(d.stability, 0.0);
      EXPECT_LE(d.stability, 1.0);
      EXPECT_GT(std::abs(d.n.dot(normal)), 0.999)
        << variantName(v) << " z = " << zh << "h offset " << offset << "h: n = " << d.n.transpose();
    }
  }
}

} // namespace

// Truth: n_MLS flips from normal to tangent at h/sqrt(2) (tangent moment h^2/2 vs z^2); 3% covers
// the Gaussian truncation at 3h (relative moment loss ~1e-3) with margin.
TEST(Direction, LevinFlipHeightOnLine2D)
{
  const double h = 0.5;
  PointIndex index(lineCloud(12 * h, 0.1 * h), 2);
  checkLevinFlip(index, h);
}

// Truth: same flip at h/sqrt(2) above a plane (per-axis tangent moment h^2/2); 3% as in 2D.
TEST(Direction, LevinFlipHeightOnPlane3D)
{
  const double h = 2.0;
  PointIndex index(planeCloud(8 * h, 0.1 * h), 3);
  checkLevinFlip(index, h);
}

// Truth: n_COM above a straight line is exactly the normal (all neighbours lie on the line, so the
// centred covariance has no normal variance); 0.999 allows only rounding-level tilts.
TEST(Direction, CenterOfMassStaysNormal2D)
{
  PointIndex index(lineCloud(12 * 0.5, 0.1 * 0.5), 2);
  checkStaysNormal(index, 0.5, Variant::CenterOfMass, { 0.1, 0.5, 1, 2, 5, 10, 100, -0.5, -10 },
    { 0.0, 0.37 });
}

// Truth: as above for a plane in 3D.
TEST(Direction, CenterOfMassStaysNormal3D)
{
  PointIndex index(planeCloud(8 * 2.0, 0.1 * 2.0), 3);
  checkStaysNormal(index, 2.0, Variant::CenterOfMass, { 0.1, 0.5, 1, 2, 5, 10, -2 }, { 0.0, 0.37 });
}

// Truth: e_I over the line parallel to the cloud is (z^2+h^2/2)^2 sqrt(pi) h, over a line tilted by
// phi it grows by 3 z^2 h^2 sin^2(phi) sqrt(pi) h (>0 at every height), so n_I is the normal;
// |n.normal| > 0.999 (2.6 degrees) is far outside the golden-section search accuracy.
TEST(Direction, IntegralAndDeltaStayNormal2D)
{
  PointIndex index(lineCloud(12 * 0.5, 0.1 * 0.5), 2);
  for (Variant v : { Variant::Integral, Variant::Delta })
  {
    checkStaysNormal(index, 0.5, v, { 0.1, 0.5, 1, 2, 5, 10, 100, -2 }, { 0.0, 0.37 });
  }
}

// Truth: as in 2D for the plane (tilting the integration plane always adds 3 z^2 h^2 sin^2 terms);
// only a handful of heights because each 3D direction costs hundreds of 36-node integrals.
TEST(Direction, IntegralAndDeltaStayNormal3D)
{
  PointIndex index(planeCloud(8 * 2.0, 0.1 * 2.0), 3);
  checkStaysNormal(index, 2.0, Variant::Integral, { 0.1, 0.5, 1, 2, 5, 10 }, { 0.37 });
  checkStaysNormal(index, 2.0, Variant::Delta, { 0.5, 2, 10 }, { 0.37 });
}

// Truth: on a sphere n is radial for every definition. A projection's later iterates find n from
// the direction the previous iterate left (directionNear): a step of h/20 later it must still be
// radial, and agree with the search from scratch (eigen definitions: to rounding; n_I: to the
// angular tolerance of its Newton iteration).
TEST(Direction, DirectionNearAgreesWithDirectionFromScratch)
{
  Workspace ws;
  const double R = 10.0;
  const double h = 1.0;
  PointIndex index(sphereCap(R, 0.6, 0.15 * h), 3);
  SurfaceParameters params;
  params.h = h;
  const Vec3 radial = Vec3(0.1, -0.2, 1.0).normalized();
  const Vec3 first = (R + 0.3 * h) * radial;
  const Vec3 second = first + 0.05 * h * Vec3(1.0, 0.5, -0.2).normalized();
  for (const Variant v : { Variant::LevinMLS, Variant::CenterOfMass, Variant::Integral })
  {
    const auto s = makeSurface(v, index, params);
    DirectionMemory memory;
    s->directionNear(first, memory, ws);
    const Direction warm = s->directionNear(second, memory, ws);
    const Direction cold = s->direction(second, ws);
    // 1 - |cos| of the angle between them: 1e-12 is an angle of 1.4e-6.
    const double tolerance = v == Variant::Integral ? 1e-12 : 1e-14;
    ASSERT_TRUE(warm.defined) << variantName(v);
    EXPECT_NEAR(std::abs(warm.n.dot(cold.n)), 1.0, tolerance) << variantName(v);
    EXPECT_NEAR(std::abs(warm.n.dot(second.normalized())), 1.0, 1e-4) << variantName(v);
    EXPECT_NEAR(warm.stability, cold.stability, 1e-3 * cold.stability) << variantName(v);
  }
}

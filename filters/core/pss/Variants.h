// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Variants.h
 * @brief The five surface definitions of the paper. Construct them through makeSurface() or
 *        directly; all share SurfaceDefinition's contract (thread-safe, const queries).
 */
#pragma once

#include "pss/Kernel.h"
#include "pss/Quadrature.h"
#include "pss/SurfaceDefinition.h"

namespace pss
{

/**
 * @brief Levin's MLS surface (Eq. 1 with the plain Gaussian theta).
 *
 * e(y, a) = sum_i theta(y, p_i) <a, p_i - y>^2 = a^T C(y) a, n = smallest eigenvector of C(y),
 * C about the query point y (not the centroid). The energy is reported at its true scale, which
 * is tiny and flat far from the cloud: that is the paper's point about this definition.
 */
class LevinMLS : public SurfaceDefinition
{
public:
  using SurfaceDefinition::SurfaceDefinition;
  Variant variant() const override { return Variant::LevinMLS; }
  Direction direction(const Vec3& x) const override;
  LineSample lineSample(const Vec3& y, const Vec3& a) const override;
  Direction directionNear(const Vec3& x, DirectionMemory& memory) const override;
  Direction planeFit(const Vec3& x, Vec3& centroidOffset, DirectionMemory& memory) const override;
};

/**
 * @brief Eq. 1 with normalized weights theta_N (Alexa et al., Sec. 4).
 *
 * Same n as LevinMLS (a positive factor does not move an argmin), hence the inheritance; the
 * energy is a weighted mean of squared plane distances, so it grows away from the cloud instead
 * of fading out.
 */
class NormalizedMLS : public LevinMLS
{
public:
  using LevinMLS::LevinMLS;
  Variant variant() const override { return Variant::NormalizedMLS; }
  LineSample lineSample(const Vec3& y, const Vec3& a) const override;
};

/**
 * @brief n_COM: the normal of the total-least-squares plane through the weighted centre of mass
 *        c(x) (Sec. 5, PointShop3D's heuristic); the energy is NormalizedMLS's.
 *
 * The paper prints <a, x> in the n_COM formula; the plane passes through c, so we use <a, c>.
 */
class CenterOfMass : public NormalizedMLS
{
public:
  using NormalizedMLS::NormalizedMLS;
  Variant variant() const override { return Variant::CenterOfMass; }
  Direction directionNear(const Vec3& x, DirectionMemory& memory) const override;
};

/**
 * @brief The integral energy e_I(x, a) = int over P(x, a) of delta(y)^2 theta(y, x) dA (Sec. 5).
 *
 * Quadrature: with y = x + h (u b1 + v b2) for an orthonormal basis (b1, b2) of the plane (one
 * axis b in 2D), theta(y, x) = exp(-u^2 - v^2) and
 *   e_I ~= h^2 sum_jk w_j w_k delta(y_jk)^p    (3D),    h sum_j w_j delta(y_j)^p    (2D),
 * with the Gauss-Hermite rule of SurfaceParameters::quadratureOrder and p = integrandPower.
 * The slope along the normal is the same sum of p delta^(p-1) a . grad delta.
 *
 * n_I = argmin over unit a of e_I: in 2D a scan of the half circle refined by golden-section
 * search; in 3D the best of a fixed set of candidate directions (13 lattice directions plus the
 * centre-of-mass eigenvectors), refined by Newton's method on the sphere. Tilting the plane by an
 * angle towards an in-plane axis moves each node along a in proportion to its coordinate on that
 * axis, so the tilt gradient is one more sum over the same nodes as the slope (see integrate());
 * the Hessian is a difference of two such gradients. Within a projection (directionNear), an
 * iterate less than h/10 from the last one starts Newton from the last n_I instead of scanning
 * the candidates, and the e_perp search from the last e_perp direction: about half the e_I of
 * a cold search. Such a short step cannot carry n_I far, but where two minima of e_I over
 * directions are nearly equal the warm search keeps following the one it had. Stability is
 * (e_perp - e_min) / (e_perp + e_min), e_perp the least energy over directions orthogonal to n_I:
 * for a quadratic form this is exactly the eigenvalue measure the other variants report.
 */
class IntegralEnergy : public SurfaceDefinition
{
public:
  IntegralEnergy(const PointIndex& index, const SurfaceParameters& params);
  Variant variant() const override { return Variant::Integral; }
  Direction direction(const Vec3& x) const override;
  Direction directionNear(const Vec3& x, DirectionMemory& memory) const override;
  LineSample lineSample(const Vec3& y, const Vec3& a) const override;
  double energy(const Vec3& y, const Vec3& a) const override;

private:
  /// The plane through a point with unit normal a and orthonormal in-plane axes b1, b2 (in 2D
  /// the line with direction b1; b2 is unused).
  struct Frame
  {
    Vec3 a, b1, b2;
  };

  /// e_I over a frame's plane, with (when asked) its slope along a and its tilt gradient: the
  /// derivatives of e_I as a turns towards b1 and towards b2 with the plane pivoting about x.
  struct PlaneIntegral
  {
    double value = 0.0;
    double slope = 0.0;
    Eigen::Vector2d tilt = Eigen::Vector2d::Zero();
  };

  /// A direction with the value of e_I there.
  struct Minimum
  {
    Vec3 n = Vec3::Zero();
    double value = 0.0;
  };
  /// The least e_I over the directions orthogonal to n_I, and where it is.
  struct Across
  {
    double value = 0.0;
    Vec3 direction = Vec3::Zero();
  };

  Frame frameOf(const Vec3& a) const;
  static Frame tilted(const Frame& f, const Eigen::Vector2d& step);
  PlaneIntegral integrate(const Vec3& x, const Frame& f, bool derivatives) const;
  Minimum refineDirection(const Vec3& x, const Vec3& start) const;
  /// The searches for n_I and e_perp start near @p near (the last iterate's answer) when given.
  Across leastEnergyOrthogonalTo(const Vec3& x, const Vec3& n, const Vec3* near) const;
  Minimum minimum2D(const Vec3& x, const Vec3* near) const;
  Minimum minimum3D(const Vec3& x, const Vec3* near) const;

  GaussHermiteRule Rule;
  DistanceField Field;
};

/**
 * @brief The delta variant: n = n_I and e(y, a) = delta(y), independent of a (end of Sec. 5).
 */
class DeltaEnergy : public SurfaceDefinition
{
public:
  DeltaEnergy(const PointIndex& index, const SurfaceParameters& params);
  Variant variant() const override { return Variant::Delta; }
  Direction direction(const Vec3& x) const override { return Directions.direction(x); }
  Direction directionNear(const Vec3& x, DirectionMemory& memory) const override
  {
    return Directions.directionNear(x, memory);
  }
  LineSample lineSample(const Vec3& y, const Vec3& a) const override;

private:
  IntegralEnergy Directions;
  DistanceField Field;
};

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DirectionRulesAndEnergies.h
 * @brief The direction rules and energies the paper's five definitions, APSS and RIMLS are
 *        composed of (VariantCatalog.h says which definition takes which). Each is a small value over the
 *        cloud's index and the parameters; its state lives in the caller's Workspace.
 */
#pragma once

#include "pss/DeltaLattice.h"
#include "pss/Kernel.h"
#include "pss/Quadrature.h"
#include "pss/SurfaceDefinition.h"

#include <limits>

namespace pss
{

/**
 * @brief The smallest eigenvector of a weighted covariance of x's neighbourhood: about x itself
 *        (Levin's C(x) of Eq. 1; normalizing the weights divides it by a positive number, which
 *        moves no eigenvector, so the normalized MLS has the same n) or about the weighted centre
 *        of mass c(x) (n_COM, Sec. 5, PointShop3D's heuristic).
 *
 * The paper prints <a, x> in the n_COM formula; the plane passes through c, so we use <a, c>.
 * The fit hands on x's neighbourhood (Workspace::query), so a plane step gets c(x) without a
 * second gather.
 */
class CovarianceDirection : public DirectionRule
{
public:
  enum class About
  {
    Query,   ///< C(x) = sum_i theta(x, p_i)(p_i - x)(p_i - x)^T
    Centroid ///< sum_i theta_N(x, p_i)(p_i - c(x))(p_i - c(x))^T
  };
  CovarianceDirection(const PointIndex& index, const SurfaceParameters& params, About about);
  DirectionFit fit(const Vec3& x, DirectionMemory& memory, Workspace& ws) const override;

private:
  const PointIndex& Index;
  const SurfaceParameters Params;
  const About Centre;
};

/**
 * @brief The MLS energy of Eq. 1, e(y, a) = sum_i theta(y, p_i) <a, p_i - y>^2 = a^T C(y) a, with
 *        the plain Gaussian weights (Levin) or normalized ones theta_N (Alexa et al., Sec. 4).
 *
 * Levin's is reported at its true scale, which is tiny and flat far from the cloud: that is the
 * paper's point about that definition. The normalized one is a weighted mean of squared plane
 * distances, so it grows away from the cloud instead of fading out.
 */
class MLSEnergy : public Energy
{
public:
  enum class Weights
  {
    Plain,     ///< theta(y, p_i)
    Normalized ///< theta_N(y, p_i) = theta(y, p_i) / sum_j theta(y, p_j)
  };
  MLSEnergy(const PointIndex& index, const SurfaceParameters& params, Weights weights);
  LineSample lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const override;

private:
  const PointIndex& Index;
  const SurfaceParameters Params;
  const Weights Weighting;
};

/**
 * @brief The integral energy e_I(x, a) = int over P(x, a) of delta(y)^2 theta(y, x) dA (Sec. 5).
 *
 * Quadrature: with y = x + h (u b1 + v b2) for an orthonormal basis (b1, b2) of the plane (one
 * axis b in 2D), theta(y, x) = exp(-u^2 - v^2) and
 *   e_I ~= h^2 sum_jk w_j w_k delta(y_jk)^p    (3D),    h sum_j w_j delta(y_j)^p    (2D),
 * with the Gauss-Hermite rule of SurfaceParameters::quadratureOrder and p = integrandPower.
 * The slope along the normal is the same sum of p delta^(p-1) a . grad delta; tilting the plane
 * by an angle towards an in-plane axis moves each node along a in proportion to its coordinate
 * on that axis, so the tilt gradient is one more sum over the same nodes (see integrate()).
 * The second derivatives (curvature along a, tilt Hessian) need only delta's curvature along a
 * at each node besides its gradient (approximateSqDistanceJet): the line search and the search
 * for n_I take Newton steps without extra integrals to difference.
 */
class IntegralEnergy : public Energy
{
public:
  /// The plane through a point with unit normal a and orthonormal in-plane axes b1, b2 (in 2D
  /// the line with direction b1; b2 is unused).
  struct Frame
  {
    Vec3 a, b1, b2;
  };

  /// How many derivatives integrate() computes.
  enum class Derivatives
  {
    None,      ///< the value only
    UpToSecond ///< and slope, tilt, curvature, tiltHessian
  };

  /// e_I over a frame's plane, with (when asked) its first and second derivatives along a (the
  /// plane moving along its normal) and in tilt (a turning towards b1 and b2, the plane pivoting
  /// about x; coordinates of IntegralEnergy::tilted, so Newton's steps mean what they say).
  struct PlaneIntegral
  {
    double value = 0.0;
    double slope = 0.0;
    Eigen::Vector2d tilt = Eigen::Vector2d::Zero();
    double curvature = 0.0;
    Eigen::Matrix2d tiltHessian = Eigen::Matrix2d::Zero();
    /// sum weight F'(delta) <grad delta, w> (w the node's in-plane offset in units of h): how e
    /// changes with the window's scale, for the slope when that scale moves (a scale per point).
    double radial = 0.0;
  };

  IntegralEnergy(const PointIndex& index, const SurfaceParameters& params);
  LineSample lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const override;
  double value(const Vec3& y, const Vec3& a, Workspace& ws) const override;

  Frame frameOf(const Vec3& a) const;
  /// The frame turned by the tangent step (radians, in b1/b2 coordinates), axes carried along.
  static Frame tilted(const Frame& f, const Eigen::Vector2d& step);
  PlaneIntegral integrate(const Vec3& x, const Frame& f, Derivatives order, Workspace& ws) const;
  /// e_I with a rule of order at most 3 (9 nodes in 3D instead of 36 at the default order 6):
  /// good enough to rank candidate directions before Newton's method refines the best with the
  /// full rule, not to replace it (order 3 is off by about 2e-3 relative, order 6 by 2e-4).
  double roughValue(const Vec3& x, const Vec3& a, Workspace& ws) const;

private:
  PlaneIntegral sum(const Vec3& x, const Frame& f, Derivatives order, const GaussHermiteRule& rule, Workspace& ws) const;
  /// The window's scale at @p x and, with a scale per point, its gradient (else left unchanged).
  double windowScale(const Vec3& x, Vec3& gradient, Workspace& ws) const;
  /// The slope's term for a window whose scale @p h changes at the rate @p dh along the normal.
  static PlaneIntegral withWindow(PlaneIntegral sums, double h, double dh, bool planar);

  const PointIndex& Index;
  const SurfaceParameters Params;
  GaussHermiteRule Rule;
  GaussHermiteRule RoughRule;
  DistanceField Field;
  DeltaLattice Lattice; ///< used when Params.deltaLattice > 0
};

/**
 * @brief n_I = argmin over unit a of e_I(x, a) (Sec. 5).
 *
 * The best of a set of candidate directions (in 2D 36 across the half circle; in 3D the 13
 * lattice directions plus the centre-of-mass eigenvectors), ranked by a rough e_I (a rule of
 * order 3), is refined by Newton's method on the circle or sphere with the analytic tilt gradient
 * and Hessian and the full rule. Within a projection (a warm DirectionMemory), an iterate less
 * than h/10 from the last one starts Newton from the last n_I instead of ranking candidates, and
 * the e_perp search from the last e_perp direction. Such a short step cannot carry n_I far, but
 * where two minima of e_I over directions are nearly equal the warm search keeps following the
 * one it had. Stability is (e_perp - e_min) / (e_perp + e_min), e_perp the least energy over
 * directions orthogonal to n_I: for a quadratic form this is exactly the eigenvalue measure the
 * other rules report. Where the caller only needs to know that n is defined (a projection's
 * intermediate iterates), e_perp may be estimated from the tilt Hessian (see fit()). The fast path
 * (SurfaceParameters::deltaLattice > 0) takes both energies of the ratio from the rough rule.
 */
class IntegralDirection : public DirectionRule
{
public:
  IntegralDirection(const PointIndex& index, const SurfaceParameters& params);
  DirectionFit fit(const Vec3& x, DirectionMemory& memory, Workspace& ws) const override;

private:
  /// A direction with the value of e_I there.
  struct Minimum
  {
    Vec3 n = Vec3::Zero();
    double value = 0.0;
    /// 3D: the direction orthogonal to n towards which e_I grows least (the tilt Hessian's
    /// softest eigenvector), where the search for e_perp starts; zero when unknown.
    Vec3 softest = Vec3::Zero();
    /// 3D: the tilt Hessian's least eigenvalue there (NaN when unknown).
    double softCurvature = std::numeric_limits<double>::quiet_NaN();
  };
  /// The least e_I over the directions orthogonal to n_I, and where it is.
  struct Across
  {
    double value = 0.0;
    Vec3 direction = Vec3::Zero();
  };

  int dimension() const { return Index.dimension(); }
  Minimum refineDirection(const Vec3& x, const Vec3& start, Workspace& ws) const;
  /// The searches for n_I and e_perp start near @p near (the last iterate's answer) when given.
  /// @p rough: e_I with IntegralEnergy::roughValue's rule.
  Across leastEnergyOrthogonalTo(const Vec3& x, const Vec3& n, const Vec3* near, bool rough, Workspace& ws) const;
  Minimum minimum2D(const Vec3& x, const Vec3* near, Workspace& ws) const;
  Minimum minimum3D(const Vec3& x, const Vec3* near, Workspace& ws) const;

  const PointIndex& Index;
  const SurfaceParameters Params;
  IntegralEnergy Integral;
};

/**
 * @brief The approximate squared distance as an energy: e(y, a) = delta(y), independent of a
 *        (the delta variant, end of Sec. 5).
 */
class DeltaEnergy : public Energy
{
public:
  DeltaEnergy(const PointIndex& index, const SurfaceParameters& params);
  LineSample lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const override;

private:
  DistanceField Field;
};

/// The two fits of points with oriented normals.
enum class NormalFitKind
{
  /// APSS (Guennebaud and Gross 2007): the algebraic sphere u0 + ul . r + uq |r|^2 fitted to the
  /// weighted points and normals around x, Pratt-normalized (|ul|^2 - 4 u0 uq = 1), so that its
  /// value at x is about the signed distance; planes are the case uq = 0.
  AlgebraicSphere,
  /// RIMLS (Oztireli, Guennebaud and Gross 2009): f(x) = sum w_i (x - p_i) . n_i / sum w_i with
  /// the weights refitted robustly (residuals over sigma_r h, normals over sigma_n).
  RobustImplicit
};

/**
 * What a fit of points with normals gives at its point x: f(x), about the signed distance to the
 * surface (positive on the side the normals point to), its gradient, the move along n onto the
 * fitted surface, and a stability: the length of the weighted mean of the neighbours' normals,
 * in [0, 1] (1 where they agree, 0 where they cancel, as on both sides of a thin sheet).
 */
struct NormalFit
{
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  Vec3 step = Vec3::Zero();
  /// The fit's own second derivative along any unit direction (it is isotropic): 2 uq for the
  /// algebraic sphere, 0 for RIMLS, whose f is held linear about x.
  double secondDerivative = 0.0;
  double stability = 0.0;
  /// False where the fit has no surface: no weight, normals that cancel (stability below the
  /// threshold), an imaginary sphere (|ul|^2 - 4 u0 uq <= 0) or a zero gradient.
  bool defined = false;
};

/// The fit of @p kind at @p x (its neighbourhood gathered in ws.query with normals).
NormalFit fitWithNormals(
  NormalFitKind kind, const PointIndex& index, const SurfaceParameters& params, const Vec3& x, Workspace& ws);

/**
 * @brief n(x) of a fit with normals: its gradient's direction, with the fit's own step onto its
 *        surface for the plane procedure (DirectionFit::step), which is then Guennebaud and
 *        Gross's iterated sphere projection (APSS) or Oztireli et al.'s x - f grad f (RIMLS).
 */
class NormalFitDirection : public DirectionRule
{
public:
  /// Throws std::invalid_argument when @p index has no normals.
  NormalFitDirection(const PointIndex& index, const SurfaceParameters& params, NormalFitKind kind);
  DirectionFit fit(const Vec3& x, DirectionMemory& memory, Workspace& ws) const override;

private:
  const PointIndex& Index;
  const SurfaceParameters Params;
  const NormalFitKind Kind;
};

/**
 * @brief e(y, a) = f(y)^2 for the f of a fit with normals, independent of a: its minima along any
 *        line that crosses the surface are the zeros of f, so the extremal surface is the fit's
 *        zero set. The slope is 2 f grad f . a with the fit's gradient (APSS: the sphere's, the
 *        sphere held fixed; RIMLS: with the weights' derivatives, the robust factors held fixed);
 *        it changes sign exactly where f does, so the line search finds f = 0 exactly. The
 *        curvature is the same fit's, held fixed: 2 (grad f . a)^2 + 2 f f''|a|^2 (f'' its
 *        NormalFit::secondDerivative), so the end point's type costs no further fit.
 */
class NormalFitEnergy : public Energy
{
public:
  NormalFitEnergy(const PointIndex& index, const SurfaceParameters& params, NormalFitKind kind);
  LineSample lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const override;

private:
  const PointIndex& Index;
  const SurfaceParameters Params;
  const NormalFitKind Kind;
};

} // namespace pss

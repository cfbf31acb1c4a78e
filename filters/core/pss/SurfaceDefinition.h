// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SurfaceDefinition.h
 * @brief A point-set surface definition: a direction rule n(x) composed with an energy e(y, a),
 *        the two ingredients of an extremal surface (Definition 1).
 *
 * The paper's five definitions are the rows of a product table (DirectionRulesAndEnergies.h):
 * three direction rules (the smallest eigenvector of the covariance about x, or about the weighted
 * centre of mass, or the argmin of e_I over directions) and four energies (Eq. 1, its normalized form, e_I, delta).
 * Everything else (the implicit function g of Eq. 2, projection to minima or maxima, domain
 * classification, field sampling) is written once against SurfaceDefinition in
 * ExtremalSurface.h. Adding a definition means a new rule or energy where the existing ones do
 * not serve, one Variant value and one row of variantTable() (as APSS and RIMLS were added).
 *
 * Every evaluation takes the caller's Workspace (Workspace.h); none keeps state of its own.
 */
#pragma once

#include "pss/Kernel.h"
#include "pss/PointIndex.h"
#include "pss/Types.h"

#include <memory>

namespace pss
{

struct Workspace;
struct VariantInfo;

/**
 * What one iterate of a projection leaves for the direction at the next (see
 * SurfaceDefinition::directionNear). Start each projection with a default-constructed one.
 */
struct DirectionMemory
{
  EigenFrame frame;           ///< eigenvector rules: the last fit's eigenvectors
  bool valid = false;         ///< direction-search rules (n_I): the fields below are set
  Vec3 point = Vec3::Zero();  ///< where the last n was found
  Vec3 n = Vec3::Zero();      ///< that n
  Vec3 across = Vec3::Zero(); ///< the least-energy direction orthogonal to it (for the stability)
  /// Set by the caller: the stability of this fit only decides whether n is defined (a
  /// projection's intermediate iterates), so a rule may estimate it where it is clearly above
  /// the threshold (n_I: from the tilt Hessian, see IntegralDirection::fit).
  bool estimateStability = false;
  /// Set by the rule: the last fit's stability was such an estimate.
  bool stabilityEstimated = false;
};

/// A direction with the neighbourhood of x it was fitted from, for rules that fit one.
struct DirectionFit
{
  Direction direction;
  /// x's neighbourhood, in the workspace given to the fit (valid until that workspace's next
  /// use), or nullptr when the rule gathered none it could hand on (n_I).
  const Neighbourhood* neighbourhood = nullptr;
  /// Rules that fit a surface of their own at x (APSS's sphere, RIMLS's implicit function) set
  /// this to the move from x onto it along n, which the plane procedure then takes instead of
  /// the move onto the plane through the centre of mass.
  bool hasStep = false;
  Vec3 step = Vec3::Zero();
};

/// n(x): how a definition picks the direction of the line along which it minimizes its energy.
class DirectionRule
{
public:
  virtual ~DirectionRule() = default;
  /**
   * n(x) for an iterate that follows, closely, one whose direction filled @p memory (a
   * projection's steps; a default-constructed memory for a cold start): eigenvector rules start
   * their decomposition from the last eigenvectors (same result to rounding); n_I starts its
   * search from the last n_I instead of scanning every direction. Updates @p memory.
   */
  virtual DirectionFit fit(const Vec3& x, DirectionMemory& memory, Workspace& ws) const = 0;
};

/// e(y, a): the energy whose minima along the line of n define the surface.
class Energy
{
public:
  virtual ~Energy() = default;
  /**
   * e(y, a) and d/dt e(y + t a, a) at t = 0 (a fixed, the weights moving with y); @p a a unit
   * vector (z = 0 in 2D).
   */
  virtual LineSample lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const = 0;
  /// e(y, a) at its true scale (may underflow to 0 for Levin's, never NaN). The default takes
  /// it from lineSample; energies whose slope costs extra override it.
  virtual double value(const Vec3& y, const Vec3& a, Workspace& ws) const;
};

class SurfaceDefinition
{
public:
  /// The definition of @p recipe's row over @p index. Throws std::invalid_argument when @p index
  /// is empty or @p params are invalid.
  SurfaceDefinition(const VariantInfo& recipe, const PointIndex& index, const SurfaceParameters& params);
  SurfaceDefinition(const SurfaceDefinition&) = delete;
  SurfaceDefinition& operator=(const SurfaceDefinition&) = delete;

  Variant variant() const { return Kind; }

  /// n(x): the unoriented direction with its stability.
  Direction direction(const Vec3& x, Workspace& ws) const;

  /// n(x) continuing from what an earlier iterate left in @p memory (see DirectionRule::fit).
  Direction directionNear(const Vec3& x, DirectionMemory& memory, Workspace& ws) const;

  /// See Energy::lineSample.
  LineSample lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const;

  /// e(y, a) at its true scale (may underflow to 0 for LevinMLS, never NaN).
  double energy(const Vec3& y, const Vec3& a, Workspace& ws) const;

  /**
   * n(x) and c(x) - x, the offset of the normalized-weight centre of mass: what one step of the
   * plane procedure needs. Rules that fit x's neighbourhood hand it on, so both come from one
   * gather; for the others x's neighbourhood is gathered once more. @p memory as in
   * directionNear. For APSS and RIMLS the offset is the move along n onto their own local fit
   * (DirectionFit::step): the plane procedure is then their usual projection.
   *
   * @p contraction, when given, receives the fraction of x's distance to the plane procedure's
   * fixed point (along n) that the step onto the plane leaves (centroidContraction; NaN for
   * APSS and RIMLS, whose step is not onto that plane).
   */
  Direction planeFit(const Vec3& x, Vec3& centroidOffset, DirectionMemory& memory, Workspace& ws,
    double* contraction = nullptr) const;

  const PointIndex& index() const { return Index; }
  const SurfaceParameters& parameters() const { return Params; }
  int dimension() const { return Index.dimension(); }
  /// The scale parameter: h itself, or with a scale per point (PointIndex::hasScales) a typical
  /// value (see SurfaceParameters::h); scaleAt() is the scale that holds at a point.
  double h() const { return Params.h; }
  /// The scale at @p x: h, or with a scale per point the neighbours' scales averaged with the
  /// normalized weights at x (Neighbourhood::localScale). What "units of h" mean at x.
  double scaleAt(const Vec3& x, Workspace& ws) const;

private:
  const PointIndex& Index;
  const SurfaceParameters Params;
  const Variant Kind;
  const std::unique_ptr<const DirectionRule> Directions;
  const std::unique_ptr<const Energy> Energies;
};

/// The definition named by @p v: variantTable()'s row for it (defined in VariantCatalog.cxx). Throws
/// like the constructor, and std::invalid_argument for a value outside the table.
std::unique_ptr<SurfaceDefinition> makeSurface(Variant v, const PointIndex& index, const SurfaceParameters& params);

} // namespace pss

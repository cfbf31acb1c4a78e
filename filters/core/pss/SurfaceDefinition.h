// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SurfaceDefinition.h
 * @brief The interface every point-set surface definition implements: a direction field n(x)
 *        and an energy e(y, a), the two ingredients of an extremal surface (Definition 1).
 *
 * Everything else (the implicit function g of Eq. 2, projection to minima or maxima, domain
 * classification, field sampling) is written once against this interface in ExtremalSurface.h.
 * Adding a definition (APSS, RIMLS, ...) means one new subclass and one Variant value.
 */
#pragma once

#include "pss/Kernel.h"
#include "pss/PointIndex.h"
#include "pss/Types.h"

#include <memory>

namespace pss
{

/**
 * What one iterate of a projection leaves for the direction at the next (see
 * SurfaceDefinition::directionNear). Start each projection with a default-constructed one.
 */
struct DirectionMemory
{
  EigenFrame frame;           ///< eigenvector definitions: the last fit's eigenvectors
  bool valid = false;         ///< direction-search definitions (n_I): the fields below are set
  Vec3 point = Vec3::Zero();  ///< where the last n was found
  Vec3 n = Vec3::Zero();      ///< that n
  Vec3 across = Vec3::Zero(); ///< the least-energy direction orthogonal to it (for the stability)
};

class SurfaceDefinition
{
public:
  /// Throws std::invalid_argument when @p index is empty or @p params are invalid.
  SurfaceDefinition(const PointIndex& index, const SurfaceParameters& params);
  virtual ~SurfaceDefinition() = default;
  SurfaceDefinition(const SurfaceDefinition&) = delete;
  SurfaceDefinition& operator=(const SurfaceDefinition&) = delete;

  virtual Variant variant() const = 0;

  /// n(x): the unoriented direction with its stability. Thread-safe.
  virtual Direction direction(const Vec3& x) const = 0;

  /**
   * n(x) for an iterate that follows, closely, one whose direction filled @p memory (a
   * projection's steps): eigenvector definitions start their decomposition from the last
   * eigenvectors (same result to rounding); IntegralEnergy starts its search for n_I from the
   * last n_I instead of scanning every direction (see its class comment). Updates @p memory.
   * The default ignores it and calls direction().
   */
  virtual Direction directionNear(const Vec3& x, DirectionMemory& memory) const;

  /**
   * e(y, a) and d/dt e(y + t a, a) at t = 0 (a fixed, the weights moving with y). @p a must be a
   * unit vector (z = 0 in 2D). Thread-safe.
   */
  virtual LineSample lineSample(const Vec3& y, const Vec3& a) const = 0;

  /// e(y, a) at its true scale (may underflow to 0 for LevinMLS, never NaN).
  virtual double energy(const Vec3& y, const Vec3& a) const;

  /**
   * n(x) and c(x) - x, the offset of the normalized-weight centre of mass: what one step of the
   * plane procedure needs. The default takes n from directionNear() and gathers the
   * neighbourhood a second time; definitions whose n comes from the same weighted neighbourhood
   * override it to gather once. @p memory carries what one iterate's fit leaves for the next.
   */
  virtual Direction planeFit(const Vec3& x, Vec3& centroidOffset, DirectionMemory& memory) const;

  const PointIndex& index() const { return Index; }
  const SurfaceParameters& parameters() const { return Params; }
  int dimension() const { return Index.dimension(); }
  double h() const { return Params.h; }

protected:
  const PointIndex& Index;
  const SurfaceParameters Params;
};

/// Factory: the definition named by @p v over @p index. Throws like the constructor.
std::unique_ptr<SurfaceDefinition> makeSurface(
  Variant v, const PointIndex& index, const SurfaceParameters& params);

} // namespace pss

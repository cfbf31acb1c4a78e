// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Types.h
 * @brief Small value types shared by every part of the VTK-free core.
 *
 * The core always works with 3-vectors. In two dimensions (a cloud in the xy-plane) the z
 * coordinate of every point, query and direction is zero; see PointIndex.
 */
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <string>

namespace pss
{

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// The five surface definitions of the paper (Sections 2, 4 and 5), and the two that fit points
/// with oriented normals (docs/paper.md, "Definitions with normals").
enum class Variant : int
{
  LevinMLS = 0,      ///< Eq. 1 with Gaussian weights; n = argmin_a e_MLS.
  NormalizedMLS = 1, ///< Eq. 1 with normalized Gaussian weights (Alexa et al.).
  CenterOfMass = 2,  ///< n_COM: normal of the weighted total-least-squares plane (Sec. 5).
  Integral = 3,      ///< e_I: integral of delta^2 over the plane P(x, a) (Sec. 5).
  Delta = 4,         ///< n = n_I and e(y, a) = delta(y) (end of Sec. 5).
  APSS = 5,          ///< algebraic point-set surfaces: spheres fitted to points and normals.
  RIMLS = 6          ///< robust implicit MLS: points and normals, robustly reweighted.
};

constexpr int VariantCount = 7;

/// True for the definitions that need an oriented normal at every cloud point (APSS, RIMLS).
constexpr bool needsNormals(Variant v)
{
  return v == Variant::APSS || v == Variant::RIMLS;
}

/// Canonical lower-case name: "levin", "normalized", "com", "integral", "delta", "apss", "rimls"
/// (from variantTable(), VariantCatalog.h).
const char* variantName(Variant v);
/// Parses the table's canonical names and enum spellings ("LevinMLS", ...), ignoring case, '-',
/// '_' and ' ', and "mls" for Levin's; returns false if unknown.
bool parseVariant(const std::string& text, Variant& out);

/// Kind of critical point of t -> e(x + t n, n) at t = 0 (the sign of its second derivative).
enum class ExtremumType : int
{
  None = 0,    ///< not a critical point, or the curvature is zero/undetermined
  Minimum = 1, ///< on the extremal surface (blue in Figures 9 and 10)
  Maximum = 2  ///< on the larger implicit surface g = 0 but not extremal (green)
};

/// Why a projection stopped.
enum class StopReason : int
{
  Converged = 0,          ///< the last step was below tolerance * h
  MaxIterations = 1,      ///< iteration budget exhausted before convergence
  UndefinedDirection = 2, ///< n(x) not unique (stability below threshold) or no support
  NoExtremum = 3,         ///< no local extremum of the requested kind along the line of n
  InvalidInput = 4        ///< the start point had a NaN or infinite coordinate
};

const char* stopReasonName(StopReason r);

/// Direction n(x) with the stability measure the design asks for beside every n.
struct Direction
{
  Vec3 n = Vec3::Zero();  ///< unit vector (unoriented: n and -n are the same direction)
  double stability = 0.0; ///< in [0, 1]; 0 = n not unique, 1 = perfectly determined
  bool defined = false;   ///< false when n is not well defined at x (see stability)
};

/**
 * Energy on the line y(t) = x + t a with a fixed, at t = 0: value e(x, a), slope d/dt and, where
 * the definition has it in closed form, curvature d2/dt2 (NaN otherwise).
 *
 * Levin's unnormalized energy underflows far from the cloud, so the numbers are stored relative
 * to a scale: true value = value * exp(logScale) (likewise slope and curvature). Signs and ratios
 * of the stored numbers stay exact even where the true values underflow to zero.
 */
struct LineSample
{
  double value = 0.0;
  double slope = 0.0;
  double curvature = std::numeric_limits<double>::quiet_NaN();
  double logScale = 0.0;
  double nearestSqDist = 0.0; ///< squared distance from y to the nearest cloud point

  double trueValue() const;
  double trueSlope() const;
};

} // namespace pss

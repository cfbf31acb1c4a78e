// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Domain.h
 * @brief Is a start point inside the domain of a surface definition? (Sections 3, 4 and 6.)
 *
 * A start point x is projected; the label says what became of it and the evidence says why:
 * - InDomain: the projection converged to a point near the cloud whose n agrees with the cloud's
 *   own normal there;
 * - Spurious: it converged, but to a fixed point far from the cloud, or one whose n disagrees
 *   with the cloud's local normal (the spurious components of Figures 6 and 9);
 * - Undefined: n(x) was not well defined along the way (or x had NaN/Inf coordinates);
 * - NotConverged: the iteration limit was reached, or no extremum was found along the line.
 *
 * The cloud's local normal at the fixed point f is the centre-of-mass normal (total least squares
 * plane of the Gaussian-weighted neighbours) evaluated at the cloud point nearest to f: it depends
 * on the cloud alone, whatever definition is being classified. A cloud with normals
 * (PointIndex::hasNormals: APSS, RIMLS) brings its own, and they are taken instead.
 */
#pragma once

#include "pss/ExtremalSurface.h"
#include "pss/SurfaceDefinition.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace pss
{

enum class DomainLabel : int
{
  InDomain = 0,
  Spurious = 1,
  Undefined = 2,
  NotConverged = 3
};

const char* domainLabelName(DomainLabel label);

struct DomainThresholds
{
  double maxDistance = 1.0;      ///< fixed point farther than this (in h) from every cloud point: Spurious
  double maxNormalAngle = 30.0;  ///< degrees between n at the fixed point and the cloud's normal there
  /// Past the cloud's border: the weighted centroid of the neighbours of the fixed point lies
  /// farther than this (in the local h) from it along the surface (perpendicular to n): Spurious.
  /// Inside a sampled surface the centroid sits about over the point; at a straight border of the
  /// samples it trails by h / sqrt(pi) = 0.56 h, and by more beyond it. 0 (the default): not tested.
  double maxBorderOffset = 0.0;

  void validate() const; ///< throws std::invalid_argument
};

struct DomainEvidence
{
  DomainLabel label = DomainLabel::Undefined;
  ProjectionResult projection;
  double distanceToCloud = 0.0;  ///< from the fixed point to the nearest cloud point (absolute units)
  double normalAngle = 0.0;      ///< degrees, in [0, 90]: n at the fixed point vs the cloud's normal there
  double startAngle = 0.0;       ///< degrees, in [0, 90]: n at the start point vs n at the fixed point
  double startStability = 0.0;   ///< stability of n at the start point
  double borderOffset = 0.0;     ///< in local h: the neighbours' centroid along the surface (with maxBorderOffset)
};

/**
 * The cloud's own normal at each of its points (see the file comment), computed the first time a
 * point's is asked for and kept: many start points share their nearest cloud point (a mesh's
 * crossings, a dense grid). Safe to share between threads; a normal is a function of the cloud
 * alone, so what a thread gets does not depend on which thread computed it first.
 */
class CloudNormals
{
public:
  explicit CloudNormals(const SurfaceDefinition& s);
  /// The normal at cloud point @p point (computed in @p ws when not yet kept). When computing it
  /// read beyond the index's complete region (a rank's piece and ghosts), every call for that
  /// point sets @p ws.leftCompleteRegion, not only the one that computed it.
  Direction at(std::size_t point, Workspace& ws) const;

private:
  const SurfaceDefinition& Surface;
  mutable std::vector<Direction> Normal;
  /// Per point: 0 not computed, 1 being computed by a thread, 2 stored in Normal, 3 stored but
  /// computed from a neighbourhood beyond the complete region.
  mutable std::unique_ptr<std::atomic<std::uint8_t>[]> State;
};

/// The centre-of-mass normal at @p x from the cloud's points alone (in ws.local), whatever
/// normals the index carries: how the cloud's own normals are estimated.
Direction centreOfMassNormal(const PointIndex& index, const SurfaceParameters& params, const Vec3& x, Workspace& ws);

/// The cloud's own normal at cloud point @p point, uncached.
Direction cloudNormalAt(const SurfaceDefinition& s, std::size_t point, Workspace& ws);

/// Projects @p start with @p options and labels the outcome (see the file comment). @p normals,
/// when given, must be of @p s's cloud: the cloud's normals are then taken from it.
DomainEvidence classifyStart(const SurfaceDefinition& s, const Vec3& start, const ProjectionOptions& options,
  const DomainThresholds& thresholds, Workspace& ws, const CloudNormals* normals = nullptr);

/// Unoriented angle between two directions, in degrees within [0, 90].
double unorientedAngleDegrees(const Vec3& a, const Vec3& b);

} // namespace pss

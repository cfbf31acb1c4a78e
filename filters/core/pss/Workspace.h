// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Workspace.h
 * @brief The caches and scratch arrays of the core's evaluations, owned by their caller.
 *
 * Every evaluation (a direction, an energy sample, a projection, a cloud normal, ...) takes a
 * Workspace by reference and keeps its neighbourhoods and the candidate points of its last k-d
 * tree query there, so that consecutive evaluations nearby (the iterates of a projection, the
 * samples of a line search, the quadrature nodes of e_I) reuse them. What a workspace holds only
 * ever saves work: a result is bitwise the same with a fresh workspace or with one that served
 * any other cloud, scale or definition before (tests/core/WorkspaceTest.cxx checks this).
 *
 * One workspace serves one thread at a time: a parallel loop gives each worker its own
 * (pss::parallelFor's workspace overload, or vtkSMPThreadLocal<pss::Workspace> in a VTK functor).
 * It is a plain value: default-constructed empty (no allocation until first use), copyable and
 * movable. Its members are the core's business; callers only create, keep and pass it.
 */
#pragma once

#include "pss/DeltaLattice.h"
#include "pss/Kernel.h"
#include "pss/PointIndex.h"

#include <Eigen/Core>

#include <cstdint>

namespace pss
{

/**
 * The candidate points of one k-d tree query (absolute coordinates, ordered by index): every
 * point that a neighbourhood of any query near the fetch centre can need (see
 * gatherNeighbourhood). Defined in CandidateCache.cxx.
 */
struct CandidateCache
{
  std::uint64_t indexSerial = 0; ///< 0: empty
  double h = 0.0;
  double band = 0.0;
  Vec3 center = Vec3::Zero();
  double centerMinDist = 0.0;
  double radius = 0.0;
  Eigen::ArrayXd px, py, pz;
  /// Each candidate's index in the PointIndex.
  std::vector<std::uint32_t> ids;
  /// The candidates' unit normals when the index has them (PointIndex::hasNormals), fetched once
  /// here so that each neighbourhood compacts them with the coordinates (APSS, RIMLS).
  bool withNormals = false;
  Eigen::ArrayXd nx, ny, nz;
  /// A scale per point (PointIndex::hasScales): each candidate's 1 / h_i^2 and h_i. The fetch
  /// then holds every point that a query within margin of center can need, whatever its scale.
  bool scaled = false;
  Eigen::ArrayXd pk, ph;
  double margin = 0.0;
  double cutoffSq = 0.0;
  Eigen::Index count = 0;
  bool reusable = false; ///< the fetched ball is exact, so later queries may rely on it
  std::vector<std::uint64_t> ranks, rankScratch; ///< scratch of a fetch in coordinate order

  /// True when every point within sqrt(dmin(y)^2 + band) of y is among the candidates (with
  /// @p extra > 0: for every query within extra of y).
  bool covers(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, double extra = 0.0) const;
  /// Fetches the candidates around y with a margin of at least @p minMargin.
  void fetch(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, PointIndex::LeafRanges& leaves,
    double minMargin = 0.0);
  /// |p - y|^2 for the first count candidates, into out (resized when short); returns them.
  Eigen::VectorBlock<Eigen::ArrayXd> squaredDistances(const Vec3& y, Eigen::ArrayXd& out) const;
  /// The candidates of @p wider (which must cover every query within @p reach of @p c) that any
  /// such query can need; @p sq is scratch.
  void focus(const CandidateCache& wider, const Vec3& c, double reach, Eigen::ArrayXd& sq);
  /// Room for @p n candidates, keeping the first count.
  void reserve(Eigen::Index n);

private:
  /// Fills nx, ny, nz from ids (when the index has normals) and sets withNormals.
  void fetchNormals(const PointIndex& index);
  /// Copies wider's normal @p from to @p to (focus), when there are normals.
  void copyNormal(const CandidateCache& wider, Eigen::Index from, Eigen::Index to);
  void fetchScaled(const PointIndex& index, const Vec3& y, std::size_t nearest, PointIndex::LeafRanges& leaves,
    double minMargin);
  void focusScaled(const CandidateCache& wider, const Vec3& c, double reach, Eigen::ArrayXd& sq);
};

struct Workspace
{
  /// The neighbourhood of the last covariance fit or MLS energy sample. Shared between them so
  /// that evaluations at the same point, such as a projection's last plane fit and the energy at
  /// its end point, gather once.
  Neighbourhood query;
  /// The neighbourhood of the last delta evaluation (DistanceField: e_I's quadrature nodes, the
  /// delta energy), which happen inside other evaluations and must not overwrite query.
  Neighbourhood field;
  /// For gathers nested in other evaluations that keep query or field in use (n_I's starting
  /// candidates, a plane fit's centroid for rules that fit no neighbourhood, cloud normals).
  Neighbourhood local;
  /// The neighbourhood behind the last SurfaceDefinition::scaleAt (a scale per point only).
  Neighbourhood scale;

  /// The last k-d tree query's candidates, and a subset of them for a smaller region (see
  /// focusNeighbourhoods): every gather scans the smaller one that covers it.
  CandidateCache wide;
  CandidateCache focused;
  /// Scratch: candidates' squared distances (gather, focus) and a tree query's leaf ranges.
  Eigen::ArrayXd candidateSq;
  Eigen::ArrayXd focusSq;
  Eigen::ArrayXd scaledSq; ///< candidates' |p - y|^2 / h_i^2 (a scale per point)
  PointIndex::LeafRanges leaves;
  /// The delta lattice's shared node table and the bricks this workspace has looked up there.
  LatticeCache lattice;
  /// Set by a caller whose start set the lattice does not serve (latticeServes): delta is then
  /// evaluated exactly, as with SurfaceParameters::deltaLattice 0.
  bool exactDelta = false;
  /// Slack, in units of h, that a gather's candidate fetch adds around its query at least (one h
  /// scale only; a fetch adds 0.5 h anyway). A wider fetch serves more of the following queries
  /// but costs every one of them a longer scan: the plane procedure, one gather per step, gains
  /// from 1 h; the extremal one, many gathers per step along a line, loses. Never changes a result.
  double fetchSlack = 0.0;

  /// Not a cache but a report: set (never cleared by the core) when an evaluation needed cloud
  /// points beyond the index's complete region (PointIndex::setCompleteRegion), so that its result
  /// may differ from the whole cloud's. A distributed caller clears it before a projection and
  /// finishes the flagged ones again with more ghost points.
  bool leftCompleteRegion = false;
};

} // namespace pss

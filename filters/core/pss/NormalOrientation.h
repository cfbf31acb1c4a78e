// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NormalOrientation.h
 * @brief One orientation for unoriented normals: over a neighbour graph (Hoppe et al.'s rule) or
 * toward a sensor.
 *
 * n is a line, not a vector: every definition's n(x) has an arbitrary sign. Users who want normals
 * as a product (to shade, to mesh elsewhere, or for the definitions that need oriented normals)
 * need one sign that neighbours agree on. Propagation walks a maximum spanning tree of
 * |n_i . n_j| over the graph, most parallel neighbours first, so that the sign crosses sharp
 * bends last; each connected piece starts from its seed. Deterministic: the result does not
 * depend on the number of threads.
 */
#pragma once

#include "pss/Kernel.h"
#include "pss/PointIndex.h"
#include "pss/Types.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace pss
{

/// An undirected graph over points 0 .. size() - 1 (compressed rows).
struct NeighbourGraph
{
  std::vector<std::size_t> start;      ///< point i's neighbours: adjacent[start[i] .. start[i + 1])
  std::vector<std::uint32_t> adjacent;
  std::size_t size() const { return start.empty() ? 0 : start.size() - 1; }
};

/// The symmetric k-nearest-neighbour graph of the indexed points (i and j are linked when either
/// is among the other's @p k nearest), in the index's numbering.
NeighbourGraph nearestNeighbourGraph(const PointIndex& index, std::size_t k, int threads = 1);

/**
 * Flips the normals @p normals (three doubles per point of @p graph, x y z; a zero normal is
 * skipped and breaks no tie) so that neighbours agree: from each seed of @p seeds, in that order,
 * that is not yet reached, whose sign @p flipSeed decides (true: flip it), along the maximum
 * spanning tree of |n_i . n_j|. @p flipped, when given, is called for every point flipped (the
 * seeds too). Returns the number of points flipped.
 */
std::size_t propagateOrientation(const NeighbourGraph& graph, double* normals, const std::vector<std::uint32_t>& seeds,
  const std::function<bool(std::uint32_t)>& flipSeed, const std::function<void(std::uint32_t)>& flipped = nullptr);

/**
 * Orients @p normals, one per indexed point of @p index (zero where unknown): toward
 * @p viewpoint, point by point, when one is given (a single view sees each surface from its
 * front); else by propagation over the @p k-nearest-neighbour graph, each connected piece from its
 * highest point (largest z; y in 2D) with its normal pointing up (Hoppe et al.'s rule: right for
 * an object's outside). Returns the number of normals flipped.
 */
std::size_t orientNormals(const PointIndex& index, std::vector<Vec3>& normals, const std::optional<Vec3>& viewpoint,
  std::size_t k = 10, int threads = 1);

/**
 * Oriented normals estimated from the cloud alone, for the definitions that need them (APSS,
 * RIMLS) when the cloud brings none: at each indexed point the cloud's own normal (the
 * centre-of-mass plane of its neighbours at scale @p params, Domain.h's centreOfMassNormal), oriented
 * by orientNormals(@p viewpoint, @p k). A point where no normal is defined (isolated, or on a line
 * in 3D) takes the oriented normal of the nearest point that has one; @p borrowed, when given,
 * receives how many did. Returned in the index's input order (zero for skipped points), ready for
 * PointIndex::setNormals. Throws std::invalid_argument when no point has a normal. The same for
 * every thread count.
 */
std::vector<Vec3> estimateOrientedNormals(const PointIndex& index, const SurfaceParameters& params,
  const std::optional<Vec3>& viewpoint, std::size_t k = 10, int threads = 1, std::size_t* borrowed = nullptr);

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DeltaLattice.h
 * @brief delta read from a lattice instead of evaluated at every quadrature node of e_I: the fast
 *        path of the integral and delta definitions (SurfaceParameters::deltaLattice; docs/paper.md,
 *        "Reading: the integral energy's fast path").
 *
 * One e_I is 36 quadrature nodes, each a full neighbourhood of some 200 points; a projection
 * takes some 45 e_I, and neighbouring projections put their nodes in the same region of space.
 * The lattice evaluates delta exactly, with its gradient and Hessian, at the nodes of a regular
 * grid of spacing s (a fraction of h), and interpolates between them with the tricubic Hermite
 * polynomial of those data (values, first derivatives and the three mixed second derivatives at
 * the 8 corners of a cell; the third mixed derivative is taken as 0). The interpolant is C1 across
 * cell faces, so e_I's slope and tilt stay continuous and Newton's steps well defined.
 *
 * Determinism: a node's data are a function of its integer coordinates only (the exact delta there,
 * whose neighbourhood is canonical), so which thread computed a node, and when, changes the time,
 * never a bit of a result. Nodes are computed when a cell first needs them and kept in bricks of
 * 9 x 9 x 9 nodes in a table shared by every workspace that reads the same lattice (same index, h,
 * cutoff and spacing; LatticeTable), so threads projecting nearby points compute each node once. The
 * table holds at most LatticeCache::MaxBricks bricks; past that it lets go of the oldest quarter,
 * which live on while a workspace still reads them (a brick is shared by the table and the
 * workspaces that looked it up, and freed with the last of them). A node computed from cloud
 * points beyond the index's complete region keeps that flag, and every read of it sets
 * Workspace::leftCompleteRegion, as the exact evaluation would.
 *
 * In 2D (a cloud in the xy-plane) the lattice is the plane's: nodes at z = 0, bicubic Hermite.
 * Beyond 2^50 cells from the origin (coordinates of 1e15 h and more) delta is evaluated exactly.
 */
#pragma once

#include "pss/Kernel.h"
#include "pss/Types.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace pss
{

class PointIndex;
struct Workspace;

class LatticeTable;

/// A workspace's view of the lattice nodes computed so far, for one index, h, cutoff and spacing.
/// The nodes themselves are shared by every thread reading that lattice (LatticeTable); its
/// members are DeltaLattice's business.
struct LatticeCache
{
  /// A brick covers 8 x 8 x 8 cells and holds their 9 x 9 x 9 corner nodes: every cell finds its
  /// eight corners in one brick. Nodes on a brick's faces are held by its neighbours too (copied
  /// from there when they have them, else computed: the same bits either way).
  static constexpr int BrickCells = 8;
  static constexpr int BrickSide = BrickCells + 1;
  static constexpr int BrickNodes = BrickSide * BrickSide * BrickSide;
  /// Per node, in two groups of four that the interpolation contracts as vectors (with s the
  /// spacing): delta, s d/dz, s d/dy, s^2 d2/dydz; s d/dx, s^2 d2/dxdz, s^2 d2/dxdy, 0.
  static constexpr int NodeData = 8;
  /// About 96 MB of bricks (47 KB each) in a shared table; past that it forgets its oldest quarter.
  static constexpr std::size_t MaxBricks = 2048;
  /// The bricks a workspace keeps looked up before it forgets them (and asks the table again).
  static constexpr std::size_t MaxSeen = 1024;

  struct BrickKey
  {
    std::int64_t i = 0, j = 0, k = 0;
    bool operator==(const BrickKey& o) const { return i == o.i && j == o.j && k == o.k; }
  };
  struct BrickHash
  {
    std::size_t operator()(const BrickKey& key) const;
  };
  /// Node states.
  enum : std::uint8_t
  {
    Empty = 0,
    Ready = 1,
    ReadyFromBeyond = 2, ///< computed from cloud points beyond the index's complete region
    Busy = 3             ///< being computed by some thread
  };
  /// Whether a node in @p state may be read.
  static bool isReady(std::uint8_t state) { return state == Ready || state == ReadyFromBeyond; }
  struct Brick
  {
    Brick();
    std::array<double, BrickNodes * NodeData> data;
    /// A node's data may be read once its state isReady (acquire).
    std::array<std::atomic<std::uint8_t>, BrickNodes> state;
  };

  /// The table of this lattice, and the bricks this workspace has looked up there (which it keeps
  /// alive, whatever the table forgets meanwhile).
  std::shared_ptr<LatticeTable> table;
  std::unordered_map<BrickKey, std::shared_ptr<Brick>, BrickHash> seen;
  /// The brick of the last lookup, which most lookups of a cell's corners hit again.
  BrickKey lastKey;
  Brick* lastBrick = nullptr;

  void clear();
};

/**
 * delta and its derivatives interpolated from a lattice of spacing params.deltaLattice * h; the
 * node data come from @p field, the cache from Workspace::lattice.
 */
class DeltaLattice
{
public:
  explicit DeltaLattice(const DistanceField& field);

  /// The lattice's spacing for @p index and @p params, in the cloud's units: deltaLattice times h,
  /// or with a scale per point times the smallest h_i (every region sampled at least as finely).
  static double spacingFor(const PointIndex& index, const SurfaceParameters& params);

  /// The interpolated delta at y.
  double value(const Vec3& y, Workspace& ws) const;
  /// The interpolated delta, its gradient, and its second derivative along the unit @p a.
  DeltaJet jet(const Vec3& y, const Vec3& a, Workspace& ws) const;

private:
  /// The interpolant at y (with its gradient and Hessian when asked); false, with nothing
  /// computed, where the cell indices would overflow (coordinates beyond 2^50 cells, NaN).
  template <bool WithDerivatives>
  bool interpolate(const Vec3& y, Workspace& ws, double& value, Vec3* gradient, Mat3* hessian) const;
  /// The brick of @p key, added (empty) when the table lacks it.
  LatticeCache::Brick& brickAt(const LatticeCache::BrickKey& key, Workspace& ws) const;
  /// Node @p local of @p brick (whose key is @p key) once it is ready, computed by this thread
  /// or waited for while another computes it; returns its state (Ready or ReadyFromBeyond).
  std::uint8_t readyNode(LatticeCache::Brick& brick, const LatticeCache::BrickKey& key, int local, Workspace& ws) const;
  /// Writes node @p local's data: copied from a neighbouring brick that shares it, else
  /// computed; returns the state it is to take.
  std::uint8_t computeNode(LatticeCache::Brick& brick, const LatticeCache::BrickKey& key, int local, Workspace& ws) const;

  const DistanceField& Field;
  double Spacing; ///< in the cloud's units
  bool Planar;
};

/// Start points per occupied lattice brick from which the lattice pays: a projection far from any
/// other computes some 2,000 nodes of its own (docs/paper.md, "Reading: the integral energy's
/// fast path"), so a start set thinner than this is projected on the exact path. Measured on 200
/// bunny points (h 1 mm, 2 threads): 1.04 starts per brick, lattice 1.35x the exact path's time;
/// 1.9 per brick (each start twice, jittered), 0.86x; 3.3 per brick, 0.51x.
constexpr double LatticeStartsPerBrick = 1.5;

/**
 * The bricks (LatticeCache::BrickCells cells of DeltaLattice::spacingFor a side) that hold the
 * finite members of @p points, as sorted unique keys: the brick's three integer coordinates, 21
 * bits each, wrapped (a collision merges two bricks' counts; the rule stays a function of the
 * start set). In 2D (the index's dimension) z is ignored.
 */
std::vector<std::uint64_t> latticeBrickKeys(
  const std::vector<Vec3>& points, const PointIndex& index, const SurfaceParameters& params);

/// The rule on a whole start set: @p starts start points that occupy @p bricks bricks are
/// projected with the lattice when they number at least LatticeStartsPerBrick per brick.
bool latticeServes(std::size_t starts, std::size_t bricks);

} // namespace pss

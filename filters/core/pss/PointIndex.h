// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointIndex.h
 * @brief A k-d tree (nanoflann) over a point cloud in 2D (xy-plane) or 3D.
 *
 * Built once, then queried concurrently from any number of threads: every query is const and
 * keeps its scratch space on the caller's side (forEachLeafInBall takes it as an argument).
 *
 * Points with a NaN or infinite coordinate are not indexed; skippedCount() says how many were
 * dropped. The indexed points are stored in the tree's leaf order (spatially coherent), so index
 * i is generally not input point i: originalId() maps an indexed point back to its position in
 * the input. In 2D every z coordinate (of points and of queries) is taken as zero.
 */
#pragma once

#include "pss/Types.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace pss
{

class PointIndex
{
public:
  /// @param points the cloud (taken by value: move a large cloud in, the index keeps its memory);
  /// @param dimension 2 (xy-plane) or 3. Throws std::invalid_argument for any other dimension;
  /// @param threads threads the construction may use (0 = all cores). The index is the same, bit
  /// for bit, for every count; the default 1 keeps a caller that does not ask on its own thread.
  PointIndex(std::vector<Vec3> points, int dimension, int threads = 1);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  int dimension() const { return Dimension; }
  std::size_t size() const { return Points.size(); }
  bool empty() const { return Points.empty(); }
  /// Number of input points dropped because a coordinate was NaN or infinite.
  std::size_t skippedCount() const { return Skipped; }

  const Vec3& point(std::size_t i) const { return Points[i]; }
  const std::vector<Vec3>& points() const { return Points; }
  /// Index in the constructor's input of indexed point @p i.
  std::size_t originalId(std::size_t i) const { return OriginalIds[i]; }

  /// An order to visit the indexed cloud's own points in, neighbours together.
  struct VisitingOrder
  {
    /// Every position in points() once, in spatialOrder() of points().
    std::vector<std::uint32_t> positions;
    /// Every index of the constructor's input once: originalId() of each position above, then
    /// the skipped points in ascending order.
    std::vector<std::uint32_t> ids;
  };
  /// The Morton order, not the leaf order: within a leaf the tree's partitioning leaves points in
  /// no order, and projections visited leaf by leaf fetched candidates twice as often (the bunny:
  /// 0.56 fetches per point against 0.26). Computed on @p threads threads (0 = all cores), the
  /// same for every count.
  VisitingOrder visitingOrder(int threads = 1) const;

  /// Centroid and axis-aligned bounds of the indexed points (zero when empty).
  const Vec3& centroid() const { return Centroid; }
  const Vec3& boundsMin() const { return BoundsMin; }
  const Vec3& boundsMax() const { return BoundsMax; }

  /**
   * In a distributed run the index holds a rank's piece of the cloud plus ghost points: every
   * cloud point inside the box [lo, hi] (a side at -inf/+inf is open: the cloud has no point
   * beyond it), but not the points outside. Default: the whole space, i.e. the whole cloud.
   */
  void setCompleteRegion(const Vec3& lo, const Vec3& hi);
  /// True when the ball of radius @p r around @p c lies inside the complete region, so that a
  /// query of that ball sees exactly the points the whole cloud has there.
  bool holdsBall(const Vec3& c, double r) const;

  /**
   * Orders the points of every neighbourhood by their coordinates (x, then y, then z), not by
   * their place in this index, when @p on. A neighbourhood's sums then add the same terms in the
   * same order in any index that holds the same points around it: a rank's piece plus its ghost
   * points gives bitwise what the whole cloud gives. Costs a sort of the points once and of the
   * candidates at each k-d tree fetch (see CandidateCache::fetch). Off by default.
   */
  void setCoordinateOrder(bool on);
  bool coordinateOrder() const { return CoordinateOrder; }
  /// With coordinateOrder(): point @p i's place in the coordinate order (equal points, whose
  /// terms are equal, are ranked by index).
  std::uint32_t coordinateRank(std::size_t i) const { return CoordinateRanks[i]; }

  /// A number no other PointIndex of this process has: a safe cache key (addresses get reused).
  /// setScales() gives the index a new one, since every cached neighbourhood changes.
  std::uint64_t serial() const { return Serial; }

  /**
   * Per-point scales: @p scales[i] is the Gaussian scale h_i of input point i (the constructor's
   * input order; the entries of skipped points are not read). With scales, every weight is
   * theta_i(y) = exp(-|y - p_i|^2 / h_i^2) (docs/paper.md, "A scale per point"). Throws
   * std::invalid_argument when the size is not the input's or when a scale of an indexed point is
   * not a positive finite number (naming the first such point). An empty vector removes them.
   */
  void setScales(const std::vector<double>& scales);
  bool hasScales() const { return !Scales.empty(); }
  /// h_i of indexed point @p i (with hasScales()).
  double scale(std::size_t i) const { return Scales[i]; }
  /// 1 / h_i^2 of indexed point @p i (with hasScales()).
  double inverseSqScale(std::size_t i) const { return InverseSqScales[i]; }
  /// The smallest and largest h_i (0 without scales).
  double minScale() const { return MinScale; }
  double maxScale() const { return MaxScale; }

  /**
   * Oriented normals, one per input point (the constructor's input order; entries of skipped
   * points are not read), for the definitions that fit points with normals (APSS, RIMLS). Stored
   * as unit vectors (in 2D their z is dropped first). Throws std::invalid_argument when the size
   * is not the input's or when the normal of an indexed point is zero, NaN or infinite (naming
   * the first such point). An empty vector removes them. Defined in OrientedNeighbourhood.cxx.
   */
  void setNormals(const std::vector<Vec3>& normals);
  bool hasNormals() const { return !Normals.empty(); }
  /// The unit normal of indexed point @p i (with hasNormals()).
  const Vec3& normal(std::size_t i) const { return Normals[i]; }

  /// Drops z in 2D; leaves 3D points untouched.
  Vec3 restrict(const Vec3& x) const { return restrictTo(Dimension, x); }
  /// The same for a cloud of @p dimension, without an index (e.g. before a distributed run has one).
  static Vec3 restrictTo(int dimension, const Vec3& x) { return dimension == 2 ? Vec3(x.x(), x.y(), 0.0) : x; }

  /// Nearest indexed point to @p x: (index, squared distance). Requires !empty().
  std::pair<std::size_t, double> nearest(const Vec3& x) const;

  /// The @p k nearest points, closest first, as (index, squared distance).
  void kNearest(const Vec3& x, std::size_t k, std::vector<std::pair<std::uint32_t, double>>& out) const;

  /// All points with squared distance to @p x strictly below @p sqRadius, unsorted.
  void withinSqRadius(const Vec3& x, double sqRadius, std::vector<std::pair<std::uint32_t, double>>& out) const;

  /// The leaf ranges forEachLeafInBall collects: its caller's scratch, kept between queries so
  /// that its capacity is reused.
  using LeafRanges = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

  /**
   * Calls @p visit(begin, end) for ranges of consecutive indices, in ascending order, that
   * together hold every point with squared distance to @p x strictly below @p sqRadius (and may
   * hold a few more: the caller filters). The ranges are the tree's leaves whose bounding boxes
   * reach the ball; since points are stored in leaf order, visiting leaves left to right gives
   * indices already sorted, which spares the caller a sort. The ranges are collected in
   * @p scratch (its contents before the call do not matter).
   */
  template <class Visit>
  void forEachLeafInBall(const Vec3& x, double sqRadius, LeafRanges& scratch, Visit&& visit) const
  {
    leavesInBall(x, sqRadius, scratch);
    for (const auto& r : scratch)
    {
      visit(r.first, r.second);
    }
  }

  /**
   * With scales: like forEachLeafInBall, ranges that hold every point p_i with
   * |p_i - x| < margin + sigma h_i (the tree's nodes keep the largest h_i below them, so a region
   * of small scales is not searched as widely as one of large scales).
   */
  template <class Visit>
  void forEachLeafInScaledBall(const Vec3& x, double margin, double sigma, LeafRanges& scratch, Visit&& visit) const
  {
    leavesInScaledBall(x, margin, sigma, scratch);
    for (const auto& r : scratch)
    {
      visit(r.first, r.second);
    }
  }

private:
  struct Tree;
  /// A new serial(): every neighbourhood cached for this index is stale.
  void renewSerial();
  /// The leaves for forEachLeafInBall, into @p ranges.
  void leavesInBall(const Vec3& x, double sqRadius, LeafRanges& ranges) const;
  void leavesInScaledBall(const Vec3& x, double margin, double sigma, LeafRanges& ranges) const;
  /// One entry per tree node in depth-first order (low child first): the largest h_i below it
  /// and the number of nodes in its subtree (so a walk that skips a subtree knows where the next
  /// one starts).
  struct NodeScale
  {
    double maxScale = 0.0;
    std::uint32_t nodes = 1;
  };
  int Dimension;
  std::vector<Vec3> Points;
  std::vector<std::uint32_t> OriginalIds; // fits: at most 2^32 - 2 points
  std::size_t Skipped = 0;
  std::uint64_t Serial = 0;
  bool CoordinateOrder = false;
  std::vector<std::uint32_t> CoordinateRanks; // with CoordinateOrder: rank of point i
  Vec3 Centroid = Vec3::Zero();
  Vec3 BoundsMin = Vec3::Zero();
  Vec3 BoundsMax = Vec3::Zero();
  std::vector<double> Scales;          // leaf order
  std::vector<double> InverseSqScales; // leaf order
  std::vector<NodeScale> NodeScales;
  std::vector<Vec3> Normals; // leaf order
  double MinScale = 0.0;
  double MaxScale = 0.0;
  Vec3 CompleteLo = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec3 CompleteHi = Vec3::Constant(std::numeric_limits<double>::infinity());
  std::unique_ptr<Tree> Impl;
};

/**
 * A visiting order for @p points that keeps neighbours together: ascending Morton (Z-order) code
 * of each point's cell in a 2^21 grid over the points' bounding box, ties in input order, points
 * with a NaN or infinite coordinate last (in input order). Projections visited in this order reuse each other's
 * cached neighbours, and memory is read coherently, whatever order the input came in.
 * Computed on @p threads threads (0 = all cores); the order is the same for every count.
 * Throws std::invalid_argument beyond 2^32 - 1 points.
 */
std::vector<std::uint32_t> spatialOrder(const std::vector<Vec3>& points, int threads = 1);

/// True when all three coordinates are finite.
bool isFinite(const Vec3& x);

/// The bounds (lo, hi) of the points whose coordinates are all finite; +inf and -inf when there is
/// none. Runs on @p threads threads (0 = all cores), the same bounds for every count.
std::pair<Vec3, Vec3> finiteBounds(const std::vector<Vec3>& points, int threads = 1);

/**
 * 2 when every finite point has the same z (to 1e-12 of the cloud's extent), else 3: the rule
 * behind Dimension = Auto. An empty cloud counts as 3. Runs on @p threads threads (0 = all cores).
 */
int detectDimension(const std::vector<Vec3>& points, int threads = 1);

/// The same rule from the finite points' bounds [lo, hi] (lo.x > hi.x: no finite point), which
/// a distributed run reduces over its ranks.
int detectDimension(const Vec3& lo, const Vec3& hi);

/**
 * The automatic scale: h = multiplier * median over points of the distance to their k-th nearest
 * neighbour (k >= 1; at most 2000 evenly spread points are measured, so the cost stays small).
 * With the defaults k = 10, multiplier = 1 this is about 5 spacings along a curve and 1.8
 * spacings on a surface, enough neighbours for every definition to be defined near the cloud.
 * Returns 0 when the cloud has fewer than k + 1 distinct points. The queries run on @p threads
 * threads (0 = all cores); h is the same for every count.
 */
double estimateScale(const PointIndex& index, int k = 10, double multiplier = 1.0, int threads = 1);

/**
 * A scale per point (for PointIndex::setScales; input order, NaN for skipped points): the distance
 * from each point to its @p k-th nearest neighbour, replaced @p smoothing times by the median of
 * the values over the point and its k nearest neighbours (so the scale follows the density but
 * not the jitter of one neighbourhood), at most @p maxRatio times their median, times
 * @p multiplier. With even density every h_i is near estimateScale's h. The cap is for isolated
 * points (outliers, a few stray returns far behind the scene): their k-th neighbour is far, and
 * such a scale would let them reach, and cost, every evaluation across the frame and hold up a
 * surface far from the data; 6 leaves a depth camera's range (0.6 to 3 m, spacing 5 times apart)
 * alone. Points whose neighbours all coincide with them take the smallest positive scale.
 * Throws std::invalid_argument for k < 1, smoothing < 0, a multiplier or maxRatio that is not
 * positive (maxRatio may be infinite: no cap), or fewer than k + 1 points. The same for every
 * thread count.
 */
std::vector<double> estimateLocalScales(const PointIndex& index, int k = 10, double multiplier = 1.0,
  int smoothing = 2, int threads = 1, double maxRatio = 6.0);

/**
 * The local point spacing, in two steps so that a caller with its own loop (the mesher's stages)
 * can run them: rawSpacing() is sqrt(pi / k) times the distance from index point @p i to its
 * @p k-th nearest other point (the side of the square each sample covers: a square grid of
 * spacing s gives 1.02 s with k = 12), and fills @p neighbours with those k (index order);
 * smoothedSpacing() is the median of @p raw over the point and those neighbours. It follows the
 * density, also where a depth frame's quantization puts the points in stripes. 0 when the cloud
 * has no k other points. The mesher's trim (MeshOptions::trimDistance) and the reference-free
 * mesh metric measure distances in it.
 */
double rawSpacing(const PointIndex& index, std::size_t i, std::size_t k, std::vector<std::uint32_t>& neighbours,
  std::vector<std::pair<std::uint32_t, double>>& scratch);
double smoothedSpacing(const std::vector<double>& raw, std::size_t i, const std::uint32_t* neighbours, std::size_t k,
  std::vector<double>& scratch);
/// Both steps for every point (index order), on @p threads threads.
std::vector<double> estimateLocalSpacings(const PointIndex& index, std::size_t k = 12, int threads = 1);

/// How much the positive finite @p scales vary: their 90th percentile over their 10th (1 when
/// there is none). The automatic scale mode compares it to a threshold (docs/paper.md).
double scaleSpread(const std::vector<double>& scales);

/// Clouds above this many points have their scales' spread measured on a sample. The sample
/// costs about 0.1 s whatever the cloud, every point's scale about 1 us a point on 2 threads: at
/// 10^6 points the index stage took 0.37 s against 1.14 s, the spread 1.36 either way (the
/// bunny's scans, 362,272 points: 0.16 against 0.36 s, spread 1.42 against 1.41).
constexpr std::size_t ScaleSpreadSampledAbove = std::size_t{ 1 } << 18;
/// How many evenly spread points (in index order) that sample holds.
constexpr std::size_t ScaleSpreadSamples = 4096;

/**
 * scaleSpread(estimateLocalScales(index, k, 1, smoothing, threads, maxRatio)) without the scales
 * of every point: up to ScaleSpreadSampledAbove points it is exactly that; above, the same
 * scales (each point's k-th neighbour distance, median-smoothed @p smoothing times over its k
 * nearest, capped at maxRatio times the median) are computed at ScaleSpreadSamples points only,
 * evenly spread in index order (Morton order at that size), from the neighbourhoods they
 * depend on: at 10^7 points about 250,000 neighbour queries instead of 10^7, and none of the n * k
 * neighbour table. The same for every thread count.
 */
double estimateScaleSpread(const PointIndex& index, int k = 10, int smoothing = 2, int threads = 1, double maxRatio = 6.0);

} // namespace pss

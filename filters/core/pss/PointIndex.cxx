// SPDX-License-Identifier: BSD-3-Clause
#include "pss/PointIndex.h"

#include "pss/ChunkedLoops.h"
#include "pss/Memory.h"
#include "pss/NanoflannInternals.h" // nanoflann, and the internals PointIndex reads
#include "pss/Parallel.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>
#include <stdexcept>
#include <variant>

namespace pss
{

namespace
{

// nanoflann reads coordinates through this adaptor; in 2D it simply never asks for z.
struct CloudAdaptor
{
  const std::vector<Vec3>* points = nullptr;
  // The cloud's bounds, already known: nanoflann would otherwise spend a serial pass over every
  // point finding the same values (min and max are exact, so the tree does not change).
  const Vec3* boundsMin = nullptr;
  const Vec3* boundsMax = nullptr;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*points)[i][static_cast<int>(dim)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox& box) const
  {
    for (std::size_t d = 0; d < box.size(); ++d)
    {
      box[d].low = (*boundsMin)[static_cast<int>(d)];
      box[d].high = (*boundsMax)[static_cast<int>(d)];
    }
    return true;
  }
};

template <int D>
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>,
  CloudAdaptor, D, std::uint32_t>;

} // namespace

struct PointIndex::Tree
{
  CloudAdaptor adaptor;
  std::variant<std::unique_ptr<KdTree<2>>, std::unique_ptr<KdTree<3>>> tree;

  template <class Fn>
  void visit(Fn&& fn) const
  {
    std::visit([&](const auto& t) { fn(*t); }, tree);
  }
};

bool isFinite(const Vec3& x)
{
  return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
}

void PointIndex::setCompleteRegion(const Vec3& lo, const Vec3& hi)
{
  CompleteLo = lo;
  CompleteHi = hi;
}

void PointIndex::setCoordinateOrder(bool on)
{
  CoordinateOrder = on;
  CoordinateRanks = {};
  if (!on)
  {
    return;
  }
  // One comparison sort on one thread, once per prepared index (a rank prepares its piece and
  // ghosts once per round).
  std::vector<std::uint32_t> byRank(Points.size());
  std::iota(byRank.begin(), byRank.end(), 0u);
  // A total order on the values: -0.0 before +0.0, so that points whose terms differ only in the
  // sign of a zero are still told apart; equal points (duplicates) by index, which cannot change
  // a sum since their terms are the same.
  const auto less = [](double a, double b) { return a < b || (a == b && std::signbit(a) && !std::signbit(b)); };
  std::sort(byRank.begin(), byRank.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Vec3& p = Points[a];
    const Vec3& q = Points[b];
    for (int d = 0; d < 3; ++d)
    {
      if (less(p[d], q[d]))
      {
        return true;
      }
      if (less(q[d], p[d]))
      {
        return false;
      }
    }
    return a < b;
  });
  CoordinateRanks.resize(Points.size());
  for (std::size_t r = 0; r < byRank.size(); ++r)
  {
    CoordinateRanks[byRank[r]] = static_cast<std::uint32_t>(r);
  }
}

bool PointIndex::holdsBall(const Vec3& c, double r) const
{
  // Written so that a NaN radius or centre counts as outside (and an open side never limits).
  for (int a = 0; a < Dimension; ++a)
  {
    if (!(c[a] - r >= CompleteLo[a]) || !(c[a] + r <= CompleteHi[a]))
    {
      return false;
    }
  }
  return true;
}

int detectDimension(const std::vector<Vec3>& points, int threads)
{
  const auto [lo, hi] = finiteBounds(points, threads);
  return detectDimension(lo, hi);
}

int detectDimension(const Vec3& lo, const Vec3& hi)
{
  if (!(lo.x() <= hi.x()))
  {
    return 3;
  }
  const double extent = (hi - lo).maxCoeff();
  return hi.z() - lo.z() <= 1e-12 * extent ? 2 : 3;
}

namespace
{

// out[i] = in[order[i]] through @p scratch (then holding the old values; large clouds are permuted
// twice). Its reads jump, so both buffers are on huge pages (pss/Memory.h); one write per i.
template <class T, class Index>
void permute(std::vector<T>& values, const std::vector<Index>& order, std::vector<T>& scratch, int threads)
{
  resizeOnHugePages(scratch, values.size());
  forEachRange(order.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      scratch[i] = values[order[i]];
    }
  });
  values.swap(scratch);
}

// values[i] = i for every i.
void fillIota(std::vector<std::uint32_t>& values, int threads)
{
  forEachRange(values.size(), threads, [&](std::size_t begin, std::size_t end) {
    std::iota(values.begin() + static_cast<std::ptrdiff_t>(begin), values.begin() + static_cast<std::ptrdiff_t>(end),
      static_cast<std::uint32_t>(begin));
  });
}

// Serials for PointIndex::serial(): unique within the process.
std::uint64_t nextSerial()
{
  static std::atomic<std::uint64_t> counter{ 0 };
  return ++counter;
}

} // namespace

PointIndex::PointIndex(std::vector<Vec3> points, int dimension, int threads)
  : Dimension(dimension)
  , Points(std::move(points))
{
  Serial = nextSerial();
  if (dimension != 2 && dimension != 3)
  {
    throw std::invalid_argument("PointIndex: dimension must be 2 or 3, got " + std::to_string(dimension));
  }
  if (Points.size() >= std::size_t(UINT32_MAX))
  {
    throw std::invalid_argument("PointIndex: more than 2^32 - 1 points are not supported");
  }
  std::vector<Vec3> scratchPoints;
  std::vector<std::uint32_t> scratchIds;
  // Keep the finite points in input order: each chunk counts its own, and the counts of the
  // chunks before it say where its points go.
  const Chunks chunks(Points.size(), threads);
  std::vector<std::size_t> offset(chunks.count + 1, 0);
  chunks.run(threads, [&](std::size_t c, std::size_t begin, std::size_t end) {
    offset[c + 1] = static_cast<std::size_t>(
      std::count_if(Points.begin() + static_cast<std::ptrdiff_t>(begin), Points.begin() + static_cast<std::ptrdiff_t>(end),
        [](const Vec3& p) { return isFinite(p); }));
  });
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  const std::size_t finite = offset.back();
  Skipped = Points.size() - finite;
  resizeOnHugePages(OriginalIds, finite);
  if (Skipped == 0)
  {
    fillIota(OriginalIds, threads);
    if (Dimension == 2)
    {
      forEachRange(Points.size(), threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
        {
          Points[i] = restrict(Points[i]);
        }
      });
    }
  }
  else
  {
    // Into the scratch buffer, not in place: a chunk's points would land where the chunk before
    // it may still be reading.
    scratchPoints.resize(finite);
    chunks.run(threads, [&](std::size_t c, std::size_t begin, std::size_t end) {
      std::size_t to = offset[c];
      for (std::size_t i = begin; i < end; ++i)
      {
        if (isFinite(Points[i]))
        {
          scratchPoints[to] = restrict(Points[i]);
          OriginalIds[to] = static_cast<std::uint32_t>(i);
          ++to;
        }
      }
    });
    Points.swap(scratchPoints);
  }
  if (!Points.empty())
  {
    // Serial on purpose: the centroid is a floating-point sum, whose bits depend on the order of
    // its terms, and the bounds come for free in the same pass.
    Vec3 sum = Vec3::Zero();
    BoundsMin = BoundsMax = Points.front();
    for (const Vec3& p : Points)
    {
      sum += p;
      BoundsMin = BoundsMin.cwiseMin(p);
      BoundsMax = BoundsMax.cwiseMax(p);
    }
    Centroid = sum / static_cast<double>(Points.size());
  }

  // A cloud too large for the processor's caches is sorted in spatial order before the tree is
  // built: the construction partitions index ranges again and again, and with nearby points at
  // nearby addresses those ranges stay in cache (10^7 points: 4.8-6.7 s in input order, 1.1 s in
  // this order). Smaller clouds keep their input order, in which the build is as fast: the tree's
  // leaf order (and so the points estimateScale samples, and the automatic h) stays what it was.
  // A fixed count, not the machine's cache size, so that results do not depend on the machine.
  constexpr std::size_t SortedBuildThreshold = std::size_t(1) << 20; // 24 MiB of coordinates
  if (Points.size() > SortedBuildThreshold)
  {
    std::vector<std::uint32_t> order = spatialOrder(Points, threads);
    permute(Points, order, scratchPoints, threads);
    if (Skipped == 0)
    {
      OriginalIds = std::move(order); // the ids are the identity, permuted: the order itself
    }
    else
    {
      permute(OriginalIds, order, scratchIds, threads);
    }
  }
  Impl = std::make_unique<Tree>();
  Impl->adaptor.points = &Points;
  Impl->adaptor.boundsMin = &BoundsMin;
  Impl->adaptor.boundsMax = &BoundsMax;
  // Leaves of up to 64 points: the neighbourhoods here hold hundreds of points, and walking fewer,
  // larger leaves costs less than filtering the few more points they bring (measured on the
  // bunny: 16 -> 64 made the plane-procedure projection about 15% faster). nanoflann 1.4 builds
  // the tree on one thread.
  const nanoflann::KDTreeSingleIndexAdaptorParams params(64);
  if (Dimension == 2)
  {
    Impl->tree = std::make_unique<KdTree<2>>(2, Impl->adaptor, params);
  }
  else
  {
    Impl->tree = std::make_unique<KdTree<3>>(3, Impl->adaptor, params);
  }
  // Store the points in the tree's leaf order: every leaf then covers a contiguous range of
  // indices, so a neighbourhood reads nearby memory. The tree's nodes refer to positions in its
  // permutation, which becomes the identity.
  std::visit(
    [&](auto& tree) {
      auto& permutation = nanoflann_internals::permutation(*tree);
      permute(Points, permutation, scratchPoints, threads);
      permute(OriginalIds, permutation, scratchIds, threads);
      fillIota(permutation, threads);
    },
    Impl->tree);
}

PointIndex::~PointIndex() = default;

PointIndex::VisitingOrder PointIndex::visitingOrder(int threads) const
{
  VisitingOrder out;
  out.positions = spatialOrder(Points, threads);
  out.ids.resize(OriginalIds.size());
  forEachRange(OriginalIds.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      out.ids[k] = OriginalIds[out.positions[k]];
    }
  });
  if (Skipped == 0)
  {
    return out;
  }
  out.ids.reserve(OriginalIds.size() + Skipped);
  std::vector<bool> indexed(OriginalIds.size() + Skipped, false);
  for (const std::uint32_t id : OriginalIds)
  {
    indexed[id] = true;
  }
  for (std::size_t id = 0; id < indexed.size(); ++id)
  {
    if (!indexed[id])
    {
      out.ids.push_back(static_cast<std::uint32_t>(id));
    }
  }
  return out;
}

std::pair<std::size_t, double> PointIndex::nearest(const Vec3& x) const
{
  if (Points.empty())
  {
    throw std::logic_error("PointIndex::nearest on an empty index");
  }
  const Vec3 q = restrict(x);
  std::uint32_t index = 0;
  double sqDist = 0.0;
  Impl->visit([&](const auto& tree) {
    nanoflann::KNNResultSet<double, std::uint32_t> result(1);
    result.init(&index, &sqDist);
    tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
  });
  return { index, sqDist };
}

void PointIndex::kNearest(
  const Vec3& x, std::size_t k, std::vector<std::pair<std::uint32_t, double>>& out) const
{
  out.clear();
  k = std::min(k, Points.size());
  if (k == 0)
  {
    return;
  }
  const Vec3 q = restrict(x);
  std::vector<std::uint32_t> ids(k);
  std::vector<double> d2(k);
  std::size_t found = 0;
  Impl->visit([&](const auto& tree) { found = tree.knnSearch(q.data(), k, ids.data(), d2.data()); });
  out.reserve(found);
  for (std::size_t i = 0; i < found; ++i)
  {
    out.emplace_back(ids[i], d2[i]);
  }
}

void PointIndex::withinSqRadius(
  const Vec3& x, double sqRadius, std::vector<std::pair<std::uint32_t, double>>& out) const
{
  out.clear();
  if (Points.empty())
  {
    return;
  }
  const Vec3 q = restrict(x);
  nanoflann::SearchParams params;
  params.sorted = false;
  Impl->visit([&](const auto& tree) { tree.radiusSearch(q.data(), sqRadius, out, params); });
}

namespace
{

// Left-to-right walk of the nodes whose boxes come closer to q than sqrt(sqRadius). dist[d] is
// the squared distance from q to the current box along axis d, so their sum bounds the distance
// to every point below the node (the boxes narrow as the walk descends: see nanoflann's own
// searchLevel, which walks the nearer child first instead and so yields unsorted indices).
template <class Node, int D>
void collectLeaves(const Node* node, const double* q, double sqRadius, double boxSqDist,
  std::array<double, D>& dist, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out)
{
  namespace nf = nanoflann_internals;
  if (nf::isLeaf(*node))
  {
    out.emplace_back(static_cast<std::uint32_t>(nf::leafBegin(*node)), static_cast<std::uint32_t>(nf::leafEnd(*node)));
    return;
  }
  const int axis = nf::axis(*node);
  const double saved = dist[axis];
  // The low child holds the points with coordinate <= low, the high child those >= high.
  const double below = q[axis] - nf::low(*node);
  const double first = below > 0.0 ? below * below : saved;
  if (boxSqDist - saved + first < sqRadius)
  {
    dist[axis] = first;
    collectLeaves<Node, D>(nf::lowChild(*node), q, sqRadius, boxSqDist - saved + first, dist, out);
  }
  const double above = nf::high(*node) - q[axis];
  const double second = above > 0.0 ? above * above : saved;
  if (boxSqDist - saved + second < sqRadius)
  {
    dist[axis] = second;
    collectLeaves<Node, D>(nf::highChild(*node), q, sqRadius, boxSqDist - saved + second, dist, out);
  }
  dist[axis] = saved;
}

// collectLeaves for PointIndex::leavesInScaledBall: a node is entered when its box comes closer
// to q than margin + sigma times the largest h_i below it. @p at is the node's place in the
// depth-first table of NodeScales (its low child follows it, its high child follows the low
// child's subtree).
template <class Node, int D, class NodeScale>
void collectScaledLeaves(const Node* node, const NodeScale* table, std::size_t at, const double* q, double margin,
  double sigma, double boxSqDist, std::array<double, D>& dist, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out)
{
  namespace nf = nanoflann_internals;
  if (nf::isLeaf(*node))
  {
    out.emplace_back(static_cast<std::uint32_t>(nf::leafBegin(*node)), static_cast<std::uint32_t>(nf::leafEnd(*node)));
    return;
  }
  const auto reaches = [&](std::size_t child, double sqDist) {
    const double r = margin + sigma * table[child].maxScale;
    return sqDist < r * r;
  };
  const int axis = nf::axis(*node);
  const double saved = dist[axis];
  const std::size_t lowAt = at + 1;
  const std::size_t highAt = lowAt + table[lowAt].nodes;
  const double below = q[axis] - nf::low(*node);
  const double first = below > 0.0 ? below * below : saved;
  if (reaches(lowAt, boxSqDist - saved + first))
  {
    dist[axis] = first;
    collectScaledLeaves<Node, D>(
      nf::lowChild(*node), table, lowAt, q, margin, sigma, boxSqDist - saved + first, dist, out);
  }
  const double above = nf::high(*node) - q[axis];
  const double second = above > 0.0 ? above * above : saved;
  if (reaches(highAt, boxSqDist - saved + second))
  {
    dist[axis] = second;
    collectScaledLeaves<Node, D>(
      nf::highChild(*node), table, highAt, q, margin, sigma, boxSqDist - saved + second, dist, out);
  }
  dist[axis] = saved;
}

// Appends @p node's subtree to @p table in depth-first order (low child first) with the largest
// of @p scales below each node; returns that largest scale.
template <class Node, class NodeScale>
double tabulateScales(const Node* node, const std::vector<double>& scales, std::vector<NodeScale>& table)
{
  namespace nf = nanoflann_internals;
  const std::size_t at = table.size();
  table.emplace_back();
  double largest = 0.0;
  if (nf::isLeaf(*node))
  {
    for (std::size_t i = nf::leafBegin(*node); i < nf::leafEnd(*node); ++i)
    {
      largest = std::max(largest, scales[i]);
    }
  }
  else
  {
    // Two statements: the low child's subtree must be appended first.
    const double low = tabulateScales(nf::lowChild(*node), scales, table);
    largest = std::max(low, tabulateScales(nf::highChild(*node), scales, table));
  }
  table[at].maxScale = largest;
  table[at].nodes = static_cast<std::uint32_t>(table.size() - at);
  return largest;
}

} // namespace

void PointIndex::leavesInBall(const Vec3& x, double sqRadius, LeafRanges& ranges) const
{
  ranges.clear();
  if (Points.empty())
  {
    return;
  }
  const Vec3 q = restrict(x);
  Impl->visit([&](const auto& tree) {
    using Tree = std::decay_t<decltype(tree)>;
    const auto& box = nanoflann_internals::rootBox(tree);
    constexpr int D = static_cast<int>(std::tuple_size<std::decay_t<decltype(box)>>::value);
    std::array<double, D> dist{};
    double boxSqDist = 0.0;
    for (int d = 0; d < D; ++d)
    {
      const double lo = box[d].low - q[d];
      const double hi = q[d] - box[d].high;
      const double gap = std::max({ lo, hi, 0.0 });
      dist[d] = gap * gap;
      boxSqDist += dist[d];
    }
    if (boxSqDist < sqRadius)
    {
      collectLeaves<nanoflann_internals::Node<Tree>, D>(
        nanoflann_internals::rootNode(tree), q.data(), sqRadius, boxSqDist, dist, ranges);
    }
  });
}

void PointIndex::renewSerial() { Serial = nextSerial(); }

void PointIndex::setScales(const std::vector<double>& scales)
{
  renewSerial();
  Scales.clear();
  InverseSqScales.clear();
  NodeScales.clear();
  MinScale = MaxScale = 0.0;
  if (scales.empty())
  {
    return;
  }
  if (scales.size() != Points.size() + Skipped)
  {
    throw std::invalid_argument("the scale array has " + std::to_string(scales.size()) + " values for " +
      std::to_string(Points.size() + Skipped) + " points");
  }
  std::vector<double> ordered(Points.size());
  for (std::size_t i = 0; i < Points.size(); ++i)
  {
    const double h = scales[OriginalIds[i]];
    if (!(h > 0.0) || !std::isfinite(h) || !std::isfinite(1.0 / (h * h)) || !(1.0 / (h * h) > 0.0))
    {
      throw std::invalid_argument("the scale of point " + std::to_string(OriginalIds[i]) +
        " must be a positive finite number whose inverse square is too, got " + std::to_string(h));
    }
    ordered[i] = h;
  }
  Scales = std::move(ordered);
  InverseSqScales.resize(Scales.size());
  for (std::size_t i = 0; i < Scales.size(); ++i)
  {
    InverseSqScales[i] = 1.0 / (Scales[i] * Scales[i]);
  }
  const auto [lo, hi] = std::minmax_element(Scales.begin(), Scales.end());
  MinScale = *lo;
  MaxScale = *hi;
  if (!Points.empty())
  {
    Impl->visit([&](const auto& tree) {
      using Node = nanoflann_internals::Node<std::decay_t<decltype(tree)>>;
      tabulateScales<Node>(nanoflann_internals::rootNode(tree), Scales, NodeScales);
    });
  }
}

void PointIndex::leavesInScaledBall(const Vec3& x, double margin, double sigma, LeafRanges& ranges) const
{
  ranges.clear();
  if (Points.empty() || NodeScales.empty())
  {
    return;
  }
  const Vec3 q = restrict(x);
  Impl->visit([&](const auto& tree) {
    using Tree = std::decay_t<decltype(tree)>;
    const auto& box = nanoflann_internals::rootBox(tree);
    constexpr int D = static_cast<int>(std::tuple_size<std::decay_t<decltype(box)>>::value);
    std::array<double, D> dist{};
    double boxSqDist = 0.0;
    for (int d = 0; d < D; ++d)
    {
      const double gap = std::max({ box[d].low - q[d], q[d] - box[d].high, 0.0 });
      dist[d] = gap * gap;
      boxSqDist += dist[d];
    }
    const double r = margin + sigma * NodeScales.front().maxScale;
    if (boxSqDist < r * r)
    {
      collectScaledLeaves<nanoflann_internals::Node<Tree>, D>(
        nanoflann_internals::rootNode(tree), NodeScales.data(), 0, q.data(), margin, sigma, boxSqDist, dist, ranges);
    }
  });
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
#include "pss/SurfaceMesh.h"

#include "pss/Parallel.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numeric>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace pss
{

void MeshOptions::validate() const
{
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(cellSize))
  {
    throw std::invalid_argument("the mesh cell size must be a positive finite multiple of h");
  }
  if (!positive(band))
  {
    throw std::invalid_argument("the mesh band must be a positive finite multiple of h");
  }
  if (!positive(maxVertexTravel))
  {
    throw std::invalid_argument("the mesh's largest vertex travel must be a positive finite number of cells");
  }
  if (!(maxSeamAngle >= 0.0 && maxSeamAngle <= 180.0) || !(maxFoldAngle >= 0.0 && maxFoldAngle <= 180.0))
  {
    throw std::invalid_argument("the mesh's seam and fold angles must be in [0, 180] degrees");
  }
  if (!(minPieceArea >= 0.0 && std::isfinite(minPieceArea)))
  {
    throw std::invalid_argument("the mesh's smallest piece area must be a finite number of h^2, at least 0");
  }
  if (maxBandCells == 0)
  {
    throw std::invalid_argument("the mesh's largest band must be at least one cell");
  }
  projection.validate();
  domain.validate();
}

namespace
{

using Key = std::uint64_t;
using Coords = std::array<long long, 3>;

// Keys of a grid of size S, with the axes ordered fastest first by `order`.
struct KeyOrder
{
  std::array<int, 3> order;
  Coords size;

  Key encode(const Coords& c) const
  {
    return (static_cast<Key>(c[order[2]]) * size[order[1]] + c[order[1]]) * size[order[0]] + c[order[0]];
  }
  Coords decode(Key k) const
  {
    Coords c{};
    c[order[0]] = static_cast<long long>(k % size[order[0]]);
    k /= size[order[0]];
    c[order[1]] = static_cast<long long>(k % size[order[1]]);
    c[order[2]] = static_cast<long long>(k / size[order[1]]);
    return c;
  }
};

// Calls visit(first, last) for the maximal runs of keys [first, last] covered by the sorted @p keys
// each widened by [-low, +high] along the fastest axis of @p o (clamped to the grid), in order.
template <class Visit>
void forEachWidenedRun(const std::vector<Key>& keys, const KeyOrder& o, long long low, long long high, Visit&& visit)
{
  const Key width = static_cast<Key>(o.size[o.order[0]]);
  std::size_t i = 0;
  while (i < keys.size())
  {
    const Key line = keys[i] / width;
    const Key base = line * width;
    long long first = std::max(0LL, static_cast<long long>(keys[i] % width) - low);
    long long last = std::min(static_cast<long long>(width) - 1, static_cast<long long>(keys[i] % width) + high);
    for (++i; i < keys.size() && keys[i] / width == line; ++i)
    {
      const long long pos = static_cast<long long>(keys[i] % width);
      if (pos - low > last + 1)
      {
        visit(base + first, base + last);
        first = std::max(0LL, pos - low);
      }
      last = std::min(static_cast<long long>(width) - 1, pos + high);
    }
    visit(base + first, base + last);
  }
}

// Re-keys @p keys (in order @p from) by @p to, sorted.
std::vector<Key> rekey(const std::vector<Key>& keys, const KeyOrder& from, const KeyOrder& to)
{
  std::vector<Key> out(keys.size());
  std::transform(keys.begin(), keys.end(), out.begin(), [&](Key k) { return to.encode(from.decode(k)); });
  std::sort(out.begin(), out.end());
  return out;
}

// Widens every key along each axis in turn (a separable dilation of the set of cells), ending in
// the canonical order (x fastest). Refuses, before allocating, a result above @p limit keys.
std::vector<Key> widen(std::vector<Key> keys, const Coords& size, int dimension, long long low, long long high,
  std::size_t limit, const std::string& what)
{
  KeyOrder current{ { 0, 1, 2 }, size };
  for (int axis = dimension - 1; axis >= 0; --axis)
  {
    KeyOrder next{ { axis, axis == 0 ? 1 : 0, axis == 2 ? 1 : 2 }, size };
    keys = rekey(keys, current, next);
    std::size_t count = 0;
    forEachWidenedRun(keys, next, low, high, [&](Key a, Key b) { count += static_cast<std::size_t>(b - a + 1); });
    if (count > limit)
    {
      std::ostringstream msg;
      msg << "the mesh " << what << " would have more than " << count << " cells (the limit is " << limit
          << "): use a larger cell size or a narrower band";
      throw std::invalid_argument(msg.str());
    }
    std::vector<Key> widened;
    widened.reserve(count);
    forEachWidenedRun(keys, next, low, high, [&](Key a, Key b) {
      for (Key k = a; k <= b; ++k)
      {
        widened.push_back(k);
      }
    });
    keys = std::move(widened);
    current = next;
  }
  if (current.order != std::array<int, 3>{ { 0, 1, 2 } })
  {
    keys = rekey(keys, current, KeyOrder{ { 0, 1, 2 }, size });
  }
  return keys;
}

// A disjoint-set forest for counting connected pieces.
class UnionFind
{
public:
  explicit UnionFind(std::size_t n) : Parent(n) { std::iota(Parent.begin(), Parent.end(), 0); }
  std::size_t find(std::size_t x)
  {
    while (Parent[x] != x)
    {
      Parent[x] = Parent[Parent[x]];
      x = Parent[x];
    }
    return x;
  }
  void unite(std::size_t a, std::size_t b)
  {
    a = find(a);
    b = find(b);
    if (a != b)
    {
      Parent[std::max(a, b)] = std::min(a, b);
    }
  }

private:
  std::vector<std::size_t> Parent;
};

constexpr std::uint32_t NoIndex = static_cast<std::uint32_t>(-1);

} // namespace

SurfaceMesher::SurfaceMesher(const SurfaceDefinition& surface, const MeshOptions& options)
  : Surface(surface)
  , Options(options)
  , Normals(surface)
{
  Options.validate();
  Dimension = surface.dimension();
  Cell = Options.cellSize * surface.h();
  buildBand();
}

SurfaceMesher::Key SurfaceMesher::keyOf(const std::array<long long, 3>& c) const
{
  return KeyOrder{ { 0, 1, 2 }, Size }.encode(c);
}

std::array<long long, 3> SurfaceMesher::coordsOf(Key k) const
{
  return KeyOrder{ { 0, 1, 2 }, Size }.decode(k);
}

Vec3 SurfaceMesher::positionOf(Key k) const
{
  const Coords c = coordsOf(k);
  Vec3 x = Origin;
  for (int a = 0; a < Dimension; ++a)
  {
    x[a] += static_cast<double>(c[a]) * Cell;
  }
  return x;
}

void SurfaceMesher::linkNeighbours()
{
  // Keys + stride is sorted like Keys, so one merge finds every neighbour along an axis.
  const std::size_t n = Keys.size();
  Key stride = 1;
  for (int a = 0; a < Dimension; ++a)
  {
    std::vector<std::uint32_t>& up = Step[2 * a];
    std::vector<std::uint32_t>& down = Step[2 * a + 1];
    up.assign(n, NoIndex);
    down.assign(n, NoIndex);
    std::size_t j = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Key target = Keys[i] + stride;
      while (j < n && Keys[j] < target)
      {
        ++j;
      }
      if (j < n && Keys[j] == target)
      {
        up[i] = static_cast<std::uint32_t>(j);
        down[j] = static_cast<std::uint32_t>(i);
      }
    }
    stride *= static_cast<Key>(Size[a]);
  }
  CellCorner.resize(Cells.size());
  std::size_t j = 0;
  for (std::size_t c = 0; c < Cells.size(); ++c)
  {
    while (Keys[j] < Cells[c])
    {
      ++j;
    }
    CellCorner[c] = static_cast<std::uint32_t>(j);
  }
}

void SurfaceMesher::buildBand()
{
  const PointIndex& index = Surface.index();
  const double ratio = Options.band / Options.cellSize;
  if (ratio > 1e5)
  {
    throw std::invalid_argument("the mesh band is more than 1e5 cells wide: use a larger cell size");
  }
  const long long reach = static_cast<long long>(std::ceil(ratio));
  // Axis lengths leave room for the band and the cells' far corners on either side.
  std::ostringstream dims;
  for (int a = 0; a < 3; ++a)
  {
    if (a >= Dimension)
    {
      Size[a] = 1;
      continue;
    }
    const double cells = std::floor((index.boundsMax()[a] - index.boundsMin()[a]) / Cell) + 2.0 * reach + 3.0;
    dims << (a > 0 ? " x " : "") << cells;
    if (!(cells <= static_cast<double>(1LL << 20)))
    {
      throw std::invalid_argument("the mesh grid over the cloud's bounds would be " + dims.str() +
        " cells, more than 2^20 along an axis: use a larger cell size");
    }
    Size[a] = static_cast<long long>(cells);
    Origin[a] = index.boundsMin()[a] - static_cast<double>(reach + 1) * Cell;
  }

  std::vector<Key> occupied(index.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    Coords c{ { 0, 0, 0 } };
    for (int a = 0; a < Dimension; ++a)
    {
      // Clamped to the cells the axis lengths were sized for: rounding in p - Origin may add one.
      c[a] = std::clamp(static_cast<long long>(std::floor((index.point(i)[a] - Origin[a]) / Cell)), reach + 1,
        Size[a] - reach - 2);
    }
    occupied[i] = keyOf(c);
  }
  std::sort(occupied.begin(), occupied.end());
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());

  Cells = widen(std::move(occupied), Size, Dimension, reach, reach, Options.maxBandCells, "band");
  Keys = widen(Cells, Size, Dimension, 0, 1, 2 * Options.maxBandCells, "band's corners");
  Values.assign(Keys.size(), CornerValue{});
  linkNeighbours();
  Statistics.bandCells = Cells.size();
  Statistics.gridVertices = Keys.size();
}

void SurfaceMesher::evaluateVertex(std::size_t i, Workspace& ws)
{
  const Vec3 x = positionOf(Keys[i]);
  const Direction d = Surface.direction(x, ws);
  CornerValue& v = Values[i];
  v.defined = d.defined;
  if (d.defined)
  {
    v.n = d.n;
    v.g = Surface.lineSample(x, d.n, ws).trueSlope();
    v.defined = std::isfinite(v.g);
  }
}

void SurfaceMesher::orient()
{
  const std::size_t n = Keys.size();
  Sign.assign(n, 0);
  const Orientation away = Orientation::awayFromCentroid(Surface.index());
  // Max-heap of (|n_a . n_b|, b, a): the most parallel edge out of the oriented set goes first.
  using Edge = std::tuple<double, std::uint32_t, std::uint32_t>;
  std::priority_queue<Edge> heap;
  auto pushNeighbours = [&](std::size_t v) {
    for (int k = 0; k < 2 * Dimension; ++k)
    {
      const std::uint32_t w = Step[k][v];
      if (w != NoIndex && Values[w].defined && Sign[w] == 0)
      {
        heap.emplace(std::abs(Values[v].n.dot(Values[w].n)), w, static_cast<std::uint32_t>(v));
      }
    }
  };
  for (std::size_t seed = 0; seed < n; ++seed)
  {
    if (!Values[seed].defined || Sign[seed] != 0)
    {
      continue;
    }
    const Vec3& ns = Values[seed].n;
    Sign[seed] = away.apply(ns, positionOf(Keys[seed])).dot(ns) < 0.0 ? -1 : 1;
    pushNeighbours(seed);
    while (!heap.empty())
    {
      const auto [weight, to, from] = heap.top();
      heap.pop();
      (void)weight;
      if (Sign[to] != 0)
      {
        continue;
      }
      Sign[to] = static_cast<signed char>(Values[to].n.dot(Values[from].n) * Sign[from] < 0.0 ? -1 : 1);
      pushNeighbours(to);
    }
  }
}

std::uint32_t SurfaceMesher::crossingOn(std::uint32_t a, std::uint32_t b, int direction)
{
  std::uint32_t& slot = CrossingOfEdge[7 * static_cast<std::size_t>(a) + static_cast<std::size_t>(direction - 1)];
  if (slot != NoIndex)
  {
    return slot;
  }
  const double fa = Values[a].g * Sign[a];
  const double fb = Values[b].g * Sign[b];
  // Clamped away from the corners so that the crossings of edges sharing a corner stay apart.
  const double t = std::clamp(fa / (fa - fb), 1e-3, 1.0 - 1e-3);
  Crossing c;
  c.point = positionOf(Keys[a]) + t * (positionOf(Keys[b]) - positionOf(Keys[a]));
  c.reference = (t < 0.5 ? Values[a].n * Sign[a] : Values[b].n * Sign[b]);
  // Minimum or maximum of e along n (Eq. 2's g rises through a minimum): read off the edge when it
  // runs clearly along n, not across it.
  const Vec3 edge = (positionOf(Keys[b]) - positionOf(Keys[a])).normalized();
  const double along = edge.dot(Values[a].n * Sign[a] + Values[b].n * Sign[b]) / 2.0;
  if (std::abs(along) > 0.2)
  {
    c.type = (fb - fa) * along > 0.0 ? ExtremumType::Minimum : ExtremumType::Maximum;
  }
  slot = static_cast<std::uint32_t>(Crossings.size());
  Crossings.push_back(std::move(c));
  return slot;
}

void SurfaceMesher::contourSimplex(const std::array<std::uint32_t, 4>& corners, const std::array<int, 4>& bits, int count)
{
  std::array<double, 4> f{};
  int positives = 0;
  for (int k = 0; k < count; ++k)
  {
    if (!Values[corners[k]].defined)
    {
      return;
    }
    f[k] = Values[corners[k]].g * Sign[corners[k]];
    positives += f[k] > 0.0 ? 1 : 0;
  }
  if (positives == 0 || positives == count)
  {
    return;
  }
  const double seamCos = std::cos(Options.maxSeamAngle * M_PI / 180.0);
  for (int a = 0; a < count; ++a)
  {
    for (int b = a + 1; b < count; ++b)
    {
      const CornerValue& va = Values[corners[a]];
      const CornerValue& vb = Values[corners[b]];
      if (va.n.dot(vb.n) * Sign[corners[a]] * Sign[corners[b]] < seamCos)
      {
        ++Statistics.seamSimplices;
        return;
      }
    }
  }
  // From the negative corners' centroid to the positive ones': the surface's cells are wound
  // counter-clockwise about it.
  Vec3 positiveSum = Vec3::Zero();
  Vec3 negativeSum = Vec3::Zero();
  for (int k = 0; k < count; ++k)
  {
    (f[k] > 0.0 ? positiveSum : negativeSum) += positionOf(Keys[corners[k]]);
  }
  const Vec3 towardPositive = positiveSum / positives - negativeSum / (count - positives);
  std::array<int, 4> pos{};
  std::array<int, 4> neg{};
  int np = 0;
  int nn = 0;
  for (int k = 0; k < count; ++k)
  {
    (f[k] > 0.0 ? pos[np++] : neg[nn++]) = k;
  }
  // The simplex's corners go up one axis at a time, so the lower end of an edge is the earlier one.
  auto cross = [&](int p, int q) {
    const int lo = std::min(p, q);
    const int hi = std::max(p, q);
    return crossingOn(corners[lo], corners[hi], bits[hi] & ~bits[lo]);
  };
  if (count == 3)
  {
    // 2D: one segment between the two edges that leave the lone corner.
    const int lone = np == 1 ? pos[0] : neg[0];
    const int o1 = np == 1 ? neg[0] : pos[0];
    const int o2 = np == 1 ? neg[1] : pos[1];
    std::array<std::uint32_t, 2> s{ { cross(lone, o1), cross(lone, o2) } };
    const Vec3 d = Crossings[s[1]].point - Crossings[s[0]].point;
    if (Vec3(-d.y(), d.x(), 0.0).dot(towardPositive) < 0.0)
    {
      std::swap(s[0], s[1]);
    }
    Segments.push_back(s);
    return;
  }
  auto addTriangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vec3 normal =
      (Crossings[b].point - Crossings[a].point).cross(Crossings[c].point - Crossings[a].point);
    if (normal.dot(towardPositive) < 0.0)
    {
      std::swap(b, c);
    }
    Triangles.push_back({ { a, b, c } });
  };
  if (np == 1 || nn == 1)
  {
    const int lone = np == 1 ? pos[0] : neg[0];
    std::array<int, 3> others{};
    int m = 0;
    for (int k = 0; k < 4; ++k)
    {
      if (k != lone)
      {
        others[m++] = k;
      }
    }
    addTriangle(cross(lone, others[0]), cross(lone, others[1]), cross(lone, others[2]));
    return;
  }
  // Two corners on each side: a quadrilateral around the cycle p0-n0, p0-n1, p1-n1, p1-n0.
  const std::uint32_t q0 = cross(pos[0], neg[0]);
  const std::uint32_t q1 = cross(pos[0], neg[1]);
  const std::uint32_t q2 = cross(pos[1], neg[1]);
  const std::uint32_t q3 = cross(pos[1], neg[0]);
  addTriangle(q0, q1, q2);
  addTriangle(q0, q2, q3);
}

void SurfaceMesher::contour()
{
  if (Sign.size() != Keys.size())
  {
    throw std::logic_error("SurfaceMesher::contour() before orient()");
  }
  const int cornersPerCell = 1 << Dimension;
  // Kuhn's subdivision: one simplex per ordering of the axes, walking from corner 0 to the far
  // corner one axis at a time.
  std::vector<std::array<int, 3>> orders;
  std::array<int, 3> axes{ { 0, 1, 2 } };
  do
  {
    orders.push_back(axes);
  } while (std::next_permutation(axes.begin(), axes.begin() + Dimension));
  CrossingOfEdge.assign(7 * Keys.size(), NoIndex);
  // About one crossing per band cell and two triangles per crossing on a surface (measured: the
  // bunny 1.08 and 1.97): reserved so that they do not grow by copying.
  Crossings.reserve(Cells.size() + Cells.size() / 4);
  if (Dimension == 3)
  {
    Triangles.reserve(2 * Crossings.capacity());
  }
  std::array<std::uint32_t, 8> corner{};
  for (const std::uint32_t lowest : CellCorner)
  {
    // Every corner of a band cell is a grid vertex, so these steps never fall off the band.
    for (int bits = 0; bits < cornersPerCell; ++bits)
    {
      std::uint32_t v = lowest;
      for (int a = 0; a < Dimension && v != NoIndex; ++a)
      {
        v = (bits >> a) & 1 ? Step[2 * a][v] : v;
      }
      if (v == NoIndex)
      {
        throw std::logic_error("SurfaceMesher: a band cell lacks a corner (a bug: please report it)");
      }
      corner[bits] = v;
    }
    for (const auto& order : orders)
    {
      std::array<std::uint32_t, 4> simplex{};
      std::array<int, 4> bits{};
      simplex[0] = corner[0];
      for (int k = 0; k < Dimension; ++k)
      {
        bits[k + 1] = bits[k] | (1 << order[k]);
        simplex[k + 1] = corner[bits[k + 1]];
      }
      contourSimplex(simplex, bits, Dimension + 1);
    }
  }
  Statistics.crossings = Crossings.size();
  Statistics.undefinedVertices = static_cast<std::size_t>(
    std::count_if(Values.begin(), Values.end(), [](const CornerValue& v) { return !v.defined; }));
  // What only the grid stages need goes before the projections, the stage with the largest state.
  Evidence.assign(Crossings.size(), DomainEvidence{});
  CrossingOfEdge = {};
  Step = {};
  CellCorner = {};
  Values = {};
}

void SurfaceMesher::classifyCrossing(std::size_t i, Workspace& ws)
{
  Evidence[i] = classifyStart(Surface, Crossings[i].point, Options.projection, Options.domain, ws, &Normals);
}

namespace
{

// Keeps the cells @p keep accepts and renumbers the vertices they use, in their old order
// (newIndex: old vertex -> new, or -1 when unused).
template <std::size_t K, class Keep>
std::vector<std::array<std::uint32_t, K>> keepCells(const std::vector<std::array<std::uint32_t, K>>& cells,
  std::size_t vertices, Keep&& keep, std::vector<std::uint32_t>& newIndex)
{
  std::vector<std::array<std::uint32_t, K>> out;
  std::copy_if(cells.begin(), cells.end(), std::back_inserter(out), keep);
  std::vector<char> used(vertices, 0);
  for (const auto& cell : out)
  {
    for (std::uint32_t v : cell)
    {
      used[v] = 1;
    }
  }
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < used.size(); ++v)
  {
    newIndex[v] = used[v] ? next++ : static_cast<std::uint32_t>(-1);
  }
  for (auto& cell : out)
  {
    for (std::uint32_t& v : cell)
    {
      v = newIndex[v];
    }
  }
  return out;
}

double cellMeasure(const std::array<std::uint32_t, 3>& t, const std::vector<Vec3>& points)
{
  return 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
}

double cellMeasure(const std::array<std::uint32_t, 2>& s, const std::vector<Vec3>& points)
{
  return (points[s[1]] - points[s[0]]).norm();
}

// The connected pieces of a mesh's cells (triangles or segments): which piece each vertex is in
// (the root of its set), the measure (area or length) of each piece at its root, -1 where no piece
// is rooted, and the total, summed in the cells' order.
struct Pieces
{
  UnionFind sets;
  std::vector<double> measure;
  double total = 0.0;
};

template <std::size_t K>
Pieces piecesOf(const std::vector<std::array<std::uint32_t, K>>& cells, const std::vector<Vec3>& points)
{
  Pieces p{ UnionFind(points.size()), std::vector<double>(points.size(), -1.0), 0.0 };
  for (const auto& c : cells)
  {
    for (std::size_t k = 1; k < K; ++k)
    {
      p.sets.unite(c[0], c[k]);
    }
  }
  for (const auto& c : cells)
  {
    const double m = cellMeasure(c, points);
    double& root = p.measure[p.sets.find(c[0])];
    root = std::max(root, 0.0) + m;
    p.total += m;
  }
  return p;
}

// Per vertex: whether the connected piece of @p triangles it belongs to has an area of at least
// @p minArea; counts the smaller pieces in @p smallPieces.
std::vector<char> largePieces(const std::vector<std::array<std::uint32_t, 3>>& triangles,
  const std::vector<Vec3>& points, double minArea, std::size_t& smallPieces)
{
  Pieces pieces = piecesOf(triangles, points);
  smallPieces = static_cast<std::size_t>(std::count_if(pieces.measure.begin(), pieces.measure.end(),
    [minArea](double a) { return a >= 0.0 && a < minArea; }));
  std::vector<char> large(points.size());
  for (std::size_t v = 0; v < points.size(); ++v)
  {
    large[v] = pieces.measure[pieces.sets.find(v)] >= minArea ? 1 : 0;
  }
  return large;
}

// The sides of @p triangles grouped by their edge's lower vertex: for a vertex v, entries
// first[v] .. first[v + 1] - 1 of `ends` are (higher vertex, whether the side runs from v to it),
// sorted, one per triangle side (an edge of two triangles appears twice). Bucketed by vertex
// rather than sorted as a whole: several times faster on a million triangles.
struct EdgeList
{
  std::vector<std::uint32_t> first;
  std::vector<std::pair<std::uint32_t, bool>> ends;
};

EdgeList edgesOf(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::size_t vertices)
{
  EdgeList e;
  e.first.assign(vertices + 1, 0);
  for (const auto& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++e.first[std::min(t[k], t[(k + 1) % 3]) + 1];
    }
  }
  std::partial_sum(e.first.begin(), e.first.end(), e.first.begin());
  e.ends.resize(3 * triangles.size());
  std::vector<std::uint32_t> next(e.first.begin(), e.first.end() - 1);
  for (const auto& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      e.ends[next[std::min(a, b)]++] = { std::max(a, b), a < b };
    }
  }
  for (std::size_t v = 0; v < vertices; ++v)
  {
    std::sort(e.ends.begin() + e.first[v], e.ends.begin() + e.first[v + 1]);
  }
  return e;
}

// Calls visit(lower, higher, sides, forward) for every distinct edge of @p e: how many triangle
// sides it has and, for one side, whether that side runs from lower to higher.
template <class Visit>
void forEachEdge(const EdgeList& e, Visit&& visit)
{
  for (std::size_t v = 0; v + 1 < e.first.size(); ++v)
  {
    for (std::uint32_t i = e.first[v]; i < e.first[v + 1];)
    {
      std::uint32_t j = i + 1;
      while (j < e.first[v + 1] && e.ends[j].first == e.ends[i].first)
      {
        ++j;
      }
      visit(static_cast<std::uint32_t>(v), e.ends[i].first, j - i, e.ends[i].second);
      i = j;
    }
  }
}

} // namespace

void countTopology(SurfaceMesh& mesh)
{
  MeshStatistics& st = mesh.statistics;
  st.boundaryEdges = st.nonManifoldEdges = 0;
  const std::size_t nv = mesh.points.size();
  const bool surface = mesh.dimension == 3;
  const std::size_t cells = surface ? mesh.triangles.size() : mesh.segments.size();
  const Pieces pieces = surface ? piecesOf(mesh.triangles, mesh.points) : piecesOf(mesh.segments, mesh.points);
  st.components = 0;
  st.measure = pieces.total;
  st.largestComponentMeasure = 0.0;
  for (const double m : pieces.measure)
  {
    st.components += m >= 0.0 ? 1 : 0;
    st.largestComponentMeasure = std::max(st.largestComponentMeasure, m);
  }
  std::size_t distinct = 0;
  if (surface)
  {
    forEachEdge(edgesOf(mesh.triangles, nv), [&](std::uint32_t, std::uint32_t, std::uint32_t sides, bool) {
      ++distinct;
      st.boundaryEdges += sides == 1 ? 1 : 0;
      st.nonManifoldEdges += sides > 2 ? 1 : 0;
    });
  }
  else
  {
    // In 2D the border is the polylines' ends: vertices of one segment (three or more: a branch).
    std::vector<std::uint32_t> degree(nv, 0);
    for (const auto& seg : mesh.segments)
    {
      ++degree[seg[0]];
      ++degree[seg[1]];
    }
    for (const std::uint32_t d : degree)
    {
      st.boundaryEdges += d == 1 ? 1 : 0;
      st.nonManifoldEdges += d > 2 ? 1 : 0;
    }
  }
  st.eulerCharacteristic = surface
    ? static_cast<long long>(nv) - static_cast<long long>(distinct) + static_cast<long long>(cells)
    : static_cast<long long>(nv) - static_cast<long long>(cells);
}

SurfaceMesh SurfaceMesher::finish(Workspace& ws)
{
  SurfaceMesh mesh;
  mesh.dimension = Dimension;
  const std::size_t n = Crossings.size();
  std::vector<char> keep(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Crossing& c = Crossings[i];
    const DomainEvidence& ev = Evidence[i];
    const bool inDomain = ev.label == DomainLabel::InDomain;
    const bool near = (ev.projection.point - c.point).norm() <= Options.maxVertexTravel * Cell;
    const ExtremumType unwanted = Options.projection.seekMaxima ? ExtremumType::Minimum : ExtremumType::Maximum;
    const bool wanted = c.type != unwanted;
    Statistics.maximumCrossings += wanted ? 0 : 1;
    keep[i] = inDomain && near && wanted ? 1 : 0;
    Statistics.droppedVertices += keep[i] ? 0 : 1;
  }
  std::vector<Vec3> point(n);
  std::vector<Vec3> normal(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Direction& d = Evidence[i].projection.direction;
    point[i] = Options.projectVertices ? Evidence[i].projection.point : Crossings[i].point;
    normal[i] = d.defined ? (d.n.dot(Crossings[i].reference) < 0.0 ? Vec3(-d.n) : d.n) : Vec3::Zero();
  }
  // A cell whose own normal (from its final vertices) is more than maxFoldAngle off its vertices'
  // normals is folded over, or bridges two sheets whose crossings projected apart: dropped.
  // Degenerate cells (a tiny area or length) have no normal to judge and are kept.
  std::size_t folded = 0;
  auto keepTriangle = [&](const std::array<std::uint32_t, 3>& t) {
    if (!keep[t[0]] || !keep[t[1]] || !keep[t[2]])
    {
      return false;
    }
    const Vec3 face = (point[t[1]] - point[t[0]]).cross(point[t[2]] - point[t[0]]);
    const bool ok = isUnfolded(face, normal[t[0]] + normal[t[1]] + normal[t[2]]);
    folded += ok ? 0 : 1;
    return ok;
  };
  auto keepSegment = [&](const std::array<std::uint32_t, 2>& s) {
    if (!keep[s[0]] || !keep[s[1]])
    {
      return false;
    }
    const Vec3 d = point[s[1]] - point[s[0]];
    const bool ok = isUnfolded(Vec3(-d.y(), d.x(), 0.0), normal[s[0]] + normal[s[1]]);
    folded += ok ? 0 : 1;
    return ok;
  };
  std::vector<std::uint32_t> newIndex(n);
  if (Dimension == 3)
  {
    std::vector<std::array<std::uint32_t, 3>> kept;
    std::copy_if(Triangles.begin(), Triangles.end(), std::back_inserter(kept), keepTriangle);
    const double h = Surface.h();
    const std::vector<char> large =
      largePieces(kept, point, Options.minPieceArea * h * h, Statistics.removedPieces);
    mesh.triangles = keepCells(kept, n, [&](const std::array<std::uint32_t, 3>& t) { return large[t[0]] != 0; }, newIndex);
    Statistics.droppedSimplices = Triangles.size() - mesh.triangles.size();
  }
  else
  {
    mesh.segments = keepCells(Segments, n, keepSegment, newIndex);
    Statistics.droppedSimplices = Segments.size() - mesh.segments.size();
  }
  Statistics.foldedSimplices = folded;
  // The kept vertices move down in place (newIndex[i] <= i): the per-crossing arrays become the
  // mesh's without a second copy of the largest one (the evidence).
  std::vector<Vec3> crossing(n);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (newIndex[i] != NoIndex)
    {
      point[kept] = point[i];
      normal[kept] = normal[i];
      crossing[kept] = Crossings[i].point;
      Evidence[kept] = std::move(Evidence[i]);
      ++kept;
    }
  }
  for (auto* v : { &point, &normal, &crossing })
  {
    v->resize(kept);
  }
  Evidence.resize(kept);
  mesh.points = std::move(point);
  mesh.normals = std::move(normal);
  mesh.crossings = std::move(crossing);
  mesh.evidence = std::move(Evidence);
  Crossings = {};
  closeSmallHoles(mesh, ws);
  mesh.statistics = Statistics;
  countTopology(mesh);
  return mesh;
}

bool SurfaceMesher::isUnfolded(const Vec3& face, const Vec3& vertexNormals) const
{
  const double foldCos = std::cos(Options.maxFoldAngle * M_PI / 180.0);
  const double tiny = 1e-6 * Cell;
  return face.norm() <= tiny * (Dimension == 3 ? tiny : 1.0) ||
    face.dot(vertexNormals) >= foldCos * face.norm() * vertexNormals.norm();
}

std::vector<std::vector<std::uint32_t>> SurfaceMesher::smallHoles(const SurfaceMesh& mesh) const
{
  // A border edge is the side of one triangle; the hole beside it is walked from each border
  // vertex to the next, in the triangles' winding (a -> b where the triangle runs a -> b).
  const std::size_t nv = mesh.points.size();
  std::vector<std::uint32_t> next(nv, NoIndex);
  std::vector<char> pinched(nv, 0); // two border edges leave it: holes through it are left alone
  std::vector<std::uint32_t> starts;
  forEachEdge(edgesOf(mesh.triangles, nv), [&](std::uint32_t lower, std::uint32_t higher, std::uint32_t sides, bool forward) {
    if (sides == 1)
    {
      const std::uint32_t from = forward ? lower : higher;
      pinched[from] |= next[from] != NoIndex ? 1 : 0;
      next[from] = forward ? higher : lower;
      starts.push_back(from);
    }
  });
  std::vector<std::vector<std::uint32_t>> holes;
  std::vector<char> visited(nv, 0);
  for (const std::uint32_t start : starts)
  {
    std::vector<std::uint32_t> loop;
    bool simple = true;
    std::uint32_t v = start;
    while (v != NoIndex && !visited[v])
    {
      visited[v] = 1;
      simple = simple && !pinched[v];
      loop.push_back(v);
      v = next[v];
    }
    if (simple && v == start && loop.size() >= 3 && loop.size() <= Options.maxHoleEdges)
    {
      holes.push_back(std::move(loop));
    }
  }
  return holes;
}

void SurfaceMesher::closeSmallHoles(SurfaceMesh& mesh, Workspace& ws)
{
  if (Dimension != 3 || Options.maxHoleEdges < 3)
  {
    return;
  }
  for (const std::vector<std::uint32_t>& hole : smallHoles(mesh))
  {
    const std::size_t k = hole.size();
    Vec3 centre = Vec3::Zero();
    Vec3 normalSum = Vec3::Zero();
    for (const std::uint32_t v : hole)
    {
      centre += mesh.points[v] / static_cast<double>(k);
      normalSum += mesh.normals[v];
    }
    // The border's half-edges a -> b belong to the triangles around the hole: the triangles that
    // close it run b -> a, about a new vertex where the hole's centre projects (three borders
    // need none).
    std::vector<std::array<std::uint32_t, 3>> fill;
    DomainEvidence ev;
    Vec3 apex = centre;
    Vec3 apexNormal = normalSum;
    const auto apexIndex = static_cast<std::uint32_t>(mesh.points.size());
    if (k == 3)
    {
      fill.push_back({ { hole[0], hole[2], hole[1] } });
    }
    else
    {
      ev = classifyStart(Surface, centre, Options.projection, Options.domain, ws, &Normals);
      const Direction& d = ev.projection.direction;
      if (ev.label != DomainLabel::InDomain || (ev.projection.point - centre).norm() > Options.maxVertexTravel * Cell ||
        !d.defined)
      {
        continue;
      }
      apex = Options.projectVertices ? ev.projection.point : centre;
      apexNormal = d.n.dot(normalSum) < 0.0 ? Vec3(-d.n) : d.n;
      for (std::size_t i = 0; i < k; ++i)
      {
        fill.push_back({ { hole[(i + 1) % k], hole[i], apexIndex } });
      }
    }
    auto at = [&](std::uint32_t v) -> const Vec3& { return v == apexIndex ? apex : mesh.points[v]; };
    auto normalAt = [&](std::uint32_t v) -> const Vec3& { return v == apexIndex ? apexNormal : mesh.normals[v]; };
    const bool flat = std::all_of(fill.begin(), fill.end(), [&](const std::array<std::uint32_t, 3>& t) {
      const Vec3 face = (at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0]));
      return isUnfolded(face, normalAt(t[0]) + normalAt(t[1]) + normalAt(t[2]));
    });
    if (!flat)
    {
      continue;
    }
    if (k > 3)
    {
      mesh.points.push_back(apex);
      mesh.normals.push_back(apexNormal);
      mesh.evidence.push_back(std::move(ev));
      mesh.crossings.push_back(centre);
    }
    mesh.triangles.insert(mesh.triangles.end(), fill.begin(), fill.end());
    ++Statistics.closedHoles;
  }
}

std::optional<SurfaceMesh> extractSurfaceMesh(
  const SurfaceDefinition& surface, const MeshOptions& options, const ParallelLoop& loop, MeshTimings* timings)
{
  MeshTimings local;
  MeshTimings& t = timings ? *timings : local;
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&clock](double& seconds) {
    const auto now = std::chrono::steady_clock::now();
    seconds = std::chrono::duration<double>(now - clock).count();
    clock = now;
  };
  SurfaceMesher mesher(surface, options);
  lap(t.band);
  const bool cornersDone =
    loop(mesher.gridVertexCount(), LoopShare(0.0, 0.45), [&](std::size_t begin, std::size_t end, Workspace& ws) {
      for (std::size_t i = begin; i < end; ++i)
      {
        mesher.evaluateVertex(i, ws);
      }
    });
  if (!cornersDone)
  {
    return std::nullopt;
  }
  lap(t.corners);
  mesher.orient();
  lap(t.orient);
  mesher.contour();
  lap(t.contour);
  const bool crossingsDone =
    loop(mesher.crossingCount(), LoopShare(0.5, 0.98), [&](std::size_t begin, std::size_t end, Workspace& ws) {
      for (std::size_t i = begin; i < end; ++i)
      {
        mesher.classifyCrossing(i, ws);
      }
    });
  if (!crossingsDone)
  {
    return std::nullopt;
  }
  lap(t.projection);
  Workspace ws;
  SurfaceMesh mesh = mesher.finish(ws);
  lap(t.finish);
  return mesh;
}

SurfaceMesh extractSurfaceMesh(const SurfaceDefinition& surface, const MeshOptions& options, int threads, MeshTimings* timings)
{
  return *extractSurfaceMesh(surface, options, threadLoop(threads), timings); // threadLoop never stops early
}

} // namespace pss

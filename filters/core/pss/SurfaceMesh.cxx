// SPDX-License-Identifier: BSD-3-Clause
#include "pss/SurfaceMesh.h"

#include "pss/Parallel.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
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
  if (!(maxSeamAngle >= 0.0 && maxSeamAngle <= 180.0))
  {
    throw std::invalid_argument("the mesh's seam angle must be in [0, 180] degrees");
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

constexpr std::size_t NoVertex = static_cast<std::size_t>(-1);

} // namespace

std::size_t SurfaceMesher::EdgeHash::operator()(const std::pair<Key, Key>& e) const
{
  return static_cast<std::size_t>(e.first * 0x9E3779B97F4A7C15ULL ^ (e.second + 0x632BE59BD9B4E019ULL));
}

SurfaceMesher::SurfaceMesher(const SurfaceDefinition& surface, const MeshOptions& options)
  : Surface(surface)
  , Options(options)
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

std::size_t SurfaceMesher::vertexIndex(Key k) const
{
  const auto it = std::lower_bound(Keys.begin(), Keys.end(), k);
  return it != Keys.end() && *it == k ? static_cast<std::size_t>(it - Keys.begin()) : NoVertex;
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
      c[a] = std::clamp(static_cast<long long>(std::floor((index.point(i)[a] - Origin[a]) / Cell)), 0LL, Size[a] - 2);
    }
    occupied[i] = keyOf(c);
  }
  std::sort(occupied.begin(), occupied.end());
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());

  Cells = widen(std::move(occupied), Size, Dimension, reach, reach, Options.maxBandCells, "band");
  Keys = widen(Cells, Size, Dimension, 0, 1, 2 * Options.maxBandCells, "band's corners");
  Values.assign(Keys.size(), CornerValue{});
  Statistics.bandCells = Cells.size();
  Statistics.gridVertices = Keys.size();
}

void SurfaceMesher::evaluateVertex(std::size_t i)
{
  const Vec3 x = positionOf(Keys[i]);
  const Direction d = Surface.direction(x);
  CornerValue& v = Values[i];
  v.defined = d.defined;
  if (d.defined)
  {
    v.n = d.n;
    v.g = Surface.lineSample(x, d.n).trueSlope();
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
    const Coords c = coordsOf(Keys[v]);
    for (int a = 0; a < Dimension; ++a)
    {
      for (int step : { -1, 1 })
      {
        Coords d = c;
        d[a] += step;
        if (d[a] < 0 || d[a] >= Size[a])
        {
          continue;
        }
        const std::size_t w = vertexIndex(keyOf(d));
        if (w != NoVertex && Values[w].defined && Sign[w] == 0)
        {
          heap.emplace(std::abs(Values[v].n.dot(Values[w].n)), static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(v));
        }
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

std::uint32_t SurfaceMesher::crossingOn(std::size_t a, std::size_t b)
{
  if (Keys[a] > Keys[b])
  {
    std::swap(a, b);
  }
  const auto found = CrossingOfEdge.find({ Keys[a], Keys[b] });
  if (found != CrossingOfEdge.end())
  {
    return found->second;
  }
  const double fa = Values[a].g * Sign[a];
  const double fb = Values[b].g * Sign[b];
  // Clamped away from the corners so that the crossings of edges sharing a corner stay apart.
  const double t = std::clamp(fa / (fa - fb), 1e-3, 1.0 - 1e-3);
  Crossing c;
  c.point = positionOf(Keys[a]) + t * (positionOf(Keys[b]) - positionOf(Keys[a]));
  c.reference = (t < 0.5 ? Values[a].n * Sign[a] : Values[b].n * Sign[b]);
  const auto id = static_cast<std::uint32_t>(Crossings.size());
  Crossings.push_back(std::move(c));
  CrossingOfEdge.emplace(std::make_pair(Keys[a], Keys[b]), id);
  return id;
}

void SurfaceMesher::contourSimplex(const std::array<std::size_t, 4>& corners, int count)
{
  std::array<double, 4> f{};
  int positives = 0;
  for (int k = 0; k < count; ++k)
  {
    if (corners[k] == NoVertex || !Values[corners[k]].defined)
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
  // The side where the oriented g is positive: the surface's cells are wound around it.
  Vec3 towardPositive = Vec3::Zero();
  for (int k = 0; k < count; ++k)
  {
    towardPositive += (f[k] > 0.0 ? 1.0 : -1.0) * positionOf(Keys[corners[k]]);
  }
  std::array<int, 4> pos{};
  std::array<int, 4> neg{};
  int np = 0;
  int nn = 0;
  for (int k = 0; k < count; ++k)
  {
    (f[k] > 0.0 ? pos[np++] : neg[nn++]) = k;
  }
  auto cross = [&](int p, int q) { return crossingOn(corners[p], corners[q]); };
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
  std::array<std::size_t, 8> corner{};
  for (const Key cell : Cells)
  {
    const Coords c0 = coordsOf(cell);
    for (int bits = 0; bits < cornersPerCell; ++bits)
    {
      const Coords c{ { c0[0] + (bits & 1), c0[1] + ((bits >> 1) & 1), c0[2] + ((bits >> 2) & 1) } };
      corner[bits] = vertexIndex(keyOf(c));
    }
    for (const auto& order : orders)
    {
      std::array<std::size_t, 4> simplex{};
      int bits = 0;
      simplex[0] = corner[0];
      for (int k = 0; k < Dimension; ++k)
      {
        bits |= 1 << order[k];
        simplex[k + 1] = corner[bits];
      }
      contourSimplex(simplex, Dimension + 1);
    }
  }
  Statistics.crossings = Crossings.size();
  CrossingOfEdge.clear();
}

void SurfaceMesher::classifyCrossing(std::size_t i)
{
  Crossings[i].evidence = classifyStart(Surface, Crossings[i].point, Options.projection, Options.domain);
}

namespace
{

template <std::size_t K>
bool allKept(const std::array<std::uint32_t, K>& cell, const std::vector<char>& keep)
{
  return std::all_of(cell.begin(), cell.end(), [&](std::uint32_t v) { return keep[v] != 0; });
}

// Drops the cells with a dropped vertex and renumbers the kept vertices in their old order.
template <std::size_t K>
std::vector<std::array<std::uint32_t, K>> keepCells(const std::vector<std::array<std::uint32_t, K>>& cells,
  const std::vector<char>& keep, std::vector<std::uint32_t>& newIndex, std::size_t& dropped)
{
  std::vector<std::array<std::uint32_t, K>> out;
  for (const auto& cell : cells)
  {
    if (allKept(cell, keep))
    {
      out.push_back(cell);
    }
    else
    {
      ++dropped;
    }
  }
  std::vector<char> used(keep.size(), 0);
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

} // namespace

void countTopology(SurfaceMesh& mesh)
{
  MeshStatistics& st = mesh.statistics;
  st.components = st.boundaryEdges = st.nonManifoldEdges = 0;
  st.measure = st.largestComponentMeasure = 0.0;
  const std::size_t nv = mesh.points.size();
  UnionFind pieces(nv);
  std::vector<double> cellMeasure;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  if (mesh.dimension == 3)
  {
    for (const auto& t : mesh.triangles)
    {
      pieces.unite(t[0], t[1]);
      pieces.unite(t[0], t[2]);
      for (int k = 0; k < 3; ++k)
      {
        edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
      }
      cellMeasure.push_back(
        0.5 * (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]).norm());
    }
  }
  else
  {
    for (const auto& s : mesh.segments)
    {
      pieces.unite(s[0], s[1]);
      // In 2D the "edges" counted for the border are the polylines' vertices.
      edges.emplace_back(s[0], s[0]);
      edges.emplace_back(s[1], s[1]);
      cellMeasure.push_back((mesh.points[s[1]] - mesh.points[s[0]]).norm());
    }
  }
  std::sort(edges.begin(), edges.end());
  std::size_t distinct = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
    {
      ++j;
    }
    ++distinct;
    st.boundaryEdges += (j - i == 1) ? 1 : 0;
    st.nonManifoldEdges += (j - i > 2) ? 1 : 0;
    i = j;
  }
  const std::size_t cells = mesh.dimension == 3 ? mesh.triangles.size() : mesh.segments.size();
  st.eulerCharacteristic = mesh.dimension == 3
    ? static_cast<long long>(nv) - static_cast<long long>(distinct) + static_cast<long long>(cells)
    : static_cast<long long>(nv) - static_cast<long long>(cells);
  std::unordered_map<std::size_t, double> measureOf;
  for (std::size_t c = 0; c < cells; ++c)
  {
    const std::uint32_t v = mesh.dimension == 3 ? mesh.triangles[c][0] : mesh.segments[c][0];
    measureOf[pieces.find(v)] += cellMeasure[c];
    st.measure += cellMeasure[c];
  }
  st.components = measureOf.size();
  for (const auto& entry : measureOf)
  {
    st.largestComponentMeasure = std::max(st.largestComponentMeasure, entry.second);
  }
}

SurfaceMesh SurfaceMesher::finish()
{
  SurfaceMesh mesh;
  mesh.dimension = Dimension;
  const std::size_t n = Crossings.size();
  std::vector<char> keep(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Crossing& c = Crossings[i];
    const bool inDomain = c.evidence.label == DomainLabel::InDomain;
    const bool near = (c.evidence.projection.point - c.point).norm() <= Options.maxVertexTravel * Cell;
    keep[i] = inDomain && near ? 1 : 0;
    Statistics.droppedVertices += keep[i] ? 0 : 1;
  }
  std::vector<std::uint32_t> newIndex(n);
  if (Dimension == 3)
  {
    mesh.triangles = keepCells(Triangles, keep, newIndex, Statistics.droppedSimplices);
  }
  else
  {
    mesh.segments = keepCells(Segments, keep, newIndex, Statistics.droppedSimplices);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (newIndex[i] == static_cast<std::uint32_t>(-1))
    {
      continue;
    }
    const Crossing& c = Crossings[i];
    const Direction& d = c.evidence.projection.direction;
    mesh.points.push_back(Options.projectVertices ? c.evidence.projection.point : c.point);
    mesh.normals.push_back(d.defined ? (d.n.dot(c.reference) < 0.0 ? Vec3(-d.n) : d.n) : Vec3::Zero());
    mesh.evidence.push_back(c.evidence);
    mesh.crossings.push_back(c.point);
  }
  mesh.statistics = Statistics;
  mesh.statistics.undefinedVertices = static_cast<std::size_t>(
    std::count_if(Values.begin(), Values.end(), [](const CornerValue& v) { return !v.defined; }));
  countTopology(mesh);
  return mesh;
}

SurfaceMesh extractSurfaceMesh(const SurfaceDefinition& surface, const MeshOptions& options, int threads)
{
  SurfaceMesher mesher(surface, options);
  parallelFor(mesher.gridVertexCount(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      mesher.evaluateVertex(i);
    }
  });
  mesher.orient();
  mesher.contour();
  parallelFor(mesher.crossingCount(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      mesher.classifyCrossing(i);
    }
  });
  return mesher.finish();
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
// The mesher's last stage (SurfaceMesher::finish): keeping the triangles whose corners are in the
// domain, removing small pieces, closing small holes, and the topology and measures of the result.
// The band, the corners' values, the orientation and the contouring are in SurfaceMesh.cxx.
#include "pss/SurfaceMesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <vector>

namespace pss
{

namespace
{

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

} // namespace pss

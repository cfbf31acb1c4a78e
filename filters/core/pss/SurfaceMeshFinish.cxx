// SPDX-License-Identifier: BSD-3-Clause
// The mesher's last stage (SurfaceMesher::finish): keeping the triangles whose corners are in the
// domain, removing small pieces, closing small holes, and the topology and measures of the result.
// The band, the corners' values, the orientation and the contouring are in SurfaceMesh.cxx.
#include "pss/Kernel.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceMesh.h"
#include "pss/SurfaceMeshPieces.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <vector>

namespace pss
{

namespace
{

using namespace piece_utils;


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

// Per vertex: whether it is in a piece of @p triangles, other than the largest, smaller than
// @p maxArea, whose every vertex has for nearest vertex of the largest piece within @p reach an
// interior one (not on its border): a second layer over surface that the largest piece already
// covers. A piece beside a hole of the largest piece has border vertices of it nearest, and stays.
// Counts the covered pieces in @p coveredPieces.
std::vector<char> coveredPieces(const std::vector<std::array<std::uint32_t, 3>>& triangles, const std::vector<Vec3>& points,
  double maxArea, double reach, std::size_t& coveredPieces)
{
  coveredPieces = 0;
  std::vector<char> covered(points.size(), 0);
  if (maxArea <= 0.0 || triangles.empty())
  {
    return covered;
  }
  Pieces pieces = piecesOf(triangles, points);
  const auto largest = static_cast<std::size_t>(std::max_element(pieces.measure.begin(), pieces.measure.end()) - pieces.measure.begin());
  std::vector<char> used(points.size(), 0);
  for (const auto& t : triangles)
  {
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  const std::vector<char> border = borderVertices(triangles, points.size());
  // The largest piece's vertices in a k-d tree, to find each candidate's nearest.
  std::vector<Vec3> largestPoints;
  std::vector<std::uint32_t> largestVertex; // input position in largestPoints -> mesh vertex
  std::vector<std::uint32_t> candidates;    // vertices of small pieces other than the largest
  for (std::size_t v = 0; v < points.size(); ++v)
  {
    if (!used[v])
    {
      continue;
    }
    const std::size_t root = pieces.sets.find(v);
    if (root == largest)
    {
      largestPoints.push_back(points[v]);
      largestVertex.push_back(static_cast<std::uint32_t>(v));
    }
    else if (pieces.measure[root] < maxArea)
    {
      candidates.push_back(static_cast<std::uint32_t>(v));
    }
  }
  if (candidates.empty())
  {
    return covered;
  }
  const PointIndex largestIndex(largestPoints, 3);
  std::vector<char> uncovered(points.size(), 0); // per piece root: a vertex of it is not over the largest piece
  for (const std::uint32_t v : candidates)
  {
    const auto [i, sqDist] = largestIndex.nearest(points[v]);
    if (!(sqDist < reach * reach) || border[largestVertex[largestIndex.originalId(i)]])
    {
      uncovered[pieces.sets.find(v)] = 1;
    }
  }
  std::vector<char> counted(points.size(), 0);
  for (const std::uint32_t v : candidates)
  {
    const std::size_t root = pieces.sets.find(v);
    covered[v] = uncovered[root] ? 0 : 1;
    coveredPieces += covered[v] && !counted[root] ? 1 : 0;
    counted[root] = 1;
  }
  return covered;
}

} // namespace

std::vector<char> piece_utils::borderVertices(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::size_t vertices)
{
  std::vector<char> border(vertices, 0);
  forEachEdge(edgesOf(triangles, vertices), [&](std::uint32_t a, std::uint32_t b, std::uint32_t sides, bool) {
    if (sides == 1)
    {
      border[a] = border[b] = 1;
    }
  });
  return border;
}

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
  SurfaceMesh mesh = assemble();
  findHoles(mesh);
  for (std::size_t j = 0; j < holeCount(); ++j)
  {
    evaluateHole(j, ws);
  }
  closeHoles(mesh);
  for (beginSpacings(); spacingCount() > 0;)
  {
    for (std::size_t i = 0; i < spacingCount(); ++i)
    {
      evaluateSpacing(i, ws);
    }
    if (!nextSpacingPass())
    {
      break;
    }
  }
  for (beginTrim(mesh); trimSampleCount() > 0; refineTrim(mesh))
  {
    for (std::size_t i = 0; i < trimSampleCount(); ++i)
    {
      evaluateTrimSample(i, ws);
    }
  }
  cutFar(mesh);
  return mesh;
}

SurfaceMesh SurfaceMesher::assemble()
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
    const bool near = (ev.projection.point - c.point).norm() <= Options.maxVertexTravel * c.cell;
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
    const double h = Frame.h;
    const std::vector<char> large =
      largePieces(kept, point, Options.minPieceArea * h * h, Statistics.removedPieces);
    const std::vector<char> covered =
      coveredPieces(kept, point, Options.coveredPieceArea * h * h, 3.0 * h, Statistics.coveredPieces);
    mesh.triangles = keepCells(
      kept, n, [&](const std::array<std::uint32_t, 3>& t) { return large[t[0]] != 0 && covered[t[0]] == 0; }, newIndex);
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
  VertexCell.assign(n, 0.0);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (newIndex[i] != NoIndex)
    {
      VertexCell[kept] = Crossings[i].cell;
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
  VertexCell.resize(kept);
  Evidence.resize(kept);
  mesh.points = std::move(point);
  mesh.normals = std::move(normal);
  mesh.crossings = std::move(crossing);
  mesh.evidence = std::move(Evidence);
  Crossings = {};
  return mesh;
}

bool SurfaceMesher::isUnfolded(const Vec3& face, const Vec3& vertexNormals) const
{
  const double foldCos = std::cos(Options.maxFoldAngle * M_PI / 180.0);
  const double tiny = 1e-6 * Cell;
  return face.norm() <= tiny * (Dimension == 3 ? tiny : 1.0) ||
    face.dot(vertexNormals) >= foldCos * face.norm() * vertexNormals.norm();
}

bool SurfaceMesher::closesFlat(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& vertexNormals) const
{
  // A sliver (thinner than a tenth of a cell across its longest side) only has to face its
  // vertices' side: the direction of so thin a triangle says more about the last digits of its
  // vertices' projections than about a fold, and closing it moves nothing off the surface. The
  // outline of a lone triangle or flap, walked as a hole, faces the other side and stays open.
  const Vec3 face = (b - a).cross(c - a);
  if (isUnfolded(face, vertexNormals))
  {
    return true;
  }
  const double longest = std::max({ (b - a).norm(), (c - b).norm(), (a - c).norm() });
  return face.dot(vertexNormals) > 0.0 && face.norm() <= 0.1 * Cell * longest;
}

std::vector<std::vector<std::uint32_t>> SurfaceMesher::smallHoles(const SurfaceMesh& mesh) const
{
  // A border edge is the side of one triangle; the hole beside it is walked from each border
  // vertex to the next, in the triangles' winding (a -> b where the triangle runs a -> b). A
  // vertex where two borders meet (a pinch: two border edges leave it) is passed twice; the walk
  // cuts a loop off each time it comes back to a vertex it has already passed, so every loop is
  // simple and a pinched hole is closed as the two holes it is.
  const std::size_t nv = mesh.points.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> border; // (from, to), sorted
  forEachEdge(edgesOf(mesh.triangles, nv), [&](std::uint32_t lower, std::uint32_t higher, std::uint32_t sides, bool forward) {
    if (sides == 1)
    {
      border.emplace_back(forward ? lower : higher, forward ? higher : lower);
    }
  });
  std::sort(border.begin(), border.end());
  std::vector<std::uint32_t> first(nv + 1, 0); // border edges out of v: first[v] .. first[v + 1] - 1
  for (const auto& e : border)
  {
    ++first[e.first + 1];
  }
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<char> used(border.size(), 0);
  auto unusedOutOf = [&](std::uint32_t v) {
    for (std::uint32_t i = first[v]; i < first[v + 1]; ++i)
    {
      if (!used[i])
      {
        return i;
      }
    }
    return NoIndex;
  };
  std::vector<std::uint32_t> position(nv, NoIndex); // where a vertex is on the current walk
  std::vector<std::vector<std::uint32_t>> holes;
  for (std::uint32_t s = 0; s < border.size(); ++s)
  {
    std::vector<std::uint32_t> walk;
    std::uint32_t e = used[s] ? NoIndex : s;
    while (e != NoIndex)
    {
      used[e] = 1;
      const std::uint32_t from = border[e].first;
      position[from] = static_cast<std::uint32_t>(walk.size());
      walk.push_back(from);
      const std::uint32_t to = border[e].second;
      if (position[to] != NoIndex)
      {
        // Back at a vertex of the walk: the part from it on is a simple loop.
        const std::uint32_t p = position[to];
        std::vector<std::uint32_t> loop(walk.begin() + p, walk.end());
        for (const std::uint32_t v : loop)
        {
          position[v] = NoIndex;
        }
        walk.resize(p);
        if (loop.size() >= 3 && loop.size() <= Options.maxHoleEdges)
        {
          holes.push_back(std::move(loop));
        }
        if (p == 0)
        {
          break;
        }
      }
      e = unusedOutOf(to);
    }
    for (const std::uint32_t v : walk) // an open walk (a border that does not close): left alone
    {
      position[v] = NoIndex;
    }
  }
  return holes;
}

std::vector<std::array<std::uint32_t, 3>> SurfaceMesher::triangulateHole(const std::vector<std::uint32_t>& hole,
  const SurfaceMesh& mesh, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges, bool unfolded) const
{
  // The triangulation of the hole's own vertices of least area whose every triangle is unfolded
  // (dynamic programming over the polygon's sub-chains, as in Liepa's hole filling), and whose
  // diagonals are not already edges of the mesh (that would make them non-manifold).
  const std::size_t k = hole.size();
  const double infinite = std::numeric_limits<double>::infinity();
  std::vector<double> cost(k * k, infinite);
  std::vector<std::size_t> split(k * k, 0);
  auto isEdge = [&](std::uint32_t a, std::uint32_t b) {
    return std::binary_search(edges.begin(), edges.end(), std::make_pair(std::min(a, b), std::max(a, b)));
  };
  std::vector<char> usable(k * k, 1); // may chain i..j be closed by the side (i, j)?
  for (std::size_t i = 0; i < k; ++i)
  {
    for (std::size_t j = i + 2; j < k; ++j)
    {
      usable[i * k + j] = (i == 0 && j == k - 1) || !isEdge(hole[i], hole[j]) ? 1 : 0;
    }
  }
  for (std::size_t i = 0; i + 1 < k; ++i)
  {
    cost[i * k + i + 1] = 0.0;
  }
  for (std::size_t span = 2; span < k; ++span)
  {
    for (std::size_t i = 0; i + span < k; ++i)
    {
      const std::size_t j = i + span;
      if (!usable[i * k + j])
      {
        continue;
      }
      for (std::size_t m = i + 1; m < j; ++m)
      {
        const double sub = cost[i * k + m] + cost[m * k + j];
        if (!(sub < cost[i * k + j]))
        {
          continue;
        }
        // The border runs hole[i] -> hole[i + 1]: the triangles that close it run the other way.
        const Vec3& a = mesh.points[hole[j]];
        const Vec3& b = mesh.points[hole[m]];
        const Vec3& c = mesh.points[hole[i]];
        if (unfolded && !closesFlat(a, b, c, mesh.normals[hole[i]] + mesh.normals[hole[m]] + mesh.normals[hole[j]]))
        {
          continue;
        }
        const double total = sub + 0.5 * (b - a).cross(c - a).norm();
        if (total < cost[i * k + j])
        {
          cost[i * k + j] = total;
          split[i * k + j] = m;
        }
      }
    }
  }
  std::vector<std::array<std::uint32_t, 3>> fill;
  if (cost[k - 1] == infinite)
  {
    return fill;
  }
  std::vector<std::pair<std::size_t, std::size_t>> todo{ { 0, k - 1 } };
  while (!todo.empty())
  {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j - i < 2)
    {
      continue;
    }
    const std::size_t m = split[i * k + j];
    fill.push_back({ { hole[j], hole[m], hole[i] } });
    todo.emplace_back(i, m);
    todo.emplace_back(m, j);
  }
  return fill;
}

void SurfaceMesher::findHoles(const SurfaceMesh& mesh)
{
  Holes.clear();
  if (Dimension == 3 && Options.maxHoleEdges >= 3)
  {
    Holes = smallHoles(mesh);
  }
  HoleCentres.assign(Holes.size(), Vec3::Zero());
  HoleCell.assign(Holes.size(), 0.0);
  for (std::size_t j = 0; j < Holes.size(); ++j)
  {
    const std::vector<std::uint32_t>& hole = Holes[j];
    for (const std::uint32_t v : hole)
    {
      HoleCentres[j] += mesh.points[v] / static_cast<double>(hole.size());
      HoleCell[j] = std::max(HoleCell[j], v < VertexCell.size() ? VertexCell[v] : Cell);
    }
  }
  HoleEvidence.assign(Holes.size(), DomainEvidence{});
  HoleCloudGapSq.assign(Holes.size(), 0.0);
}

void SurfaceMesher::evaluateHole(std::size_t j, Workspace& ws)
{
  const Vec3& centre = HoleCentres[j];
  if (Holes[j].size() > 3)
  {
    HoleEvidence[j] = classifyStart(*Surface, centre, Options.projection, Options.domain, ws, Normals.get());
  }
  const PointIndex& index = Surface->index();
  const auto [nearest, sqDist] = index.nearest(centre);
  noteReach(index, index.restrict(centre), sqDist, ws);
  // In units of the nearest point's own scale when each point has one, as the domain test does.
  const double local = index.hasScales() ? index.scale(nearest) : Frame.h;
  HoleCloudGapSq[j] = sqDist / (local * local);
}

void SurfaceMesher::closeHoles(SurfaceMesh& mesh)
{
  const std::vector<std::vector<std::uint32_t>>& holes = Holes;
  // The mesh's edges between two vertices of these holes, sorted (a diagonal of a hole's
  // triangulation must not be one of them), grown as holes are closed.
  std::vector<char> onHole(mesh.points.size(), 0);
  for (const auto& hole : holes)
  {
    for (const std::uint32_t v : hole)
    {
      onHole[v] = 1;
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : mesh.triangles)
  {
    for (int i = 0; i < 3; ++i)
    {
      const std::uint32_t a = t[i];
      const std::uint32_t b = t[(i + 1) % 3];
      if (onHole[a] && onHole[b])
      {
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Pieces pieces = piecesOf(mesh.triangles, mesh.points);
  const auto largest = static_cast<std::size_t>(
    std::max_element(pieces.measure.begin(), pieces.measure.end()) - pieces.measure.begin());
  // A border of three edges that is one triangle's own (a triangle hanging by a vertex) is not a
  // hole: closing it would lay a second, reversed triangle over the first. Such a triangle is
  // removed instead.
  std::vector<std::array<std::uint32_t, 3>> lone;
  for (const auto& hole : holes)
  {
    if (hole.size() == 3)
    {
      lone.push_back(sortedTriangle({ { hole[0], hole[1], hole[2] } }));
    }
  }
  std::sort(lone.begin(), lone.end());
  std::vector<char> isTriangle(lone.size(), 0);
  for (const auto& t : mesh.triangles)
  {
    const auto it = std::lower_bound(lone.begin(), lone.end(), sortedTriangle(t));
    if (it != lone.end() && *it == sortedTriangle(t))
    {
      isTriangle[static_cast<std::size_t>(it - lone.begin())] = 1;
    }
  }
  for (std::size_t j = 0; j < holes.size(); ++j)
  {
    const std::vector<std::uint32_t>& hole = holes[j];
    const std::size_t k = hole.size();
    if (k == 3)
    {
      const auto it = std::lower_bound(lone.begin(), lone.end(), sortedTriangle({ { hole[0], hole[1], hole[2] } }));
      if (isTriangle[static_cast<std::size_t>(it - lone.begin())])
      {
        isTriangle[static_cast<std::size_t>(it - lone.begin())] = 2;
        continue;
      }
    }
    const Vec3& centre = HoleCentres[j];
    Vec3 normalSum = Vec3::Zero();
    for (const std::uint32_t v : hole)
    {
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
    bool fan = k > 3;
    if (k == 3)
    {
      fill.push_back({ { hole[0], hole[2], hole[1] } });
    }
    else
    {
      ev = HoleEvidence[j];
      const Direction& d = ev.projection.direction;
      fan = ev.label == DomainLabel::InDomain &&
        (ev.projection.point - centre).norm() <= Options.maxVertexTravel * HoleCell[j] && d.defined;
      if (fan)
      {
        apex = Options.projectVertices ? ev.projection.point : centre;
        apexNormal = d.n.dot(normalSum) < 0.0 ? Vec3(-d.n) : d.n;
        for (std::size_t i = 0; i < k; ++i)
        {
          fill.push_back({ { hole[(i + 1) % k], hole[i], apexIndex } });
        }
      }
    }
    auto at = [&](std::uint32_t v) -> const Vec3& { return v == apexIndex ? apex : mesh.points[v]; };
    auto normalAt = [&](std::uint32_t v) -> const Vec3& { return v == apexIndex ? apexNormal : mesh.normals[v]; };
    const bool flat = !fill.empty() && std::all_of(fill.begin(), fill.end(), [&](const std::array<std::uint32_t, 3>& t) {
      return closesFlat(at(t[0]), at(t[1]), at(t[2]), normalAt(t[0]) + normalAt(t[1]) + normalAt(t[2]));
    });
    if (!flat)
    {
      // No flat fan: its apex is outside the domain or a triangle of it folds (a flap over a seam
      // of the orientation). The hole is still closed when the scan has data at its centre (a
      // cloud point within MaxDistance): only a hole over a gap of the scan, where the surface is
      // not defined, must stay open. First from its own vertices without a fold; then, in the
      // largest piece, with folds: there such holes are where the projection turned a border
      // inside out (the triangles around it overlap it by a fraction of a cell) or a pleat of the
      // contour twisted it, and any closing lies nearer the surface than the hole. A smaller
      // piece's outline walks the wrong way round too, but closing it would make a closed lens.
      const bool scanHasData = HoleCloudGapSq[j] <= Options.domain.maxDistance * Options.domain.maxDistance;
      const bool anyFold = scanHasData && pieces.sets.find(hole[0]) == largest;
      std::vector<std::array<std::uint32_t, 3>> folding;
      if (anyFold)
      {
        folding.swap(fill);
      }
      fill.clear();
      fan = false;
      if (scanHasData && k > 3)
      {
        fill = triangulateHole(hole, mesh, edges, true);
      }
      if (fill.empty() && anyFold)
      {
        fan = k > 3 && !folding.empty();
        fill = fan || k == 3 ? folding : triangulateHole(hole, mesh, edges, false);
      }
      if (fill.empty())
      {
        continue;
      }
      if (!fan)
      {
        for (const auto& t : fill)
        {
          for (int i = 0; i < 3; ++i)
          {
            edges.emplace_back(std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3]));
          }
        }
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      }
    }
    if (fan)
    {
      mesh.points.push_back(apex);
      mesh.normals.push_back(apexNormal);
      mesh.evidence.push_back(std::move(ev));
      mesh.crossings.push_back(centre);
    }
    mesh.triangles.insert(mesh.triangles.end(), fill.begin(), fill.end());
    ++Statistics.closedHoles;
  }
  Holes = {};
  if (std::find(isTriangle.begin(), isTriangle.end(), 2) != isTriangle.end())
  {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::copy_if(mesh.triangles.begin(), mesh.triangles.end(), std::back_inserter(triangles),
      [&](const std::array<std::uint32_t, 3>& t) {
        const auto it = std::lower_bound(lone.begin(), lone.end(), sortedTriangle(t));
        return it == lone.end() || *it != sortedTriangle(t) || isTriangle[static_cast<std::size_t>(it - lone.begin())] != 2;
      });
    Statistics.danglingTriangles = mesh.triangles.size() - triangles.size();
    keepLargePieces(mesh, triangles);
  }
  mesh.statistics = Statistics;
  countTopology(mesh);
}

} // namespace pss

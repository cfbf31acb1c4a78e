// SPDX-License-Identifier: BSD-3-Clause
// Stage 8 of the mesher (SurfaceMesh.h): a distance criterion between the vertices. A triangle
// can run on past the scan's edge although each of its vertices lies near a cloud point (a
// smoothed h_i exceeds the spacing where the density changes); the trim cuts the mesh back where
// it runs farther than trimDistance local point spacings from the cloud.
#include "pss/SurfaceMesh.h"
#include "pss/SurfaceMeshPieces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pss
{

namespace
{

Vec3 unitOrZero(const Vec3& v)
{
  const double norm = v.norm();
  return norm > 0.0 ? Vec3(v / norm) : Vec3::Zero();
}

// A new vertex at fraction t of the way from vertex a to vertex b: the geometry between
// projected vertices is the flat triangle anyway, so the trim moves no surface. It carries the
// evidence of a (the inside end where the cut falls).
std::uint32_t addVertexOnEdge(SurfaceMesh& mesh, std::uint32_t a, std::uint32_t b, double t)
{
  const auto v = static_cast<std::uint32_t>(mesh.points.size());
  mesh.points.push_back((1.0 - t) * mesh.points[a] + t * mesh.points[b]);
  const Vec3 n = (1.0 - t) * mesh.normals[a] + t * mesh.normals[b];
  mesh.normals.push_back(unitOrZero(n));
  mesh.crossings.push_back((1.0 - t) * mesh.crossings[a] + t * mesh.crossings[b]);
  mesh.evidence.push_back(mesh.evidence[a]);
  return v;
}

} // namespace

void SurfaceMesher::keepLargePieces(SurfaceMesh& mesh, const std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  const double h = Frame.h;
  std::size_t removed = 0;
  const std::vector<char> large = piece_utils::largePieces(triangles, mesh.points, Options.minPieceArea * h * h, removed);
  Statistics.removedPieces += removed;
  std::vector<std::uint32_t> newIndex(mesh.points.size());
  mesh.triangles = piece_utils::keepCells(triangles, mesh.points.size(),
    [&](const std::array<std::uint32_t, 3>& t) { return large[t[0]] != 0; }, newIndex);
  // The kept vertices move down in place (newIndex[i] <= i).
  std::size_t kept = 0;
  for (std::size_t i = 0; i < newIndex.size(); ++i)
  {
    if (newIndex[i] != NoIndex)
    {
      mesh.points[kept] = mesh.points[i];
      mesh.normals[kept] = mesh.normals[i];
      mesh.crossings[kept] = mesh.crossings[i];
      mesh.evidence[kept] = std::move(mesh.evidence[i]);
      ++kept;
    }
  }
  mesh.points.resize(kept);
  mesh.normals.resize(kept);
  mesh.crossings.resize(kept);
  mesh.evidence.resize(kept);
}

bool SurfaceMesher::trims() const
{
  return Dimension == 3 && Options.trimDistance > 0.0 && Surface != nullptr;
}

std::size_t SurfaceMesher::spacingCount() const
{
  return trims() ? Surface->index().size() : 0;
}

void SurfaceMesher::beginSpacings()
{
  const std::size_t n = spacingCount();
  SpacingPass = 0;
  RawSpacing.assign(n, 0.0);
  CloudSpacing.assign(n, 0.0);
  SpacingNeighbours.assign(n * SpacingNeighbourCount, 0);
}

void SurfaceMesher::evaluateSpacing(std::size_t i, Workspace&)
{
  thread_local std::vector<std::uint32_t> near;
  thread_local std::vector<std::pair<std::uint32_t, double>> found;
  thread_local std::vector<double> values;
  const std::size_t k = SpacingNeighbourCount;
  if (SpacingPass == 0)
  {
    RawSpacing[i] = rawSpacing(Surface->index(), i, k, near, found);
    std::copy(near.begin(), near.end(), SpacingNeighbours.begin() + static_cast<std::ptrdiff_t>(i * k));
    std::fill(SpacingNeighbours.begin() + static_cast<std::ptrdiff_t>(i * k + near.size()),
      SpacingNeighbours.begin() + static_cast<std::ptrdiff_t>((i + 1) * k), static_cast<std::uint32_t>(i));
  }
  else
  {
    CloudSpacing[i] = smoothedSpacing(RawSpacing, i, SpacingNeighbours.data() + i * k, k, values);
  }
}

std::vector<double> SurfaceMesher::spacingValues() const
{
  return SpacingPass == 0 ? RawSpacing : CloudSpacing;
}

void SurfaceMesher::setSpacingValues(const std::vector<double>& values)
{
  (SpacingPass == 0 ? RawSpacing : CloudSpacing) = values;
}

bool SurfaceMesher::nextSpacingPass()
{
  if (++SpacingPass < 2)
  {
    return true;
  }
  RawSpacing = {};
  SpacingNeighbours = {};
  // Coincident points (a dozen duplicates) have no spacing of their own: the typical h stands in.
  for (double& spacing : CloudSpacing)
  {
    spacing = spacing > 0.0 ? spacing : Frame.h;
  }
  return false;
}

void SurfaceMesher::beginTrim(const SurfaceMesh& mesh)
{
  TrimSamples.clear();
  TrimLevel = 0;
  VertexExcess.assign(mesh.points.size(), std::numeric_limits<double>::quiet_NaN());
  VertexSpacing.assign(mesh.points.size(), 0.0);
  MidpointExcess.clear();
  TrimActive.assign(mesh.triangles.size(), 1);
  if (trims())
  {
    MidpointExcess.reserve(3 * mesh.triangles.size() / 2); // the edges of a mesh with few borders
    queueTrimSamples(mesh);
  }
}

void SurfaceMesher::queueTrimSamples(const SurfaceMesh& mesh)
{
  TrimSamples.clear();
  TrimSlots.clear();
  std::vector<char> queued(mesh.points.size(), 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (!TrimActive[t])
    {
      continue;
    }
    const auto& tri = mesh.triangles[t];
    for (int i = 0; i < 3; ++i)
    {
      const std::uint32_t a = tri[i];
      const std::uint32_t b = tri[(i + 1) % 3];
      if (std::isnan(VertexExcess[a]) && !queued[a])
      {
        queued[a] = 1;
        TrimSamples.push_back(mesh.points[a]);
        TrimSlots.push_back({ TrimSlot::Vertex, a });
      }
      if (MidpointExcess.tryEmplace(edgeKey(a, b), TrimSample{}).second)
      {
        TrimSamples.push_back(0.5 * (mesh.points[a] + mesh.points[b]));
        TrimSlots.push_back({ TrimSlot::Midpoint, edgeKey(a, b) });
      }
    }
    TrimSamples.push_back((mesh.points[tri[0]] + mesh.points[tri[1]] + mesh.points[tri[2]]) / 3.0);
    TrimSlots.push_back({ TrimSlot::Centroid, t });
  }
  TrimValues.assign(2 * TrimSamples.size(), 0.0);
}

void SurfaceMesher::evaluateTrimSample(std::size_t i, Workspace& ws)
{
  const PointIndex& index = Surface->index();
  const auto [nearest, sqDist] = index.nearest(TrimSamples[i]);
  noteReach(index, index.restrict(TrimSamples[i]), sqDist, ws);
  const double local = CloudSpacing[nearest];
  TrimValues[2 * i] = std::sqrt(sqDist) - Options.trimDistance * local;
  TrimValues[2 * i + 1] = local;
}

std::vector<double> SurfaceMesher::trimValues() const
{
  return TrimValues;
}

void SurfaceMesher::setTrimValues(const std::vector<double>& values)
{
  TrimValues = values;
}

bool SurfaceMesher::refineTrim(SurfaceMesh& mesh)
{
  if (TrimSamples.empty())
  {
    return false;
  }
  std::vector<TrimSample> centroid(mesh.triangles.size());
  for (std::size_t s = 0; s < TrimSlots.size(); ++s)
  {
    const TrimSample value{ TrimValues[2 * s], TrimValues[2 * s + 1] };
    switch (TrimSlots[s].kind)
    {
      case TrimSlot::Vertex:
        VertexExcess[TrimSlots[s].id] = value.excess;
        VertexSpacing[TrimSlots[s].id] = value.spacing;
        break;
      case TrimSlot::Midpoint:
        MidpointExcess[TrimSlots[s].id] = value;
        break;
      case TrimSlot::Centroid:
        centroid[TrimSlots[s].id] = value;
        break;
    }
  }
  const bool last = ++TrimLevel >= TrimLevels;
  // Edges to split: long ones (in the local h) near where the mesh leaves the cloud, at an end,
  // at their midpoint or at the centre of a triangle they bound. Whether an edge splits is decided
  // once for the edge, so both of its triangles split it and the mesh stays conforming.
  EdgeMap<std::uint32_t> split;
  const double near = TrimNearFraction;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (!TrimActive[t])
    {
      continue;
    }
    const auto& tri = mesh.triangles[t];
    double longest = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      longest = std::max(longest, (mesh.points[tri[i]] - mesh.points[tri[(i + 1) % 3]]).norm());
    }
    const bool centreNear = centroid[t].excess > -near * longest;
    for (int i = 0; i < 3; ++i)
    {
      const std::uint32_t a = tri[i];
      const std::uint32_t b = tri[(i + 1) % 3];
      const std::uint64_t key = edgeKey(a, b);
      const TrimSample& mid = MidpointExcess[key];
      const double length = (mesh.points[a] - mesh.points[b]).norm();
      const double worst = std::max({ VertexExcess[a], VertexExcess[b], mid.excess });
      if (length > TrimFinest * mid.spacing && (centreNear || worst > -near * length))
      {
        split.tryEmplace(key, NoIndex);
      }
    }
  }
  if (split.empty())
  {
    TrimSamples.clear();
    return false;
  }
  // New vertices in the order of their edges' keys, not the hash table's.
  std::vector<std::uint64_t> keys;
  keys.reserve(split.size());
  split.forEach([&](std::uint64_t key, std::uint32_t) { keys.push_back(key); });
  std::sort(keys.begin(), keys.end());
  // Only a triangle with two vertices on split edges can hold one: the others skip the look-ups.
  std::vector<char> onSplit(mesh.points.size(), 0);
  for (const std::uint64_t key : keys)
  {
    const auto a = static_cast<std::uint32_t>(key >> 32);
    const auto b = static_cast<std::uint32_t>(key & 0xffffffffu);
    onSplit[a] = onSplit[b] = 1;
    split[key] = addVertexOnEdge(mesh, a, b, 0.5);
    VertexExcess.push_back(MidpointExcess[key].excess);
    VertexSpacing.push_back(MidpointExcess[key].spacing);
  }
  // Every triangle with a split edge (also one whose own samples were settled) is cut into two,
  // three or four; its pieces are sampled at the next level.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<char> active;
  triangles.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles)
  {
    std::array<std::uint32_t, 3> mid{ { NoIndex, NoIndex, NoIndex } };
    int count = 0;
    for (int i = 0; i < 3; ++i)
    {
      if (!onSplit[tri[i]] || !onSplit[tri[(i + 1) % 3]])
      {
        continue;
      }
      if (const std::uint32_t* vertex = split.find(edgeKey(tri[i], tri[(i + 1) % 3])))
      {
        mid[i] = *vertex;
        ++count;
      }
    }
    if (count == 0)
    {
      triangles.push_back(tri);
      active.push_back(0);
      continue;
    }
    const std::size_t first = triangles.size();
    if (count == 3)
    {
      triangles.push_back({ { tri[0], mid[0], mid[2] } });
      triangles.push_back({ { mid[0], tri[1], mid[1] } });
      triangles.push_back({ { mid[2], mid[1], tri[2] } });
      triangles.push_back({ { mid[0], mid[1], mid[2] } });
    }
    else
    {
      // Rotate so that edge 0 (tri[0] -> tri[1]) is split; then edge 1 or 2 may be as well.
      int r = mid[0] != NoIndex ? 0 : (mid[1] != NoIndex ? 1 : 2);
      if (count == 2 && mid[(r + 2) % 3] != NoIndex)
      {
        r = (r + 2) % 3;
      }
      const std::uint32_t p = tri[r], q = tri[(r + 1) % 3], s = tri[(r + 2) % 3];
      const std::uint32_t m0 = mid[r], m1 = mid[(r + 1) % 3];
      if (count == 1)
      {
        triangles.push_back({ { p, m0, s } });
        triangles.push_back({ { m0, q, s } });
      }
      else
      {
        triangles.push_back({ { p, m0, s } });
        triangles.push_back({ { m0, q, m1 } });
        triangles.push_back({ { m0, m1, s } });
      }
    }
    active.resize(triangles.size(), 0);
    std::fill(active.begin() + static_cast<std::ptrdiff_t>(first), active.end(), 1);
  }
  mesh.triangles.swap(triangles);
  TrimActive.swap(active);
  if (last)
  {
    TrimSamples.clear();
    return false;
  }
  queueTrimSamples(mesh);
  return true;
}

void SurfaceMesher::spareShallowRegions(const SurfaceMesh& mesh)
{
  // The vertices beyond the trim distance, linked by the edges between two of them.
  const std::size_t nv = mesh.points.size();
  std::vector<std::uint32_t> first(nv + 1, 0);
  auto forOutsideEdges = [&](auto&& visit) {
    for (const auto& tri : mesh.triangles)
    {
      for (int i = 0; i < 3; ++i)
      {
        const std::uint32_t a = tri[i];
        const std::uint32_t b = tri[(i + 1) % 3];
        if (VertexExcess[a] > 0.0 && VertexExcess[b] > 0.0)
        {
          visit(a, b);
        }
      }
    }
  };
  forOutsideEdges([&](std::uint32_t a, std::uint32_t b) {
    ++first[a + 1];
    ++first[b + 1];
  });
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
  std::vector<std::uint32_t> linked(first.back());
  forOutsideEdges([&](std::uint32_t a, std::uint32_t b) {
    linked[next[a]++] = b;
    linked[next[b]++] = a;
  });
  // Each region, flooded from its lowest vertex: kept (its excess set to 0) when it nowhere
  // reaches TrimMargin local spacings beyond the trim distance, or TrimEnclosedMargin when it has
  // no vertex on the border.
  const std::vector<char> border = piece_utils::borderVertices(mesh.triangles, nv);
  std::vector<char> seen(nv, 0);
  std::vector<std::uint32_t> region;
  for (std::uint32_t seed = 0; seed < nv; ++seed)
  {
    if (seen[seed] || !(VertexExcess[seed] > 0.0))
    {
      continue;
    }
    region.assign(1, seed);
    seen[seed] = 1;
    double reach = 0.0; // in local spacings beyond the trim distance
    bool open = false;
    for (std::size_t r = 0; r < region.size(); ++r)
    {
      const std::uint32_t v = region[r];
      reach = std::max(reach, VertexExcess[v] / VertexSpacing[v]);
      open = open || border[v] != 0;
      for (std::uint32_t e = first[v]; e < first[v + 1]; ++e)
      {
        if (!seen[linked[e]])
        {
          seen[linked[e]] = 1;
          region.push_back(linked[e]);
        }
      }
    }
    if (!(reach > (open ? TrimMargin : TrimEnclosedMargin)))
    {
      for (const std::uint32_t v : region)
      {
        VertexExcess[v] = 0.0;
      }
    }
  }
}

void SurfaceMesher::cutFar(SurfaceMesh& mesh)
{
  if (!trims())
  {
    return;
  }
  spareShallowRegions(mesh);
  // Linear in the excess along each edge: the cut crosses an edge once, where both of its
  // triangles put it.
  EdgeMap<std::uint32_t> cut;
  auto cutVertex = [&](std::uint32_t inside, std::uint32_t outside) {
    const auto [vertex, added] = cut.tryEmplace(edgeKey(inside, outside), NoIndex);
    if (added)
    {
      const double fi = VertexExcess[inside]; // <= 0 < fo
      const double fo = VertexExcess[outside];
      vertex = addVertexOnEdge(mesh, inside, outside, fi / (fi - fo));
    }
    return vertex;
  };
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(mesh.triangles.size());
  std::size_t trimmed = 0;
  for (const auto& tri : mesh.triangles)
  {
    int inside = 0;
    for (const std::uint32_t v : tri)
    {
      inside += VertexExcess[v] <= 0.0 ? 1 : 0;
    }
    if (inside == 3)
    {
      triangles.push_back(tri);
      continue;
    }
    ++trimmed;
    if (inside == 0)
    {
      continue;
    }
    // Rotate so that tri[r] is the lone inside vertex (one inside) or the lone outside one (two).
    int r = 0;
    while ((VertexExcess[tri[r]] <= 0.0) != (inside == 1))
    {
      ++r;
    }
    const std::uint32_t p = tri[r], q = tri[(r + 1) % 3], s = tri[(r + 2) % 3];
    if (inside == 1)
    {
      triangles.push_back({ { p, cutVertex(p, q), cutVertex(p, s) } });
    }
    else
    {
      const std::uint32_t pq = cutVertex(q, p);
      const std::uint32_t ps = cutVertex(s, p);
      triangles.push_back({ { pq, q, s } });
      triangles.push_back({ { pq, s, ps } });
    }
  }
  Statistics.trimmedSimplices = trimmed;
  // Cut-off corners can leave islands: the small-piece rule of stage 6 applies again.
  keepLargePieces(mesh, triangles);
  VertexExcess = {};
  VertexSpacing = {};
  CloudSpacing = {};
  MidpointExcess = {};
  TrimActive = {};
  TrimSlots = {};
  TrimValues = {};
  mesh.statistics = Statistics;
  countTopology(mesh);
}

} // namespace pss

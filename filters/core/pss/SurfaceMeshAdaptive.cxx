// SPDX-License-Identifier: BSD-3-Clause
// The mesher's adaptive cells (SurfaceMesh.h, stages 1 and 4 with a scale per point): a balanced
// octree (a quadtree in 2D) whose cells follow h_i, its hanging corners, and the crossings and
// triangles where cells of two sizes meet.
#include "pss/SurfaceMesh.h"
#include "pss/SurfaceMeshGrid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace pss
{

namespace
{

using grid::Coords;
using grid::Key;
using grid::KeyOrder;

Coords sizeAtLevel(const Coords& finest, int level, int dimension)
{
  Coords s{ { 1, 1, 1 } };
  for (int a = 0; a < dimension; ++a)
  {
    s[a] = (finest[a] >> level) + 1;
  }
  return s;
}

// The cells one level up that hold @p keys (cells of a grid of size @p from).
std::vector<Key> parentsOf(const std::vector<Key>& keys, const Coords& from, const Coords& to, int dimension)
{
  std::vector<Key> out;
  out.reserve(keys.size() / 2 + 1);
  const KeyOrder f{ { 0, 1, 2 }, from };
  const KeyOrder t{ { 0, 1, 2 }, to };
  for (const Key k : keys)
  {
    Coords c = f.decode(k);
    for (int a = 0; a < dimension; ++a)
    {
      c[a] >>= 1;
    }
    out.push_back(t.encode(c));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Every child, one level down, of the cells @p keys (of a grid of size @p from), sorted.
std::vector<Key> childrenOf(const std::vector<Key>& keys, const Coords& from, const Coords& to, int dimension)
{
  std::vector<Key> out;
  out.reserve(keys.size() << dimension);
  const KeyOrder f{ { 0, 1, 2 }, from };
  const KeyOrder t{ { 0, 1, 2 }, to };
  for (const Key k : keys)
  {
    const Coords c = f.decode(k);
    for (int bits = 0; bits < (1 << dimension); ++bits)
    {
      Coords child = c;
      for (int a = 0; a < dimension; ++a)
      {
        child[a] = 2 * c[a] + ((bits >> a) & 1);
      }
      out.push_back(t.encode(child));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void refuseAbove(std::size_t count, std::size_t limit, const char* what)
{
  if (count > limit)
  {
    throw std::invalid_argument("the mesh " + std::string(what) + " would have " + std::to_string(count) +
      " (the limit is " + std::to_string(limit) + "): use a larger cell size or a narrower band");
  }
}

} // namespace

bool SurfaceMesher::buildAdaptiveBand(const PointIndex& index)
{
  const std::size_t n = index.size();
  if (n == 0 || !(Frame.h > 0.0))
  {
    return false;
  }
  // Level 0 is the regular grid's (cells of cellSize x the typical h); a point asks for the
  // coarsest level whose cells are at most cellSize x h_i. Never finer than level 0: on the
  // frames of docs/adaptive-scale.md finer cells where h_i is small cost more and open more small
  // holes (the room scan: 2.7 -> 6.1 s, 32 -> 85), where the surface at that scale sees single
  // scan layers.
  std::vector<std::uint8_t> level(n);
  int highest = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double l = std::floor(std::log2(index.scale(i) / Frame.h));
    const int li = std::isfinite(l) ? static_cast<int>(std::clamp(l, 0.0, MaxCellLevels - 1.0)) : 0;
    level[i] = static_cast<std::uint8_t>(li);
    highest = std::max(highest, li);
  }
  if (highest == 0)
  {
    return false;
  }
  const int levels = highest + 1; // the side of a level-L cell is 2^L Cell
  // Room on every side for the coarsest level's band and the balance's growth.
  const long long margin = (Reach + 2) << (levels - 1);
  sizeGrid(margin);

  std::vector<Coords> size(static_cast<std::size_t>(levels));
  std::vector<std::vector<Key>> occupied(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l)
  {
    size[l] = sizeAtLevel(Size, l, Dimension);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3& p = index.point(i);
    const int l = level[i];
    Coords c{ { 0, 0, 0 } };
    for (int a = 0; a < Dimension; ++a)
    {
      c[a] = std::clamp(static_cast<long long>(std::floor((p[a] - Origin[a]) / Cell)), margin, Size[a] - margin - 1) >> l;
    }
    occupied[l].push_back(KeyOrder{ { 0, 1, 2 }, size[l] }.encode(c));
  }
  // R_l: the level-l cells of the tree (leaves or split), with all siblings of each. A level-l
  // cell is needed where a point of level l has its band, and next to any finer cell (grown by one
  // cell before going up a level), which keeps neighbouring leaves at most one level apart.
  std::vector<std::pair<Key, std::uint8_t>> leaves;
  std::vector<Key> below;
  for (int l = 0; l < levels; ++l)
  {
    auto& own = occupied[l];
    std::sort(own.begin(), own.end());
    own.erase(std::unique(own.begin(), own.end()), own.end());
    std::vector<Key> needed = grid::widen(std::move(own), size[l], Dimension, Reach, Reach, Options.maxBandCells, "band");
    std::vector<Key> split;
    if (l > 0)
    {
      split = parentsOf(below, size[l - 1], size[l], Dimension);
      const std::vector<Key> near = parentsOf(
        grid::widen(below, size[l - 1], Dimension, 1, 1, Options.maxBandCells, "band"), size[l - 1], size[l], Dimension);
      std::vector<Key> merged;
      std::set_union(needed.begin(), needed.end(), near.begin(), near.end(), std::back_inserter(merged));
      needed = std::move(merged);
    }
    if (l + 1 < levels)
    {
      needed = childrenOf(parentsOf(needed, size[l], size[l + 1], Dimension), size[l + 1], size[l], Dimension);
    }
    std::vector<Key> leaf;
    std::set_difference(needed.begin(), needed.end(), split.begin(), split.end(), std::back_inserter(leaf));
    refuseAbove(leaves.size() + leaf.size(), Options.maxBandCells, "band's cells");
    const KeyOrder o{ { 0, 1, 2 }, size[l] };
    for (const Key k : leaf)
    {
      Coords c = o.decode(k);
      for (int a = 0; a < Dimension; ++a)
      {
        c[a] <<= l;
      }
      leaves.emplace_back(keyOf(c), static_cast<std::uint8_t>(l));
    }
    below = std::move(needed);
  }
  std::sort(leaves.begin(), leaves.end());
  Cells.resize(leaves.size());
  CellLevel.resize(leaves.size());
  // Every cell's corners by key, sorted once: the corners' keys and each cell's corner indices.
  const int perCell = 1 << Dimension;
  std::vector<std::pair<Key, std::uint32_t>> slots;
  slots.reserve(leaves.size() * static_cast<std::size_t>(perCell));
  for (std::size_t c = 0; c < leaves.size(); ++c)
  {
    Cells[c] = leaves[c].first;
    CellLevel[c] = leaves[c].second;
    const Coords base = coordsOf(Cells[c]);
    for (int bits = 0; bits < perCell; ++bits)
    {
      Coords k = base;
      for (int a = 0; a < Dimension; ++a)
      {
        k[a] += static_cast<long long>((bits >> a) & 1) << CellLevel[c];
      }
      slots.emplace_back(keyOf(k), static_cast<std::uint32_t>(c * static_cast<std::size_t>(perCell) + static_cast<std::size_t>(bits)));
    }
  }
  std::sort(slots.begin(), slots.end());
  Keys.clear();
  CellCorners.resize(Cells.size());
  for (const auto& [key, slot] : slots)
  {
    if (Keys.empty() || Keys.back() != key)
    {
      Keys.push_back(key);
    }
    CellCorners[slot / static_cast<std::uint32_t>(perCell)][slot % static_cast<std::uint32_t>(perCell)] =
      static_cast<std::uint32_t>(Keys.size() - 1);
  }
  refuseAbove(Keys.size(), 2 * Options.maxBandCells, "band's corners");
  Values.assign(Keys.size(), CornerValue{});
  findHanging();
  linkCorners();
  Statistics.bandCells = Cells.size();
  Statistics.gridVertices = Keys.size() - HangingCorners.size();
  Statistics.cellLevels = static_cast<std::size_t>(levels);
  Statistics.hangingVertices = HangingCorners.size();
  return true;
}

void SurfaceMesher::findHanging()
{
  // A corner in the middle of a cell's edge, or of one of its faces, belongs to finer cells only:
  // with neighbours at most one level apart no other corner lies on a cell's boundary.
  Hanging.assign(Keys.size(), 0);
  std::vector<std::pair<int, HangingCorner>> found;
  for (std::size_t c = 0; c < Cells.size(); ++c)
  {
    const int l = CellLevel[c];
    if (l == 0)
    {
      continue;
    }
    const Coords base = coordsOf(Cells[c]);
    const long long side = 1LL << l;
    auto at = [&](const Coords& offset, long long scale) {
      Coords k = base;
      for (int a = 0; a < 3; ++a)
      {
        k[a] += offset[a] * scale;
      }
      return keyOf(k);
    };
    auto note = [&](const Coords& from, const Coords& to) {
      Coords mid{};
      for (int a = 0; a < 3; ++a)
      {
        mid[a] = from[a] + to[a]; // in half cells
      }
      const std::uint32_t m = cornerOf(at(mid, side / 2));
      if (m != NoIndex)
      {
        auto bitsOf = [](const Coords& o) { return static_cast<int>(o[0] | (o[1] << 1) | (o[2] << 2)); };
        found.push_back({ -l, HangingCorner{ m, CellCorners[c][bitsOf(from)], CellCorners[c][bitsOf(to)] } });
      }
    };
    for (int bits = 0; bits < (1 << Dimension); ++bits)
    {
      const Coords from{ { bits & 1, (bits >> 1) & 1, (bits >> 2) & 1 } };
      for (int a = 0; a < Dimension; ++a)
      {
        if (from[a] == 0)
        {
          Coords to = from;
          to[a] = 1;
          note(from, to); // an edge
          for (int b = a + 1; b < Dimension; ++b)
          {
            if (from[b] == 0)
            {
              to[b] = 1;
              note(from, to); // a face's diagonal, from its lowest corner to its highest (Kuhn's)
              to[b] = 0;
            }
          }
        }
      }
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
    return std::tie(x.first, x.second.corner) < std::tie(y.first, y.second.corner);
  });
  HangingCorners.clear();
  for (const auto& [order, h] : found)
  {
    (void)order;
    if (h.a == NoIndex || h.b == NoIndex)
    {
      throw std::logic_error("SurfaceMesher: a hanging corner without its cell's corners (a bug: please report it)");
    }
    if (!Hanging[h.corner])
    {
      Hanging[h.corner] = 1;
      HangingCorners.push_back(h);
    }
  }
}

void SurfaceMesher::linkCorners()
{
  // Orientation runs over the cells' edges between evaluated corners: a coarser cell's edge links
  // its ends past a hanging midpoint. A corner has at most one such edge up each axis (a finer
  // cell's edge from it would end at that midpoint).
  for (int k = 0; k < 2 * Dimension; ++k)
  {
    Step[k].assign(Keys.size(), NoIndex);
  }
  for (const auto& corners : CellCorners)
  {
    for (int bits = 0; bits < (1 << Dimension); ++bits)
    {
      for (int a = 0; a < Dimension; ++a)
      {
        const std::uint32_t u = corners[bits];
        const std::uint32_t v = corners[bits | (1 << a)];
        if (!((bits >> a) & 1) && !Hanging[u] && !Hanging[v])
        {
          Step[2 * a][u] = v;
          Step[2 * a + 1][v] = u;
        }
      }
    }
  }
}

std::uint32_t SurfaceMesher::cornerOf(Key k) const
{
  const auto it = std::lower_bound(Keys.begin(), Keys.end(), k);
  return it != Keys.end() && *it == k ? static_cast<std::uint32_t>(it - Keys.begin()) : NoIndex;
}

std::uint32_t SurfaceMesher::midpointOf(std::uint32_t a, std::uint32_t b) const
{
  const Coords ca = coordsOf(Keys[a]);
  const Coords cb = coordsOf(Keys[b]);
  Coords mid{};
  for (int k = 0; k < 3; ++k)
  {
    if ((ca[k] + cb[k]) % 2 != 0)
    {
      return NoIndex;
    }
    mid[k] = (ca[k] + cb[k]) / 2;
  }
  const std::uint32_t m = cornerOf(keyOf(mid));
  return m != NoIndex && Hanging[m] ? m : NoIndex;
}

std::uint32_t SurfaceMesher::crossingBetween(std::uint32_t a, std::uint32_t b)
{
  if (a > b)
  {
    std::swap(a, b);
  }
  // Where a finer cell's corner hangs in the middle, the crossing is the finer side's: the
  // interpolated midpoint gives the same point on the half that changes sign.
  const std::uint32_t m = midpointOf(a, b);
  if (m != NoIndex)
  {
    const bool positiveA = Values[a].g * Sign[a] > 0.0;
    const bool positiveM = Values[m].g * Sign[m] > 0.0;
    return positiveA != positiveM ? crossingBetween(a, m) : crossingBetween(m, b);
  }
  const auto [slot, added] = CrossingOfPair.tryEmplace(static_cast<std::uint64_t>(a) * Keys.size() + b, NoIndex);
  if (added)
  {
    slot = newCrossing(a, b); // touches no map: the reference stays valid
  }
  return slot;
}

void SurfaceMesher::crossingsInside(const std::array<std::uint32_t, 3>& face, std::uint32_t from, std::uint32_t to,
  std::vector<std::uint32_t>& out)
{
  out.clear();
  // On a face that finer cells share, the triangle is split at its sides' midpoints (all three
  // hang); the contour crosses the middle triangle's sides there, on the segment from -> to.
  std::array<std::uint32_t, 3> mid{};
  for (int k = 0; k < 3; ++k)
  {
    mid[k] = midpointOf(face[k], face[(k + 1) % 3]);
    if (mid[k] == NoIndex)
    {
      return;
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    const std::uint32_t p = mid[k];
    const std::uint32_t q = mid[(k + 1) % 3];
    if ((Values[p].g * Sign[p] > 0.0) != (Values[q].g * Sign[q] > 0.0) && Values[p].defined && Values[q].defined)
    {
      out.push_back(crossingBetween(p, q));
    }
  }
  const Vec3 origin = Crossings[from].point;
  const Vec3 along = Crossings[to].point - origin;
  std::sort(out.begin(), out.end(), [&](std::uint32_t x, std::uint32_t y) {
    return (Crossings[x].point - origin).dot(along) < (Crossings[y].point - origin).dot(along);
  });
}

void SurfaceMesher::triangulatePolygon(
  const std::vector<std::uint32_t>& loop, const std::vector<unsigned>& sides, const Vec3& towardPositive)
{
  // Ear clipping of a convex polygon: any ear will do except three vertices on one side (no area).
  std::vector<std::uint32_t> v = loop;
  std::vector<unsigned> s = sides;
  while (v.size() > 3)
  {
    bool clipped = false;
    for (std::size_t k = 0; k < v.size() && !clipped; ++k)
    {
      const std::size_t p = (k + v.size() - 1) % v.size();
      const std::size_t q = (k + 1) % v.size();
      if ((s[p] & s[k] & s[q]) != 0)
      {
        continue;
      }
      addTriangle(v[p], v[k], v[q], towardPositive);
      v.erase(v.begin() + static_cast<std::ptrdiff_t>(k));
      s.erase(s.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped)
    {
      return;
    }
  }
  if (v.size() == 3 && (s[0] & s[1] & s[2]) == 0)
  {
    addTriangle(v[0], v[1], v[2], towardPositive);
  }
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SurfaceMeshPieces.h
 * @brief The mesher's connected pieces (internal): counting them, measuring them, keeping cells.
 */
#pragma once

#include "pss/Types.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <vector>

namespace pss
{
namespace piece_utils
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

inline double cellMeasure(const std::array<std::uint32_t, 3>& t, const std::vector<Vec3>& points)
{
  return 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
}

inline double cellMeasure(const std::array<std::uint32_t, 2>& s, const std::vector<Vec3>& points)
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

inline std::array<std::uint32_t, 3> sortedTriangle(std::array<std::uint32_t, 3> t)
{
  std::sort(t.begin(), t.end());
  return t;
}

// Per vertex: whether the connected piece of @p triangles it belongs to has an area of at least
// @p minArea; counts the smaller pieces in @p smallPieces.
inline std::vector<char> largePieces(const std::vector<std::array<std::uint32_t, 3>>& triangles,
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

/// Per vertex: whether it is an end of a border edge of @p triangles (an edge of one triangle).
std::vector<char> borderVertices(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::size_t vertices);

} // namespace piece_utils
} // namespace pss

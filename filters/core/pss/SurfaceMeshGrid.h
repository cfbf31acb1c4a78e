// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SurfaceMeshGrid.h
 * @brief The mesher's sparse grids (internal): cell keys and the dilation of a set of cells.
 */
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace pss
{
namespace grid
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
inline void forEachWidenedRun(const std::vector<Key>& keys, const KeyOrder& o, long long low, long long high, Visit&& visit)
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
inline std::vector<Key> rekey(const std::vector<Key>& keys, const KeyOrder& from, const KeyOrder& to)
{
  std::vector<Key> out(keys.size());
  std::transform(keys.begin(), keys.end(), out.begin(), [&](Key k) { return to.encode(from.decode(k)); });
  std::sort(out.begin(), out.end());
  return out;
}

// Widens every key along each axis in turn (a separable dilation of the set of cells), ending in
// the canonical order (x fastest). Refuses, before allocating, a result above @p limit keys.
inline std::vector<Key> widen(std::vector<Key> keys, const Coords& size, int dimension, long long low, long long high,
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

} // namespace grid
} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
// spatialOrder() and finiteBounds(): the Morton order that the index's build and every batch of
// projections visit points in.
#include "pss/PointIndex.h"

#include "pss/ChunkedLoops.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

namespace pss
{

// The bounds of the finite points, +inf/-inf when there is none. Chunks are combined as they
// come: min and max of the same values are the same values in any order (only the sign of a zero
// may differ, which no caller's arithmetic can see).
std::pair<Vec3, Vec3> finiteBounds(const std::vector<Vec3>& points, int threads)
{
  const double inf = std::numeric_limits<double>::infinity();
  const Chunks chunks(points.size(), threads);
  std::vector<std::pair<Vec3, Vec3>> part(chunks.count, { Vec3::Constant(inf), Vec3::Constant(-inf) });
  chunks.run(threads, [&](std::size_t c, std::size_t begin, std::size_t end) {
    Vec3 lo = part[c].first;
    Vec3 hi = part[c].second;
    for (std::size_t i = begin; i < end; ++i)
    {
      if (isFinite(points[i]))
      {
        lo = lo.cwiseMin(points[i]);
        hi = hi.cwiseMax(points[i]);
      }
    }
    part[c] = { lo, hi };
  });
  std::pair<Vec3, Vec3> bounds = part.front();
  for (const auto& [lo, hi] : part)
  {
    bounds.first = bounds.first.cwiseMin(lo);
    bounds.second = bounds.second.cwiseMax(hi);
  }
  return bounds;
}

namespace
{

// The 21 low bits of v spread to every third bit (bit k moves to bit 3k).
std::uint64_t spreadBits(std::uint64_t v)
{
  v &= 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffu;
  v = (v | v << 16) & 0x1f0000ff0000ffu;
  v = (v | v << 8) & 0x100f00f00f00f00fu;
  v = (v | v << 4) & 0x10c30c30c30c30c3u;
  v = (v | v << 2) & 0x1249249249249249u;
  return v;
}

// A point's Morton code and its input index. The empty constructor leaves both unset on purpose:
// the arrays of them are filled in parallel right away, and zeroing them first would be a serial
// pass over 16 bytes a point.
struct Keyed
{
  Keyed() {} // not = default: vector(n) would then zero every item
  Keyed(std::uint64_t k, std::uint32_t i)
    : key(k)
    , id(i)
  {
  }
  std::uint64_t key;
  std::uint32_t id;
};

// The ids of @p keyed in ascending key order, equal keys by ascending id: what std::sort of the
// (key, id) pairs gives when the ids come in ascending order, as they do here, but a stable
// least-significant-digit radix sort of 8-bit digits, several times faster on millions of points
// (a comparison sort's random accesses dominated building the index of a large cloud). Digits
// that every key shares are skipped. Each pass counts the digits of each chunk on its own thread;
// a chunk's items of one digit value then go after those of every smaller value and of every
// earlier chunk, which is where the serial pass puts them, so the order is the same for every
// thread count.
std::vector<std::uint32_t> sortedIds(std::vector<Keyed>& keyed, int threads)
{
  constexpr int Bits = 8;
  constexpr std::size_t Buckets = std::size_t(1) << Bits;
  const std::size_t n = keyed.size();
  std::vector<Keyed> scratch(n);
  const Chunks chunks(n, threads);
  std::vector<std::array<std::size_t, Buckets>> start(chunks.count);
  for (int shift = 0; shift < 64; shift += Bits)
  {
    chunks.run(threads, [&](std::size_t c, std::size_t begin, std::size_t end) {
      std::array<std::size_t, Buckets>& count = start[c];
      count.fill(0);
      for (std::size_t i = begin; i < end; ++i)
      {
        ++count[(keyed[i].key >> shift) & (Buckets - 1)];
      }
    });
    bool moves = true;
    for (std::size_t b = 0; b < Buckets && moves; ++b)
    {
      std::size_t total = 0;
      for (const auto& count : start)
      {
        total += count[b];
      }
      moves = total != n;
    }
    if (!moves)
    {
      continue; // one digit value for all: this pass would not move anything
    }
    std::size_t sum = 0;
    for (std::size_t b = 0; b < Buckets; ++b)
    {
      for (auto& count : start)
      {
        sum += std::exchange(count[b], sum);
      }
    }
    chunks.run(threads, [&](std::size_t c, std::size_t begin, std::size_t end) {
      std::array<std::size_t, Buckets>& next = start[c];
      for (std::size_t i = begin; i < end; ++i)
      {
        scratch[next[(keyed[i].key >> shift) & (Buckets - 1)]++] = keyed[i];
      }
    });
    keyed.swap(scratch);
  }
  std::vector<std::uint32_t> order(n);
  forEachRange(n, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      order[i] = keyed[i].id;
    }
  });
  return order;
}

} // namespace

std::vector<std::uint32_t> spatialOrder(const std::vector<Vec3>& points, int threads)
{
  if (points.size() >= std::size_t(UINT32_MAX))
  {
    throw std::invalid_argument("more than 2^32 - 1 points are not supported");
  }
  const auto [lo, hi] = finiteBounds(points, threads);
  // Cells per unit length on each axis (0 on a flat axis); the extent may overflow to infinity
  // for coordinates near double's limits, which only coarsens the grid to one cell.
  const double cells = double((1u << 21) - 1);
  Vec3 scale = Vec3::Zero();
  for (int d = 0; d < 3; ++d)
  {
    const double extent = hi[d] - lo[d];
    scale[d] = extent > 0.0 && std::isfinite(extent) ? cells / extent : 0.0;
  }
  std::vector<Keyed> keyed(points.size());
  forEachRange(points.size(), threads, [&, lo = lo](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const Vec3& p = points[i];
      std::uint64_t code = std::numeric_limits<std::uint64_t>::max();
      if (isFinite(p))
      {
        code = 0;
        for (int d = 0; d < 3; ++d)
        {
          const double cell = std::min(cells, std::max(0.0, (p[d] - lo[d]) * scale[d]));
          code |= spreadBits(static_cast<std::uint64_t>(cell)) << d;
        }
      }
      keyed[i] = Keyed(code, static_cast<std::uint32_t>(i));
    }
  });
  return sortedIds(keyed, threads);
}

} // namespace pss

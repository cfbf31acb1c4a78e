// SPDX-License-Identifier: BSD-3-Clause
// The index's loops over every point (private to the core: not installed, included by
// PointIndex.cxx and SpatialOrder.cxx only): short loops stay on one thread, and loops whose
// per-chunk results are combined run in chunks whose order, not count, decides the result.
#ifndef pss_ChunkedLoops_h
#define pss_ChunkedLoops_h

#include "pss/Parallel.h"

#include <algorithm>
#include <cstddef>
#include <functional>

namespace pss
{

// Below this many items a loop stays on the calling thread: starting threads would cost more than
// the loop (small clouds are indexed often, e.g. once per test or per filter update).
constexpr std::size_t MinParallelItems = std::size_t(1) << 14;

// parallelFor for the index's cheap per-item loops: on one thread when the loop is short.
inline void forEachRange(std::size_t n, int threads, const std::function<void(std::size_t, std::size_t)>& body)
{
  parallelFor(n, n < MinParallelItems ? 1 : threads, body);
}

// [0, n) cut into a few contiguous chunks per thread, numbered in index order, for loops whose
// per-chunk results (counts, histograms, bounds) are then combined in chunk order: a result that
// depends only on that order is the same for every chunk count. One chunk for one thread.
struct Chunks
{
  Chunks(std::size_t items, int threads)
    : n(items)
  {
    const auto workers = static_cast<std::size_t>(resolveThreadCount(threads));
    count = workers <= 1 ? 1 : std::clamp<std::size_t>(n / MinParallelItems, 1, 4 * workers);
  }
  std::size_t begin(std::size_t c) const { return n * c / count; }
  /// Calls body(c, begin, end) for every chunk c, each chunk on one thread.
  template <class Body>
  void run(int threads, Body&& body) const
  {
    parallelFor(count, threads, [&](std::size_t first, std::size_t last) {
      for (std::size_t c = first; c < last; ++c)
      {
        body(c, begin(c), begin(c + 1));
      }
    });
  }
  std::size_t n = 0;
  std::size_t count = 1;
};

} // namespace pss

#endif

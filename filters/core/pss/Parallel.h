// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Parallel.h
 * @brief A minimal parallel-for for the VTK-free core, and the loop type through which an
 *        application runs the core's batch entry points on its own threads (the VTK layer's is
 *        built on vtkSMPTools).
 */
#pragma once

#include <cstddef>
#include <functional>
#include <mutex>
#include <utility>
#include <vector>

namespace pss
{

struct Workspace;

/// Number of threads meant by @p requested: itself when > 0, all hardware threads when 0.
int resolveThreadCount(int requested);

/**
 * Calls body(begin, end) on disjoint chunks covering [0, n) from @p threads threads (0 = all
 * cores). Each index is visited exactly once; chunking does not change what is computed, so
 * results written per index are independent of the thread count.
 */
void parallelFor(std::size_t n, int threads, const std::function<void(std::size_t, std::size_t)>& body);

/**
 * The chunks of [0, n) that @p workers workers take in turn. Each worker owns a contiguous part
 * and takes chunks from its front; a worker whose part is done takes chunks from the back of the
 * part with the most left. The batch entry points visit points in spatial order, so contiguous
 * parts keep each worker's points, and what its workspace caches (candidate points, neighbourhoods),
 * together, while the stealing still balances uneven per-point cost (projections far from the
 * cloud take many more iterations than those near it). Which worker runs a chunk never changes
 * what it computes.
 */
class ChunkQueue
{
public:
  /// Chunks of @p chunk indices (at least 1), the last of a part shorter.
  ChunkQueue(std::size_t n, std::size_t workers, std::size_t chunk);
  /// The next chunk [begin, end) for @p worker (in [0, workers)); false when none is left.
  bool take(std::size_t worker, std::size_t& begin, std::size_t& end);

private:
  struct Part
  {
    std::size_t front = 0;
    std::size_t back = 0;
  };
  std::size_t Chunk;
  std::vector<Part> Parts;
  std::mutex Mutex;
};

/// A chunk of a loop's work: the indices [begin, end), with the workspace of the thread running it.
using ChunkBody = std::function<void(std::size_t begin, std::size_t end, Workspace& ws)>;

/// The same, with a Workspace per worker thread, which every chunk that worker runs is handed
/// (created empty: what a chunk leaves there only saves the next chunk work).
void parallelFor(std::size_t n, int threads, const ChunkBody& body);

/// The part [first, second] of an entry point's whole work, within [0, 1], that one loop does.
using LoopShare = std::pair<double, double>;

/**
 * How the batch entry points (forEachStart, projectEach, extractSurfaceMesh) run their loops:
 * loop(n, share, body) calls body on disjoint chunks covering [0, n), each with the workspace of
 * the thread that runs it, and returns false when it stopped early (the user aborted: some chunks
 * did not run). @p share says which part of the whole work the loop is, for progress reports.
 * threadLoop() is the core's own; the VTK filters pass one on vtkSMPTools that reports progress
 * and honours AbortExecute, so the entry points' stages are written once, here.
 */
using ParallelLoop = std::function<bool(std::size_t n, LoopShare share, const ChunkBody& body)>;

/// parallelFor on @p threads threads (0 = all cores) as a ParallelLoop: it never stops early.
ParallelLoop threadLoop(int threads);

} // namespace pss

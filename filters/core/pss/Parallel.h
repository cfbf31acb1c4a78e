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
#include <utility>

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

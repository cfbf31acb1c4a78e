// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Parallel.h
 * @brief A minimal parallel-for for the VTK-free core (the VTK layer uses vtkSMPTools instead).
 */
#pragma once

#include <cstddef>
#include <functional>

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

/// The same, with a Workspace per worker thread, which every chunk that worker runs is handed
/// (created empty: what a chunk leaves there only saves the next chunk work).
void parallelFor(
  std::size_t n, int threads, const std::function<void(std::size_t, std::size_t, Workspace&)>& body);

} // namespace pss

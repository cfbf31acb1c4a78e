// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Parallel.h"

#include "pss/Workspace.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace pss
{

int resolveThreadCount(int requested)
{
  if (requested > 0)
  {
    return requested;
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

void parallelFor(std::size_t n, int threads, const std::function<void(std::size_t, std::size_t)>& body)
{
  // An empty workspace allocates nothing: unused, it costs nothing.
  parallelFor(n, threads, [&](std::size_t begin, std::size_t end, Workspace&) { body(begin, end); });
}

ParallelLoop threadLoop(int threads)
{
  return [threads](std::size_t n, LoopShare, const ChunkBody& body) {
    parallelFor(n, threads, body);
    return true;
  };
}

void parallelFor(std::size_t n, int threads, const ChunkBody& body)
{
  if (n == 0)
  {
    return;
  }
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(resolveThreadCount(threads)), n);
  if (workers <= 1)
  {
    Workspace ws;
    body(0, n, ws);
    return;
  }
  // Small chunks handed out on demand balance uneven per-point cost (projections far from the
  // cloud take many more iterations than those near it).
  const std::size_t chunk = std::max<std::size_t>(1, n / (workers * 16));
  std::atomic<std::size_t> next{ 0 };
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&]() {
    try
    {
      Workspace ws;
      for (std::size_t begin = next.fetch_add(chunk); begin < n; begin = next.fetch_add(chunk))
      {
        body(begin, std::min(n, begin + chunk), ws);
      }
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure)
      {
        failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t i = 1; i < workers; ++i)
  {
    pool.emplace_back(work);
  }
  work();
  for (std::thread& t : pool)
  {
    t.join();
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
}

} // namespace pss

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

ChunkQueue::ChunkQueue(std::size_t n, std::size_t workers, std::size_t chunk)
  : Chunk(std::max<std::size_t>(1, chunk))
  , Parts(std::max<std::size_t>(1, workers))
{
  for (std::size_t w = 0; w < Parts.size(); ++w)
  {
    Parts[w] = { n * w / Parts.size(), n * (w + 1) / Parts.size() };
  }
}

bool ChunkQueue::take(std::size_t worker, std::size_t& begin, std::size_t& end)
{
  // A lock per chunk costs nothing beside a chunk's work.
  std::lock_guard<std::mutex> lock(Mutex);
  Part& own = Parts[worker];
  if (own.front < own.back)
  {
    begin = own.front;
    end = std::min(own.back, begin + Chunk);
    own.front = end;
    return true;
  }
  Part* victim = &own;
  for (Part& p : Parts)
  {
    if (p.back - p.front > victim->back - victim->front)
    {
      victim = &p;
    }
  }
  if (victim->front >= victim->back)
  {
    return false;
  }
  end = victim->back;
  begin = end - std::min(end - victim->front, Chunk);
  victim->back = begin;
  return true;
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
  // Some 16 chunks a worker.
  ChunkQueue queue(n, workers, n / (workers * 16));
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&](std::size_t self) {
    try
    {
      Workspace ws;
      std::size_t begin = 0;
      std::size_t end = 0;
      while (queue.take(self, begin, end))
      {
        body(begin, end, ws);
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
    pool.emplace_back(work, i);
  }
  work(0);
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

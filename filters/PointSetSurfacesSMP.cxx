// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesSMP.h"

#include "pss/Workspace.h"

#include "vtkAlgorithm.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>

namespace pss_vtk
{

namespace
{

// The loop behind every other: chunks of the range on vtkSMPTools, each with its thread's workspace.
bool ForChunks(vtkAlgorithm* algorithm, vtkIdType n, const pss::ChunkBody& body, double progressBegin, double progressEnd)
{
  if (n <= 0)
  {
    return true;
  }
  std::atomic<vtkIdType> done{ 0 };
  std::atomic<bool> aborted{ false };
  // Chunks small enough for balance (far-off points cost many iterations) and for progress.
  const int threads = std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
  const vtkIdType grain = std::max<vtkIdType>(1, std::min<vtkIdType>(1024, n / (threads * 32)));
  vtkSMPThreadLocal<pss::Workspace> workspaces;
  // One task per thread, each taking its chunks from a ChunkQueue (its own part of the range
  // first: the range is in spatial order, and a workspace's caches serve nearby points).
  pss::ChunkQueue queue(static_cast<std::size_t>(n), static_cast<std::size_t>(threads), static_cast<std::size_t>(grain));
  vtkSMPTools::For(0, threads, 1, [&](vtkIdType firstWorker, vtkIdType lastWorker) {
    for (vtkIdType worker = firstWorker; worker < lastWorker; ++worker)
    {
      std::size_t begin = 0;
      std::size_t end = 0;
      while (!aborted.load(std::memory_order_relaxed) && queue.take(static_cast<std::size_t>(worker), begin, end))
      {
        body(begin, end, workspaces.Local());
        const vtkIdType total = done.fetch_add(static_cast<vtkIdType>(end - begin)) + static_cast<vtkIdType>(end - begin);
        // When the whole range fits one chunk, vtkSMPTools::For runs it inline, outside any
        // parallel scope, where GetSingleThread() must not be asked (it crashes with VTK 9.2's
        // STDThread).
        const bool reporter = !vtkSMPTools::IsParallelScope() || vtkSMPTools::GetSingleThread();
        if (algorithm && reporter)
        {
          algorithm->UpdateProgress(progressBegin + (progressEnd - progressBegin) * double(total) / double(n));
          if (algorithm->GetAbortExecute())
          {
            aborted = true;
          }
        }
      }
    }
  });
  return !aborted.load();
}

} // namespace

bool ParallelFor(vtkAlgorithm* algorithm, vtkIdType n, const std::function<void(vtkIdType)>& body,
  double progressBegin, double progressEnd)
{
  // An empty workspace allocates nothing: unused, it costs nothing.
  return ParallelFor(
    algorithm, n, [&](vtkIdType i, pss::Workspace&) { body(i); }, progressBegin, progressEnd);
}

bool ParallelFor(vtkAlgorithm* algorithm, vtkIdType n, const std::function<void(vtkIdType, pss::Workspace&)>& body,
  double progressBegin, double progressEnd)
{
  return ForChunks(
    algorithm, n,
    [&](std::size_t begin, std::size_t end, pss::Workspace& ws) {
      for (std::size_t i = begin; i < end; ++i)
      {
        body(static_cast<vtkIdType>(i), ws);
      }
    },
    progressBegin, progressEnd);
}

pss::ParallelLoop SMPLoop(vtkAlgorithm* algorithm)
{
  return [algorithm](std::size_t n, pss::LoopShare share, const pss::ChunkBody& body) {
    return ForChunks(algorithm, static_cast<vtkIdType>(n), body, share.first, share.second);
  };
}

int CoreThreads()
{
  return vtkSMPTools::IsParallelScope() ? 1 : std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
}

}

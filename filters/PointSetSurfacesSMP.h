// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesSMP.h
 * @brief Private helpers of the VTK module: a threaded loop with progress and abort.
 *
 * The loop runs on vtkSMPTools' backend as the application set it; the filters never change it
 * (see vtkPointSetSurface::UseThreadedBackend).
 */
#ifndef PointSetSurfacesSMP_h
#define PointSetSurfacesSMP_h

#include "vtkType.h"

#include <functional>

class vtkAlgorithm;

#include "pss/Parallel.h"

namespace pss_vtk
{

/**
 * Calls @p body(i) for every i in [0, n) through vtkSMPTools, in chunks. The thread that owns the
 * single scope reports progress to @p algorithm (from @p progressBegin to @p progressEnd) and
 * polls its AbortExecute flag; once set, the remaining chunks are skipped. Returns false when
 * the loop was aborted.
 */
bool ParallelFor(vtkAlgorithm* algorithm, vtkIdType n, const std::function<void(vtkIdType)>& body,
  double progressBegin = 0.0, double progressEnd = 1.0);

/// The same, handing @p body the core's Workspace of the thread that runs it (one per thread,
/// through vtkSMPThreadLocal, for the loop's duration).
bool ParallelFor(vtkAlgorithm* algorithm, vtkIdType n, const std::function<void(vtkIdType, pss::Workspace&)>& body,
  double progressBegin = 0.0, double progressEnd = 1.0);

/**
 * The core's batch entry points (pss::forEachStart, pss::extractSurfaceMesh) run on this loop
 * inside @p algorithm's RequestData: vtkSMPTools threads, a workspace per thread, progress over
 * each loop's share of the work, and a stop once AbortExecute is set.
 */
pss::ParallelLoop SMPLoop(vtkAlgorithm* algorithm);

/**
 * The thread count for the core's own loops (pss::parallelFor: the index, the automatic scale):
 * vtkSMPTools' estimate, so that they follow the backend and the count the application set
 * (Sequential or `pss --threads 1`: one thread), and 1 inside a vtkSMPTools parallel scope, where
 * the other threads are busy already.
 */
int CoreThreads();

}

#endif

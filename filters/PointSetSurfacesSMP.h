// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesSMP.h
 * @brief Private helpers of the VTK module: a threaded loop with progress and abort.
 *
 * ParaView's VTK on Debian defaults vtkSMPTools to the Sequential backend although STDThread is
 * compiled in. Unless the user chose a backend through VTK_SMP_BACKEND_IN_USE, the first filter
 * run switches Sequential to STDThread, so every filter uses all cores by default.
 */
#ifndef PointSetSurfacesSMP_h
#define PointSetSurfacesSMP_h

#include "vtkType.h"

#include <functional>

class vtkAlgorithm;

namespace pss
{
struct Workspace;
}

namespace pss_vtk
{

/// Switches vtkSMPTools from Sequential to STDThread unless VTK_SMP_BACKEND_IN_USE is set.
void EnsureParallelBackend();

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

}

#endif

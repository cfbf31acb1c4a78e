// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesDistributedRun.h
 * @brief Private to the filters: the one driver of a per-point evaluator's run, in one process or
 *        distributed over MPI ranks (on the gathered cloud, or with ghost points in rounds).
 *
 * A filter's RequestData reads as prepare, evaluate, attach:
 * @code
 *   pss_vtk::DistributedRun run(this, this->Surface, controller, this->GhostMargin);
 *   if (!run.Prepare(inputVector, watch, cloud, "", this->GatheredCloud)) return 0;
 *   const vtkIdType first = run.FirstGlobalId(n);            // collective: before any early return
 *   if (!run.Evaluate(order, n, pointAt, evaluate)) return 0; // once, or in ghost rounds
 *   run.AttachGhostFieldData(output);
 *   run.AttachGlobalIds(output->GetPointData(), first, n);
 * @endcode
 * Every collective step is taken on every rank in the same order whatever it holds, so no rank
 * waits for one that stopped; every failure is reported on every rank alike.
 */
#ifndef PointSetSurfacesDistributedRun_h
#define PointSetSurfacesDistributedRun_h

#include "PointSetSurfacesDistributed.h"

#include "pss/Types.h"

#include <cstddef>

namespace pss_vtk
{

class DistributedRun
{
public:
  /// @p controller: the filter's distributed controller (nullptr in one process);
  /// @p ghostMargin: its GhostMargin, in h (above 0 in MPI: ghost points instead of the gathered
  /// cloud; above 0 in one process: neighbourhoods summed in coordinate order, as with ghosts).
  DistributedRun(
    vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkMultiProcessController* controller, double ghostMargin);

  /**
   * Collective. The upstream-failure vote over every input of the algorithm (@p inputVector, as
   * RequestData has it, against @p watch), then the surface: the ghost run's shared frame
   * (BeginGhostRun) with ghost points, else the surface prepared on @p cloud, gathered from every
   * rank into @p gathered in MPI. @p what completes "cannot define the surface<what>". False on
   * every rank after the same error.
   */
  bool Prepare(vtkInformationVector** inputVector, UpstreamErrorWatch& watch, vtkPointSet* cloud, const char* what,
    vtkSmartPointer<vtkPolyData>& gathered);

  /// Collective in MPI: the global id of this rank's first of its @p count items (the items of
  /// the ranks before it); 0 in one process.
  vtkIdType FirstGlobalId(vtkIdType count);

  /**
   * Evaluates this rank's points @p order (indices below @p n, in the order to visit them) with
   * @p evaluate. In one process (or on the gathered cloud) it is called once, with an empty
   * escape list. With ghost points it is collective: the points are evaluated in ghost rounds
   * (RunGhostRounds; @p pointAt gives their coordinates), and a rank with no point still takes
   * part in every round. False after an error (reported) or when @p evaluate returned false.
   */
  bool Evaluate(std::vector<std::uint32_t> order, std::size_t n, const GhostPointAt& pointAt,
    const GhostEvaluation& evaluate);

  /// Evaluate() of every point 0..@p n-1 for an @p evaluate that, in one process, visits them
  /// its own way: it is then called with an empty order (no list of n indices is built).
  bool EvaluateAll(std::size_t n, const GhostPointAt& pointAt, const GhostEvaluation& evaluate);

  /// Collective in MPI: the largest @p value of every rank (@p value itself in one process).
  double MaximumOverRanks(double value);

  /**
   * Collective in MPI (after Prepare, before any early return). Whether the delta lattice serves
   * the start points @p starts of every rank (pss::latticeServes on their number and the lattice
   * bricks they occupy, so that the choice is the one process's); true when the surface reads no
   * lattice (another definition, or DeltaLatticeSpacing 0).
   */
  bool LatticeServes(vtkPoints* starts);

  vtkMultiProcessController* GetController() const { return this->Controller; }
  /// Whether the run uses ghost points (MPI and GhostMargin > 0).
  bool HasGhosts() const { return this->Ghosts; }
  /// The ghost run's shared frame (meaningful with ghost points only).
  GhostRun& GetGhostRun() { return this->Ghost; }
  /// The most ghost rounds any Evaluate() took (0 without ghost points).
  int GetRounds() const { return this->Rounds; }

  /// The one-process h, dimension and centroid of the cloud, on every rank alike (a rank with
  /// ghost points may hold no surface of its own).
  double GetScale() const;
  int GetDimension() const;
  pss::Vec3 GetCentroid() const;

  /// Field data `ScaleFactor` and `Dimension` of @p output (the run's, with ghost points).
  void AttachSurfaceFieldData(vtkDataObject* output) const;
  /// Field data `GhostRounds` and `GhostPoints` of @p output, with ghost points; else nothing.
  void AttachGhostFieldData(vtkDataObject* output) const;
  /// `GlobalPointIds` first, first + 1, ... on the @p n tuples of @p pd, in MPI; else nothing.
  void AttachGlobalIds(vtkPointData* pd, vtkIdType first, vtkIdType n) const;

private:
  vtkAlgorithm* Algorithm;
  vtkPointSetSurface* Surface;
  vtkMultiProcessController* Controller;
  double Margin;
  bool Ghosts;
  GhostRun Ghost;
  int Rounds = 0;
};

}

#endif

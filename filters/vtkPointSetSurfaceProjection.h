// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceProjection
 * @brief   move points onto a moving-least-squares point-set surface, reporting how each got there
 *
 * Input 0 is the point cloud that defines the surface (any vtkPointSet). Input 1, optional, holds
 * the start points; without it the cloud's own points are projected. Each start point x is moved
 * by the procedure f of the paper: take n(x), go to the nearest local minimum (or maximum, with
 * SeekMaxima) of e along the line through x in direction n(x), repeat until a step is shorter
 * than Tolerance * h (Procedure EXTREMAL); or x <- x - <n, x - c(x)> n (Procedure PLANE, the
 * centre-of-mass fast path). Which surface, at which scale, is GetSurface()'s business.
 *
 * Output 0: one vertex per start point, at the end of its projection, with the start points'
 * point data passed through and these arrays:
 * - `Normal` (3 doubles): n at the end point, oriented away from the cloud's centroid (toward the
 *   viewpoint when there is one), or consistently over the end points with PropagateNormals;
 * - `Energy`: e(x, n(x)) at the end point (LevinMLS may underflow to 0);
 * - `Displacement` (3 doubles): end point minus start point;
 * - `Iterations`, `Converged` (0/1), `Stability` (of n at the end point);
 * - `ExtremumType`: 0 none, 1 minimum (on the extremal surface), 2 maximum;
 * - `StopReason`: 0 converged, 1 iteration limit, 2 n undefined, 3 no extremum along the line,
 *   4 start point with NaN/Inf coordinates (left where it was, and flagged here).
 *
 * Output 1 (GenerateProjectionLines on): one line cell per start point from the start to the end
 * point (Figure 1 of the paper), with `Converged` and `StopReason` as cell data.
 *
 * Runs threaded through vtkSMPTools (on the backend the application chose: see
 * vtkPointSetSurface::UseThreadedBackend), reports progress and honours AbortExecute.
 *
 * Under MPI (a global controller of several processes) every rank must execute; each rank
 * projects its own start points and the output stays distributed, with `GlobalPointIds`, equal
 * to the one-process output. GhostMargin 0 gathers the whole cloud on every rank; GhostMargin > 0
 * exchanges only ghost points around each rank's start points. See docs/distributed.md.
 *
 * @sa vtkPointSetSurface vtkPointSetSurfaceDomainClassifier
 */
#ifndef vtkPointSetSurfaceProjection_h
#define vtkPointSetSurfaceProjection_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPointSetSurfaceAlgorithm.h"

#include <cstdint> // for std::uint32_t
#include <vector>  // for std::vector

class vtkPointData;
class vtkPointSet;
class vtkPoints;

#ifndef __VTK_WRAP__
namespace pss
{
class SurfaceDefinition;
struct ProjectionOptions;
struct ProjectionResult;
struct Workspace;
}
#endif

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceProjection : public vtkPointSetSurfaceAlgorithm
{
public:
  static vtkPointSetSurfaceProjection* New();
  vtkTypeMacro(vtkPointSetSurfaceProjection, vtkPointSetSurfaceAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ProcedureType
  {
    EXTREMAL = 0,
    PLANE = 1
  };

  /// Start points (input 1). Without them the cloud itself is projected.
  void SetStartPointsConnection(vtkAlgorithmOutput* output);
  void SetStartPointsData(vtkDataObject* data);

  ///@{
  /// EXTREMAL (Definition 1, default) or PLANE (the centre-of-mass procedure).
  vtkSetClampMacro(Procedure, int, EXTREMAL, PLANE);
  vtkGetMacro(Procedure, int);
  void SetProcedureToExtremal() { this->SetProcedure(EXTREMAL); }
  void SetProcedureToPlane() { this->SetProcedure(PLANE); }
  ///@}

  ///@{
  /// Iteration limit per point. Default 100.
  vtkSetClampMacro(MaxIterations, int, 1, 100000);
  vtkGetMacro(MaxIterations, int);
  ///@}

  ///@{
  /// Convergence: a step shorter than Tolerance * h. Default 1e-6.
  vtkSetClampMacro(Tolerance, double, 1e-14, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /// Longest search along one line, in units of h. Default 1000.
  vtkSetClampMacro(MaxTravel, double, 1e-3, 1e9);
  vtkGetMacro(MaxTravel, double);
  ///@}

  ///@{
  /// Converge to maxima of e along n instead of minima (the green curves of Figures 9 and 10).
  vtkSetMacro(SeekMaxima, bool);
  vtkGetMacro(SeekMaxima, bool);
  vtkBooleanMacro(SeekMaxima, bool);
  ///@}

  ///@{
  /**
   * Orient `Normal` consistently over the end points instead of point by point: a maximum
   * spanning tree of |n_i . n_j| over their NormalNeighbors-nearest-neighbour graph (Hoppe et
   * al.), each connected piece from its highest point (largest z) with its normal up, or with
   * every normal toward the viewpoint when there is one (pss::orientNormals). The cloud projected
   * onto itself gives the cloud's oriented normals. Default off. One process only: a distributed
   * run with it is an error.
   */
  vtkSetMacro(PropagateNormals, bool);
  vtkGetMacro(PropagateNormals, bool);
  vtkBooleanMacro(PropagateNormals, bool);
  ///@}

  ///@{
  /// Neighbours of each end point in PropagateNormals' graph, within [1, 100]. Default 10.
  vtkSetClampMacro(NormalNeighbors, int, 1, 100);
  vtkGetMacro(NormalNeighbors, int);
  ///@}

  ///@{
  /// Fill output 1 with a segment from each start point to its projection. Default off.
  vtkSetMacro(GenerateProjectionLines, bool);
  vtkGetMacro(GenerateProjectionLines, bool);
  vtkBooleanMacro(GenerateProjectionLines, bool);
  ///@}

  ///@{
  /**
   * Distributed runs only (ignored in one process): 0 (default) gathers the whole cloud on every
   * rank, exact (bitwise the one-process result, automatic h allowed) but with every point on
   * every rank; > 0 exchanges only ghost points, within this many h of the box of a rank's start
   * points, for memory that shrinks with the number of ranks. A margin too small costs extra
   * rounds, never accuracy. 4 (the kernel's support of 3 h plus 1 h of travel) is a good start.
   * With the automatic h, rank 0 gathers the whole cloud once to estimate it.
   */
  vtkSetClampMacro(GhostMargin, double, 0.0, 1e6);
  vtkGetMacro(GhostMargin, double);
  ///@}

  /// The rounds of ghost exchange the last distributed update with GhostMargin > 0 took (1: no
  /// projection needed more ghost points; 0 otherwise). Also the output's field data
  /// `GhostRounds` on ranks with start points, beside `GhostPoints`: the other ranks' points the
  /// rank held in its last round (its memory overhead).
  vtkGetMacro(GhostRounds, int);

protected:
  vtkPointSetSurfaceProjection();
  ~vtkPointSetSurfaceProjection() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Projection and classification give the one-process result in a distributed run.
  bool SupportsDistributedRun() const override { return true; }

#ifndef __VTK_WRAP__
  /**
   * Hook for subclasses, called before the per-point loop with the prepared surface and the
   * number of start points (to validate parameters, size per-point storage). With ghost points
   * it is called again before each later round, with that round's surface: per-point storage of
   * the same size must then be kept (only some points are projected again).
   * Return false (after vtkErrorMacro) to fail the update. The default does nothing.
   */
  virtual bool BeginProjection(const pss::SurfaceDefinition& surface, vtkIdType numberOfStarts);

  /**
   * Hook for subclasses: the per-point work for start point @p i at @p start. Called from several
   * threads at once, exactly once per i: an override may only write state belonging to i. It must
   * return the projection of @p start with @p options (the standard arrays are made from it).
   * @p ws is the calling thread's. The default is pss::project.
   */
  virtual pss::ProjectionResult ProjectPoint(vtkIdType i, const double start[3],
    const pss::SurfaceDefinition& surface, const pss::ProjectionOptions& options, pss::Workspace& ws);

  /**
   * Hook for subclasses: add the arrays they filled during the per-point loop to the output point
   * data. Called after the standard arrays; return false (after vtkErrorMacro) to fail the update.
   */
  virtual bool AddPointArrays(vtkPointSet* starts, vtkPointData* outPD);
#endif

  int Procedure = EXTREMAL;
  int MaxIterations = 100;
  double Tolerance = 1e-6;
  double MaxTravel = 1000.0;
  bool SeekMaxima = false;
  bool GenerateProjectionLines = false;
  bool PropagateNormals = false;
  int NormalNeighbors = 10;
  double GhostMargin = 0.0;
  int GhostRounds = 0;

private:
  /// PropagateNormals: orients @p normals (three per end point) over @p endPoints' graph.
  bool OrientOutputNormals(vtkPoints* endPoints, double* normals);
  /// The order to project @p startPoints in (neighbours together); when the starts are the indexed
  /// cloud, @p positions receives where each of them is in the index (else it is left empty).
  /// False after an error.
  bool OrderStartPoints(vtkPointSet* starts, vtkPointSet* cloud, vtkPoints* startPoints, bool distributed,
    std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& positions);

  vtkPointSetSurfaceProjection(const vtkPointSetSurfaceProjection&) = delete;
  void operator=(const vtkPointSetSurfaceProjection&) = delete;
};

#endif

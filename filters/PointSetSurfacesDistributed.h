// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesDistributed.h
 * @brief Private to the filters: the MPI protocol of a distributed run (the surface prepared on
 *        the gathered cloud or with ghost points, the upstream-failure vote, global ids). The
 *        filters reach it through pss_vtk::DistributedRun (PointSetSurfacesDistributedRun.h).
 */
#ifndef PointSetSurfacesDistributed_h
#define PointSetSurfacesDistributed_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "pss/SurfaceMesh.h"

#include <climits>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkInformationVector;
class vtkMultiProcessController;
class vtkPointData;
class vtkPoints;
class vtkPointSet;
class vtkPointSetSurface;
class vtkPolyData;

namespace pss_vtk
{
class UpstreamErrorWatch;

/**
 * What every filter does first: prepares @p surface on @p cloud, reporting a missing surface or a
 * failed Prepare() as an error of @p algorithm ("cannot define the surface<what>: ...") and
 * returning false, and warning when cloud points with NaN/Inf coordinates were left out.
 * Unless @p gathered says that @p cloud is already the whole cloud of every rank (GatherCloud),
 * an MPI run of more than one process is refused: each rank would take its piece for the whole.
 * @p coordinateOrder: vtkPointSetSurface::Prepare(cloud, coordinateOrder).
 */
bool PrepareSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkPointSet* cloud, const char* what = "",
  bool gathered = false, bool coordinateOrder = false);

/// The global vtkMultiProcessController when this process is one of several (an MPI run of more
/// than one process), else nullptr.
vtkMultiProcessController* MultiProcessController();

/**
 * PrepareSurface for a filter that runs distributed. With @p controller (an MPI run) it is
 * collective: every rank's @p cloud is gathered into @p gathered (GatherCloud) and the surface
 * prepared on that, so every rank gets the one-process surface or the same error. Without, the
 * surface is prepared on @p cloud and @p gathered released.
 */
bool PrepareDistributedSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface,
  vtkMultiProcessController* controller, vtkPointSet* cloud, const char* what, vtkSmartPointer<vtkPolyData>& gathered,
  bool coordinateOrder = false);

/// Where every rank's items go in an AllGatherV of @p length items from this rank.
struct GatherLayout
{
  std::vector<vtkIdType> Lengths; ///< per rank
  std::vector<vtkIdType> Offsets; ///< per rank, in rank order
  vtkIdType Total = 0;
  /// MPI counts are ints: beyond this the exchange cannot be one message (every rank knows Total,
  /// so all of them find it together).
  bool FitsOneMessage() const { return Total <= vtkIdType(INT_MAX); }
};

/// Collective over @p controller: one AllGather of every rank's @p length. (Not const where used:
/// vtkMultiProcessController's AllGatherV and GatherV take the counts by non-const pointer.)
GatherLayout LayoutOfAllGather(vtkMultiProcessController* controller, vtkIdType length);

/**
 * Collective over @p controller: every rank's @p cloud points (nullptr counts as none) as one
 * double-precision point set on every rank, ranks in order, each rank's points in their order,
 * NaN/Inf points included (Prepare sets them aside and counts them as in one process). So the
 * surface, its automatic h, centroid and bounds are bitwise those of the one-process run over the
 * pieces concatenated. The point arrays named in @p arrays (the normals APSS and RIMLS read, the
 * scales of PointScales FromArray) come along, as doubles, where the pieces have them, and so do
 * the field data a sensor frame carries (Viewpoint, GridDimensions: the lowest rank's that has
 * them), which decide the automatic scale and orient the estimated normals as in one process.
 * Returns nullptr on every rank (after an error of @p algorithm) when the cloud has more
 * coordinates than one MPI message holds (2^31 - 1), or when some ranks' points carry one of
 * @p arrays and others' do not (or with other component counts).
 */
vtkSmartPointer<vtkPolyData> GatherCloud(vtkAlgorithm* algorithm, vtkMultiProcessController* controller,
  vtkPointSet* cloud, const std::vector<std::string>& arrays = {});

/**
 * What the ranks of a run with ghost points (GhostMargin > 0) share, from BeginGhostRun(): the
 * finite cloud's bounds and centroid over every rank, its dimension and h (all as one process
 * computes them), and this rank's own finite cloud points, which it sends to the ranks that ask.
 */
struct GhostRun
{
  double H = 0.0;
  double Lo[3] = { 0.0, 0.0, 0.0 };
  double Hi[3] = { 0.0, 0.0, 0.0 };
  double Centroid[3] = { 0.0, 0.0, 0.0 };
  int Dimension = 3;
  std::vector<double> Own; ///< x, y, z of this rank's finite cloud points
  vtkIdType Ghosts = 0;    ///< other ranks' points the last PrepareGhostSurface() received
};

/**
 * Collective over @p controller: the GhostRun of every rank's @p cloud. The centroid is summed in
 * rank order along a chain of the ranks, so it is bitwise the one-process centroid; the automatic
 * h (AutomaticScale on) is the one-process estimate, made on rank 0 over the finite points
 * gathered there for the purpose (so rank 0 holds the whole cloud for a moment). On an empty
 * cloud (or one with no finite point, or an automatic h of 0) every rank reports the one-process
 * error and returns false; otherwise it warns, on every rank, of the cloud points left out for
 * NaN/Inf as one process does.
 */
bool BeginGhostRun(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkMultiProcessController* controller,
  vtkPointSet* cloud, GhostRun& run);

/**
 * Collective over @p controller: prepares @p surface on this rank's own points plus every other
 * rank's points inside the box [@p lo, @p hi] (lo[0] > hi[0]: none, and the surface is left as
 * it is), complete inside that box (vtkPointSetSurface::PreparePiece). The parameters are
 * checked alike on every rank, so all fail or none. Returns false after an error of
 * @p algorithm.
 */
bool PrepareGhostSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface,
  vtkMultiProcessController* controller, GhostRun& run, const double lo[3], const double hi[3]);

/// Coordinates of a ghost run's point @p k (RunGhostRounds).
using GhostPointAt = std::function<void(std::uint32_t k, double x[3])>;

/// Evaluates a ghost run's points @p ks in that order on the surface as prepared, setting
/// escaped[k] for each when its evaluation read beyond the complete region
/// (pss::Workspace::leftCompleteRegion). Returns false after reporting an error.
using GhostEvaluation = std::function<bool(const std::vector<std::uint32_t>& ks, std::vector<unsigned char>& escaped)>;

/**
 * Collective over @p controller: evaluates this rank's points @p ks (indices below @p n) with
 * ghost points, in rounds. Round 1 prepares @p surface (PrepareGhostSurface) in the box of the
 * points grown by @p margin and evaluates them all; each later round doubles the margin around
 * the points whose evaluation escaped, on any rank, and evaluates those again. Once a box holds
 * the cloud's bounds no read can leave it, so the rounds end. A rank without a surface yet (no
 * cloud point in its box) counts its points as escaped. When preparing its surface or @p evaluate
 * fails on one rank, every rank fails. Returns the rounds taken, 0 after an error of @p algorithm.
 */
int RunGhostRounds(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkMultiProcessController* controller,
  GhostRun& run, double margin, std::vector<std::uint32_t> ks, std::size_t n, const GhostPointAt& pointAt,
  const GhostEvaluation& evaluate);

/// Field data `GhostRounds` (@p rounds) and `GhostPoints` (the other ranks' points this rank held
/// in its last round: its memory overhead) of a filter's @p output after RunGhostRounds.
void AddGhostFieldData(vtkDataObject* output, int rounds, const GhostRun& run);


/**
 * Collective over @p controller: true on every rank when no rank's @p upstreamError (from
 * UpstreamErrorWatch::Check) is set; otherwise false on every rank after the same error of
 * @p algorithm on each, naming the ranks that had one (their logs hold the upstream error).
 */
bool AgreeOnInputs(vtkAlgorithm* algorithm, vtkMultiProcessController* controller, const std::string& upstreamError);

/// Collective over @p controller (when not nullptr; else true at once): AgreeOnInputs on what
/// @p watch finds against every input of @p algorithm (@p inputVector, as RequestData has it).
bool UpstreamSucceededEverywhere(vtkAlgorithm* algorithm, vtkInformationVector** inputVector,
  vtkMultiProcessController* controller, UpstreamErrorWatch& watch);

/// Unless @p pd has global ids already, gives its @p n tuples the global ids first, first + 1, ...
/// as `GlobalPointIds` (the distributed filters' outputs, gathered, then match one process's).
void AddGlobalPointIds(vtkPointData* pd, vtkIdType first, vtkIdType n);

/// Collective over @p controller: the number of items on the ranks before this one (each rank
/// has @p count), i.e. the global id of this rank's first item when pieces are concatenated.
vtkIdType GlobalOffset(vtkMultiProcessController* controller, vtkIdType count);

/**
 * The mesher's split of its stages over the ranks of @p controller: this rank's part, and a share
 * step that, collective, stops every rank when one did not complete its block and otherwise
 * exchanges every rank's block of the stage's items. Sets @p tooLarge (which must outlive the
 * split) and stops when a stage's items exceed one MPI message.
 */
pss::StageSplit SplitAcrossRanks(vtkMultiProcessController* controller, bool& tooLarge);

/// Collective over @p controller: every rank's occupied cell keys @p own, merged into @p all (a
/// band that depends on no rank's split). False, with @p tooLarge, beyond one MPI message.
bool GatherCellKeys(vtkMultiProcessController* controller, const std::vector<std::uint64_t>& own,
  std::vector<std::uint64_t>& all, bool& tooLarge);

}

#endif

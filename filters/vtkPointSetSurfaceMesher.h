// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceMesher
 * @brief   the point-set surface as a triangle mesh (polylines in 2D), only where it is defined
 *
 * Input: the cloud (any vtkPointSet). Output: a vtkPolyData of triangles (3D) or line segments
 * (2D) approximating the extremal surface (Definition 1 of Amenta & Kil) of the Surface's
 * definition, restricted to its domain. The zero crossings of g (Eq. 2) are contoured on a sparse
 * band of grid cells of side CellSize * h around the cloud, with n oriented consistently over the
 * band; every crossing is projected onto the surface and labelled as
 * vtkPointSetSurfaceDomainClassifier does, and a triangle is kept only when its three vertices are
 * InDomain, travelled at most MaxVertexTravel cells and do not fold; small holes are then closed
 * and covered islands removed (pss::SurfaceMesher, filters/core/pss/SurfaceMesh.h). The stages and
 * the reasons for each default are in docs/mesh.md.
 *
 * Point arrays: `Normals` (n at the vertex, oriented consistently over each piece; the active
 * normals; triangles are counter-clockwise about them), `Stability`, `Energy`, `DomainLabel`,
 * `DistanceToCloud`, `NormalAngle`, `StartAngle`, `StartStability` (the classifier's evidence for
 * the crossing that became the vertex), `Displacement` (from the grid crossing to the vertex),
 * `Iterations`, `StopReason`. Field data: `ScaleFactor`, `Dimension`, `CellSize`, `Band`,
 * `MaxDistance`, `MaxBorderOffset` and `TrimDistance` (as applied, automatic values resolved), `Procedure` and the
 * counts `BandCells`, `CellLevels`, `HangingVertices` (adaptive cells), `GridVertices`, `Crossings`, `DroppedVertices`, `MaximumCrossings`,
 * `SeamSimplices`, `FoldedTriangles`, `UndefinedGridVertices` (why parts are missing),
 * `RemovedPieces`, `CoveredPieces`, `ClosedHoles`, `Components`, `BoundaryEdges`,
 * `NonManifoldEdges`, `EulerCharacteristic`.
 *
 * Errors (vtkErrorMacro, empty output): an empty cloud, h <= 0, invalid parameters, and a band of
 * more than MaximumNumberOfBandCells cells (refused before it is allocated). Threads with
 * vtkSMPTools; reports progress and honours AbortExecute; the output is bitwise the same on any
 * number of threads. Under MPI the costly stages are split over the ranks and each rank keeps a
 * share of the cells with `GlobalPointIds`; merged by global id, the ranks' outputs are the
 * one-process mesh (docs/distributed.md).
 *
 * @sa vtkPointSetSurfaceDomainClassifier vtkPointSetSurfaceFieldSampler vtkPointSetSurface
 */

#ifndef vtkPointSetSurfaceMesher_h
#define vtkPointSetSurfaceMesher_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPointSetSurfaceAlgorithm.h"

#include <optional> // for std::optional
#include <string>   // for std::string

namespace pss
{
struct MeshOptions;
struct MeshTimings;
struct StageSplit;
struct SurfaceMesh;
}
namespace pss_vtk
{
class DistributedRun;
}

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceMesher : public vtkPointSetSurfaceAlgorithm
{
public:
  static vtkPointSetSurfaceMesher* New();
  vtkTypeMacro(vtkPointSetSurfaceMesher, vtkPointSetSurfaceAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How crossings are projected (EXTREMAL and PLANE match vtkPointSetSurfaceProjection's).
  enum ProcedureType
  {
    EXTREMAL = 0,
    PLANE = 1,
    AUTOMATIC = 2
  };

  ///@{
  /**
   * Side of the grid's cells, in units of h, within [0.05, 100]. Smaller cells catch finer
   * features and cost about 1/CellSize^2 more on a surface. Default 1 (with projected vertices,
   * the mesh's accuracy does not depend on it much: docs/mesh.md).
   */
  vtkSetClampMacro(CellSize, double, 0.05, 100.0);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /**
   * How far from the cloud cells are visited, in units of h, within [0.1, 100]: cells holding a
   * cloud point, grown by this much in every direction. It must reach past the noise and the
   * surface's offset from the points. Default 1 (on the bunny, 2 visits 68% more cells for
   * the same mesh).
   */
  vtkSetClampMacro(Band, double, 0.1, 100.0);
  vtkGetMacro(Band, double);
  ///@}

  ///@{
  /**
   * With a scale per point, cells that follow it (default on): where h_i is 2^L times the typical
   * h or more, cells 2^L times CellSize * h (at most 64 times), in a balanced octree whose cells
   * of two sizes meet without cracks (docs/mesh.md). Cells are never finer than CellSize * h. Off,
   * or with one h, one grid of CellSize * h. Field data CellLevels says how many sizes ran.
   */
  vtkSetMacro(AdaptiveCells, bool);
  vtkGetMacro(AdaptiveCells, bool);
  vtkBooleanMacro(AdaptiveCells, bool);
  ///@}

  ///@{
  /// Move the vertices onto the surface (else leave them at the grid's zero crossings). Default on.
  vtkSetMacro(ProjectVertices, bool);
  vtkGetMacro(ProjectVertices, bool);
  vtkBooleanMacro(ProjectVertices, bool);
  ///@}

  ///@{
  /**
   * How the crossings are projected: EXTREMAL (Definition 1), PLANE (the centre-of-mass fast path,
   * x <- x - <n, x - c(x)> n) or AUTOMATIC (the default): PLANE for the centre of mass with a
   * scale per point (a sensor frame: the same pieces and holes at 0.4-0.55x the time, measured in
   * docs/adaptive-scale.md) and for APSS and RIMLS (whose plane procedure is their own projection
   * onto their fit), EXTREMAL otherwise, so a cloud of even density is meshed as before.
   * GetUsedProcedure() says which one the last run took.
   */
  vtkSetClampMacro(Procedure, int, EXTREMAL, AUTOMATIC);
  vtkGetMacro(Procedure, int);
  ///@}

  /// EXTREMAL or PLANE: the procedure the last run used (Procedure, with AUTOMATIC resolved).
  vtkGetMacro(UsedProcedure, int);

  ///@{
  /**
   * Domain criteria, as vtkPointSetSurfaceDomainClassifier's: a vertex whose projection ends
   * farther than MaxDistance * h (the local h_i with a scale per point) from every cloud point,
   * or with n more than MaxNormalAngle degrees off the cloud's own normal there, is outside the
   * domain. MaxNormalAngle defaults to 30. MaxDistance <= 0 (the default,
   * MAX_DISTANCE_AUTOMATIC) takes 1 with one h and 0.6 with a scale per point: an estimated h_i
   * is three k-th neighbour distances wide (PointScaleMultiplier, so the weights reach across a
   * depth frame's layers), about five point spacings, and one h_i would let the mesh cover gaps
   * of the scan ten spacings across; 0.6 h_i is about three spacings, as 1 h is about two with one h.
   */
  static constexpr double MAX_DISTANCE_AUTOMATIC = -1.0;
  vtkSetClampMacro(MaxDistance, double, MAX_DISTANCE_AUTOMATIC, 1e6);
  vtkGetMacro(MaxDistance, double);
  vtkSetClampMacro(MaxNormalAngle, double, 0.0, 90.0);
  vtkGetMacro(MaxNormalAngle, double);
  ///@}

  ///@{
  /**
   * The mesher's own domain criterion, beyond the paper's two: a vertex is outside the domain
   * when the weighted centroid of the cloud points around it lies farther than MaxBorderOffset
   * local h from it along the surface. Inside a sampled surface the centroid sits over the vertex;
   * at a straight border of the samples it trails by h / sqrt(pi) = 0.56 h and by more past it,
   * so the mesh stops at the cloud's borders instead of running on for MaxDistance: the rim that
   * a depth frame's per-point scales (about five spacings wide) leave. 0 turns it off;
   * BORDER_OFFSET_AUTOMATIC (the default) takes 0.6 with a scale per point and 0 with one h,
   * where MaxDistance (1 h, about two spacings) already keeps the mesh to the cloud and the
   * paper's own two criteria decide.
   */
  static constexpr double BORDER_OFFSET_AUTOMATIC = -1.0;
  vtkSetClampMacro(MaxBorderOffset, double, BORDER_OFFSET_AUTOMATIC, 100.0);
  vtkGetMacro(MaxBorderOffset, double);
  ///@}

  ///@{
  /**
   * The last stage (3D): the mesh is cut back where it runs farther than TrimDistance local
   * point spacings from every cloud point (the spacing of the nearest point:
   * sqrt(pi / 12) times its distance to its 12th nearest neighbour, median-smoothed; a square grid
   * of spacing s gives 1.02 s). Each vertex passed MaxDistance, but the mesh can run on past the
   * edge of the data, where a smoothed h_i is wider than the spacing. The cut follows the line
   * where the distance crosses TrimDistance spacings (on edges split down to half a spacing near
   * it) and removes the pieces below MinPieceArea it leaves. A far region is cut where it exceeds
   * the distance by 0.1 spacing somewhere, or by 0.6 spacing when it does not reach the mesh's
   * border (its outline or a hole's): on a depth frame such an enclosed region spans a gap of the
   * data between the stripes of its quantized depths, kept while it stays within 3.1 spacings of
   * the scan at the default 2.5. TRIM_DISTANCE_AUTOMATIC (-1, the default; any negative value) takes 2.5 with a scale per point and
   * GhostMargin 0, and turns the trim off otherwise (one h: an even cloud's mesh as before; ghost
   * points: the spacing needs each point's neighbours). 0 turns it off. On the shared Kinect
   * frames 2.5 takes the mesh's area farther than three spacings from the scan from 0.2-1.3% to
   * 0.02% or less (docs/mesh.md).
   * A TrimDistance > 0 with ghost points in a distributed run is refused.
   */
  static constexpr double TRIM_DISTANCE_AUTOMATIC = -1.0;
  vtkSetClampMacro(TrimDistance, double, TRIM_DISTANCE_AUTOMATIC, 1e6);
  vtkGetMacro(TrimDistance, double);
  ///@}

  ///@{
  /// The distance, border and trim criteria the last run applied, the automatic values resolved
  /// (also the output's field data MaxDistance, MaxBorderOffset and TrimDistance; 0: no trim).
  vtkGetMacro(UsedMaxDistance, double);
  vtkGetMacro(UsedMaxBorderOffset, double);
  vtkGetMacro(UsedTrimDistance, double);
  ///@}

  ///@{
  /**
   * A crossing whose projection moves farther than this many cells is dropped (it was a maximum
   * of e, or a sign change of g that is not the surface). Within [0.1, 100]. Default 2.
   */
  vtkSetClampMacro(MaxVertexTravel, double, 0.1, 100.0);
  vtkGetMacro(MaxVertexTravel, double);
  ///@}

  ///@{
  /**
   * Cells across which the oriented n turns by more than this many degrees are not contoured:
   * a seam of the orientation, where g's sign change is not a crossing. Within [0, 180]. Default 80 (on the bunny, 60 left 4,992 boundary edges, 80 leaves 4,197, with the same accuracy).
   */
  vtkSetClampMacro(MaxSeamAngle, double, 0.0, 180.0);
  vtkGetMacro(MaxSeamAngle, double);
  ///@}

  ///@{
  /**
   * A triangle (segment) whose own normal, once its vertices are projected, is more than this many
   * degrees off its vertices' n is dropped: it folded over, or its corners projected onto two
   * different sheets (two sheets 1.5 h apart give such bridges at 80). Within [0, 180]. Default 60.
   */
  vtkSetClampMacro(MaxFoldAngle, double, 0.0, 180.0);
  vtkGetMacro(MaxFoldAngle, double);
  ///@}

  ///@{
  /**
   * 3D: a hole of the mesh bounded by at most this many edges is closed by a fan about the
   * projection of its centre, when that projection is in the domain and the fan does not fold,
   * else, when the scan has data at its centre (a cloud point within MaxDistance), by the
   * least-area unfolded triangulation of its own vertices (a seam of the orientation or a dropped
   * crossing left it, not the end of the domain). A pinched hole is closed as the simple loops it
   * is made of. 0 (or 1, 2) closes none. Within [0, 1000]. Default 100.
   */
  vtkSetClampMacro(MaxHoleEdges, int, 0, 1000);
  vtkGetMacro(MaxHoleEdges, int);
  ///@}

  ///@{
  /**
   * 3D: connected pieces of the mesh with a smaller area than this, in units of h^2, are removed
   * (islands of a few cells that stray points define). Within [0, 1e6]; 0 keeps every piece.
   * Default 10: on the bunny scans it leaves one piece (49 islands without it), at the price of
   * a few bun_zipper vertices beyond 1 mm (the farthest goes from 0.99 to 1.19 mm).
   */
  vtkSetClampMacro(MinPieceArea, double, 0.0, 1e6);
  vtkGetMacro(MinPieceArea, double);
  ///@}

  ///@{
  /**
   * 3D: pieces other than the largest with a smaller area than this, in units of h^2, are removed
   * when every vertex of theirs lies within 3 h of the largest piece's interior (the nearest vertex
   * of the largest piece is not on a border): a second layer over surface that the largest piece
   * already covers, defined by stray scan points. A piece beside a hole of the largest piece stays.
   * Within [0, 1e6]; 0 keeps them. Default 10 (on the bunny scans: 59 of 108 islands).
   */
  vtkSetClampMacro(CoveredPieceArea, double, 0.0, 1e6);
  vtkGetMacro(CoveredPieceArea, double);
  ///@}

  ///@{
  /// Refuse bands of more cells than this (about 60 bytes each). Default 2^24.
  vtkSetClampMacro(MaximumNumberOfBandCells, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfBandCells, vtkIdType);
  ///@}

  ///@{
  /**
   * Distributed runs: 0 (default) gathers the whole cloud on every rank; > 0 exchanges only the
   * ghost points within this many h of the box of each block of grid corners, crossings or hole
   * centres a rank evaluates (vtkPointSetSurfaceProjection::SetGhostMargin says more). In one
   * process, > 0 only sums neighbourhoods in coordinate order, as the ranks then do.
   */
  vtkSetClampMacro(GhostMargin, double, 0.0, 1e6);
  vtkGetMacro(GhostMargin, double);
  ///@}

  /// The most rounds of ghost exchange a stage of the last distributed update with GhostMargin > 0
  /// took (0 otherwise); also the output's field data `GhostRounds`, beside `GhostPoints`.
  vtkGetMacro(GhostRounds, int);

  /**
   * Wall time of the last update's stages, e.g. "band 0.05 s, corners 2.1 s, ...": what `pss mesh
   * --verbose` prints (kept out of the output so that the output stays bitwise reproducible).
   */
  const char* GetTimingReport() const { return this->TimingReport.c_str(); }

protected:
  vtkPointSetSurfaceMesher();
  ~vtkPointSetSurfaceMesher() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The mesh gives the one-process result in a distributed run (see the class description).
  bool SupportsDistributedRun() const override { return true; }

#ifndef __VTK_WRAP__
  /// The distributed run with GhostMargin > 0: the mesh (every rank the same), or none after an
  /// error (@p failed; @p tooLarge: an exchange beyond one MPI message). Throws
  /// std::invalid_argument on every rank alike for an absurd band.
  std::optional<pss::SurfaceMesh> MeshWithGhostPoints(pss_vtk::DistributedRun& run, const pss::MeshOptions& options,
    const pss::StageSplit& split, pss::MeshTimings& t, bool& tooLarge, bool& failed);
#endif

  double CellSize = 1.0;
  bool AdaptiveCells = true;
  double Band = 1.0;
  bool ProjectVertices = true;
  int Procedure = AUTOMATIC;
  int UsedProcedure = EXTREMAL;
  double UsedMaxDistance = 1.0;
  double UsedMaxBorderOffset = 0.0;
  double TrimDistance = TRIM_DISTANCE_AUTOMATIC;
  double UsedTrimDistance = 0.0;
  double MaxDistance = MAX_DISTANCE_AUTOMATIC;
  double MaxNormalAngle = 30.0;
  double MaxBorderOffset = BORDER_OFFSET_AUTOMATIC;
  double MaxVertexTravel = 2.0;
  double MaxSeamAngle = 80.0;
  double MaxFoldAngle = 60.0;
  int MaxHoleEdges = 100;
  double MinPieceArea = 10.0;
  double CoveredPieceArea = 10.0;
  vtkIdType MaximumNumberOfBandCells = vtkIdType(1) << 24;
  double GhostMargin = 0.0;
  int GhostRounds = 0;
  std::string TimingReport;

private:
  vtkPointSetSurfaceMesher(const vtkPointSetSurfaceMesher&) = delete;
  void operator=(const vtkPointSetSurfaceMesher&) = delete;
};

#endif

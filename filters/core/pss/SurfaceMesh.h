// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SurfaceMesh.h
 * @brief The extremal surface as a triangle mesh (polylines in 2D), only where it is defined.
 *
 * The method, in stages (each a member of SurfaceMesher, so that a caller with its own thread
 * pool, progress and abort, such as the VTK filter, can drive them):
 * 1. band: the cells of a regular grid (spacing cellSize * h) that hold a cloud point, grown by
 *    band * h in every direction. Only these cells are ever visited, so time and memory follow
 *    the surface's area, never the bounding box's volume. With a scale per point (and
 *    adaptiveCells) the cells follow the local scale instead: a point whose h_i is at least 2^L
 *    times h asks for cells of level L (side 2^L cellSize * h; never finer), its band is grown by
 *    band * h_i, and where levels meet the coarser cells are split until every cell's neighbours
 *    are at most one level apart (a balanced octree, a quadtree in 2D). A corner of a finer cell in
 *    the middle of a coarser cell's edge or face (a hanging corner) is not evaluated: its n and g
 *    are interpolated along that edge, or along the face's diagonal, once the coarser corners are
 *    oriented, so both sides of a face contour the same piecewise-linear g and the crossings on a
 *    coarser edge are the finer side's (see contour).
 * 2. evaluate: at every corner of a band cell, n(x) and g(x) = d/dt e(x + t n, n) at t = 0
 *    (Eq. 2) for the n as computed (unoriented).
 * 3. orient: n is unoriented, so g's sign is meaningless until the n of neighbouring corners
 *    agree. Orientation is propagated over the grid edges of the band, most parallel neighbours
 *    first (a maximum spanning tree of |n_a . n_b|, as in Hoppe et al.'s normal orientation); each
 *    connected piece starts from its first corner, oriented away from the cloud's centroid (toward
 *    MeshOptions::viewpoint when one is given).
 * 4. contour: every band cell is split into d! simplices along its main diagonal (Kuhn's
 *    subdivision: 6 tetrahedra, or 2 triangles in 2D, the same split in every cell, so
 *    neighbouring cells share their faces' triangulations and the contour has no cracks); a
 *    simplex gives a triangle or two (a segment in 2D) where the oriented g changes sign (Kuhn's
 *    split of a cell's face refines, at half the size, into the midpoint split of each of its two
 *    triangles; a coarser cell's triangle whose side runs over such a face takes in the crossings
 *    the finer side has along it, so no T-junction opens when the vertices move). Simplices
 *    with an undefined n at a corner, or across which n turns by more than maxSeamAngle (a seam
 *    of the orientation, where a sign change of g means nothing), are skipped.
 * 5. classify: every crossing vertex (linearly interpolated on its grid edge) is projected onto
 *    the surface and labelled as the domain classifier does (pss::classifyStart). Zero crossings
 *    of g at maxima of e, on spurious sheets, or outside the domain project far away or are not
 *    InDomain.
 * 6. finish: a simplex is kept only when all its vertices are InDomain and their projections
 *    travelled at most maxVertexTravel cells, and when its own normal, once its vertices have
 *    moved to their projections (projectVertices), is within maxFoldAngle of its vertices' n (a
 *    cell whose crossings projected onto two different sheets, or folded over, is not). The
 *    unused vertices are dropped and the mesh's topology is counted. In 3D, connected pieces
 *    smaller than minPieceArea h^2 are removed when asked (islands of a few cells), and small
 *    pieces lying over the largest piece's interior (coveredPieceArea) are.
 * 7. close: a hole of the result bounded by at most maxHoleEdges edges (a pinched border is cut
 *    into its simple loops) is closed by a fan about the projection of its vertices' centroid,
 *    when that projection is InDomain, travelled at most maxVertexTravel cells, and no triangle of
 *    the fan folds (maxFoldAngle); a hole of three edges by one triangle. Where the fan fails but
 *    the cloud has a point within maxDistance of the centre, by the least-area triangulation of the
 *    hole's own vertices whose triangles do not fold. Such holes are where a seam of the
 *    orientation, a fold or one dropped crossing left a few cells out, not where the domain ends:
 *    the scan has data there, so the mesh covers it. In the largest piece such a hole is closed
 *    even when every closing folds (by the fan, else the least-area triangulation): its border was
 *    turned inside out by the projection or twisted by a pleat of the contour, and any closing
 *    lies nearer the surface than the hole; a smaller piece's outline is left alone.
 * 8. trim (3D, when trimDistance > 0): every vertex passed the distance criterion, but the mesh
 *    can still run on past the edge of the scan's data, where a smoothed h_i is wider than the
 *    spacing. Every cloud point's local spacing is measured (two parallel passes), then the excess
 *    of the distance to the nearest cloud point over trimDistance times that point's spacing is
 *    sampled at the vertices, the edges' midpoints and the triangles' centres; edges longer than
 *    half a spacing with a sample near the cut are split at their midpoints (the decision is the
 *    edge's own, so both of its triangles split it and no crack opens), level by level (at most
 *    TrimLevels); then each triangle is cut along the line where the excess, linear along its
 *    edges, changes sign. A region beyond the distance is cut when it exceeds the distance
 *    somewhere by 0.1 spacing, or by 0.6 when it is enclosed (no vertex on the mesh's border):
 *    on a depth frame such a region lies between the stripes of the quantized depths, surface the
 *    sensor saw but measured only on the stripes; the mesh keeps it while it stays within 3.1
 *    spacings of the data, and opens a hole (at the trim distance) where it would not. Pieces
 *    below minPieceArea that the cut leaves are removed. The new vertices lie on the flat
 *    triangles, so the trim moves no surface.
 * Every stage is deterministic: the result does not depend on the number of threads.
 */
#pragma once

#include "pss/Domain.h"
#include "pss/EdgeMap.h"
#include "pss/ExtremalSurface.h"
#include "pss/Parallel.h"
#include "pss/SurfaceDefinition.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pss
{

struct MeshOptions
{
  double cellSize = 1.0;        ///< grid spacing, in units of h (> 0)
  double band = 1.0;            ///< how far from the cloud cells are visited, in units of h (> 0)
  bool projectVertices = true;  ///< move the vertices onto the surface (else keep the grid crossings)
  double maxVertexTravel = 2.0; ///< in cells: a crossing whose projection moves farther is dropped
  double maxSeamAngle = 80.0;   ///< degrees: simplices across which oriented n turns more are skipped
  double maxFoldAngle = 60.0;   ///< degrees: cells whose own normal is farther off their vertices' n are dropped
  /// Holes bounded by at most this many edges are closed where their centre projects InDomain
  /// (3D; fewer than 3 turns closing off).
  std::size_t maxHoleEdges = 100;
  /// 3D: connected pieces of a smaller area, in units of h^2, are removed (islands that a few
  /// stray points define; on the bunny scans 10 leaves one piece). 0 keeps every piece.
  double minPieceArea = 10.0;
  /// 3D: the mesh is cut back where it runs farther than this many local point
  /// spacings (of the nearest cloud point, pss::smoothedSpacing) from every cloud point (stage 8).
  /// 0 (the default here; the VTK filter turns it on for a scale per point) turns the trim off.
  /// The mesher must hold the whole cloud (no ghost points).
  double trimDistance = 0.0;
  /// 3D: pieces smaller than this, in units of h^2, other than the largest, are removed when every
  /// vertex of theirs lies within 3 h of the largest piece's interior (its nearest vertex of the
  /// largest piece is not on a border): a second layer over surface the largest piece already
  /// covers (on the bunny, islands that stray scan points define). 0 keeps them.
  double coveredPieceArea = 10.0;
  std::size_t maxBandCells = std::size_t(1) << 24; ///< refuse larger bands (about 60 bytes a cell)
  /// With a scale per point, cells of side about cellSize * h_i (levels of a balanced octree, see
  /// stage 1) instead of one grid of side cellSize * h. Without per-point scales there is one level.
  bool adaptiveCells = true;
  /// How crossings are projected (Definition 1 by default). The tolerance is 1e-5 h, not the
  /// projection's 1e-6 h: vertices need no better, and the integral energy's steps can hover
  /// around 1e-6 h until the iteration limit (measured on a circle in 2D).
  ProjectionOptions projection = [] {
    ProjectionOptions p;
    p.tolerance = 1e-5;
    return p;
  }();
  DomainThresholds domain;       ///< what counts as InDomain (the classifier's thresholds)
  /// A sensor's position: each piece's first corner, and so the piece's n and normals, is
  /// oriented toward it instead of away from the cloud's centroid (a single view sees every
  /// surface from its front).
  std::optional<Vec3> viewpoint;
  /// The cloud's own normals (a scan's, e.g. PLY nx ny nz or PCD normal_x/y/z), one per input
  /// point in input order (PointIndex::originalId), zero where unknown: each piece's first corner
  /// then agrees with the normal of the cloud point nearest to it, before the viewpoint's or the
  /// centroid's rule. Empty: not used. The mesher throws std::invalid_argument for another size.
  std::vector<Vec3> cloudNormals;
  void validate() const;         ///< throws std::invalid_argument
};

/// Counts that say what the mesher did and what the mesh is.
struct MeshStatistics
{
  std::size_t bandCells = 0;          ///< cells visited
  std::size_t cellLevels = 1;         ///< cell sizes in use (adaptive cells: up to MaxCellLevels)
  std::size_t hangingVertices = 0;    ///< corners interpolated on a coarser cell's edge or face
  std::size_t gridVertices = 0;       ///< their corners, where n and g were evaluated
  std::size_t undefinedVertices = 0;  ///< corners where n is undefined
  std::size_t seamSimplices = 0;      ///< simplices skipped because n turns too much across them
  std::size_t crossings = 0;          ///< zero crossings of g found (before the domain test)
  std::size_t droppedVertices = 0;    ///< crossings not InDomain, travelled too far, or of the other extremum
  std::size_t maximumCrossings = 0;   ///< of which: g falls along n there (a maximum of e; a minimum with seekMaxima)
  std::size_t droppedSimplices = 0;   ///< triangles (segments) dropped, with those vertices or folded
  std::size_t foldedSimplices = 0;    ///< of which: cells turned more than maxFoldAngle off their vertices' n
  std::size_t removedPieces = 0;      ///< pieces smaller than MeshOptions::minPieceArea (3D)
  std::size_t coveredPieces = 0;      ///< small pieces over the largest one (MeshOptions::coveredPieceArea)
  std::size_t closedHoles = 0;        ///< small holes closed (3D: see MeshOptions::maxHoleEdges)
  std::size_t danglingTriangles = 0;   ///< triangles hanging by a vertex alone, removed (3D)
  std::size_t trimmedSimplices = 0;   ///< triangles cut or dropped by the trim (MeshOptions::trimDistance)
  std::size_t components = 0;         ///< connected pieces of the result
  std::size_t boundaryEdges = 0;      ///< edges of one triangle (3D); polyline ends (2D)
  std::size_t nonManifoldEdges = 0;   ///< edges of three or more triangles (3D); vertices of 3+ segments (2D)
  long long eulerCharacteristic = 0;  ///< V - E + F (3D); V - E (2D)
  double measure = 0.0;               ///< total area (3D) or length (2D)
  double largestComponentMeasure = 0.0;
};

/// The result: points, per-point evidence and cells (triangles in 3D, segments in 2D).
struct SurfaceMesh
{
  int dimension = 3;
  std::vector<Vec3> points;
  std::vector<Vec3> normals;            ///< consistently oriented n at each point (zero if undefined)
  std::vector<DomainEvidence> evidence; ///< the projection and domain label of each point
  std::vector<Vec3> crossings;          ///< where each point was found on its grid edge
  std::vector<std::array<std::uint32_t, 3>> triangles; ///< 3D, counter-clockwise about the normal
  std::vector<std::array<std::uint32_t, 2>> segments;  ///< 2D
  MeshStatistics statistics;
};

/**
 * What the mesher needs of the whole cloud besides its points' cells. One process takes it from
 * the surface (of()); a distributed run whose ranks hold only pieces reduces it over them.
 */
struct MeshFrame
{
  int dimension = 3;
  double h = 0.0;
  Vec3 boundsMin = Vec3::Zero(); ///< of the finite cloud points
  Vec3 boundsMax = Vec3::Zero();
  Vec3 centroid = Vec3::Zero();  ///< n is oriented away from it
  static MeshFrame of(const SurfaceDefinition& surface);
};

/**
 * A split of the mesher's three parallel stages over cooperating processes (an MPI run where every
 * process holds the whole cloud): each process computes its part of a stage's items, a
 * contiguous block, then share() hands every process every part. An item is computed alike
 * wherever it is (it depends on the cloud and its position only), so the mesh is bitwise the one
 * of a single process, with each stage's work divided by the number of parts.
 */
struct StageSplit
{
  int part = 0;  ///< this process's part, in [0, parts)
  int parts = 1;
  /// Called by every part after each stage with its @p count items of @p width doubles each, of
  /// which this part filled [begin(count), end(count)); fills in the other parts' items. Collective:
  /// @p completed says whether this part finished its items (false: the user aborted), and it
  /// returns true only when every part completed and the exchange succeeded, so all stop together.
  std::function<bool(std::vector<double>& items, std::size_t width, std::size_t count, bool completed)> share;
  std::size_t begin(std::size_t count) const { return count * static_cast<std::size_t>(part) / static_cast<std::size_t>(parts); }
  std::size_t end(std::size_t count) const { return count * static_cast<std::size_t>(part + 1) / static_cast<std::size_t>(parts); }
};

/**
 * Runs the stages of the file comment. Construct (validates and sizes the band, throwing
 * std::invalid_argument with the cell count when it is absurd), then call evaluateVertex() for
 * every index below gridVertexCount(), orient(), contour(), classifyCrossing() for every index
 * below crossingCount(), and finish(), which is assemble(), findHoles(), evaluateHole() for every
 * index below holeCount() and closeHoles(). The three loops may run on any number of threads
 * (distinct indices, a Workspace per thread); the other stages are sequential and cheap.
 *
 * A process that holds only part of the cloud (a distributed run with ghost points) constructs
 * from a MeshFrame, gives buildBand() the cells of every rank's points (cellKeysOf() of each
 * rank's own, merged), and before each loop calls useSurface() with a surface complete around
 * the indices it evaluates; an evaluation that read beyond that surface's complete region sets
 * Workspace::leftCompleteRegion, and the caller evaluates that index again on a wider one.
 * Everything else depends on the frame, the band and the evaluations only, so with the same
 * evaluations every process builds the same mesh.
 */
class SurfaceMesher
{
public:
  SurfaceMesher(const SurfaceDefinition& surface, const MeshOptions& options);
  /// Sizes the grid for @p frame; buildBand() and useSurface() must follow.
  SurfaceMesher(const MeshFrame& frame, const MeshOptions& options);

  /// The keys of the grid cells that hold @p points (the finite ones), sorted, without repeats.
  std::vector<std::uint64_t> cellKeysOf(const std::vector<Vec3>& points) const;
  /// Builds the band around the cells @p occupied (cellKeysOf() of the whole cloud, or of its
  /// pieces merged: sorted and made unique here). Throws std::invalid_argument when too large.
  void buildBand(std::vector<std::uint64_t> occupied);
  /// The surface the loops evaluate from now on.
  void useSurface(const SurfaceDefinition& surface);

  /// The most cell sizes the adaptive cells use (each twice the next): 7 span a 64-fold spread of h_i.
  static constexpr int MaxCellLevels = 7;

  std::size_t gridVertexCount() const { return Keys.size(); }
  Vec3 gridVertex(std::size_t i) const { return positionOf(Keys[i]); }
  void evaluateVertex(std::size_t i, Workspace& ws);
  void orient();
  void contour();
  std::size_t crossingCount() const { return Crossings.size(); }
  const Vec3& crossing(std::size_t i) const { return Crossings[i].point; }
  void classifyCrossing(std::size_t i, Workspace& ws);
  SurfaceMesh finish(Workspace& ws);

  /// The mesh of the kept cells (stage 6), before any hole is closed.
  SurfaceMesh assemble();
  /// Finds @p mesh's small holes (stage 7) and their centres, which evaluateHole() projects.
  void findHoles(const SurfaceMesh& mesh);
  std::size_t holeCount() const { return HoleCentres.size(); }
  const Vec3& holeCentre(std::size_t j) const { return HoleCentres[j]; }
  /// Projects hole @p j's centre (a hole of more than three edges) and measures how far the cloud is.
  void evaluateHole(std::size_t j, Workspace& ws);
  /// Closes the holes findHoles() found, as evaluateHole() judged them, and counts the topology.
  void closeHoles(SurfaceMesh& mesh);

  /// Whether stage 8 runs (3D, trimDistance > 0).
  bool trims() const;
  /// Stage 8 first measures every cloud point's local spacing (pss::rawSpacing, then
  /// pss::smoothedSpacing): two passes of spacingCount() items (none without the trim), each
  /// after beginSpacings() or a nextSpacingPass() that returned true.
  std::size_t spacingCount() const;
  void beginSpacings();
  const Vec3& spacingPoint(std::size_t i) const { return Surface->index().point(i); }
  void evaluateSpacing(std::size_t i, Workspace& ws);
  bool nextSpacingPass();
  std::vector<double> spacingValues() const;
  void setSpacingValues(const std::vector<double>& values);
  /// Starts stage 8 on @p mesh (the closed mesh): queues the samples of its first level (none when
  /// trims() is false).
  void beginTrim(const SurfaceMesh& mesh);
  std::size_t trimSampleCount() const { return TrimSamples.size(); }
  const Vec3& trimSample(std::size_t i) const { return TrimSamples[i]; }
  /// How far sample @p i is from the cloud beyond trimDistance local spacings, and that spacing.
  void evaluateTrimSample(std::size_t i, Workspace& ws);
  /// Splits the edges that need a closer look and queues the next level's samples; false when
  /// none remain (then cutFar() follows).
  bool refineTrim(SurfaceMesh& mesh);
  /// Cuts @p mesh along the line where its excess over trimDistance local h changes sign, then
  /// removes pieces below minPieceArea and counts the topology again.
  void cutFar(SurfaceMesh& mesh);

  /// The results of evaluateVertex() (CornerWidth doubles per corner), classifyCrossing()
  /// (EvidenceWidth per crossing) and evaluateHole() (HoleWidth per hole) as flat arrays, and
  /// back: what a StageSplit exchanges.
  static constexpr std::size_t CornerWidth = 5;
  static constexpr std::size_t EvidenceWidth = 24;
  static constexpr std::size_t HoleWidth = EvidenceWidth + 1;
  static constexpr std::size_t TrimWidth = 2;
  std::vector<double> cornerValues() const;
  void setCornerValues(const std::vector<double>& values);
  std::vector<double> crossingEvidence() const;
  void setCrossingEvidence(const std::vector<double>& values);
  std::vector<double> holeValues() const;
  void setHoleValues(const std::vector<double>& values);
  std::vector<double> trimValues() const;
  void setTrimValues(const std::vector<double>& values);

private:
  using Key = std::uint64_t;
  static constexpr std::uint32_t NoIndex = static_cast<std::uint32_t>(-1); ///< no corner, crossing or vertex
  struct CornerValue
  {
    Vec3 n = Vec3::Zero();
    double g = 0.0;
    bool defined = false;
  };
  struct Crossing
  {
    Vec3 point = Vec3::Zero();
    Vec3 reference = Vec3::Zero(); ///< oriented n of the grid edge's end, to orient the result
    ExtremumType type = ExtremumType::None; ///< how g changes along n here (None: edge across n)
    double cell = 0.0; ///< the side of the cells of its edge: how far its projection may travel
  };
  /// A corner in the middle of a coarser cell's edge (or face diagonal) from corner a to corner b.
  struct HangingCorner
  {
    std::uint32_t corner = 0, a = 0, b = 0;
  };

  /// The sign that orients the band's corner @p seed, the first of its piece (stage 3).
  signed char seedSign(std::size_t seed, const Orientation& away) const;

  Key keyOf(const std::array<long long, 3>& c) const;
  std::array<long long, 3> coordsOf(Key k) const;
  Vec3 positionOf(Key k) const;
  /// Size and Origin: the cloud's bounds in cells of side Cell, and @p margin cells on every side.
  void sizeGrid(long long margin);
  void linkNeighbours();
  /// Stage 1 with a scale per point: the balanced octree's cells and corners and its hanging
  /// corners. Returns false (and changes nothing) when every point asks for one level.
  bool buildAdaptiveBand(const PointIndex& index);
  void findHanging();  ///< HangingCorners: the midpoints of cells' edges and faces that are corners
  void linkCorners();  ///< Step: the cells' edges between corners that are not hanging
  /// The hanging corner halfway between corners @p a and @p b, or NoIndex.
  std::uint32_t midpointOf(std::uint32_t a, std::uint32_t b) const;
  /// The hanging corners' n and oriented g, from their coarser corners (after orient()).
  void interpolateHanging();
  /// The index of the corner with key @p k, or NoIndex.
  std::uint32_t cornerOf(Key k) const;
  void contourSimplex(const std::array<std::uint32_t, 4>& corners, const std::array<int, 4>& bits, int count);
  std::uint32_t crossingOn(std::uint32_t lower, std::uint32_t upper, int direction);
  /// The crossing on the cell edge between corners @p a and @p b (adaptive cells), on the half of
  /// it that changes sign when its midpoint is a hanging corner.
  std::uint32_t crossingBetween(std::uint32_t a, std::uint32_t b);
  std::uint32_t newCrossing(std::uint32_t a, std::uint32_t b);
  /// The crossings the finer cells have inside the triangle of corners @p face (a coarser cell's
  /// face, split at its edges' hanging midpoints), between crossings @p from and @p to, in order.
  void crossingsInside(const std::array<std::uint32_t, 3>& face, std::uint32_t from, std::uint32_t to,
    std::vector<std::uint32_t>& out);
  /// Triangles of the convex polygon @p loop whose vertex k lies on the sides of bit mask @p sides[k].
  void triangulatePolygon(const std::vector<std::uint32_t>& loop, const std::vector<unsigned>& sides, const Vec3& towardPositive);
  void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vec3& towardPositive);
  /// Keeps the @p triangles of pieces of at least minPieceArea h^2 as @p mesh's, without the unused vertices.
  void keepLargePieces(SurfaceMesh& mesh, const std::vector<std::array<std::uint32_t, 3>>& triangles);
  /// Sets to 0 the excess of every connected region beyond the trim distance that the cut spares:
  /// one that nowhere exceeds the distance by TrimMargin local spacings (a nick where a gap is
  /// just wider than the distance), or by TrimEnclosedMargin when no vertex of it lies on the
  /// mesh's border.
  void spareShallowRegions(const SurfaceMesh& mesh);
  /// Queues the samples of the trim's active triangles: unsettled vertices, edge midpoints, centres.
  void queueTrimSamples(const SurfaceMesh& mesh);
  /// True when a cell of normal @p face (unnormalized) is within maxFoldAngle of @p vertexNormals' sum.
  bool isUnfolded(const Vec3& face, const Vec3& vertexNormals) const;
  /// True when a triangle a, b, c that closes a hole is unfolded, or is a sliver facing @p vertexNormals' side.
  bool closesFlat(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& vertexNormals) const;
  /// The simple border loops of @p mesh of at most maxHoleEdges edges, each in its triangles' winding.
  std::vector<std::vector<std::uint32_t>> smallHoles(const SurfaceMesh& mesh) const;
  /// The triangulation of least area of @p hole's own vertices whose new edges are not in @p edges
  /// (sorted (lower, higher) vertex pairs), or none; every triangle unfolded when @p unfolded.
  std::vector<std::array<std::uint32_t, 3>> triangulateHole(const std::vector<std::uint32_t>& hole,
    const SurfaceMesh& mesh, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges, bool unfolded) const;

  const SurfaceDefinition* Surface = nullptr;
  MeshOptions Options;
  MeshFrame Frame;
  /// The cloud's own normals, for the domain test of the crossings and hole centres.
  std::unique_ptr<CloudNormals> Normals;
  int Dimension = 3;
  double Cell = 0.0;
  long long Reach = 0; ///< the band's width in cells
  Vec3 Origin = Vec3::Zero();
  std::array<long long, 3> Size{ { 1, 1, 1 } };
  std::vector<Key> Cells;          ///< band cells, by the key of their lowest corner, sorted
  std::vector<Key> Keys;           ///< their corners, sorted
  std::vector<CornerValue> Values; ///< per corner
  /// Step[2a][i] / Step[2a+1][i]: the corner one cell up / down axis a from corner i (or none;
  /// adaptive cells: along the edge of i's cells that ends at a corner that does not hang).
  std::array<std::vector<std::uint32_t>, 6> Step;
  std::vector<std::uint32_t> CellCorner; ///< per band cell: its lowest corner
  std::vector<std::uint8_t> CellLevel;   ///< per band cell: its level (adaptive cells only)
  std::vector<std::array<std::uint32_t, 8>> CellCorners; ///< per band cell: its corners (adaptive cells only)
  std::vector<char> Hanging;             ///< per corner (adaptive cells only)
  std::vector<HangingCorner> HangingCorners; ///< coarser cells' first
  EdgeMap<std::uint32_t> CrossingOfPair; ///< adaptive cells: per corner pair
  struct
  {
    std::vector<std::uint32_t> loop, inside;
    std::vector<unsigned> sides;
  } Polygon; ///< contourSimplex()'s scratch with adaptive cells
  std::vector<signed char> Sign;   ///< per corner: +1 / -1 after orient(), 0 where undefined
  std::vector<Crossing> Crossings;
  std::vector<DomainEvidence> Evidence; ///< per crossing, from classifyCrossing()
  /// CrossingOfEdge[7 i + d - 1]: the crossing on the edge from corner i along the axes of bit
  /// mask d (Kuhn's simplices only have edges that go up along one to three axes), or none.
  std::vector<std::uint32_t> CrossingOfEdge;
  std::vector<std::array<std::uint32_t, 3>> Triangles;
  std::vector<std::array<std::uint32_t, 2>> Segments;
  std::vector<std::vector<std::uint32_t>> Holes; ///< findHoles(): small holes' vertex loops
  std::vector<Vec3> HoleCentres;                 ///< their vertices' centroids
  std::vector<double> HoleCell;                  ///< the largest cell side of their vertices
  std::vector<double> VertexCell;                ///< assemble(): each vertex's cell side
  std::vector<DomainEvidence> HoleEvidence;      ///< evaluateHole(): each centre's projection (more than 3 edges)
  std::vector<double> HoleCloudGapSq;           ///< and its squared distance to the cloud, in local h^2
  /// Stage 8's state: the samples of the current level, what each one is, their values (excess
  /// and local spacing, TrimWidth each), each vertex's excess, each sampled edge midpoint's, and which
  /// triangles are sampled at this level.
  struct TrimSample
  {
    double excess = 0.0;
    double spacing = 0.0;
  };
  struct TrimSlot
  {
    enum Kind : std::uint8_t { Vertex, Midpoint, Centroid } kind;
    std::uint64_t id; ///< the vertex, the edge's key or the triangle
  };
  /// Levels of edge splitting at most (each halves the edges it splits).
  static constexpr int TrimLevels = 8;
  /// An edge is split when one of its samples is within this fraction of its length of the cut...
  static constexpr double TrimNearFraction = 0.25;
  /// ... and it is longer than this, in local spacings.
  static constexpr double TrimFinest = 0.5;
  /// Regions beyond the trim distance by less than this, in local spacings, everywhere are kept.
  static constexpr double TrimMargin = 0.1;
  /// ... and enclosed regions (no vertex on the border) by less than this: at the default distance
  /// 2.5 they are cut only where they reach 3.1 spacings, past the 3 at which the project's metric
  /// counts area as far, so that a gap just wider than the distance opens no pinhole.
  static constexpr double TrimEnclosedMargin = 0.6;
  static constexpr std::size_t SpacingNeighbourCount = 12;
  int SpacingPass = 0;
  std::vector<double> RawSpacing;   ///< per cloud point (index order), the first pass
  std::vector<double> CloudSpacing; ///< the smoothed spacing, the second (the typical h where it is 0)
  std::vector<std::uint32_t> SpacingNeighbours; ///< SpacingNeighbourCount per cloud point
  std::vector<Vec3> TrimSamples;
  std::vector<TrimSlot> TrimSlots;
  std::vector<double> TrimValues;
  std::vector<double> VertexExcess;
  std::vector<double> VertexSpacing;
  EdgeMap<TrimSample> MidpointExcess;
  std::vector<char> TrimActive;
  int TrimLevel = 0;
  MeshStatistics Statistics;
};

/**
 * Fills @p mesh.statistics' topology and measure (components, boundary and non-manifold edges,
 * Euler characteristic, area or length, largest piece) from its points and cells; the other
 * counts are left alone. finish() calls it; so can anyone measuring a mesh made elsewhere.
 */
void countTopology(SurfaceMesh& mesh);

/// Wall time of each stage of one extractSurfaceMesh() call, in seconds.
struct MeshTimings
{
  double band = 0.0, corners = 0.0, orient = 0.0, contour = 0.0, projection = 0.0, finish = 0.0;
};

/// One of SurfaceMesher's three parallel stages, as runMeshStages() hands it out: evaluate() for
/// every index below count (each at position(i), for a caller that needs the items' region), whose
/// results get() and set() move as flat arrays of width doubles per item; share is its part of the
/// whole run's progress.
struct MeshStage
{
  std::size_t count = 0;
  std::function<Vec3(std::size_t)> position;
  void (SurfaceMesher::*evaluate)(std::size_t, Workspace&) = nullptr;
  std::vector<double> (SurfaceMesher::*get)() const = nullptr;
  void (SurfaceMesher::*set)(const std::vector<double>&) = nullptr;
  std::size_t width = 0;
  LoopShare share{ 0.0, 1.0 };
};

/**
 * The stages after the band, in order: each parallel stage through @p run (which evaluates it in
 * whatever way the caller distributes work, and returns false to stop: no mesh then), the others
 * on this thread. Fills @p timings from corners to finish.
 */
std::optional<SurfaceMesh> runMeshStages(
  SurfaceMesher& mesher, const std::function<bool(const MeshStage&)>& run, MeshTimings& timings);

/**
 * All stages, the three parallel ones through @p loop (the corners' values, then the crossings'
 * projections: about 45% and 50% of the work): the core's one-call entry point. Returns nothing
 * when the loop stopped early (the user aborted; with @p split, when any part did). Fills
 * @p timings when given. With @p split this process computes only its part of those two stages.
 */
std::optional<SurfaceMesh> extractSurfaceMesh(const SurfaceDefinition& surface, const MeshOptions& options,
  const ParallelLoop& loop, MeshTimings* timings = nullptr, const StageSplit* split = nullptr);

/// The same on @p threads threads (0 = all cores).
SurfaceMesh extractSurfaceMesh(
  const SurfaceDefinition& surface, const MeshOptions& options, int threads = 0, MeshTimings* timings = nullptr);

} // namespace pss

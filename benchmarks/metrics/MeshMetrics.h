// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MeshMetrics.h
 * @brief How good is a reconstructed mesh of a scan? The comparison of the mesh issue, written
 *        once for the bunny test, the benchmark and `pss-mesh-metrics` (any mesh, e.g. MeshLab's).
 *
 * - accuracy: distances from points spread evenly over the mesh's area to the reference surface;
 * - completeness: distances from the reference's vertices to the mesh;
 * - spurious: the share of the mesh's area farther than a distance from every cloud point;
 * - topology: pieces, the largest piece's share of the area, boundary and non-manifold edges
 *   (pss::countTopology).
 *
 * Without a reference surface (a real scan), MeasureWithoutReference judges a mesh by its cloud
 * alone: topology, small holes (boundary loops a few points across where the scan has data) and
 * far area (mesh the cloud does not support), all in units of the cloud's local point spacing.
 */
#pragma once

#include "vtkType.h"

#include <cstddef>
#include <string>
#include <vector>

class vtkPoints;
class vtkPolyData;

namespace pss_metrics
{

struct Percentiles
{
  double median = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};

struct MeshQuality
{
  vtkIdType triangles = 0;
  double area = 0.0;
  Percentiles accuracy;        ///< mesh samples to the reference surface
  Percentiles completeness;    ///< reference vertices to the mesh
  double completenessBeyond = 0.0; ///< share of reference vertices farther than the threshold
  double spuriousShare = 0.0;  ///< share of the mesh's area farther than spuriousDistance from the cloud
  std::size_t components = 0;
  double largestComponentShare = 0.0;
  std::size_t boundaryEdges = 0;
  std::size_t nonManifoldEdges = 0;
};

struct MetricOptions
{
  std::size_t samples = 200000;    ///< points spread over the mesh's area for accuracy and spurious
  double completenessThreshold = 1e-3; ///< absolute distance (1 mm for the bunny in metres)
  double spuriousDistance = 0.0;   ///< absolute (2 h); 0 skips the spurious share
};

/// One boundary loop of a mesh: a closed walk along edges of one triangle (split where the border
/// passes twice through a vertex), and where it is.
struct BoundaryLoop
{
  enum Kind
  {
    ReferenceHole, ///< around one of the reference's own holes (the scan has no data there)
    ScanGap,       ///< the cloud has no point near its centre: a hole of the scan the reference closed
    Other          ///< neither: a hole or a border where the cloud has data
  };
  std::size_t edges = 0;
  double centre[3] = { 0.0, 0.0, 0.0 }; ///< mean of its vertices
  double cloudGap = 0.0;       ///< distance from the centre to the nearest cloud point
  double toReference = 0.0;    ///< median distance from its vertices to the reference's border
  bool largestPiece = false;   ///< on the largest piece (else the border of a smaller piece)
  Kind kind = Other;
};

struct BoundaryReport
{
  std::vector<BoundaryLoop> loops;           ///< largest first
  std::size_t referenceLoops = 0;            ///< the reference's own boundary loops
  std::size_t edges[3] = { 0, 0, 0 };        ///< boundary edges by Kind
  std::size_t loopCount[3] = { 0, 0, 0 };    ///< loops by Kind
};

/**
 * Sorts every boundary loop of @p mesh: ReferenceHole when at least half its vertices lie within
 * @p referenceDistance of the reference's boundary edges (the scan's holes that the reference
 * surface, made from the same scans, also leaves open); else ScanGap when no @p cloud point lies
 * within @p gapDistance of the loop's centre (the scan has no data in the hole: the domain test's
 * MaxDistance is the natural choice); else Other.
 */
BoundaryReport ClassifyBoundary(
  vtkPolyData* mesh, vtkPolyData* reference, vtkPoints* cloud, double referenceDistance, double gapDistance);

/// A table of @p report's loops (Other and ScanGap ones in full, ReferenceHole ones summed), in @p unit.
std::string DescribeBoundary(const BoundaryReport& report, double unit, const char* unitName);

/// Measures triangle mesh @p mesh against @p reference (a triangle mesh) and @p cloud.
MeshQuality MeasureMesh(vtkPolyData* mesh, vtkPolyData* reference, vtkPoints* cloud, const MetricOptions& options);

/// One line per figure, for humans and for benchmarks/README.md (distances in @p unit, e.g. 1e-6 for um).
std::string Describe(const MeshQuality& q, double unit, const char* unitName);

struct ReferenceFreeOptions
{
  std::size_t samples = 200000;  ///< points spread over the mesh's area for the far share
  std::size_t spacingNeighbours = 12; ///< k of a point's local spacing, d_k sqrt(pi / k), median-smoothed
  double smallHoleLength = 40.0; ///< a small hole's loop is shorter than this many local spacings
  double holeCentreGap = 2.0;    ///< ... and has a cloud point within this many of its centre
  double farDistance = 3.0;      ///< mesh farther than this many local spacings from every cloud point is far
  double uncoveredDistance = 2.0; ///< a cloud point farther than this many local spacings from the mesh is uncovered
};

/// One boundary loop, measured against the cloud.
struct HoleLoop
{
  std::size_t edges = 0;
  double length = 0.0;      ///< sum of its edges' lengths
  double spacing = 0.0;     ///< local spacing: median of its vertices' nearest cloud points' spacings
  double centre[3] = { 0.0, 0.0, 0.0 }; ///< mean of its vertices
  double cloudGap = 0.0;    ///< distance from the centre to the nearest cloud point
  bool small = false;       ///< length < smallHoleLength spacings and cloudGap <= holeCentreGap spacings
};

struct ReferenceFreeQuality
{
  vtkIdType triangles = 0;
  double area = 0.0;
  std::size_t components = 0;
  double largestComponentShare = 0.0;
  std::size_t boundaryEdges = 0;
  std::size_t nonManifoldEdges = 0;
  std::size_t cloudPoints = 0;     ///< finite cloud points used
  double medianSpacing = 0.0;      ///< median of the cloud points' local spacings
  std::vector<HoleLoop> loops;     ///< every boundary loop, longest first (in edges)
  std::size_t smallHoles = 0;      ///< loops that are small holes
  std::size_t smallHoleEdges = 0;  ///< their edges
  double farShare = 0.0;           ///< share of the area farther than farDistance local spacings from the cloud
  double uncoveredShare = 0.0;     ///< share of the cloud points farther than uncoveredDistance spacings from the mesh
};

/**
 * Measures triangle mesh @p mesh against its @p cloud alone (non-finite points are left out). A
 * cloud point's local spacing comes from the density around it: d_k sqrt(pi / k), with d_k its
 * distance to the k-th nearest other point (k = spacingNeighbours), the side of the square each
 * sample covers (a square grid of spacing s gives 1.02 s), median-smoothed over its k nearest. It
 * follows the density across a scan, also where a depth frame's quantization puts the points in
 * stripes (their nearest neighbours then sit in the same stripe, far closer than the stripes). A boundary loop is a small hole when it is shorter than smallHoleLength local
 * spacings (the median spacing of the cloud points nearest its vertices) and a cloud point lies
 * within holeCentreGap of those spacings of its centre: the scan has data there, so the hole is
 * the mesher's. The far share samples the area evenly (as the spurious share does) and counts the
 * samples farther than farDistance times the nearest cloud point's spacing from it; the uncovered
 * share counts the cloud points farther than uncoveredDistance of their spacings from the mesh.
 */
ReferenceFreeQuality MeasureWithoutReference(vtkPolyData* mesh, vtkPoints* cloud, const ReferenceFreeOptions& options);

/// The figures of MeasureWithoutReference and its 20 longest small holes, for humans (lengths in @p unit).
std::string DescribeWithoutReference(const ReferenceFreeQuality& q, double unit, const char* unitName);

}

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
 */
#pragma once

#include "vtkType.h"

#include <cstddef>
#include <string>

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

/// Measures triangle mesh @p mesh against @p reference (a triangle mesh) and @p cloud.
MeshQuality MeasureMesh(vtkPolyData* mesh, vtkPolyData* reference, vtkPoints* cloud, const MetricOptions& options);

/// One line per figure, for humans and for benchmarks/README.md (distances in @p unit, e.g. 1e-6 for um).
std::string Describe(const MeshQuality& q, double unit, const char* unitName);

}

// SPDX-License-Identifier: BSD-3-Clause
#include "MeshMetrics.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkGenericCell.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"
#include "vtkStaticPointLocator.h"

#include "pss/SurfaceMesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <vector>

namespace pss_metrics
{
namespace
{

using pss::Vec3;

// The triangles of @p mesh (polygons with more than three corners are fanned).
pss::SurfaceMesh TrianglesOf(vtkPolyData* mesh)
{
  pss::SurfaceMesh out;
  out.dimension = 3;
  out.points.resize(static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoint(i, out.points[static_cast<std::size_t>(i)].data());
  }
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    for (vtkIdType k = 2; k < n; ++k)
    {
      out.triangles.push_back({ { static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[k - 1]),
        static_cast<std::uint32_t>(ids[k]) } });
    }
  }
  return out;
}

Percentiles Summarize(std::vector<double> d)
{
  Percentiles p;
  if (d.empty())
  {
    return p;
  }
  std::sort(d.begin(), d.end());
  auto at = [&](double q) { return d[std::min(d.size() - 1, static_cast<std::size_t>(q * static_cast<double>(d.size())))]; };
  p.median = at(0.5);
  p.p99 = at(0.99);
  p.max = d.back();
  return p;
}

// Distances from @p queries to the surface of @p target, on every core.
std::vector<double> DistancesTo(vtkPolyData* target, const std::vector<Vec3>& queries)
{
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(target);
  locator->BuildLocator();
  std::vector<double> d(queries.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(queries.size()), [&](vtkIdType begin, vtkIdType end) {
    vtkNew<vtkGenericCell> cell;
    for (vtkIdType i = begin; i < end; ++i)
    {
      double closest[3];
      vtkIdType cellId = 0;
      int subId = 0;
      double d2 = 0.0;
      Vec3 q = queries[static_cast<std::size_t>(i)];
      locator->FindClosestPoint(q.data(), closest, cell, cellId, subId, d2);
      d[static_cast<std::size_t>(i)] = std::sqrt(d2);
    }
  });
  return d;
}

// @p count points spread over the triangles in proportion to their areas (fixed seed).
std::vector<Vec3> SampleArea(const pss::SurfaceMesh& m, std::size_t count)
{
  std::vector<double> cumulative(m.triangles.size());
  double total = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    const auto& tri = m.triangles[t];
    total += 0.5 * (m.points[tri[1]] - m.points[tri[0]]).cross(m.points[tri[2]] - m.points[tri[0]]).norm();
    cumulative[t] = total;
  }
  std::vector<Vec3> samples;
  if (total <= 0.0)
  {
    return samples;
  }
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  samples.reserve(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    // Stratified along the cumulative area, so every part of the mesh gets its share.
    const double at = (static_cast<double>(k) + unit(rng)) / static_cast<double>(count) * total;
    const std::size_t t = std::min(m.triangles.size() - 1,
      static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin()));
    double a = unit(rng);
    double b = unit(rng);
    if (a + b > 1.0)
    {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const auto& tri = m.triangles[t];
    samples.push_back(m.points[tri[0]] + a * (m.points[tri[1]] - m.points[tri[0]]) + b * (m.points[tri[2]] - m.points[tri[0]]));
  }
  return samples;
}

} // namespace

MeshQuality MeasureMesh(vtkPolyData* mesh, vtkPolyData* reference, vtkPoints* cloud, const MetricOptions& options)
{
  MeshQuality q;
  pss::SurfaceMesh m = TrianglesOf(mesh);
  pss::countTopology(m);
  q.triangles = static_cast<vtkIdType>(m.triangles.size());
  q.area = m.statistics.measure;
  q.components = m.statistics.components;
  q.largestComponentShare = q.area > 0.0 ? m.statistics.largestComponentMeasure / q.area : 0.0;
  q.boundaryEdges = m.statistics.boundaryEdges;
  q.nonManifoldEdges = m.statistics.nonManifoldEdges;
  if (m.triangles.empty())
  {
    return q;
  }
  const std::vector<Vec3> samples = SampleArea(m, options.samples);
  q.accuracy = Summarize(DistancesTo(reference, samples));

  std::vector<Vec3> refVertices(static_cast<std::size_t>(reference->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < reference->GetNumberOfPoints(); ++i)
  {
    reference->GetPoint(i, refVertices[static_cast<std::size_t>(i)].data());
  }
  const std::vector<double> toMesh = DistancesTo(mesh, refVertices);
  q.completeness = Summarize(toMesh);
  q.completenessBeyond = static_cast<double>(std::count_if(toMesh.begin(), toMesh.end(),
                           [&](double d) { return d > options.completenessThreshold; })) /
    static_cast<double>(std::max<std::size_t>(1, toMesh.size()));

  if (options.spuriousDistance > 0.0 && cloud && cloud->GetNumberOfPoints() > 0)
  {
    vtkNew<vtkPolyData> cloudData;
    cloudData->SetPoints(cloud);
    vtkNew<vtkStaticPointLocator> points;
    points->SetDataSet(cloudData);
    points->BuildLocator();
    std::size_t far = 0;
    for (const Vec3& s : samples)
    {
      double d2 = 0.0;
      far += (points->FindClosestPointWithinRadius(options.spuriousDistance, s.data(), d2) < 0) ? 1 : 0;
    }
    q.spuriousShare = static_cast<double>(far) / static_cast<double>(samples.size());
  }
  return q;
}

std::string Describe(const MeshQuality& q, double unit, const char* unitName)
{
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << "triangles " << q.triangles << ", pieces " << q.components << " (largest " << 100.0 * q.largestComponentShare
    << "% of the area), boundary edges " << q.boundaryEdges << ", non-manifold edges " << q.nonManifoldEdges << "\n"
    << "accuracy " << unitName << ": median " << q.accuracy.median / unit << ", p99 " << q.accuracy.p99 / unit
    << ", max " << q.accuracy.max / unit << "\n"
    << "completeness " << unitName << ": median " << q.completeness.median / unit << ", p99 "
    << q.completeness.p99 / unit << ", max " << q.completeness.max / unit << "; beyond threshold "
    << 100.0 * q.completenessBeyond << "%\n"
    << "spurious area " << 100.0 * q.spuriousShare << "%\n";
  return s.str();
}

}

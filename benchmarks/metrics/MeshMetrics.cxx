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

#include "pss/PointIndex.h"
#include "pss/SurfaceMesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
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

// The border loops of @p m, each in its triangles' winding: closed walks along the sides of one
// triangle. Where a border passes twice through a vertex, the walk takes the first unused side out
// of it, so a pinched border gives two loops (or one through the vertex twice).
std::vector<std::vector<std::uint32_t>> BorderLoops(const pss::SurfaceMesh& m)
{
  struct Side
  {
    std::uint32_t low, high, from, to;
  };
  std::vector<Side> sides;
  sides.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      sides.push_back({ std::min(a, b), std::max(a, b), a, b });
    }
  }
  std::sort(sides.begin(), sides.end(),
    [](const Side& x, const Side& y) { return x.low != y.low ? x.low < y.low : x.high < y.high; });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> border; // (from, to), sorted by from
  for (std::size_t i = 0; i < sides.size();)
  {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].low == sides[i].low && sides[j].high == sides[i].high)
    {
      ++j;
    }
    if (j - i == 1)
    {
      border.emplace_back(sides[i].from, sides[i].to);
    }
    i = j;
  }
  std::sort(border.begin(), border.end());
  std::vector<char> used(border.size(), 0);
  auto unusedOutOf = [&](std::uint32_t v) -> std::size_t {
    auto it = std::lower_bound(border.begin(), border.end(), std::make_pair(v, std::uint32_t(0)));
    for (auto i = static_cast<std::size_t>(it - border.begin()); i < border.size() && border[i].first == v; ++i)
    {
      if (!used[i])
      {
        return i;
      }
    }
    return border.size();
  };
  std::vector<std::vector<std::uint32_t>> loops;
  for (std::size_t s = 0; s < border.size(); ++s)
  {
    if (used[s])
    {
      continue;
    }
    std::vector<std::uint32_t> loop;
    std::size_t e = s;
    while (e < border.size())
    {
      used[e] = 1;
      loop.push_back(border[e].first);
      if (border[e].second == border[s].first)
      {
        break;
      }
      e = unusedOutOf(border[e].second);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

double SegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double Median(std::vector<double>& v)
{
  if (v.empty())
  {
    return 0.0;
  }
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

} // namespace

BoundaryReport ClassifyBoundary(
  vtkPolyData* mesh, vtkPolyData* reference, vtkPoints* cloud, double referenceDistance, double gapDistance)
{
  BoundaryReport report;
  const pss::SurfaceMesh m = TrianglesOf(mesh);
  const pss::SurfaceMesh r = TrianglesOf(reference);
  std::vector<std::pair<Vec3, Vec3>> referenceBorder;
  for (const auto& loop : BorderLoops(r))
  {
    ++report.referenceLoops;
    for (std::size_t i = 0; i < loop.size(); ++i)
    {
      referenceBorder.emplace_back(r.points[loop[i]], r.points[loop[(i + 1) % loop.size()]]);
    }
  }
  // The largest piece by area (a small union-find over the triangles' vertices).
  std::vector<std::uint32_t> parent(m.points.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x)
    {
      x = parent[x] = parent[parent[x]];
    }
    return x;
  };
  for (const auto& t : m.triangles)
  {
    for (int k = 1; k < 3; ++k)
    {
      const std::uint32_t a = find(t[0]);
      const std::uint32_t b = find(t[k]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<double> area(m.points.size(), 0.0);
  for (const auto& t : m.triangles)
  {
    area[find(t[0])] += 0.5 * (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]).norm();
  }
  const auto largest = static_cast<std::uint32_t>(std::max_element(area.begin(), area.end()) - area.begin());

  vtkNew<vtkPolyData> cloudData;
  vtkNew<vtkStaticPointLocator> locator;
  if (cloud && cloud->GetNumberOfPoints() > 0)
  {
    cloudData->SetPoints(cloud);
    locator->SetDataSet(cloudData);
    locator->BuildLocator();
  }
  for (const auto& loop : BorderLoops(m))
  {
    BoundaryLoop b;
    b.edges = loop.size();
    Vec3 c = Vec3::Zero();
    std::vector<double> toRef;
    for (const std::uint32_t v : loop)
    {
      c += m.points[v] / static_cast<double>(loop.size());
      double d = std::numeric_limits<double>::infinity();
      for (const auto& seg : referenceBorder)
      {
        d = std::min(d, SegmentDistance(m.points[v], seg.first, seg.second));
      }
      toRef.push_back(d);
    }
    std::nth_element(toRef.begin(), toRef.begin() + static_cast<std::ptrdiff_t>(toRef.size() / 2), toRef.end());
    b.toReference = toRef[toRef.size() / 2];
    std::copy(c.data(), c.data() + 3, b.centre);
    b.cloudGap = std::numeric_limits<double>::infinity();
    if (cloud && cloud->GetNumberOfPoints() > 0)
    {
      const vtkIdType nearest = locator->FindClosestPoint(c.data());
      Vec3 p;
      cloud->GetPoint(nearest, p.data());
      b.cloudGap = (p - c).norm();
    }
    b.largestPiece = find(loop[0]) == largest;
    b.kind = b.toReference <= referenceDistance ? BoundaryLoop::ReferenceHole
      : b.cloudGap > gapDistance                ? BoundaryLoop::ScanGap
                                                : BoundaryLoop::Other;
    report.edges[b.kind] += b.edges;
    ++report.loopCount[b.kind];
    report.loops.push_back(b);
  }
  std::stable_sort(report.loops.begin(), report.loops.end(),
    [](const BoundaryLoop& x, const BoundaryLoop& y) { return x.edges > y.edges; });
  return report;
}

std::string DescribeBoundary(const BoundaryReport& report, double unit, const char* unitName)
{
  static const char* names[3] = { "at a reference hole", "scan gap", "other" };
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "boundary loops (reference has " << report.referenceLoops << "):";
  for (int k = 0; k < 3; ++k)
  {
    s << " " << names[k] << " " << report.loopCount[k] << " loops / " << report.edges[k] << " edges;";
  }
  s << "\n";
  for (const BoundaryLoop& b : report.loops)
  {
    s << "  " << names[b.kind] << ": " << b.edges << " edges at (" << b.centre[0] / unit << ", " << b.centre[1] / unit
      << ", " << b.centre[2] / unit << ") " << unitName << ", cloud gap " << b.cloudGap / unit << ", to reference border "
      << b.toReference / unit << (b.largestPiece ? "" : ", smaller piece") << "\n";
  }
  return s.str();
}

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

ReferenceFreeQuality MeasureWithoutReference(vtkPolyData* mesh, vtkPoints* cloud, const ReferenceFreeOptions& options)
{
  ReferenceFreeQuality q;
  pss::SurfaceMesh m = TrianglesOf(mesh);
  pss::countTopology(m);
  q.triangles = static_cast<vtkIdType>(m.triangles.size());
  q.area = m.statistics.measure;
  q.components = m.statistics.components;
  q.largestComponentShare = q.area > 0.0 ? m.statistics.largestComponentMeasure / q.area : 0.0;
  q.boundaryEdges = m.statistics.boundaryEdges;
  q.nonManifoldEdges = m.statistics.nonManifoldEdges;

  std::vector<Vec3> points(cloud ? static_cast<std::size_t>(cloud->GetNumberOfPoints()) : 0);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    cloud->GetPoint(static_cast<vtkIdType>(i), points[i].data());
  }
  const pss::PointIndex index(std::move(points), 3); // leaves non-finite points out
  q.cloudPoints = index.size();
  std::vector<double> spacing = pss::estimateLocalSpacings(index, std::max<std::size_t>(1, options.spacingNeighbours), 0);
  {
    // A point among a dozen coincident copies has spacing 0; it takes the median of the others, as
    // the mesher's trim takes the typical h there, or it would count as uncovered and make no
    // sample near it.
    std::vector<double> positive;
    std::copy_if(spacing.begin(), spacing.end(), std::back_inserter(positive), [](double s) { return s > 0.0; });
    q.medianSpacing = Median(positive);
    std::replace_if(spacing.begin(), spacing.end(), [](double s) { return !(s > 0.0); }, q.medianSpacing);
  }
  const double infinity = std::numeric_limits<double>::infinity();

  for (const auto& loop : BorderLoops(m))
  {
    HoleLoop h;
    h.edges = loop.size();
    Vec3 c = Vec3::Zero();
    std::vector<double> spacings;
    for (std::size_t i = 0; i < loop.size(); ++i)
    {
      const Vec3& v = m.points[loop[i]];
      c += v / static_cast<double>(loop.size());
      h.length += (m.points[loop[(i + 1) % loop.size()]] - v).norm();
      if (!index.empty())
      {
        spacings.push_back(spacing[index.nearest(v).first]);
      }
    }
    std::copy(c.data(), c.data() + 3, h.centre);
    h.spacing = Median(spacings);
    h.cloudGap = index.empty() ? infinity : std::sqrt(index.nearest(c).second);
    h.small = !index.empty() && h.length < options.smallHoleLength * h.spacing &&
      h.cloudGap <= options.holeCentreGap * h.spacing;
    q.smallHoles += h.small ? 1 : 0;
    q.smallHoleEdges += h.small ? h.edges : 0;
    q.loops.push_back(h);
  }
  std::stable_sort(
    q.loops.begin(), q.loops.end(), [](const HoleLoop& a, const HoleLoop& b) { return a.edges > b.edges; });

  if (!m.triangles.empty())
  {
    const std::vector<Vec3> samples = SampleArea(m, options.samples);
    std::atomic<std::size_t> far{ 0 };
    vtkSMPTools::For(0, static_cast<vtkIdType>(samples.size()), [&](vtkIdType begin, vtkIdType end) {
      std::size_t local = 0;
      for (vtkIdType i = begin; i < end; ++i)
      {
        if (index.empty())
        {
          ++local;
          continue;
        }
        const auto [j, d2] = index.nearest(samples[static_cast<std::size_t>(i)]);
        const double limit = options.farDistance * spacing[j];
        local += d2 > limit * limit ? 1 : 0;
      }
      far += local;
    });
    q.farShare = samples.empty() ? 0.0 : static_cast<double>(far.load()) / static_cast<double>(samples.size());
    // The other side of the far area: scan data the mesh leaves out (its borders trimmed, pieces
    // removed), which a stricter domain test could trade for less far area.
    std::vector<Vec3> cloudPoints(index.size());
    for (std::size_t i = 0; i < cloudPoints.size(); ++i)
    {
      cloudPoints[i] = index.point(i);
    }
    const std::vector<double> toMesh = DistancesTo(mesh, cloudPoints);
    std::size_t uncovered = 0;
    for (std::size_t i = 0; i < toMesh.size(); ++i)
    {
      uncovered += toMesh[i] > options.uncoveredDistance * spacing[i] ? 1 : 0;
    }
    q.uncoveredShare = toMesh.empty() ? 0.0 : static_cast<double>(uncovered) / static_cast<double>(toMesh.size());
  }
  return q;
}

std::string DescribeWithoutReference(const ReferenceFreeQuality& q, double unit, const char* unitName)
{
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << "triangles " << q.triangles << ", pieces " << q.components << " (largest " << 100.0 * q.largestComponentShare
    << "% of the area), boundary edges " << q.boundaryEdges << ", non-manifold edges " << q.nonManifoldEdges << "\n";
  s.precision(3);
  s << "cloud " << q.cloudPoints << " points, median local spacing " << q.medianSpacing / unit << " " << unitName << "\n";
  s.precision(1);
  s << "boundary loops " << q.loops.size() << ", small holes " << q.smallHoles << " (" << q.smallHoleEdges
    << " edges), far area ";
  // Three decimals: "no far area" must be told from a tenth of a percent.
  s.precision(3);
  s << 100.0 * q.farShare << "%, uncovered points ";
  s.precision(1);
  s << 100.0 * q.uncoveredShare << "%\n";
  std::size_t listed = 0;
  for (const HoleLoop& h : q.loops)
  {
    // The longest ones say where the mesher fails; a long list says no more.
    if (h.small && ++listed > 20)
    {
      s << "  ... and " << q.smallHoles - 20 << " smaller small holes\n";
      break;
    }
    if (h.small)
    {
      s << "  small hole: " << h.edges << " edges, " << h.length / h.spacing << " spacings around, at (" << h.centre[0] / unit
        << ", " << h.centre[1] / unit << ", " << h.centre[2] / unit << ") " << unitName << ", nearest point "
        << h.cloudGap / h.spacing << " spacings from its centre\n";
    }
  }
  return s.str();
}

}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss-ponca-bench: Ponca's plane and APSS projections on the bunny, measured as pss-bench measures
 * the project's own, so that the two tables compare row for row (benchmarks/README.md, "Ponca
 * side by side").
 *
 *   pss-ponca-bench [--data DIR] [--normals FILE] [--rows plane,apss] [--threads 1,2] [--h 0.001]
 *                   [--index nanoflann|ponca]
 *
 * Built only when CMake's PSS_PONCA_DIR names Ponca's source root (https://github.com/poncateam/ponca,
 * header-only); nothing of Ponca is copied into the project.
 *
 * The workload is pss-bench's "bunny com plane" row: every point of
 * DIR/stanford-bunny/bunny_scans_merged.ply is a start; h = 1 mm; Gaussian weights exp(-d^2/h^2)
 * over the points within 3 h of the current iterate; fit, move the iterate onto the fitted
 * primitive, fit again there, until a step is below 1e-6 h or after 10 steps. "iters" counts the
 * steps, as pss-bench does; each step is one fit (the last step lands on the primitive just fitted
 * and is not followed by another fit, as in the project's plane procedure).
 *
 * - ponca plane: Basket<Point, DistWeightFunc<GaussianWeightKernel>, CovariancePlaneFit>, the
 *   iterate moved with Plane::project.
 * - ponca apss: Basket<OrientedPoint, DistWeightFunc<GaussianWeightKernel>, OrientedSphereFit>
 *   (APSS, Guennebaud and Gross 2007), the iterate moved with AlgebraicSphere::project (closed
 *   form; GLSParam only reparametrizes the sphere and is not needed for the projection). It needs an
 *   oriented normal per cloud point: --normals FILE (.vtp or .ply) with a 3-component point array
 *   named Normals (or Normal, the name `pss project` writes), in the cloud's point order. The
 *   positions are always the cloud's own: a file written by `pss project` holds the projected
 *   points, and only its normals are taken.
 *
 * The weight: Ponca's GaussianWeightKernel is exp(-x^2 / 2) with x = d / t, so t = h / sqrt(2)
 * gives exactly the project's exp(-d^2 / h^2); the kernel is not compact, so the 3 h cut is the
 * neighbour query's radius. (The project cuts at d^2 < dmin^2 + 9 h^2, dmin the nearest point's
 * distance: for starts on the cloud, where dmin is about 0, the same ball.)
 *
 * Neighbours: nanoflann by default (the k-d tree the project itself is built on, default leaf
 * size 10, unsorted radius search, gathered into a per-thread buffer and fed to the fit with
 * Ponca's init/startNewPass/addNeighbor/finalize loop, as Ponca's own nanoflann example does);
 * --index ponca uses Ponca's KdTreeDense and its rangeNeighbors query through computeWithIds.
 * Building the index is not timed (pss-bench does not time its index either).
 *
 * Threads: std::thread, each with its own fit object and neighbour buffer, taking blocks of 256
 * starts from a shared counter. The median distance of the end points to bun_zipper.ply is
 * measured as pss-bench does (vtkStaticCellLocator over the mesh).
 */

#include <Ponca/Fitting>
#include <Ponca/SpatialPartitioning>

#include <nanoflann.hpp>

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStaticCellLocator.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace
{

using Scalar = double;
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;

// Ponca's DataPoint concept: positions only for the plane fit, so that it streams 24 bytes per
// neighbour as the project's core does, and positions with normals for APSS.
class Point
{
public:
  enum
  {
    Dim = 3
  };
  using Scalar = ::Scalar;
  using VectorType = Eigen::Matrix<Scalar, Dim, 1>;
  using MatrixType = Eigen::Matrix<Scalar, Dim, Dim>;

  PONCA_MULTIARCH inline Point(const VectorType& pos = VectorType::Zero())
    : m_pos(pos)
  {
  }
  PONCA_MULTIARCH inline const VectorType& pos() const { return m_pos; }
  PONCA_MULTIARCH inline VectorType& pos() { return m_pos; }

private:
  VectorType m_pos;
};

class OrientedPoint
{
public:
  enum
  {
    Dim = 3
  };
  using Scalar = ::Scalar;
  using VectorType = Eigen::Matrix<Scalar, Dim, 1>;
  using MatrixType = Eigen::Matrix<Scalar, Dim, Dim>;

  PONCA_MULTIARCH inline OrientedPoint(
    const VectorType& pos = VectorType::Zero(), const VectorType& normal = VectorType::Zero())
    : m_pos(pos)
    , m_normal(normal)
  {
  }
  PONCA_MULTIARCH inline const VectorType& pos() const { return m_pos; }
  PONCA_MULTIARCH inline VectorType& pos() { return m_pos; }
  PONCA_MULTIARCH inline const VectorType& normal() const { return m_normal; }
  PONCA_MULTIARCH inline VectorType& normal() { return m_normal; }

private:
  VectorType m_pos;
  VectorType m_normal;
};

template <class P>
using GaussianFilter = Ponca::DistWeightFunc<P, Ponca::GaussianWeightKernel<Scalar>>;
using PlaneFit = Ponca::Basket<Point, GaussianFilter<Point>, Ponca::CovariancePlaneFit>;
using SphereFit = Ponca::Basket<OrientedPoint, GaussianFilter<OrientedPoint>, Ponca::OrientedSphereFit>;

// nanoflann's dataset adaptor over a vector of Ponca points.
template <class P>
struct NanoflannCloud
{
  const std::vector<P>& points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  Scalar kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i].pos()[static_cast<int>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const
  {
    return false;
  }
};

// 32-bit indices, nanoflann's default (and the radius search's result type below).
using Index = std::uint32_t;
template <class P>
using NanoflannTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<Scalar, NanoflannCloud<P>>,
  NanoflannCloud<P>, 3, Index>;

struct Settings
{
  double h = 0.001;
  double cut = 3.0;        // neighbour radius, in h
  double tolerance = 1e-6; // a step below tolerance * h ends a projection
  int maxIterations = 10;
  bool poncaIndex = false; // Ponca's KdTreeDense instead of nanoflann
};

struct RowResult
{
  double itemsPerSecond = 0.0;
  double meanIterations = 0.0;
  double meanNeighbours = 0.0; // in the last fit of each projection
  std::size_t undefined = 0;   // projections stopped by a fit that was not STABLE
  std::size_t notConverged = 0;
  std::vector<Vec3> ends;
};

// Per-thread state of one projection kind: the fit and the neighbour buffer.
template <class P, class Fit>
class Projector
{
public:
  Projector(const std::vector<P>& cloud, const Settings& s, const NanoflannTree<P>* flann,
    const Ponca::KdTreeDense<P>* ponca)
    : m_cloud(cloud)
    , m_settings(s)
    , m_flann(flann)
    , m_ponca(ponca)
  {
    m_matches.reserve(512);
  }

  struct Outcome
  {
    Vec3 point;
    int iterations = 0;
    int neighbours = 0;
    bool undefined = false;
    bool converged = false;
  };

  Outcome project(const Vec3& start)
  {
    const double radius = m_settings.cut * m_settings.h;
    // exp(-x^2 / 2) at x = d / t is exp(-d^2 / h^2) when t = h / sqrt(2).
    const double t = m_settings.h / std::sqrt(2.0);
    Outcome out;
    Vec3 x = start;
    for (int it = 0; it < m_settings.maxIterations; ++it)
    {
      m_fit.setNeighborFilter({ x, t });
      if (fitAt(x, radius) != Ponca::STABLE)
      {
        out.undefined = true;
        break;
      }
      out.neighbours = m_fit.getNumNeighbors();
      const Vec3 next = m_fit.project(x);
      const double step = (next - x).norm();
      x = next;
      out.iterations = it + 1;
      if (step < m_settings.tolerance * m_settings.h)
      {
        out.converged = true;
        break;
      }
    }
    out.point = x;
    return out;
  }

private:
  Ponca::FIT_RESULT fitAt(const Vec3& x, double radius)
  {
    if (m_ponca)
    {
      return m_fit.computeWithIds(m_ponca->rangeNeighbors(x, radius), m_cloud);
    }
    m_matches.clear();
    nanoflann::SearchParams params;
    params.sorted = false; // the fit's sums do not need an order
    m_flann->radiusSearch(x.data(), radius * radius, m_matches, params);
    // Ponca's own loop for neighbours gathered outside it (its nanoflann example).
    m_fit.init();
    Ponca::FIT_RESULT res = Ponca::UNDEFINED;
    do
    {
      m_fit.startNewPass();
      for (const auto& match : m_matches)
      {
        m_fit.addNeighbor(m_cloud[match.first]);
      }
      res = m_fit.finalize();
    } while (res == Ponca::NEED_OTHER_PASS);
    return res;
  }

  const std::vector<P>& m_cloud;
  const Settings& m_settings;
  const NanoflannTree<P>* m_flann;
  const Ponca::KdTreeDense<P>* m_ponca;
  Fit m_fit;
  std::vector<std::pair<Index, Scalar>> m_matches;
};

// Every cloud point projected on @p threads threads; the index is built before the clock starts.
template <class P, class Fit>
RowResult ProjectAll(const std::vector<P>& cloud, const Settings& s, int threads)
{
  const NanoflannCloud<P> adaptor{ cloud };
  std::unique_ptr<NanoflannTree<P>> flann;
  std::unique_ptr<Ponca::KdTreeDense<P>> ponca;
  if (s.poncaIndex)
  {
    ponca = std::make_unique<Ponca::KdTreeDense<P>>(cloud);
  }
  else
  {
    flann = std::make_unique<NanoflannTree<P>>(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  }

  const std::size_t n = cloud.size();
  RowResult row;
  row.ends.resize(n);
  std::vector<std::uint8_t> iterations(n);
  std::vector<int> neighbours(n);
  std::vector<std::uint8_t> undefined(n), converged(n);
  std::atomic<std::size_t> next{ 0 };
  constexpr std::size_t block = 256;
  auto work = [&]() {
    Projector<P, Fit> projector(cloud, s, flann.get(), ponca.get());
    for (;;)
    {
      const std::size_t begin = next.fetch_add(block);
      if (begin >= n)
      {
        break;
      }
      const std::size_t end = std::min(n, begin + block);
      for (std::size_t i = begin; i < end; ++i)
      {
        const auto out = projector.project(cloud[i].pos());
        row.ends[i] = out.point;
        iterations[i] = static_cast<std::uint8_t>(out.iterations);
        neighbours[i] = out.neighbours;
        undefined[i] = out.undefined;
        converged[i] = out.converged;
      }
    }
  };
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k)
  {
    pool.emplace_back(work);
  }
  work();
  for (std::thread& thread : pool)
  {
    thread.join();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  row.itemsPerSecond = static_cast<double>(n) / seconds;
  double sumIterations = 0.0;
  double sumNeighbours = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    sumIterations += iterations[i];
    sumNeighbours += neighbours[i];
    row.undefined += undefined[i];
    row.notConverged += !converged[i] && !undefined[i];
  }
  row.meanIterations = sumIterations / static_cast<double>(n);
  row.meanNeighbours = sumNeighbours / static_cast<double>(n);
  return row;
}

vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& path)
{
  const auto dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
  if (ext == ".vtp")
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return reader->GetOutput();
  }
  if (ext == ".ply")
  {
    vtkNew<vtkPLYReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return reader->GetOutput();
  }
  return nullptr;
}

// Median distance from the points to the reference mesh, as pss-bench's DistanceToMesh.
double MedianDistance(vtkPolyData* mesh, const std::vector<Vec3>& points)
{
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  std::vector<double> d;
  d.reserve(points.size());
  for (const Vec3& p : points)
  {
    double query[3] = { p[0], p[1], p[2] };
    double closest[3], d2 = 0.0;
    vtkIdType cell = 0;
    int sub = 0;
    locator->FindClosestPoint(query, closest, cell, sub, d2);
    d.push_back(std::sqrt(d2));
  }
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

std::vector<std::string> Split(const std::string& list)
{
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at <= list.size())
  {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    if (comma > at)
    {
      out.push_back(list.substr(at, comma - at));
    }
    at = comma + 1;
  }
  return out;
}

int Usage(int code)
{
  std::printf("usage: pss-ponca-bench [--data DIR] [--normals FILE] [--rows plane,apss] [--threads 1,2] [--h 0.001]\n"
              "                       [--index nanoflann|ponca]\n"
              "  --normals FILE  .vtp or .ply with a point array Normals (or Normal) in the cloud's order, for apss;\n"
              "                  e.g. pss project CLOUD --variant com --procedure plane --h 0.001 --max-iterations 10\n"
              "                  --propagate-normals -o FILE (its points are projected: only the normals are used)\n");
  return code;
}

} // namespace

int main(int argc, char** argv)
{
  std::string data = PSS_BENCH_DEFAULT_DATA;
  std::string normalsPath;
  std::vector<std::string> rows = { "plane", "apss" };
  std::vector<int> threadCounts = { 1, 2 };
  Settings settings;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--data" && hasValue)
      data = argv[++i];
    else if (a == "--normals" && hasValue)
      normalsPath = argv[++i];
    else if (a == "--rows" && hasValue)
      rows = Split(argv[++i]);
    else if (a == "--threads" && hasValue)
    {
      threadCounts.clear();
      for (const std::string& t : Split(argv[++i]))
      {
        threadCounts.push_back(std::max(1, std::atoi(t.c_str())));
      }
    }
    else if (a == "--h" && hasValue)
      settings.h = std::atof(argv[++i]);
    else if (a == "--index" && hasValue)
    {
      const std::string index = argv[++i];
      if (index != "nanoflann" && index != "ponca")
        return Usage(2);
      settings.poncaIndex = index == "ponca";
    }
    else
      return Usage(a == "--help" ? 0 : 2);
  }
  if (!(settings.h > 0.0) || threadCounts.empty())
  {
    return Usage(2);
  }

  const std::string cloudPath = data + "/stanford-bunny/bunny_scans_merged.ply";
  const auto cloudData = ReadPolyData(cloudPath);
  if (!cloudData || cloudData->GetNumberOfPoints() == 0)
  {
    std::printf("cannot read %s\n", cloudPath.c_str());
    return 1;
  }
  const auto mesh = ReadPolyData(data + "/stanford-bunny/bun_zipper.ply");
  const std::size_t n = static_cast<std::size_t>(cloudData->GetNumberOfPoints());
  std::vector<Point> cloud(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    double p[3];
    cloudData->GetPoint(static_cast<vtkIdType>(i), p);
    cloud[i] = Point(Vec3(p[0], p[1], p[2]));
  }

  std::printf("Ponca from %s; neighbours from %s; h = %g, Gaussian exp(-d^2/h^2) within %g h, step < %g h, at most %d steps\n",
    PSS_PONCA_SOURCE, settings.poncaIndex ? "Ponca KdTreeDense" : "nanoflann", settings.h, settings.cut,
    settings.tolerance, settings.maxIterations);
  std::printf("%-14s %9s", "row", "items");
  for (int t : threadCounts)
  {
    std::printf(" %11s", ("items/s t" + std::to_string(t)).c_str());
  }
  std::printf(" %6s %7s %9s %9s %9s\n", "iters", "neighb", "undefined", "not conv", "median um");
  std::fflush(stdout);

  auto printRow = [&](const char* name, const std::vector<RowResult>& results) {
    std::printf("%-14s %9zu", name, n);
    for (const RowResult& r : results)
    {
      std::printf(" %11.0f", r.itemsPerSecond);
    }
    const RowResult& first = results.front();
    char distance[32] = "-";
    if (mesh && mesh->GetNumberOfCells() > 0)
    {
      std::snprintf(distance, sizeof(distance), "%.1f", MedianDistance(mesh, first.ends) * 1e6);
    }
    std::printf(" %6.2f %7.1f %9zu %9zu %9s\n", first.meanIterations, first.meanNeighbours, first.undefined,
      first.notConverged, distance);
    // The thread count must not change a projection: each is computed alone, from its own start.
    for (const RowResult& r : results)
    {
      if (r.ends != first.ends)
      {
        std::printf("  (warning: end points differ between thread counts)\n");
        break;
      }
    }
    std::fflush(stdout);
  };

  for (const std::string& row : rows)
  {
    if (row == "plane")
    {
      std::vector<RowResult> results;
      for (int t : threadCounts)
      {
        results.push_back(ProjectAll<Point, PlaneFit>(cloud, settings, t));
      }
      printRow("ponca plane", results);
    }
    else if (row == "apss")
    {
      if (normalsPath.empty())
      {
        std::printf("%-14s skipped: no --normals FILE\n", "ponca apss");
        continue;
      }
      const auto normalsData = ReadPolyData(normalsPath);
      vtkDataArray* normals = nullptr;
      const char* arrayName = "";
      for (const char* name : { "Normals", "Normal" })
      {
        if (normalsData && !normals)
        {
          normals = normalsData->GetPointData()->GetArray(name);
          arrayName = name;
        }
      }
      if (!normals || normals->GetNumberOfComponents() != 3 ||
        static_cast<std::size_t>(normals->GetNumberOfTuples()) != n)
      {
        std::printf("%-14s skipped: %s has no 3-component point array Normals or Normal of %zu tuples\n",
          "ponca apss", normalsPath.c_str(), n);
        continue;
      }
      std::vector<OrientedPoint> oriented(n);
      std::vector<double> apart(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        double nv[3];
        normals->GetTuple(static_cast<vtkIdType>(i), nv);
        const Vec3 normal = Vec3(nv[0], nv[1], nv[2]).normalized();
        oriented[i] = OrientedPoint(cloud[i].pos(), normal);
        double q[3];
        normalsData->GetPoint(static_cast<vtkIdType>(i), q);
        apart[i] = (Vec3(q[0], q[1], q[2]) - cloud[i].pos()).norm();
      }
      std::nth_element(apart.begin(), apart.begin() + static_cast<std::ptrdiff_t>(n / 2), apart.end());
      // Says whether the file held the cloud or its projection (pss project's output): either way
      // the cloud's own positions are projected.
      std::printf("  (apss normals: array %s of %s; that file's points are %.1f um from the cloud's on median;"
                  " the cloud's positions are used)\n",
        arrayName, normalsPath.c_str(), apart[n / 2] * 1e6);
      std::vector<RowResult> results;
      for (int t : threadCounts)
      {
        results.push_back(ProjectAll<OrientedPoint, SphereFit>(oriented, settings, t));
      }
      printRow("ponca apss", results);
    }
    else
    {
      std::printf("unknown row %s (plane, apss)\n", row.c_str());
      return 2;
    }
  }
  std::printf("\nitems/s: projected cloud points per second of wall time (index built before the clock);\n"
              "iters: mean steps per projection (one fit each); neighb: mean neighbours within the cut in\n"
              "the last fit; undefined: projections stopped by a fit that was not STABLE; not conv: ended\n"
              "at the step limit; median um: median distance of the end points to bun_zipper.ply.\n");
  return 0;
}

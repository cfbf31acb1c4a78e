// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss-bench: projection and field-sampling throughput, printed as a table.
 *
 *   pss-bench [--quick] [--data DIR] [--rows PATTERN]
 *
 * Rows (each run in a child process, so its peak resident memory is its own):
 * - bunny: the 362,272 merged Stanford bunny scans (DIR/stanford-bunny/bunny_scans_merged.ply,
 *   skipped when absent), h = 1 mm, Gaussian cut at 3h, iterated to a step below 1e-6 h, at most
 *   10 iterations; every definition x procedure x 1 and 2 threads. The Integral and Delta
 *   definitions, far slower, project an evenly spread subset (the points/s are per point).
 *   The median distance of the projected points to bun_zipper.ply is printed where VTK is built.
 * - bunny integral/delta ... patch|spread exact|lattice: the Integral and Delta definitions on a
 *   dense patch (the 4,000 points nearest to point 100,000), exactly and from the delta lattice
 *   (SurfaceParameters::deltaLattice 0.5), and from the lattice on the 200 spread starts; each
 *   lattice row is preceded by its end points' deviation from the exact path's.
 * - sphere-N: noisy spheres of 10k, 100k and 1M points (CenterOfMass, plane procedure), to show
 *   how the cost grows with N.
 * - bunny mesh: the bunny's mesh (SurfaceMesh.h) with pss mesh's defaults, the index included;
 *   items are triangles, and a line above the row gives each stage's time and the mesh's counts.
 *   Center of mass on 1 and 2 threads; the integral definition (delta lattice) on 2 threads.
 * - field-1024: field sampling of a 1024 x 1024 grid around a 5,000-point noisy curve
 *   (CenterOfMass, every array), through vtkPointSetSurfaceFieldSampler (when VTK is built).
 * - pss-Nm: the whole `pss project` process on a noisy sphere of N million points written by
 *   `pss generate --scene sphere --count N --noise 0.01` (center of mass, plane procedure,
 *   automatic h, 2 threads): each stage's wall time from `--verbose`, the share of the stages
 *   other than compute, and the process's peak memory per point. 1M and 10M run by default
 *   (not with --quick); 100M only when --rows names it ("pss-100m": about 20 GB and 10 minutes).
 *   The files go to $TMPDIR (default /tmp) and are removed afterwards.
 * - read 10m pcd / vtp: the read stage of `pss project` on one 10^7-point sphere stored as a
 *   binary_compressed .pcd and as an LZ4 .vtp (both written by `pss generate`), alternated, best
 *   of three each (not with --quick).
 *
 * Columns: points (or samples) per second, mean iterations, mean neighbours (points with a
 * weight above exp(-9) of the nearest one at the final point), peak RSS of the row's process when
 * its timed work ended, and that peak beyond what the process held at the row's start, per input
 * point (the bunny is read before the row starts; the synthetic clouds are made inside it, so
 * their figure includes the cloud itself). --quick runs a reduced set for smoke testing.
 */
#include "pss/Core.h"

#ifdef PSS_BENCH_WITH_VTK
#include "vtkCellLocator.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceFieldSampler.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <sys/stat.h>
#include <unistd.h>
#include <map>
#include <vector>

namespace
{

struct RowResult
{
  double itemsPerSecond = 0.0;
  double meanIterations = 0.0;
  double meanNeighbours = 0.0;
  double medianDistance = -1.0; // to the reference surface, when measured
  std::size_t cloudPoints = 0;  // size of the input cloud
  double startKiB = 0.0;        // resident memory of the row's process when it started
  double peakKiB = 0.0;         // peak resident memory when the timed work ended
  std::size_t items = 0;
};

double Seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<pss::Vec3> ReadBunny(const std::string& path)
{
  // Binary little-endian PLY with float x y z and uchar scan (see the data README).
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line) && line != "end_header")
  {
    if (line.rfind("element vertex ", 0) == 0)
    {
      n = std::stoul(line.substr(15));
    }
  }
  std::vector<pss::Vec3> points(n);
  for (pss::Vec3& p : points)
  {
    float xyz[3];
    unsigned char scan = 0;
    in.read(reinterpret_cast<char*>(xyz), sizeof(xyz));
    in.read(reinterpret_cast<char*>(&scan), 1);
    p = pss::Vec3(xyz[0], xyz[1], xyz[2]);
  }
  if (!in)
  {
    points.clear();
  }
  return points;
}

double ResidentKiB()
{
  long pages = 0;
  long resident = 0;
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f)
  {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2)
    {
      resident = 0;
    }
    std::fclose(f);
  }
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1024.0;
}

// Peak resident memory of this process so far (VmHWM), in KiB.
double PeakKiB()
{
  double kib = 0.0;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind("VmHWM:", 0) == 0)
    {
      kib = std::atof(line.c_str() + 6);
    }
  }
  return kib;
}

// Neighbours that carry weight at a point: those within the truncation band of the nearest.
double NeighbourCount(
  const pss::PointIndex& index, const pss::SurfaceParameters& params, const pss::Vec3& x, pss::Workspace& ws)
{
  pss::gatherNeighbourhood(index, params, x, ws.local, ws);
  return static_cast<double>(ws.local.size());
}

// Which starts a projection row takes from the cloud.
struct StartSet
{
  std::size_t count = 0;  ///< at most this many (all: the cloud itself, no copy)
  bool patch = false;     ///< false: evenly spread over the cloud; true: the points nearest to one point
  std::size_t centre = 0; ///< the patch's centre (a cloud index)
};

// The count cloud points nearest to cloud[centre]: a dense patch, as a whole-cloud projection
// visits its neighbourhoods.
std::vector<pss::Vec3> Patch(const std::vector<pss::Vec3>& cloud, std::size_t centre, std::size_t count)
{
  std::vector<std::pair<double, std::size_t>> byDistance(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
  {
    byDistance[i] = { (cloud[i] - cloud[centre]).squaredNorm(), i };
  }
  count = std::min(count, cloud.size());
  std::nth_element(byDistance.begin(), byDistance.begin() + static_cast<std::ptrdiff_t>(count - 1), byDistance.end());
  std::vector<pss::Vec3> out;
  for (std::size_t k = 0; k < count; ++k)
  {
    out.push_back(cloud[byDistance[k].second]);
  }
  return out;
}

// With the delta lattice: the end points' deviation from the exact path's, printed (by the row's
// child process) just above the row's own line.
void PrintDeviationFromExact(const pss::PointIndex& index, pss::SurfaceParameters params, pss::Variant variant,
  const pss::ProjectionOptions& options, int threads, const std::vector<pss::Vec3>& starts,
  const std::vector<pss::ProjectionResult>& fast)
{
  params.deltaLattice = 0.0;
  const auto exactSurface = pss::makeSurface(variant, index, params);
  const std::vector<pss::ProjectionResult> exact = pss::projectAll(*exactSurface, starts, options, threads);
  std::vector<double> apart;
  std::size_t reasonOrType = 0;
  for (std::size_t i = 0; i < starts.size(); ++i)
  {
    apart.push_back((exact[i].point - fast[i].point).norm() / params.h);
    reasonOrType += exact[i].reason != fast[i].reason || exact[i].type != fast[i].type ? 1 : 0;
  }
  std::sort(apart.begin(), apart.end());
  std::printf("  (the next row against the exact path: end points apart median %.1e h, p99 %.1e h, max %.1e h; StopReason or ExtremumType differ at %.2f%%)\n",
    apart[apart.size() / 2], apart[apart.size() * 99 / 100], apart.back(), 100.0 * reasonOrType / starts.size());
  std::fflush(stdout); // the row runs in a child process that leaves by _exit
}

RowResult ProjectRow(const std::vector<pss::Vec3>& cloud, int dimension, double h, pss::Variant variant,
  pss::Procedure procedure, int threads, const StartSet& startSet,
  const std::function<double(const std::vector<pss::Vec3>&)>& accuracy, double deltaLattice = 0.0)
{
  pss::PointIndex index(cloud, dimension);
  pss::SurfaceParameters params;
  params.h = h;
  params.deltaLattice = deltaLattice;
  if (pss::needsNormals(variant))
  {
    // APSS and RIMLS: the cloud's normals estimated and oriented as the filters do without a
    // Normals array; not timed (the rows time the projection).
    index.setNormals(pss::estimateOrientedNormals(index, params, std::nullopt, 10, threads));
  }
  const auto surface = pss::makeSurface(variant, index, params);
  pss::ProjectionOptions options;
  options.procedure = procedure;
  options.maxIterations = 10;
  options.tolerance = 1e-6;
  // Every point of the cloud, an evenly spread subset (no copy when it is all of them), or a patch.
  const std::size_t n = std::min(startSet.count, cloud.size());
  std::vector<pss::Vec3> subset;
  if (startSet.patch)
  {
    subset = Patch(cloud, startSet.centre, n);
  }
  else if (n < cloud.size())
  {
    subset.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      subset.push_back(cloud[i * cloud.size() / n]);
    }
  }
  const std::vector<pss::Vec3>& starts = startSet.patch || n < cloud.size() ? subset : cloud;
  // Keep what a caller keeps of a projection, the end point and the iteration count, not the
  // whole ProjectionResult (projectEach hands each one over as it is made).
  std::vector<pss::Vec3> ends(n);
  std::vector<std::uint8_t> iterationCounts(n);
  const auto t0 = std::chrono::steady_clock::now();
  // With the lattice every result is kept (after the timing) for the comparison with the exact path.
  std::vector<pss::ProjectionResult> kept(deltaLattice > 0.0 ? n : 0);
  pss::projectEach(*surface, starts, options, threads, [&](std::size_t i, const pss::ProjectionResult& r) {
    ends[i] = r.point;
    iterationCounts[i] = static_cast<std::uint8_t>(r.iterations);
    if (!kept.empty())
    {
      kept[i] = r;
    }
  });
  const double seconds = Seconds(t0);

  RowResult row;
  row.peakKiB = PeakKiB(); // before the accuracy check below loads a mesh
  row.items = n;
  row.itemsPerSecond = n / seconds;
  row.cloudPoints = cloud.size();
  double iterations = 0.0;
  double neighbours = 0.0;
  for (std::uint8_t count : iterationCounts)
  {
    iterations += count;
  }
  const std::size_t probe = std::min<std::size_t>(n, 2000);
  pss::Workspace ws;
  for (std::size_t i = 0; i < probe; ++i)
  {
    neighbours += NeighbourCount(index, params, ends[i * n / probe], ws);
  }
  row.meanIterations = iterations / n;
  row.meanNeighbours = neighbours / probe;
  if (accuracy)
  {
    row.medianDistance = accuracy(ends);
  }
  if (!kept.empty())
  {
    PrintDeviationFromExact(index, params, variant, options, threads, starts, kept);
  }
  return row;
}

#ifdef PSS_BENCH_WITH_VTK
// Median distance from points to the reference triangle mesh.
std::function<double(const std::vector<pss::Vec3>&)> DistanceToMesh(const std::string& meshPath)
{
  return [meshPath](const std::vector<pss::Vec3>& points) {
    vtkNew<vtkPLYReader> reader;
    reader->SetFileName(meshPath.c_str());
    reader->Update();
    vtkNew<vtkStaticCellLocator> locator;
    locator->SetDataSet(reader->GetOutput());
    locator->BuildLocator();
    std::vector<double> d;
    d.reserve(points.size());
    for (const pss::Vec3& p : points)
    {
      double closest[3], d2 = 0.0;
      vtkIdType cell = 0;
      int sub = 0;
      locator->FindClosestPoint(p.data(), closest, cell, sub, d2);
      d.push_back(std::sqrt(d2));
    }
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    return d[d.size() / 2];
  };
}

RowResult FieldRow(int threads)
{
  pss::CloudSpec spec;
  spec.scene = pss::Scene::NoisyCurve;
  spec.count = 5000;
  spec.noise = 2.0;
  const std::vector<pss::Vec3> cloud = pss::generateCloud(spec);
  vtkNew<vtkPoints> points;
  for (const pss::Vec3& p : cloud)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(threads);
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  sampler->SetSourceData(poly);
  sampler->GenerateSamplingGridOn();
  sampler->SetSampleDimensions(1024, 1024, 1);
  sampler->GetSurface()->SetVariantToCenterOfMass();
  const auto t0 = std::chrono::steady_clock::now();
  sampler->Update();
  const double seconds = Seconds(t0);
  RowResult row;
  row.peakKiB = PeakKiB();
  row.items = 1024 * 1024;
  row.itemsPerSecond = row.items / seconds;
  row.cloudPoints = row.items; // per sample, for this row
  return row;
}
#endif

// The mesh of the bunny with pss mesh's defaults (center of mass, automatic h, cell 1 h, band
// 2 h): index, then every stage of the mesher, timed together; the stages on a line of their own.
RowResult MeshRow(const std::vector<pss::Vec3>& cloud, int threads, pss::Variant variant)
{
  const auto t0 = std::chrono::steady_clock::now();
  const pss::PointIndex index(cloud, 3);
  pss::SurfaceParameters params;
  params.h = pss::estimateScale(index);
  params.deltaLattice = 0.5; // the filters' and pss mesh's default (used by Integral and Delta only)
  const auto surface = pss::makeSurface(variant, index, params);
  const double indexSeconds = Seconds(t0);
  pss::MeshTimings t;
  const pss::SurfaceMesh mesh = pss::extractSurfaceMesh(*surface, pss::MeshOptions{}, threads, &t);
  const double seconds = Seconds(t0);
  RowResult row;
  row.peakKiB = PeakKiB();
  row.items = mesh.triangles.size();
  row.itemsPerSecond = static_cast<double>(row.items) / seconds;
  row.cloudPoints = cloud.size();
  std::printf("  (%.2f s: index %.2f, band %.2f, corners %.2f, orient %.2f, contour %.2f, projection %.2f, finish %.2f;"
              " %zu band cells, %zu crossings, %zu pieces, %zu boundary edges)\n",
    seconds, indexSeconds, t.band, t.corners, t.orient, t.contour, t.projection, t.finish, mesh.statistics.bandCells,
    mesh.statistics.crossings, mesh.statistics.components, mesh.statistics.boundaryEdges);
  std::fflush(stdout);
  return row;
}

// Runs @p body in a child process; returns false when the child failed.
bool RunRow(const char* name, const std::function<RowResult()>& body)
{
  int pipefd[2];
  if (pipe(pipefd) != 0)
  {
    return false;
  }
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(pipefd[0]);
    const double startKiB = ResidentKiB();
    RowResult r = body();
    r.startKiB = startKiB;
    const ssize_t written = write(pipefd[1], &r, sizeof(r));
    _exit(written == static_cast<ssize_t>(sizeof(r)) ? 0 : 1);
  }
  close(pipefd[1]);
  RowResult r;
  const ssize_t got = read(pipefd[0], &r, sizeof(r));
  close(pipefd[0]);
  int status = 0;
  struct rusage usage
  {
  };
  wait4(pid, &status, 0, &usage);
  if (got != static_cast<ssize_t>(sizeof(r)) || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    std::printf("%-34s failed\n", name);
    return false;
  }
  // The peak when the timed work ended (later checks, such as the distance to a mesh, are not
  // the workload's); the whole process's peak when the row did not measure it.
  const double peakKiB = r.peakKiB > 0.0 ? r.peakKiB : static_cast<double>(usage.ru_maxrss);
  const double peakMiB = peakKiB / 1024.0;
  // Memory the row added to what its process held when it started, per input point.
  const double bytesPerPoint = r.cloudPoints ? (peakKiB - r.startKiB) * 1024.0 / r.cloudPoints : 0.0;
  char distance[32] = "";
  if (r.medianDistance >= 0.0)
  {
    std::snprintf(distance, sizeof(distance), "%.1f", r.medianDistance * 1e6);
  }
  std::printf("%-34s %9zu %11.0f %6.2f %7.1f %9.1f %7.0f %9s\n", name, r.items, r.itemsPerSecond, r.meanIterations,
    r.meanNeighbours, peakMiB, bytesPerPoint, distance);
  std::fflush(stdout);
  return true;
}

#ifdef PSS_BENCH_PSS
// Runs @p command through the shell, appending its standard error to @p stderrText; true when it
// exited with status 0.
bool RunCommand(const std::string& command, std::string& stderrText)
{
  std::FILE* pipe = popen((command + " 2>&1 >/dev/null").c_str(), "r");
  if (!pipe)
  {
    return false;
  }
  char buffer[512];
  while (std::fgets(buffer, sizeof(buffer), pipe))
  {
    stderrText += buffer;
  }
  return pclose(pipe) == 0;
}

// The whole `pss project` process on a generated sphere of @p n points: the stage times and the
// peak memory its --verbose prints, and the wall time around it.
void WholeProcessRow(const std::string& name, std::size_t n)
{
  const char* tmp = std::getenv("TMPDIR");
  const std::string dir = tmp && *tmp ? tmp : "/tmp";
  const std::string cloud = dir + "/pss-bench-" + std::to_string(getpid()) + "-cloud.vtp";
  const std::string output = dir + "/pss-bench-" + std::to_string(getpid()) + "-projected.vtp";
  const std::string pss = PSS_BENCH_PSS;
  std::string log;
  if (!RunCommand(pss + " generate --scene sphere --count " + std::to_string(n) + " --noise 0.01 -o " + cloud, log))
  {
    std::printf("%-34s failed to generate the cloud: %s\n", name.c_str(), log.c_str());
    std::remove(cloud.c_str());
    return;
  }
  log.clear();
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = RunCommand(
    pss + " project " + cloud + " -o " + output + " --procedure plane --threads 2 --verbose --no-progress", log);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::remove(cloud.c_str());
  std::remove(output.c_str());
  // Lines "pss: STAGE   SECONDS s" and "pss: peak memory MIB MiB".
  std::map<std::string, double> stage;
  double peakMiB = 0.0;
  std::size_t at = 0;
  while (at < log.size())
  {
    const std::size_t end = std::min(log.find('\n', at), log.size());
    const std::string line = log.substr(at, end - at);
    at = end + 1;
    char word[32] = "";
    double value = 0.0;
    if (std::sscanf(line.c_str(), "pss: peak memory %lf MiB", &value) == 1)
    {
      peakMiB = value;
    }
    else if (std::sscanf(line.c_str(), "pss: %31s %lf s", word, &value) == 2)
    {
      stage[word] += value;
    }
  }
  if (!ok || stage.count("compute") == 0 || peakMiB <= 0.0)
  {
    std::printf("%-34s failed: %s\n", name.c_str(), log.c_str());
    return;
  }
  const double bytesPerPoint = peakMiB * 1024.0 * 1024.0 / static_cast<double>(n);
  std::printf("%-34s %9zu %11.0f %6s %7s %9.1f %7.0f %9s\n", name.c_str(), n, static_cast<double>(n) / wall, "-", "-",
    peakMiB, bytesPerPoint, "-");
  // Everything but compute counts against it, process start and exit included.
  std::printf("  read %.2f s, index %.2f s, compute %.2f s, write %.2f s, whole process %.2f s: "
              "all but compute %.1f%% of the whole process\n",
    stage["read"], stage["index"], stage["compute"], stage["write"], wall, 100.0 * (wall - stage["compute"]) / wall);
  std::fflush(stdout);
}

// The read stage of `pss project` (one start point, a fixed h: nothing else of note) on the same
// generated sphere of @p n points stored as binary_compressed .pcd and as .vtp (LZ4), the two
// alternated three times in one run; prints the best read time of each.
void ReadRow(std::size_t n)
{
  const char* tmp = std::getenv("TMPDIR");
  const std::string base = std::string(tmp && *tmp ? tmp : "/tmp") + "/pss-bench-" + std::to_string(getpid());
  const std::string pss = PSS_BENCH_PSS;
  const std::string start = base + "-start.xyz";
  std::FILE* f = std::fopen(start.c_str(), "w");
  if (!f)
  {
    return;
  }
  std::fprintf(f, "0 0 50\n");
  std::fclose(f);
  const char* const formats[] = { ".pcd", ".vtp" };
  std::string log;
  for (const char* ext : formats)
  {
    if (!RunCommand(pss + " generate --scene sphere --count " + std::to_string(n) + " --noise 0.01 -o " + base + ext, log))
    {
      std::printf("read rows: failed to generate the cloud: %s\n", log.c_str());
      return;
    }
  }
  double best[2] = { 1e300, 1e300 };
  for (int repeat = 0; repeat < 3; ++repeat)
  {
    for (int k = 0; k < 2; ++k)
    {
      log.clear();
      RunCommand(pss + " project " + base + formats[k] + " --start " + start + " --h 1 --verbose --no-progress -o " +
          base + "-out.csv",
        log);
      const std::size_t at = log.find("pss: read");
      double seconds = 0.0;
      if (at != std::string::npos && std::sscanf(log.c_str() + at, "pss: read %lf s", &seconds) == 1)
      {
        best[k] = std::min(best[k], seconds);
      }
    }
  }
  for (int k = 0; k < 2; ++k)
  {
    struct stat info{};
    stat((base + formats[k]).c_str(), &info);
    std::printf("%-34s %9zu %11.0f   read %.2f s (best of 3), file %.0f MiB\n",
      (std::string("read ") + std::to_string(n / 1000000) + "m " + (formats[k] + 1)).c_str(), n,
      static_cast<double>(n) / best[k], best[k], static_cast<double>(info.st_size) / (1024.0 * 1024.0));
    std::remove((base + formats[k]).c_str());
  }
  std::remove(start.c_str());
  std::remove((base + "-out.csv").c_str());
  std::fflush(stdout);
}
#endif

} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  std::string data = PSS_BENCH_DEFAULT_DATA;
  std::string only;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--quick")
      quick = true;
    else if (a == "--data" && i + 1 < argc)
      data = argv[++i];
    else if (a == "--rows" && i + 1 < argc)
      only = argv[++i];
    else
    {
      std::printf("usage: pss-bench [--quick] [--data DIR] [--rows SUBSTRING]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  auto wanted = [&](const std::string& name) { return only.empty() || name.find(only) != std::string::npos; };
  std::printf("%-34s %9s %11s %6s %7s %9s %7s %9s\n", "row", "items", "items/s", "iters", "neighb", "peak MiB",
    "B/point", "median um");
  std::fflush(stdout); // or the header is printed again by every row's child process

  const std::string bunnyPath = data + "/stanford-bunny/bunny_scans_merged.ply";
  const std::vector<pss::Vec3> bunny = ReadBunny(bunnyPath);
  if (bunny.empty())
  {
    std::printf("(bunny rows skipped: %s not readable)\n", bunnyPath.c_str());
  }
  std::function<double(const std::vector<pss::Vec3>&)> accuracy;
#ifdef PSS_BENCH_WITH_VTK
  accuracy = DistanceToMesh(data + "/stanford-bunny/bun_zipper.ply");
#endif
  const pss::Procedure procedures[] = { pss::Procedure::Plane, pss::Procedure::Extremal };
  for (int v = 0; v < pss::VariantCount && !bunny.empty(); ++v)
  {
    const auto variant = static_cast<pss::Variant>(v);
    const bool slow = variant == pss::Variant::Integral || variant == pss::Variant::Delta;
    for (pss::Procedure procedure : procedures)
    {
      for (int threads : { 1, 2 })
      {
        if (quick && (threads == 1 || slow || procedure == pss::Procedure::Extremal) && variant != pss::Variant::CenterOfMass)
        {
          continue;
        }
        const std::string name = std::string("bunny ") + pss::variantName(variant) +
          (procedure == pss::Procedure::Plane ? " plane" : " extremal") + " t" + std::to_string(threads);
        if (!wanted(name))
        {
          continue;
        }
        StartSet starts;
        starts.count = slow ? (quick ? 20 : 200) : (quick ? 20000 : bunny.size());
        RunRow(name.c_str(), [&]() {
          return ProjectRow(bunny, 3, 0.001, variant, procedure, threads, starts, slow || quick ? nullptr : accuracy);
        });
      }
    }
  }

  // The integral and delta definitions on a dense patch (the 4,000 points nearest to point 100,000,
  // on the bunny's flank), as a whole-cloud projection or a mesh visits them: exact, and from the
  // delta lattice at its default spacing (docs/paper.md, "Reading: the integral energy's fast
  // path"), the lattice rows followed by their deviation from the exact path. Also on the 200
  // spread starts, where each projection builds its own lattice nodes.
  for (pss::Variant variant : { pss::Variant::Integral, pss::Variant::Delta })
  {
    for (pss::Procedure procedure : procedures)
    {
      for (const char* set : { "patch", "spread" })
      {
        const bool patch = std::string(set) == "patch";
        for (double lattice : { 0.0, 0.5 })
        {
          for (int threads : { 1, 2 })
          {
            if (bunny.empty() || quick || (!patch && lattice == 0.0))
            {
              continue; // the spread starts' exact rows are the table's rows above
            }
            const std::string name = std::string("bunny ") + pss::variantName(variant) +
              (procedure == pss::Procedure::Plane ? " plane " : " extremal ") + set +
              (lattice > 0.0 ? " lattice" : " exact") + " t" + std::to_string(threads);
            if (!wanted(name))
            {
              continue;
            }
            StartSet starts;
            starts.count = patch ? 4000 : 200;
            starts.patch = patch;
            starts.centre = 100000;
            RunRow(name.c_str(), [&]() {
              return ProjectRow(bunny, 3, 0.001, variant, procedure, threads, starts, patch ? accuracy : nullptr, lattice);
            });
          }
        }
      }
    }
  }

  for (std::size_t n : { std::size_t(10000), std::size_t(100000), std::size_t(1000000) })
  {
    if (quick && n > 100000)
    {
      continue;
    }
    for (int threads : { 1, 2 })
    {
      const std::string name = "sphere-" + std::to_string(n / 1000) + "k com plane t" + std::to_string(threads);
      if (!wanted(name))
      {
        continue;
      }
      RunRow(name.c_str(), [&]() {
        pss::CloudSpec spec;
        spec.scene = pss::Scene::Sphere;
        spec.dimension = 3;
        spec.count = n;
        spec.size = 100.0;
        const double spacing = std::sqrt(M_PI * spec.size * spec.size / static_cast<double>(n));
        spec.noise = 0.3 * spacing;
        const auto cloud = pss::generateCloud(spec);
        StartSet starts;
        starts.count = n;
        return ProjectRow(cloud, 3, 2.0 * spacing, pss::Variant::CenterOfMass, pss::Procedure::Plane, threads, starts, nullptr);
      });
    }
  }

  for (int threads : { 1, 2 })
  {
    const std::string name = "bunny mesh com t" + std::to_string(threads);
    if (!bunny.empty() && !quick && wanted(name))
    {
      RunRow(name.c_str(), [&]() { return MeshRow(bunny, threads, pss::Variant::CenterOfMass); });
    }
  }
  // The integral definition's mesh, from the delta lattice: about 155 s, so on 2 threads only.
  if (!bunny.empty() && !quick && wanted("bunny mesh integral t2"))
  {
    RunRow("bunny mesh integral t2", [&]() { return MeshRow(bunny, 2, pss::Variant::Integral); });
  }

#ifdef PSS_BENCH_WITH_VTK
  for (int threads : { 1, 2 })
  {
    const std::string name = "field-1024x1024 com t" + std::to_string(threads);
    if (wanted(name))
    {
      RunRow(name.c_str(), [&]() { return FieldRow(threads); });
    }
  }
#endif
#ifdef PSS_BENCH_PSS
  for (std::size_t millions : { 1, 10, 100 })
  {
    const std::string name = "pss-" + std::to_string(millions) + "m com plane t2";
    // 100M takes about 20 GB and 10 minutes: only when --rows names it.
    if (!quick && wanted(name) && (millions < 100 || only.find("100m") != std::string::npos))
    {
      WholeProcessRow(name, millions * 1000000);
    }
  }
  if (!quick && wanted("read 10m pcd vtp"))
  {
    ReadRow(10000000);
  }
#endif
  std::printf("\nitems/s: projected points (or grid samples) per second of wall time; iters: mean iterations;\n"
              "neighb: mean neighbours with weight > exp(-9) of the nearest; peak MiB: the row process's\n"
              "peak resident memory when the timed work ended; B/point: that peak minus what the process\n"
              "held at its start, per input point (per sample for the field rows), including the row's\n"
              "own copy of the input (24 B/point), its index and its outputs (end points, iterations);\n"
              "median um: median distance to bun_zipper.ply in micrometres. pss-Nm rows: items/s over the\n"
              "whole process's wall time, peak MiB the process's peak, B/point that peak per point.\n");
  return 0;
}

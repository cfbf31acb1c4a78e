// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss: the PointSetSurfaces filters from the command line.
 *
 *   pss generate  -o cloud.vtp [--scene noisy-curve] ...
 *   pss project   CLOUD -o projected.vtp [--start FILE] [--lines FILE] ...
 *   pss classify  CLOUD -o labels.vtp [--start FILE] ...
 *   pss sample    CLOUD -o field.vti [--grid NX,NY,NZ | --probe FILE] ...
 *   pss glyphs    CLOUD -o glyphs.vtp [--samples FILE] [--segments FILE] ...
 *   pss mesh      CLOUD -o mesh.vtp|.ply|.stl|.obj [--cell C] [--band B] ...
 *
 * Every subcommand drives the same VTK filters a pipeline or ParaView uses; `pss SUBCOMMAND --help`
 * lists its flags with their defaults. Exit status: 0 success, 1 failure (message on stderr),
 * 2 bad command line.
 */
#include "PssIO.h"
#include "PssOptions.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceAlgorithm.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceDomainClassifier.h"
#include "vtkPointSetSurfaceEnergyGlyphs.h"
#include "vtkPointSetSurfaceFieldSampler.h"
#include "vtkPointSetSurfaceMesher.h"
#include "vtkPointSetSurfaceProjection.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkVersion.h"

#include "pss/Kernel.h"
#include "pss/VariantCatalog.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

namespace
{

using pss_cli::AddSurfaceOptions;
using pss_cli::OptionTable;
using pss_cli::UsageError;

// Options every subcommand has, and the stage timer behind --verbose.
struct Run
{
  std::string output;
  int threads = 0;
  pss_cli::Compression compression = pss_cli::Compression::LZ4;
  bool verbose = false;
  bool progress = isatty(STDERR_FILENO) != 0;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

  template <class F>
  auto Stage(const char* name, F&& f)
  {
    const auto t0 = std::chrono::steady_clock::now();
    struct Report
    {
      const Run& run;
      const char* name;
      std::chrono::steady_clock::time_point t0;
      ~Report()
      {
        if (run.verbose)
        {
          const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          std::fprintf(stderr, "pss: %-8s %9.3f s\n", name, s);
        }
      }
    } report{ *this, name, t0 };
    return f();
  }
};

void AddCommonOptions(OptionTable& t, Run& run)
{
  t.Value("output", "FILE", "output file (.vtp .vtu .vti .ply .stl .obj .csv .xyz); required", [&](const std::string& v) { run.output = v; });
  t.Value("o", "FILE", "same as --output", [&](const std::string& v) { run.output = v; });
  t.Value("threads", "N", "worker threads; 0 = all cores (default 0)", [&](const std::string& v) {
    run.threads = pss_cli::ToInt("threads", v);
    if (run.threads < 0)
      throw UsageError{ "--threads must be >= 0" };
  });
  t.Value("compression", "NAME", "lz4 | zlib | none, for .vtp .vtu .vti output (default lz4); none also writes .pcd as binary, not binary_compressed", [&](const std::string& v) {
    run.compression = static_cast<pss_cli::Compression>(pss_cli::ToChoice("compression", v, { "lz4", "zlib", "none" }));
  });
  t.Switch("verbose", "print the wall time of each stage (read, index, compute, write), the peak memory and a summary",
    [&]() { run.verbose = true; });
  t.Switch("progress", "always draw the progress bar on stderr (default: only on a terminal)", [&]() { run.progress = true; });
  t.Switch("no-progress", "never draw the progress bar", [&]() { run.progress = false; });
}

// Where n and the normals point: the filters' ViewpointMode and Viewpoint.
void AddViewpointOption(OptionTable& t, vtkPointSetSurfaceAlgorithm* a)
{
  t.Value("viewpoint", "X,Y,Z|input|off",
    "orient n and the normals toward this sensor position; input: the cloud's own (a PCD file's VIEWPOINT), "
    "away from the centroid when it has none; off: away from the centroid (default input)",
    [a](const std::string& v) {
      if (v == "input" || v == "off")
      {
        a->SetViewpointMode(v == "input" ? vtkPointSetSurfaceAlgorithm::VIEWPOINT_FROM_INPUT
                                         : vtkPointSetSurfaceAlgorithm::VIEWPOINT_OFF);
        return;
      }
      double xyz[3];
      std::size_t at = 0;
      for (int k = 0; k < 3; ++k)
      {
        const std::size_t comma = k < 2 ? v.find(',', at) : v.size();
        if (comma == std::string::npos || (k == 2 && v.find(',', at) != std::string::npos))
        {
          throw pss_cli::UsageError{ "--viewpoint takes X,Y,Z, input or off, not '" + v + "'" };
        }
        xyz[k] = pss_cli::ToDouble("viewpoint", v.substr(at, comma - at));
        at = comma + 1;
      }
      a->SetViewpointModeToGiven();
      a->SetViewpoint(xyz);
    });
}

void AddProjectionOptions(OptionTable& t, vtkPointSetSurfaceProjection* p)
{
  t.Value("procedure", "NAME", "extremal | plane (default extremal)",
    [p](const std::string& v) { p->SetProcedure(pss_cli::ToChoice("procedure", v, { "extremal", "plane" })); });
  t.Value("max-iterations", "N", "iteration limit per point (default 100)",
    [p](const std::string& v) { p->SetMaxIterations(pss_cli::ToInt("max-iterations", v)); });
  t.Value("tolerance", "T", "convergence when a step < T * h (default 1e-6)",
    [p](const std::string& v) { p->SetTolerance(pss_cli::ToDouble("tolerance", v)); });
  t.Value("max-travel", "L", "longest line search, in h (default 1000)",
    [p](const std::string& v) { p->SetMaxTravel(pss_cli::ToDouble("max-travel", v)); });
  t.Switch("seek-maxima", "converge to maxima of e along n instead of minima", [p]() { p->SeekMaximaOn(); });
  t.Switch("propagate-normals", "orient Normal consistently over the end points' neighbours (default: point by point)",
    [p]() { p->PropagateNormalsOn(); });
  t.Value("normal-neighbors", "K", "--propagate-normals' graph: K nearest end points, within [1, 100] (default 10)",
    [p](const std::string& v) { p->SetNormalNeighbors(static_cast<int>(pss_cli::ToNumberIn("normal-neighbors", v, 1, 100))); });
}

// Draws "[=====     ]  50%" on stderr from an algorithm's ProgressEvent.
struct ProgressBar
{
  int last = -1;
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    auto* self = static_cast<ProgressBar*>(clientData);
    const double p = *static_cast<double*>(callData);
    const int percent = static_cast<int>(p * 100.0 + 0.5);
    if (percent == self->last)
    {
      return;
    }
    self->last = percent;
    const int filled = percent / 2;
    std::fprintf(stderr, "\r[%.*s%*s] %3d%%", filled, "==================================================", 50 - filled, "",
      percent);
    if (percent >= 100)
    {
      std::fprintf(stderr, "\n");
    }
    std::fflush(stderr);
  }
};

void Execute(Run& run, vtkAlgorithm* algorithm)
{
  ProgressBar bar;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(&ProgressBar::Callback);
  observer->SetClientData(&bar);
  if (run.progress)
  {
    algorithm->AddObserver(vtkCommand::ProgressEvent, observer);
  }
  const int ok = algorithm->GetExecutive()->Update();
  if (run.progress)
  {
    algorithm->RemoveObserver(observer);
    if (bar.last >= 0 && bar.last < 100)
    {
      std::fprintf(stderr, "\n");
    }
  }
  if (!ok || algorithm->GetErrorCode() != 0)
  {
    throw std::runtime_error(std::string(algorithm->GetClassName()) + " failed (see the error above)");
  }
}

// What every subcommand checks and sets once its flags are parsed.
void StartRun(const Run& run)
{
  if (run.output.empty())
  {
    throw UsageError{ "--output FILE is required" };
  }
  vtkSMPTools::Initialize(run.threads);
}

// Parses, or prints help and returns false.
bool ParseCommand(const char* name, const char* usage, const char* summary, OptionTable& table,
  const std::vector<std::string>& args, std::vector<std::string>& positional)
{
  for (const std::string& a : args)
  {
    if (a == "--help" || a == "-h")
    {
      std::cout << "usage: pss " << name << " " << usage << "\n\n" << summary << "\n\noptions:\n"
                << table.Help();
      return false;
    }
  }
  positional = table.Parse(args);
  return true;
}

// The start of the subcommands that read one cloud: returns its path, or nothing after --help.
std::optional<std::string> ParseCloudCommand(const char* name, const char* usage, const char* summary,
  OptionTable& table, const std::vector<std::string>& args, const Run& run)
{
  std::vector<std::string> positional;
  if (!ParseCommand(name, usage, summary, table, args, positional))
  {
    return std::nullopt;
  }
  if (positional.size() != 1)
  {
    throw UsageError{ std::string(name) + " needs exactly one input cloud" };
  }
  StartRun(run);
  return positional[0];
}

vtkSmartPointer<vtkPointSet> ReadPointSet(Run& run, const std::string& path, const char* what)
{
  vtkSmartPointer<vtkDataSet> data = run.Stage("read", [&]() { return pss_cli::ReadDataSet(path); });
  vtkPointSet* points = vtkPointSet::SafeDownCast(data);
  if (!points)
  {
    throw std::runtime_error(std::string("the ") + what + " " + path + " is not a point set");
  }
  // The filters read a point set's points and point data only: its cells (in most clouds one
  // vertex per point, 8 to 16 bytes a point) are let go as soon as it is read.
  auto pointsOnly = vtkSmartPointer<vtkPolyData>::New();
  pointsOnly->SetPoints(points->GetPoints());
  pointsOnly->GetPointData()->ShallowCopy(points->GetPointData());
  pointsOnly->GetFieldData()->ShallowCopy(points->GetFieldData());
  return pointsOnly;
}

// Reads the cloud and builds the index once, so --verbose can time the two stages apart.
vtkSmartPointer<vtkPointSet> PrepareCloud(Run& run, const std::string& path, vtkPointSetSurface* surface)
{
  vtkSmartPointer<vtkPointSet> cloud = ReadPointSet(run, path, "cloud");
  const bool ok = run.Stage("index", [&]() { return surface->Prepare(cloud); });
  if (!ok)
  {
    throw std::runtime_error(std::string("cannot define the surface on ") + path + ": " + surface->GetLastError());
  }
  if (run.verbose)
  {
    std::fprintf(stderr, "pss: %lld points, dimension %d, h = %.6g%s, %lld skipped (NaN/Inf)\n",
      static_cast<long long>(cloud->GetNumberOfPoints()), surface->GetEffectiveDimension(), surface->GetEffectiveScale(),
      surface->GetUsesPointScales() ? " (median of a scale per point)" : "",
      static_cast<long long>(surface->GetNumberOfSkippedPoints()));
    if (surface->GetScaleSpread() > 0.0)
    {
      std::fprintf(stderr, "pss: the points' scales spread %.3g (90th / 10th percentile)\n", surface->GetScaleSpread());
    }
  }
  return cloud;
}

void Write(Run& run, vtkDataSet* data, const std::string& path)
{
  run.Stage("write", [&]() {
    pss_cli::WriteDataSet(data, path, run.compression);
    return 0;
  });
  // The whole process's peak resident memory, the figure that decides how large a cloud fits.
  rusage usage{};
  if (run.verbose && getrusage(RUSAGE_SELF, &usage) == 0)
  {
    std::fprintf(stderr, "pss: peak memory %.1f MiB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  }
}

// Counts of an integer point array's values, printed by --verbose (StopReason, DomainLabel).
void Summarize(const Run& run, vtkDataSet* data, const char* arrayName, const std::vector<std::string>& names)
{
  vtkDataArray* a = data->GetPointData()->GetArray(arrayName);
  if (!run.verbose || !a)
  {
    return;
  }
  std::map<int, long long> counts;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    ++counts[static_cast<int>(a->GetComponent(i, 0))];
  }
  std::fprintf(stderr, "pss: %s:", arrayName);
  for (const auto& [value, count] : counts)
  {
    const bool named = value >= 0 && value < static_cast<int>(names.size());
    std::fprintf(stderr, " %s %lld", named ? names[value].c_str() : std::to_string(value).c_str(), count);
  }
  std::fprintf(stderr, "\n");
}

const std::vector<std::string> StopReasons = { "converged", "max-iterations", "undefined-n", "no-extremum", "invalid-input" };
const std::vector<std::string> DomainLabels = { "in-domain", "spurious", "undefined", "not-converged" };

int Generate(const std::vector<std::string>& args)
{
  Run run;
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  OptionTable t;
  AddCommonOptions(t, run);
  t.Value("scene", "NAME", "line | circle | corner | noisy-curve | plane | sphere | two-sheets | depth-camera (default noisy-curve)",
    [&](const std::string& v) {
      source->SetScene(pss_cli::ToChoice("scene", v,
        { "line", "circle", "corner", "noisy-curve", "plane", "sphere", "two-sheets", "depth-camera" }));
    });
  t.Value("count", "N", "number of points (default 1000)", [&](const std::string& v) {
    const int n = pss_cli::ToInt("count", v);
    if (n < 0)
      throw UsageError{ "--count must be >= 0" };
    source->SetNumberOfPoints(n);
  });
  t.Value("size", "S", "characteristic length of the scene (default 100)",
    [&](const std::string& v) { source->SetSize(pss_cli::ToDouble("size", v)); });
  t.Value("noise", "SIGMA", "Gaussian noise (noisy-curve: at its noisy end) (default 0)",
    [&](const std::string& v) { source->SetNoise(pss_cli::ToDouble("noise", v)); });
  t.Value("seed", "N", "random seed (default 1)", [&](const std::string& v) { source->SetSeed(pss_cli::ToInt("seed", v)); });
  bool dimensionGiven = false;
  t.Value("dimension", "D", "2 (xy-plane) or 3 (default 3 for plane, sphere and two-sheets, else 2)",
    [&](const std::string& v) {
      source->SetDimension(2 + pss_cli::ToChoice("dimension", v, { "2", "3" }));
      dimensionGiven = true;
    });
  t.Value("corner-angle", "DEG", "angle between the corner's segments (default 60)",
    [&](const std::string& v) { source->SetCornerAngle(pss_cli::ToDouble("corner-angle", v)); });
  t.Value("gap", "G", "distance between the two sheets (default 10)",
    [&](const std::string& v) { source->SetSheetGap(pss_cli::ToDouble("gap", v)); });
  t.Value("image", "WxH", "depth-camera: pixels across and down (default 640x480)", [&](const std::string& v) {
    const std::pair<int, int> size = pss_cli::ToImageSize("image", v, 16384);
    source->SetImageWidth(size.first);
    source->SetImageHeight(size.second);
  });
  t.Value("depth-noise", "S0", "depth-camera: depth noise sigma = S0 z^2, S0 in 1/m (default 0.0012)",
    [&](const std::string& v) { source->SetDepthNoise(pss_cli::ToDouble("depth-noise", v)); });
  std::vector<std::string> positional;
  if (!ParseCommand("generate", "-o FILE [options]", "Writes a synthetic test cloud with a known shape.", t, args,
        positional))
  {
    return 0;
  }
  if (!positional.empty())
  {
    throw UsageError{ "generate takes no input file" };
  }
  // A user asking for a sphere expects a sphere: the surface scenes are 3D unless told otherwise
  // (their 2D versions, a circle, a line and two lines, stay one flag away).
  const int scene = source->GetScene();
  if (!dimensionGiven &&
    (scene == vtkPointSetSurfaceCloudSource::PLANE || scene == vtkPointSetSurfaceCloudSource::SPHERE ||
      scene == vtkPointSetSurfaceCloudSource::TWO_SHEETS))
  {
    source->SetDimension(3);
  }
  StartRun(run);
  run.Stage("compute", [&]() {
    Execute(run, source);
    return 0;
  });
  Write(run, source->GetOutput(), run.output);
  return 0;
}

// project and classify share everything but the filter class and the extra flags.
int ProjectOrClassify(const std::vector<std::string>& args, bool classify)
{
  Run run;
  vtkSmartPointer<vtkPointSetSurfaceProjection> filter;
  vtkPointSetSurfaceDomainClassifier* classifier = nullptr;
  if (classify)
  {
    auto c = vtkSmartPointer<vtkPointSetSurfaceDomainClassifier>::New();
    classifier = c;
    filter = c;
  }
  else
  {
    filter = vtkSmartPointer<vtkPointSetSurfaceProjection>::New();
  }
  std::string startPath;
  std::string linesPath;
  OptionTable t;
  AddCommonOptions(t, run);
  AddSurfaceOptions(t, filter->GetSurface());
  AddProjectionOptions(t, filter);
  AddViewpointOption(t, filter);
  t.Value("start", "FILE", "start points to project (default: the cloud itself)", [&](const std::string& v) { startPath = v; });
  t.Value("lines", "FILE", "also write a segment from each start point to its projection (Figure 1)",
    [&](const std::string& v) { linesPath = v; });
  if (classifier)
  {
    t.Value("max-distance", "D", "Spurious when the fixed point is farther than D h from the cloud (default 1)",
      [classifier](const std::string& v) { classifier->SetMaxDistance(pss_cli::ToDouble("max-distance", v)); });
    t.Value("max-normal-angle", "DEG", "Spurious when n at the fixed point is off the cloud's normal by more (default 30)",
      [classifier](const std::string& v) { classifier->SetMaxNormalAngle(pss_cli::ToDouble("max-normal-angle", v)); });
  }
  const char* name = classify ? "classify" : "project";
  const char* summary = classify
    ? "Projects every start point and labels it: 0 InDomain, 1 Spurious, 2 Undefined, 3 NotConverged."
    : "Moves points onto the point-set surface of CLOUD (arrays Normal, Energy, Displacement, Iterations,\n"
      "Converged, Stability, ExtremumType, StopReason).";
  const std::optional<std::string> cloudPath = ParseCloudCommand(name, "CLOUD -o FILE [options]", summary, t, args, run);
  if (!cloudPath)
  {
    return 0;
  }
  vtkSmartPointer<vtkPointSet> cloud = PrepareCloud(run, *cloudPath, filter->GetSurface());
  filter->SetInputData(0, cloud);
  if (!startPath.empty())
  {
    filter->SetStartPointsData(ReadPointSet(run, startPath, "start point set"));
  }
  filter->SetGenerateProjectionLines(!linesPath.empty());
  run.Stage("compute", [&]() {
    Execute(run, filter);
    return 0;
  });
  vtkPolyData* out = filter->GetOutput(0);
  Summarize(run, out, "StopReason", StopReasons);
  Summarize(run, out, "DomainLabel", DomainLabels);
  Write(run, out, run.output);
  if (!linesPath.empty())
  {
    Write(run, filter->GetOutput(1), linesPath);
  }
  return 0;
}

int Sample(const std::vector<std::string>& args)
{
  Run run;
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  std::string probePath;
  OptionTable t;
  AddCommonOptions(t, run);
  AddSurfaceOptions(t, sampler->GetSurface());
  t.Value("probe", "FILE", "sample at the points of this dataset (image, plane, line, ...)", [&](const std::string& v) { probePath = v; });
  t.Value("grid", "NX,NY[,NZ]", "sample on a grid over the cloud's bounds plus the margin (default 101,101,1)",
    [&](const std::string& v) {
      int dims[3];
      pss_cli::ToDimensions("grid", v, dims);
      sampler->SetSampleDimensions(dims);
    });
  t.Value("margin", "M", "grid margin around the cloud's bounds, in h (default 3)",
    [&](const std::string& v) { sampler->SetSamplingMargin(pss_cli::ToDouble("margin", v)); });
  t.Switch("domain-labels", "also compute DomainLabel at every sample (projects every sample: slow)",
    [&]() { sampler->ComputeDomainLabelsOn(); });
  const std::optional<std::string> cloudPath = ParseCloudCommand("sample",
    "CLOUD -o FILE [--probe FILE | --grid NX,NY,NZ] [options]",
    "Samples Normal (oriented for stream tracers), Energy, Delta, ImplicitG, Stability, ExtremumType.", t, args, run);
  if (!cloudPath)
  {
    return 0;
  }
  vtkSmartPointer<vtkPointSet> cloud = PrepareCloud(run, *cloudPath, sampler->GetSurface());
  sampler->SetSourceData(cloud);
  if (!probePath.empty())
  {
    sampler->SetInputData(run.Stage("read", [&]() { return pss_cli::ReadDataSet(probePath); }));
    sampler->GenerateSamplingGridOff();
  }
  else
  {
    sampler->GenerateSamplingGridOn();
  }
  run.Stage("compute", [&]() {
    Execute(run, sampler);
    return 0;
  });
  Write(run, vtkDataSet::SafeDownCast(sampler->GetOutputDataObject(0)), run.output);
  return 0;
}

int Glyphs(const std::vector<std::string>& args)
{
  Run run;
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  std::string samplesPath;
  std::string segmentsPath;
  OptionTable t;
  AddCommonOptions(t, run);
  AddSurfaceOptions(t, glyphs->GetSurface());
  AddViewpointOption(t, glyphs);
  t.Value("samples", "FILE", "points where glyphs are drawn (default: the cloud's points)", [&](const std::string& v) { samplesPath = v; });
  t.Value("segments", "FILE", "also write the best-fitting line/plane segments normal to n", [&](const std::string& v) { segmentsPath = v; });
  t.Value("resolution", "N", "directions per glyph (default 72)",
    [&](const std::string& v) { glyphs->SetResolution(pss_cli::ToInt("resolution", v)); });
  t.Value("glyph-size", "S", "largest glyph radius, in h (default 1)",
    [&](const std::string& v) { glyphs->SetGlyphSize(pss_cli::ToDouble("glyph-size", v)); });
  t.Value("segment-length", "L", "half-length of the best-fit segments, in h (default 1)",
    [&](const std::string& v) { glyphs->SetSegmentLength(pss_cli::ToDouble("segment-length", v)); });
  const std::optional<std::string> cloudPath = ParseCloudCommand("glyphs", "CLOUD -o FILE [options]",
    "Energy plots x + c e(x, a) a over directions a (Figures 4 and 5) and best-fitting segments.", t, args, run);
  if (!cloudPath)
  {
    return 0;
  }
  vtkSmartPointer<vtkPointSet> cloud = PrepareCloud(run, *cloudPath, glyphs->GetSurface());
  glyphs->SetInputData(0, cloud);
  if (!samplesPath.empty())
  {
    glyphs->SetSamplePointsData(ReadPointSet(run, samplesPath, "sample point set"));
  }
  run.Stage("compute", [&]() {
    Execute(run, glyphs);
    return 0;
  });
  Write(run, glyphs->GetOutput(0), run.output);
  if (!segmentsPath.empty())
  {
    Write(run, glyphs->GetOutput(1), segmentsPath);
  }
  return 0;
}

// Prints the mesher's counts (field data of its output) for --verbose.
void SummarizeMesh(const Run& run, vtkPolyData* mesh)
{
  if (!run.verbose)
  {
    return;
  }
  std::fprintf(stderr, "pss: %lld vertices, %lld %s", static_cast<long long>(mesh->GetNumberOfPoints()),
    static_cast<long long>(mesh->GetNumberOfCells()), mesh->GetNumberOfPolys() > 0 ? "triangles" : "cells");
  for (const char* name : { "BandCells", "Crossings", "DroppedVertices", "Components", "BoundaryEdges",
         "NonManifoldEdges", "EulerCharacteristic" })
  {
    if (vtkDataArray* a = mesh->GetFieldData()->GetArray(name))
    {
      std::fprintf(stderr, ", %s %lld", name, static_cast<long long>(a->GetComponent(0, 0)));
    }
  }
  std::fprintf(stderr, "\n");
}

int Mesh(const std::vector<std::string>& args)
{
  Run run;
  vtkNew<vtkPointSetSurfaceMesher> mesher;
  OptionTable t;
  AddCommonOptions(t, run);
  AddSurfaceOptions(t, mesher->GetSurface());
  AddViewpointOption(t, mesher);
  t.Value("cell", "C", "grid cell size, in h, within [0.05, 100] (default 1)",
    [&](const std::string& v) { mesher->SetCellSize(pss_cli::ToNumberIn("cell", v, 0.05, 100.0, " (in units of h)")); });
  t.Value("band", "B", "visit cells within B h of the cloud, within [0.1, 100] (default 1)",
    [&](const std::string& v) { mesher->SetBand(pss_cli::ToNumberIn("band", v, 0.1, 100.0, " (in units of h)")); });
  t.Switch("regular-cells", "one grid of cells at the typical h even with a scale per point (default: cells follow h_i)",
    [&]() { mesher->AdaptiveCellsOff(); });
  t.Switch("no-projection", "leave the vertices at the grid's zero crossings of g (default: projected)",
    [&]() { mesher->ProjectVerticesOff(); });
  t.Value("procedure", "NAME", "extremal | plane | automatic: how the vertices are projected (default automatic: plane for com with point scales, else extremal)",
    [&](const std::string& v) { mesher->SetProcedure(pss_cli::ToChoice("procedure", v, { "extremal", "plane", "automatic" })); });
  t.Value("max-distance", "D", "outside the domain: a projection ending farther than D h from the cloud (default -1: 0.6 with point scales, else 1)",
    [&](const std::string& v) { mesher->SetMaxDistance(pss_cli::ToDouble("max-distance", v)); });
  t.Value("max-normal-angle", "DEG", "outside the domain: n off the cloud's normal by more (default 30)",
    [&](const std::string& v) { mesher->SetMaxNormalAngle(pss_cli::ToDouble("max-normal-angle", v)); });
  t.Value("max-border-offset", "B", "outside the domain: past the cloud's border, B local h (0 off; default -1: 0.6 with point scales)",
    [&](const std::string& v) { mesher->SetMaxBorderOffset(pss_cli::ToDouble("max-border-offset", v)); });
  t.Value("trim-distance", "T", "3D: cut the mesh back where it runs farther than T local point spacings from the cloud (0 off; default -1: 2.5 with point scales, else off)",
    [&](const std::string& v) { mesher->SetTrimDistance(pss_cli::ToDouble("trim-distance", v)); });
  t.Value("max-vertex-travel", "CELLS", "drop crossings whose projection moves farther (default 2)",
    [&](const std::string& v) { mesher->SetMaxVertexTravel(pss_cli::ToDouble("max-vertex-travel", v)); });
  t.Value("max-seam-angle", "DEG", "skip cells across which the oriented n turns more (default 80)",
    [&](const std::string& v) { mesher->SetMaxSeamAngle(pss_cli::ToDouble("max-seam-angle", v)); });
  t.Value("max-fold-angle", "DEG", "drop triangles whose normal is farther off their vertices' n (default 60)",
    [&](const std::string& v) { mesher->SetMaxFoldAngle(pss_cli::ToDouble("max-fold-angle", v)); });
  t.Value("max-hole-edges", "N", "3D: close holes of at most N edges unless the scan has no data at their centre (default 100)",
    [&](const std::string& v) { mesher->SetMaxHoleEdges(pss_cli::ToInt("max-hole-edges", v)); });
  t.Value("min-piece-area", "A", "3D: remove pieces smaller than A h^2 (default 10; 0 keeps all)",
    [&](const std::string& v) { mesher->SetMinPieceArea(pss_cli::ToDouble("min-piece-area", v)); });
  t.Value("covered-piece-area", "A", "3D: remove pieces smaller than A h^2 lying over the largest piece's interior (default 10; 0: keep all)",
    [&](const std::string& v) { mesher->SetCoveredPieceArea(pss_cli::ToDouble("covered-piece-area", v)); });
  const std::optional<std::string> cloudPath = ParseCloudCommand("mesh", "CLOUD -o FILE [options]",
    "Meshes the point-set surface of CLOUD where it is defined: triangles in 3D (polylines in 2D) with\n"
    "Normals, Stability, Energy, DomainLabel and the classifier's evidence. .stl and .obj keep the geometry only.",
    t, args, run);
  if (!cloudPath)
  {
    return 0;
  }
  vtkSmartPointer<vtkPointSet> cloud = PrepareCloud(run, *cloudPath, mesher->GetSurface());
  mesher->SetInputData(cloud);
  run.Stage("compute", [&]() {
    Execute(run, mesher);
    return 0;
  });
  if (run.verbose)
  {
    std::fprintf(stderr, "pss: mesh stages: %s (%s procedure)\n", mesher->GetTimingReport(), mesher->GetUsedProcedure() == vtkPointSetSurfaceMesher::PLANE ? "plane" : "extremal");
  }
  SummarizeMesh(run, mesher->GetOutput());
  Write(run, mesher->GetOutput(), run.output);
  return 0;
}

const char* const MainHelp = "usage: pss SUBCOMMAND [options]   (pss SUBCOMMAND --help for its flags)\n"
                             "\n"
                             "  generate   write a synthetic cloud (line, circle, corner, noisy-curve, plane, sphere, two-sheets, depth-camera)\n"
                             "  project    move points onto a point-set surface\n"
                             "  classify   label start points InDomain / Spurious / Undefined / NotConverged\n"
                             "  sample     sample n, e, delta and g on a grid or at the points of a dataset\n"
                             "  glyphs     energy plots and best-fitting segments (Figures 4 and 5)\n"
                             "  mesh       the surface as triangles (polylines in 2D), only where it is defined\n"
                             "  version    the versions of pss and VTK and the vector kernels in use (also --version)\n"
                             "\n"
                             "Files are read and written by extension: .vtp .vtu .vti .ply .pcd .csv .xyz (.stl .obj: written only)\n";

// `pss --version`: what a bug report needs to say which build ran, including the
// copy of the core the loader took, or in the baseline copy its vector kernels (docs/development.md).
int Version()
{
  std::cout << "pss " << PSS_VERSION << " (PointSetSurfaces)\n"
            << "VTK " << vtkVersion::GetVTKVersion() << "\n"
            << "SIMD " << pss::kernelInstructionSet() << "\n";
  return 0;
}

// VTK's errors go to stderr as single lines, not to a popup or with the debug banner.
class PlainOutputWindow : public vtkOutputWindow
{
public:
  static PlainOutputWindow* New();
  vtkTypeMacro(PlainOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { std::cerr << text << std::flush; }
};
vtkStandardNewMacro(PlainOutputWindow);

} // namespace

int main(int argc, char** argv)
{
  vtkNew<PlainOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
  vtkPointSetSurface::UseThreadedBackend();
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")
  {
    std::cout << MainHelp;
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  if (command == "--version" || command == "version")
  {
    return Version();
  }
  const std::vector<std::string> args(argv + 2, argv + argc);
  try
  {
    if (command == "generate")
      return Generate(args);
    if (command == "project")
      return ProjectOrClassify(args, false);
    if (command == "classify")
      return ProjectOrClassify(args, true);
    if (command == "sample")
      return Sample(args);
    if (command == "glyphs")
      return Glyphs(args);
    if (command == "mesh")
      return Mesh(args);
    std::cerr << "pss: unknown subcommand '" << command << "'\n\n" << MainHelp;
    return 2;
  }
  catch (const UsageError& e)
  {
    std::cerr << "pss " << command << ": " << e.message << "\n";
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "pss " << command << ": error: " << e.what() << "\n";
    return 1;
  }
}

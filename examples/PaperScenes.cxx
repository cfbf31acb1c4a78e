// SPDX-License-Identifier: BSD-3-Clause
#include "PaperScenes.h"

#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceDomainClassifier.h"
#include "vtkPointSetSurfaceFieldSampler.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include "pss/Types.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

namespace pss_paper
{

vtkSmartPointer<vtkPolyData> MakePointCloud(const std::vector<pss::Vec3>& points)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(points.size()); ++i)
  {
    pts->SetPoint(i, points[i].data());
    verts->InsertNextCell(1, &i);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetVerts(verts);
  return poly;
}

namespace
{

// The cloud of a core scene, drawn through the VTK source filter (same spec, same points).
vtkSmartPointer<vtkPolyData> GenerateWithSource(const pss::CloudSpec& spec)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetScene(static_cast<int>(spec.scene));
  source->SetNumberOfPoints(static_cast<vtkIdType>(spec.count));
  source->SetSize(spec.size);
  source->SetNoise(spec.noise);
  source->SetSeed(static_cast<int>(spec.seed));
  source->SetDimension(spec.dimension);
  source->SetCornerAngle(spec.cornerAngle);
  source->Update();
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->DeepCopy(source->GetOutput());
  if (cloud->GetNumberOfPoints() != static_cast<vtkIdType>(spec.count))
  {
    throw std::runtime_error(std::string("the cloud source failed on scene ") + pss::sceneName(spec.scene));
  }
  return cloud;
}

vtkDataArray* RequireArray(vtkPolyData* data, const char* name)
{
  vtkDataArray* a = data->GetPointData()->GetArray(name);
  if (!a)
  {
    throw std::runtime_error(std::string("filter output lacks the array ") + name);
  }
  return a;
}

} // namespace

Scene MakeLineScene()
{
  Scene s;
  s.name = "line";
  s.h = 5.0;
  s.shape.scene = pss::Scene::Line;
  s.shape.size = 40.0 * s.h;
  s.shape.count = 401; // spacing 0.1 h
  s.shape.noise = 0.0;
  s.shape.dimension = 2;
  // Evenly spaced, as in Figure 5: the core's line scene draws its points at random, whose local
  // density fluctuations move Levin's flip height by several percent from column to column.
  std::vector<pss::Vec3> points;
  const double spacing = s.shape.size / static_cast<double>(s.shape.count - 1);
  for (std::size_t i = 0; i < s.shape.count; ++i)
  {
    points.emplace_back(-0.5 * s.shape.size + spacing * static_cast<double>(i), 0.0, 0.0);
  }
  s.cloud = MakePointCloud(points);
  return s;
}

Scene MakeNoisyCurveScene(double h)
{
  Scene s;
  s.name = "noisy-curve";
  s.h = h;
  s.shape.scene = pss::Scene::NoisyCurve;
  s.shape.count = 600;
  s.shape.size = 200.0;
  s.shape.noise = 3.0; // sigma 0.6 at the dense end, 3 at the sparse end: +-sigma band 1.2 .. 6
  s.shape.seed = 1;
  s.shape.dimension = 2;
  s.cloud = GenerateWithSource(s.shape);
  return s;
}

Scene MakeCornerScene()
{
  Scene s;
  s.name = "corner";
  s.h = 5.0;
  s.shape.scene = pss::Scene::Corner;
  s.shape.count = 200;
  s.shape.size = 100.0; // two open arms of length 50 = 10 h
  s.shape.cornerAngle = 45.0;
  s.shape.noise = 0.01 * s.h; // "slightly perturbed so as to be in general position"
  s.shape.seed = 1;
  s.shape.dimension = 2;
  s.cloud = GenerateWithSource(s.shape);
  return s;
}

const std::vector<int>& AllVariants()
{
  static const std::vector<int> variants = { vtkPointSetSurface::LEVIN_MLS, vtkPointSetSurface::NORMALIZED_MLS,
    vtkPointSetSurface::CENTER_OF_MASS, vtkPointSetSurface::INTEGRAL, vtkPointSetSurface::DELTA, vtkPointSetSurface::APSS,
    vtkPointSetSurface::RIMLS };
  return variants;
}

std::string VariantName(int variant)
{
  return pss::variantName(static_cast<pss::Variant>(variant));
}

std::string VariantTitle(int variant)
{
  switch (variant)
  {
    case vtkPointSetSurface::LEVIN_MLS:
      return "Levin's MLS";
    case vtkPointSetSurface::NORMALIZED_MLS:
      return "normalized MLS";
    case vtkPointSetSurface::CENTER_OF_MASS:
      return "center of mass";
    case vtkPointSetSurface::INTEGRAL:
      return "integral (e_I)";
    case vtkPointSetSurface::DELTA:
      return "delta";
    case vtkPointSetSurface::APSS:
      return "APSS";
    case vtkPointSetSurface::RIMLS:
      return "RIMLS";
    default:
      return "unknown";
  }
}

namespace
{
double LatticeSpacing = -1.0; // < 0: the filters' default
}

void SetDeltaLatticeSpacing(double spacing)
{
  LatticeSpacing = spacing;
}

vtkSmartPointer<vtkPointSetSurface> MakeSurface(const Scene& scene, int variant)
{
  auto surface = vtkSmartPointer<vtkPointSetSurface>::New();
  if (LatticeSpacing >= 0.0)
  {
    surface->SetDeltaLatticeSpacing(LatticeSpacing);
  }
  surface->SetVariant(variant);
  surface->AutomaticScaleOff();
  surface->SetScaleFactor(scene.h);
  surface->SetDimension(vtkPointSetSurface::DIMENSION_2D);
  return surface;
}

std::vector<double> GrownBounds(const Scene& scene, double marginInH)
{
  double b[6];
  scene.cloud->GetBounds(b);
  const double m = marginInH * scene.h;
  return { b[0] - m, b[1] + m, b[2] - m, b[3] + m };
}

vtkSmartPointer<vtkPolyData> UniformStarts(const Scene& scene, int count, double marginInH, unsigned seed)
{
  const std::vector<double> b = GrownBounds(scene, marginInH);
  std::mt19937 engine(seed); // the raw 32-bit stream is the same on every platform
  auto uniform = [&engine]() { return (static_cast<double>(engine()) + 0.5) / 4294967296.0; };
  std::vector<pss::Vec3> points;
  for (int i = 0; i < count; ++i)
  {
    const double x = b[0] + (b[1] - b[0]) * uniform();
    const double y = b[2] + (b[3] - b[2]) * uniform();
    points.emplace_back(x, y, 0.0);
  }
  return MakePointCloud(points);
}

Projection Project(const Scene& scene, int variant, vtkPolyData* starts, bool seekMaxima, bool projectionLines)
{
  vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
  classifier->SetSurface(MakeSurface(scene, variant));
  classifier->SetInputData(scene.cloud);
  if (starts)
  {
    classifier->SetStartPointsData(starts);
  }
  classifier->SetSeekMaxima(seekMaxima);
  classifier->SetGenerateProjectionLines(projectionLines);
  const auto t0 = std::chrono::steady_clock::now();
  classifier->Update();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  Projection out;
  out.points = vtkSmartPointer<vtkPolyData>::New();
  out.points->DeepCopy(classifier->GetOutput(0));
  vtkPolyData* points = out.points;
  const vtkIdType n = points->GetNumberOfPoints();
  const vtkIdType expected = starts ? starts->GetNumberOfPoints() : scene.cloud->GetNumberOfPoints();
  if (n != expected)
  {
    throw std::runtime_error("the domain classifier failed on scene " + scene.name);
  }
  vtkDataArray* converged = RequireArray(points, "Converged");
  vtkDataArray* distanceToCloud = RequireArray(points, "DistanceToCloud");

  vtkNew<vtkIntArray> outcome;
  outcome->SetName("Outcome");
  outcome->SetNumberOfTuples(n);
  ProjectionStats& st = out.stats;
  st.scene = scene.name;
  st.variant = variant;
  st.starts = n;
  st.seconds = seconds;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    int o = NOT_CONVERGED;
    if (converged->GetTuple1(i) != 0.0)
    {
      ++st.converged;
      if (distanceToCloud->GetTuple1(i) > kSpuriousDistance * scene.h)
      {
        o = SPURIOUS;
        ++st.spurious;
      }
      else if (pss::distanceToShape(scene.shape, pss::Vec3(p[0], p[1], p[2])) <= kOnCurveDistance * scene.h)
      {
        o = ON_CURVE;
        ++st.onCurve;
      }
      else
      {
        o = OFF_CURVE;
      }
    }
    outcome->SetValue(i, o);
  }
  points->GetPointData()->AddArray(outcome);

  if (projectionLines)
  {
    out.lines = vtkSmartPointer<vtkPolyData>::New();
    out.lines->DeepCopy(classifier->GetOutput(1));
    vtkDataArray* startIds = out.lines->GetCellData()->GetArray("StartPointId");
    vtkNew<vtkIntArray> lineOutcome;
    lineOutcome->SetName("Outcome");
    lineOutcome->SetNumberOfTuples(out.lines->GetNumberOfCells());
    for (vtkIdType c = 0; c < out.lines->GetNumberOfCells(); ++c)
    {
      const vtkIdType id = startIds ? static_cast<vtkIdType>(startIds->GetTuple1(c)) : c;
      lineOutcome->SetValue(c, outcome->GetValue(id));
    }
    out.lines->GetCellData()->AddArray(lineOutcome);
  }
  return out;
}

std::vector<double> LineColumns(const Scene& line)
{
  std::vector<double> columns;
  for (int k = -2; k <= 2; ++k)
  {
    columns.push_back(5.0 * line.h * k);
  }
  return columns;
}

namespace
{

// n sampled by the field sampler at (x, t h) for every t of @p heights; true where n is defined
// and closer to the line's normal (y) than to its tangent (x).
std::vector<bool> NormalLike(const Scene& line, int variant, double x, const std::vector<double>& heights)
{
  std::vector<pss::Vec3> samples;
  for (double t : heights)
  {
    samples.emplace_back(x, t * line.h, 0.0);
  }
  vtkSmartPointer<vtkPolyData> column = MakePointCloud(samples);
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  sampler->SetSurface(MakeSurface(line, variant));
  sampler->SetInputData(column);
  sampler->SetSourceData(line.cloud);
  sampler->Update();
  vtkDataSet* out = sampler->GetOutput();
  vtkDataArray* normal = out ? out->GetPointData()->GetArray("Normal") : nullptr;
  if (!normal || out->GetNumberOfPoints() != column->GetNumberOfPoints())
  {
    throw std::runtime_error("the field sampler failed on the line scene");
  }
  std::vector<bool> result;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double n[3];
    normal->GetTuple(i, n);
    const bool defined = n[0] != 0.0 || n[1] != 0.0;
    result.push_back(defined && std::abs(n[1]) > std::abs(n[0]));
  }
  return result;
}

} // namespace

double FlipHeight(const Scene& line, int variant, double x, double maxHeight)
{
  constexpr double coarse = 0.01;
  std::vector<double> heights;
  for (int k = 1; k * coarse <= maxHeight + 1e-12; ++k)
  {
    heights.push_back(k * coarse);
  }
  const std::vector<bool> normal = NormalLike(line, variant, x, heights);
  const auto first = std::find(normal.begin(), normal.end(), false);
  if (first == normal.end())
  {
    return std::numeric_limits<double>::infinity();
  }
  const std::size_t k = static_cast<std::size_t>(first - normal.begin());
  const double lo = k == 0 ? 0.0 : heights[k - 1];
  std::vector<double> fine;
  constexpr int refinements = 100; // steps of 1e-4 h
  for (int j = 1; j <= refinements; ++j)
  {
    fine.push_back(lo + (heights[k] - lo) * j / refinements);
  }
  const std::vector<bool> refined = NormalLike(line, variant, x, fine);
  const auto flip = std::find(refined.begin(), refined.end(), false);
  return flip == refined.end() ? heights[k] : fine[static_cast<std::size_t>(flip - refined.begin())];
}

DomainScan LineDomainHalfWidth(const Scene& line, int variant, double maxHeight)
{
  constexpr double step = 0.05;
  const int perColumn = static_cast<int>(std::floor(maxHeight / step + 1e-9));
  const std::vector<double> columns = LineColumns(line);
  std::vector<pss::Vec3> starts;
  for (double x : columns)
  {
    for (int k = 1; k <= perColumn; ++k)
    {
      starts.emplace_back(x, k * step * line.h, 0.0);
    }
  }
  const Projection projection = Project(line, variant, MakePointCloud(starts));
  vtkDataArray* outcome = projection.points->GetPointData()->GetArray("Outcome");

  DomainScan scan;
  scan.stats = projection.stats;
  scan.halfWidth = perColumn * step;
  for (std::size_t c = 0; c < columns.size(); ++c)
  {
    for (int k = 1; k <= perColumn; ++k)
    {
      const vtkIdType id = static_cast<vtkIdType>(c * perColumn + (k - 1));
      if (outcome->GetTuple1(id) != ON_CURVE)
      {
        scan.halfWidth = std::min(scan.halfWidth, (k - 1) * step);
        scan.bounded = true;
        break;
      }
    }
  }
  return scan;
}

} // namespace pss_paper

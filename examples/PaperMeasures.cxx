// SPDX-License-Identifier: BSD-3-Clause
#include "PaperMeasures.h"

#include "vtkPointSetSurfaceEnergyGlyphs.h"
#include "vtkPointSetSurfaceFieldSampler.h"
#include "vtkPointSetSurfaceMesher.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace pss_paper
{

namespace
{

double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const std::size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  if (v.size() % 2 == 1)
  {
    return v[k];
  }
  const double upper = v[k];
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k));
  return std::isinf(upper) ? upper : 0.5 * (lower + upper);
}

// Angle in degrees between two unoriented directions (n and -n are the same): in [0, 90].
double UnorientedAngle(const pss::Vec3& a, const pss::Vec3& b)
{
  const double c = std::min(1.0, std::abs(a.dot(b)) / (a.norm() * b.norm()));
  return std::acos(c) * 180.0 / M_PI;
}

// A polyline segment in the xy plane, with the connected piece it belongs to.
struct Segment
{
  std::array<double, 2> a;
  std::array<double, 2> b;
  vtkIdType piece;
};

double DistanceToSegment(const double p[3], const Segment& s)
{
  const double dx = s.b[0] - s.a[0];
  const double dy = s.b[1] - s.a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p[0] - s.a[0]) * dx + (p[1] - s.a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (s.a[0] + t * dx), p[1] - (s.a[1] + t * dy));
}

// The segments of the mesh's line cells, each tagged with its connected piece (the root of its
// vertices in a union-find); @p pieces is the number of distinct pieces.
std::vector<Segment> Segments(vtkPolyData* mesh, vtkIdType& pieces)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<vtkIdType> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](vtkIdType x) {
    while (parent[x] != x)
    {
      x = parent[x] = parent[parent[x]];
    }
    return x;
  };
  std::vector<std::array<vtkIdType, 2>> ids;
  vtkIdType count = 0;
  const vtkIdType* cell = nullptr;
  vtkCellArray* lines = mesh->GetLines();
  for (lines->InitTraversal(); lines->GetNextCell(count, cell);)
  {
    for (vtkIdType k = 0; k + 1 < count; ++k)
    {
      ids.push_back({ cell[k], cell[k + 1] });
      parent[find(cell[k])] = find(cell[k + 1]);
    }
  }
  std::vector<Segment> out;
  std::vector<char> root(static_cast<std::size_t>(n), 0);
  for (const auto& e : ids)
  {
    double a[3];
    double b[3];
    mesh->GetPoint(e[0], a);
    mesh->GetPoint(e[1], b);
    out.push_back({ { a[0], a[1] }, { b[0], b[1] }, find(e[0]) });
    root[find(e[0])] = 1;
  }
  pieces = std::count(root.begin(), root.end(), 1);
  return out;
}

} // namespace

// ---- Figure 3 -----------------------------------------------------------------------------------

PlaneEnergies LinePlaneEnergies(const Scene& line, int variant, double x, const std::vector<double>& heightsInH)
{
  std::vector<pss::Vec3> samples;
  for (double t : heightsInH)
  {
    samples.emplace_back(x, t * line.h, 0.0);
  }
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  glyphs->SetSurface(MakeSurface(line, variant));
  glyphs->SetInputData(line.cloud);
  glyphs->SetSamplePointsData(MakePointCloud(samples));
  // Four directions a_k = (cos k pi/2, sin k pi/2): a_0 = (1, 0) is the normal of the plane
  // perpendicular to the line, a_1 = (0, 1) the normal of the plane parallel to it.
  glyphs->SetResolution(4);
  glyphs->Update();
  vtkPolyData* out = glyphs->GetOutput(0);
  vtkDataArray* energy = out->GetPointData()->GetArray("Energy");
  if (!energy || out->GetNumberOfPoints() != static_cast<vtkIdType>(4 * samples.size()))
  {
    throw std::runtime_error("the energy glyphs failed on the line scene");
  }
  PlaneEnergies e;
  e.heights = heightsInH;
  for (std::size_t s = 0; s < samples.size(); ++s)
  {
    e.perpendicular.push_back(energy->GetTuple1(static_cast<vtkIdType>(4 * s)));
    e.parallel.push_back(energy->GetTuple1(static_cast<vtkIdType>(4 * s + 1)));
  }
  return e;
}

double PerpendicularPlaneWinsHeight(const Scene& line, int variant, double x, double maxHeight)
{
  constexpr double coarse = 0.01;
  std::vector<double> heights;
  for (int k = 1; k * coarse <= maxHeight + 1e-12; ++k)
  {
    heights.push_back(k * coarse);
  }
  const PlaneEnergies c = LinePlaneEnergies(line, variant, x, heights);
  std::size_t k = 0;
  while (k < heights.size() && !(c.perpendicular[k] < c.parallel[k]))
  {
    ++k;
  }
  if (k == heights.size())
  {
    return std::numeric_limits<double>::infinity();
  }
  const double lo = k == 0 ? 0.0 : heights[k - 1];
  std::vector<double> fine;
  constexpr int refinements = 100; // steps of 1e-4 h
  for (int j = 1; j <= refinements; ++j)
  {
    fine.push_back(lo + (heights[k] - lo) * j / refinements);
  }
  const PlaneEnergies f = LinePlaneEnergies(line, variant, x, fine);
  for (std::size_t j = 0; j < fine.size(); ++j)
  {
    if (f.perpendicular[j] < f.parallel[j])
    {
      return fine[j];
    }
  }
  return heights[k];
}

// ---- Figure 8 -----------------------------------------------------------------------------------

std::vector<BandPath> NoisyBandPaths(const Scene& noisy)
{
  std::vector<BandPath> paths;
  const int count = static_cast<int>(std::lround((kBandLastU - kBandFirstU) / kBandStepU)) + 1;
  for (int i = 0; i < count; ++i)
  {
    const double u = kBandFirstU + i * kBandStepU;
    const pss::CurveFrame f = pss::noisyCurveFrame(noisy.shape, u);
    for (int side : { 1, -1 })
    {
      BandPath p;
      p.u = u;
      p.side = side;
      p.foot = f.point;
      p.normal = side * f.normal;
      p.sigma = f.sigma;
      paths.push_back(p);
    }
  }
  return paths;
}

BandMeasure MeasureNoisyBand(const Scene& noisy, int variant)
{
  const std::vector<BandPath> paths = NoisyBandPaths(noisy);
  const int perPath = static_cast<int>(std::lround(kBandPathLength / kBandPathStep)) + 1;
  std::vector<pss::Vec3> samples;
  for (const BandPath& p : paths)
  {
    for (int k = 0; k < perPath; ++k)
    {
      samples.push_back(p.foot + (k * kBandPathStep * noisy.h) * p.normal);
    }
  }
  vtkSmartPointer<vtkPolyData> probe = MakePointCloud(samples);
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  sampler->SetSurface(MakeSurface(noisy, variant));
  sampler->SetInputData(probe);
  sampler->SetSourceData(noisy.cloud);
  const auto t0 = std::chrono::steady_clock::now();
  sampler->Update();
  BandMeasure m;
  m.variant = variant;
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vtkDataSet* out = sampler->GetOutput();
  vtkDataArray* normal = out ? out->GetPointData()->GetArray("Normal") : nullptr;
  if (!normal || out->GetNumberOfPoints() != probe->GetNumberOfPoints())
  {
    throw std::runtime_error("the field sampler failed on the noisy band");
  }

  std::vector<double> atCurve;
  std::vector<double> turnSigma;
  std::vector<double> turnH;
  std::vector<double> variation;
  std::vector<double> maxima;
  int outer = 0;
  for (std::size_t i = 0; i < paths.size(); ++i)
  {
    PathProfile prof;
    prof.path = paths[i];
    const double band = kBandSigmas * paths[i].sigma / noisy.h; // in h
    pss::Vec3 previous = pss::Vec3::Zero();
    for (int k = 0; k < perPath; ++k)
    {
      double n[3];
      normal->GetTuple(static_cast<vtkIdType>(i * perPath + k), n);
      const pss::Vec3 nv(n[0], n[1], n[2]);
      const bool defined = nv.squaredNorm() > 0.0;
      const double d = k * kBandPathStep;
      const double angle = defined ? UnorientedAngle(nv, paths[i].normal) : 90.0;
      prof.distance.push_back(d);
      prof.angle.push_back(angle);
      if (angle > kTurnAngle && std::isinf(prof.turn))
      {
        prof.turn = d;
      }
      if (d <= band + 1e-12)
      {
        prof.maxAngleInBand = std::max(prof.maxAngleInBand, angle);
        if (k > 0)
        {
          // Between consecutive samples; an undefined n counts as a turn of 90 degrees.
          prof.variationInBand += defined && previous.squaredNorm() > 0.0 ? UnorientedAngle(nv, previous) : 90.0;
        }
      }
      previous = nv;
    }
    atCurve.push_back(prof.angle.front());
    turnH.push_back(prof.turn);
    turnSigma.push_back(prof.turn * noisy.h / paths[i].sigma);
    variation.push_back(prof.variationInBand);
    const double turnSigmas = prof.turn * noisy.h / paths[i].sigma;
    outer += turnSigmas >= 1.0 && turnSigmas <= kBandSigmas ? 1 : 0;
    m.maxAngleInBand = std::max(m.maxAngleInBand, prof.maxAngleInBand);
    maxima.push_back(prof.maxAngleInBand);
    m.pathsPastTurnInBand += prof.maxAngleInBand > kTurnAngle ? 1 : 0;
    m.paths.push_back(std::move(prof));
  }
  m.medianAngleAtCurve = Median(atCurve);
  m.medianTurnOverSigma = Median(turnSigma);
  m.medianTurnOverH = Median(turnH);
  m.medianVariationInBand = Median(variation);
  m.medianMaxAngleInBand = Median(maxima);
  m.turnInOuterPartFraction = paths.empty() ? 0.0 : double(outer) / double(paths.size());
  return m;
}

// ---- Mesh polylines on the 2D scenes ------------------------------------------------------------

vtkSmartPointer<vtkPolyData> MeshScene(const Scene& scene, int variant)
{
  vtkNew<vtkPointSetSurfaceMesher> mesher;
  mesher->SetSurface(MakeSurface(scene, variant));
  // Levin's and the normalized MLS have a narrow domain (h / sqrt 2 about the curve): every corner
  // of a cell crossing the curve must lie in it.
  const bool narrow = variant == vtkPointSetSurface::LEVIN_MLS || variant == vtkPointSetSurface::NORMALIZED_MLS;
  mesher->SetCellSize(narrow ? 0.25 : 0.5);
  mesher->SetInputData(scene.cloud);
  mesher->Update();
  // A copy detached from the filter, which goes out of scope here.
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(mesher->GetOutput());
  return mesh;
}

MeshAgreement MeasureMeshAgreement(vtkPolyData* mesh, vtkPolyData* ends, double h)
{
  vtkDataArray* outcome = ends->GetPointData()->GetArray("Outcome");
  if (!outcome)
  {
    throw std::runtime_error("the projection end points have no Outcome array");
  }
  MeshAgreement m;
  const std::vector<Segment> segments = Segments(mesh, m.pieces);
  m.segments = static_cast<vtkIdType>(segments.size());
  const double near = kOnCurveDistance * h;
  std::vector<char> pieceSeen(static_cast<std::size_t>(mesh->GetNumberOfPoints()), 0);
  double worst = 0.0;
  for (vtkIdType i = 0; i < ends->GetNumberOfPoints(); ++i)
  {
    const int o = static_cast<int>(outcome->GetComponent(i, 0));
    if (o == NOT_CONVERGED)
    {
      continue;
    }
    double p[3];
    ends->GetPoint(i, p);
    double best = std::numeric_limits<double>::infinity();
    const Segment* nearest = nullptr;
    for (const Segment& s : segments)
    {
      const double d = DistanceToSegment(p, s);
      if (d < best)
      {
        best = d;
        nearest = &s;
      }
    }
    if (best <= near)
    {
      pieceSeen[static_cast<std::size_t>(nearest->piece)] = 1;
    }
    if (o == ON_CURVE)
    {
      ++m.onCurve;
      m.onCurveFar += best > near ? 1 : 0;
      worst = std::max(worst, best);
    }
  }
  m.farthestOnCurve = worst / h;
  for (const Segment& s : segments)
  {
    char& seen = pieceSeen[static_cast<std::size_t>(s.piece)];
    if (!seen)
    {
      if (m.piecesWithoutEnds == 0)
      {
        m.pieceWithoutEnds = pss::Vec3(s.a[0], s.a[1], 0.0);
      }
      ++m.piecesWithoutEnds;
      seen = 1; // count each piece once
    }
  }
  return m;
}

std::string Describe(const MeshAgreement& a)
{
  std::ostringstream s;
  s << a.segments << " segments in " << a.pieces << " pieces; " << a.onCurve << " end points on the curve, "
    << a.onCurveFar << " of them farther than " << kOnCurveDistance << " h from a polyline (farthest "
    << a.farthestOnCurve << " h); " << a.piecesWithoutEnds << " pieces without an end point within "
    << kOnCurveDistance << " h";
  return s.str();
}

} // namespace pss_paper

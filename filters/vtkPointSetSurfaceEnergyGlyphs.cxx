// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceEnergyGlyphs.h"

#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesDistributedRun.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "pss/ExtremalSurface.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkPointSetSurfaceEnergyGlyphs);

namespace
{


// The unit directions a of one glyph and, in 3D, the triangles joining them.
struct DirectionSet
{
  std::vector<pss::Vec3> directions;
  std::vector<std::array<vtkIdType, 3>> triangles;
};

// 2D: resolution directions evenly spaced on the full circle of the xy-plane.
DirectionSet CircleDirections(int resolution)
{
  DirectionSet set;
  for (int k = 0; k < resolution; ++k)
  {
    const double phi = 2.0 * vtkMath::Pi() * k / resolution;
    set.directions.emplace_back(std::cos(phi), std::sin(phi), 0.0);
  }
  return set;
}

// 3D: a latitude-longitude sphere with poles, `resolution` longitudes and max(2, resolution / 2)
// latitude bands; triangles counter-clockwise seen from outside. With an even resolution the
// antipode of every direction is in the set (band i <-> bands - i, longitude j <-> j + res/2).
DirectionSet SphereDirections(int resolution)
{
  DirectionSet set;
  const int bands = std::max(2, resolution / 2);
  set.directions.emplace_back(0.0, 0.0, 1.0);
  for (int i = 1; i < bands; ++i)
  {
    const double theta = vtkMath::Pi() * i / bands;
    for (int j = 0; j < resolution; ++j)
    {
      const double phi = 2.0 * vtkMath::Pi() * j / resolution;
      set.directions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  }
  set.directions.emplace_back(0.0, 0.0, -1.0);
  const vtkIdType south = static_cast<vtkIdType>(set.directions.size()) - 1;
  auto ring = [resolution](int i, int j) -> vtkIdType { return 1 + (i - 1) * resolution + (j % resolution); };
  for (int j = 0; j < resolution; ++j)
  {
    set.triangles.push_back({ 0, ring(1, j), ring(1, j + 1) });
    for (int i = 1; i + 1 < bands; ++i)
    {
      set.triangles.push_back({ ring(i, j), ring(i + 1, j), ring(i + 1, j + 1) });
      set.triangles.push_back({ ring(i, j), ring(i + 1, j + 1), ring(i, j + 1) });
    }
    set.triangles.push_back({ ring(bands - 1, j), south, ring(bands - 1, j + 1) });
  }
  return set;
}

} // namespace

vtkPointSetSurfaceEnergyGlyphs::vtkPointSetSurfaceEnergyGlyphs()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkPointSetSurfaceEnergyGlyphs::~vtkPointSetSurfaceEnergyGlyphs() = default;

void vtkPointSetSurfaceEnergyGlyphs::SetSamplePointsConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkPointSetSurfaceEnergyGlyphs::SetSamplePointsData(vtkDataObject* data)
{
  this->SetInputData(1, data);
}

int vtkPointSetSurfaceEnergyGlyphs::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* cloud = vtkPointSet::GetData(inputVector[0], 0);
  vtkPointSet* samples =
    inputVector[1]->GetNumberOfInformationObjects() > 0 ? vtkPointSet::GetData(inputVector[1], 0) : cloud;
  vtkPolyData* glyphs = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* fits = vtkPolyData::GetData(outputVector, 1);
  this->GlyphScale = 0.0;
  this->GhostRounds = 0;
  // In a distributed run each rank plots its own samples (its piece of the sample points, or of
  // the cloud) on the gathered cloud, or with ghost points; sample ids and the global scale are
  // those of one process.
  pss_vtk::DistributedRun run(this, this->Surface, this->DistributedController(), this->GhostMargin);
  if (!this->PrepareRun(run, inputVector, cloud))
  {
    return 0;
  }
  const bool ghosts = run.HasGhosts();
  const vtkIdType sampleCount = samples ? samples->GetNumberOfPoints() : 0;
  const vtkIdType firstSampleId = run.FirstGlobalId(sampleCount);
  const bool perGlyph = this->ScaleMode == SCALE_PER_GLYPH;
  // Collective in a distributed SCALE_GLOBAL run, so every rank calls it once, samples or not.
  auto largestOfAllRanks = [&](double largest) { return perGlyph ? largest : run.MaximumOverRanks(largest); };
  if (sampleCount == 0 && !ghosts)
  {
    largestOfAllRanks(0.0);
    return 1; // nothing to plot: empty outputs
  }

  const int dimension = run.GetDimension();
  const DirectionSet set = dimension == 2 ? CircleDirections(this->Resolution) : SphereDirections(this->Resolution);
  const std::vector<pss::Vec3>& dirs = set.directions;
  const std::size_t nDirs = dirs.size();

  // Samples with finite coordinates (in 2D brought to z = 0, as every core query is).
  std::vector<pss::Vec3> xs;
  std::vector<vtkIdType> sampleIds;
  const std::vector<pss::Vec3> all = pss_vtk::ToVectors(samples ? samples->GetPoints() : nullptr);
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    if (pss::isFinite(all[i]))
    {
      xs.push_back(pss::PointIndex::restrictTo(dimension, all[i]));
      sampleIds.push_back(firstSampleId + static_cast<vtkIdType>(i));
    }
  }
  vtkIdType dropped = static_cast<vtkIdType>(all.size() - xs.size());
  const std::size_t m = xs.size();

  // n(x) per sample, then e(x, a) per sample and direction. In SCALE_PER_GLYPH the energy is kept
  // as the core's mantissa and log-scale, so a glyph whose true energies underflow keeps its shape.
  std::vector<pss::Direction> normals(m);
  std::vector<double> value(m * nDirs, 0.0);
  std::vector<double> logScale(perGlyph ? m * nDirs : 0, 0.0);
  auto energyAt = [&](const pss::SurfaceDefinition& surface, std::size_t k, pss::Workspace& ws) {
    const std::size_t s = k / nDirs;
    const std::size_t d = k % nDirs;
    if (perGlyph)
    {
      const pss::LineSample ls = surface.lineSample(xs[s], dirs[d], ws);
      value[k] = ls.value;
      logScale[k] = ls.logScale;
    }
    else
    {
      value[k] = surface.energy(xs[s], dirs[d], ws);
    }
  };
  // A glyph at a time, so that with ghost points each sample knows whether any of its reads left
  // the region; in one process (or on the gathered cloud) the normals, then every energy.
  bool completed = true;
  auto plot = [&](const std::vector<std::uint32_t>& ks, std::vector<unsigned char>& escaped) {
    const pss::SurfaceDefinition& surface = *this->Surface->GetDefinition();
    if (!ghosts)
    {
      completed = pss_vtk::ParallelFor(
                    this, static_cast<vtkIdType>(m),
                    [&](vtkIdType s, pss::Workspace& ws) { normals[s] = surface.direction(xs[s], ws); }, 0.0, 0.1) &&
        pss_vtk::ParallelFor(this, static_cast<vtkIdType>(m * nDirs),
          [&](vtkIdType k, pss::Workspace& ws) { energyAt(surface, static_cast<std::size_t>(k), ws); }, 0.1, 0.9);
      return true;
    }
    completed = pss::forEachInOrder(ks, pss_vtk::SMPLoop(this), [&](std::size_t s, pss::Workspace& ws) {
      ws.leftCompleteRegion = false;
      normals[s] = surface.direction(xs[s], ws);
      for (std::size_t d = 0; d < nDirs; ++d)
      {
        energyAt(surface, s * nDirs + d, ws);
      }
      escaped[s] = ws.leftCompleteRegion ? 1 : 0;
    }) && completed;
    return true;
  };
  const auto sampleAt = [&xs](std::uint32_t k, double x[3]) { std::copy(xs[k].data(), xs[k].data() + 3, x); };
  if (!run.EvaluateAll(m, sampleAt, plot))
  {
    return 0;
  }
  this->GhostRounds = run.GetRounds();
  if (!completed)
  {
    largestOfAllRanks(0.0);
    return 1; // aborted: leave the outputs empty
  }
  // (With ghost points a rank without samples may have no surface of its own.)
  const double h = run.GetScale();

  // Radius of every glyph point: c e(x, a) (global) or the per-glyph normalization.
  std::vector<double> radius(m * nDirs, 0.0);
  std::vector<double> trueEnergy(m * nDirs, 0.0);
  std::vector<char> good(m, 1);
  double largest = 0.0;
  for (std::size_t s = 0; s < m; ++s)
  {
    double maxLog = -std::numeric_limits<double>::infinity();
    for (std::size_t d = 0; d < nDirs; ++d)
    {
      const std::size_t k = s * nDirs + d;
      const double l = perGlyph ? logScale[k] : 0.0;
      if (!std::isfinite(value[k]) || !std::isfinite(l))
      {
        good[s] = 0;
      }
      maxLog = std::max(maxLog, l);
    }
    if (!good[s])
    {
      continue;
    }
    double glyphMax = 0.0;
    for (std::size_t d = 0; d < nDirs; ++d)
    {
      const std::size_t k = s * nDirs + d;
      if (perGlyph)
      {
        trueEnergy[k] = value[k] * std::exp(logScale[k]);
        radius[k] = value[k] * std::exp(logScale[k] - maxLog); // relative within the glyph
      }
      else
      {
        trueEnergy[k] = value[k];
        radius[k] = value[k];
      }
      glyphMax = std::max(glyphMax, radius[k]);
    }
    largest = std::max(largest, glyphMax);
    if (perGlyph)
    {
      const double c = glyphMax > 0.0 ? this->GlyphSize * h / glyphMax : 0.0;
      for (std::size_t d = 0; d < nDirs; ++d)
      {
        radius[s * nDirs + d] *= c;
      }
    }
  }
  largest = largestOfAllRanks(largest);
  if (!perGlyph)
  {
    this->GlyphScale = largest > 0.0 && std::isfinite(largest) ? this->GlyphSize * h / largest : 0.0;
    for (double& r : radius)
    {
      r *= this->GlyphScale;
    }
    if (largest == 0.0 && m > 0)
    {
      vtkWarningMacro(<< "every energy is 0 (Levin's energy underflows far from the cloud): the glyphs "
                      << "collapse onto their sample points; try ScaleMode SCALE_PER_GLYPH");
    }
  }
  const vtkIdType badEnergy = static_cast<vtkIdType>(std::count(good.begin(), good.end(), 0));
  dropped += badEnergy;
  if (dropped > 0)
  {
    vtkWarningMacro(<< dropped << " sample point(s) have NaN or infinite coordinates"
                    << (badEnergy > 0 ? " or energies" : "") << ": no glyph or best-fit segment for them");
  }

  // Output 0: the glyphs.
  vtkNew<vtkPoints> glyphPoints;
  glyphPoints->SetDataTypeToDouble();
  vtkNew<vtkCellArray> glyphCells;
  auto energy = pss_vtk::NewArray<vtkDoubleArray>("Energy", 0, 1);
  auto glyphStability = pss_vtk::NewArray<vtkDoubleArray>("Stability", 0, 1);
  auto glyphSample = pss_vtk::NewArray<vtkIdTypeArray>("SampleId", 0, 1);
  // Output 1: the best-fit segments / patches.
  vtkNew<vtkPoints> fitPoints;
  fitPoints->SetDataTypeToDouble();
  vtkNew<vtkCellArray> fitCells;
  auto fitNormal = pss_vtk::NewArray<vtkDoubleArray>("Normal", 0, 3);
  auto fitStability = pss_vtk::NewArray<vtkDoubleArray>("Stability", 0, 1);
  auto fitSample = pss_vtk::NewArray<vtkIdTypeArray>("SampleId", 0, 1);
  const pss::Orientation orientation = pss_vtk::OrientationFor(this->OrientationViewpoint(), run.GetCentroid());
  const double half = this->SegmentLength * h;
  std::vector<vtkIdType> ids;
  for (std::size_t s = 0; s < m; ++s)
  {
    if (!good[s])
    {
      continue;
    }
    const pss::Vec3& x = xs[s];
    const pss::Direction& dir = normals[s];
    const vtkIdType base = glyphPoints->GetNumberOfPoints();
    for (std::size_t d = 0; d < nDirs; ++d)
    {
      const std::size_t k = s * nDirs + d;
      const pss::Vec3 p = x + radius[k] * dirs[d];
      glyphPoints->InsertNextPoint(p.data());
      energy->InsertNextValue(trueEnergy[k]);
    }
    if (set.triangles.empty())
    {
      ids.resize(nDirs + 1);
      for (std::size_t d = 0; d < nDirs; ++d)
      {
        ids[d] = base + static_cast<vtkIdType>(d);
      }
      ids[nDirs] = base;
      glyphCells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
      glyphStability->InsertNextValue(dir.stability);
      glyphSample->InsertNextValue(sampleIds[s]);
    }
    else
    {
      for (const auto& t : set.triangles)
      {
        const vtkIdType tri[3] = { base + t[0], base + t[1], base + t[2] };
        glyphCells->InsertNextCell(3, tri);
        glyphStability->InsertNextValue(dir.stability);
        glyphSample->InsertNextValue(sampleIds[s]);
      }
    }

    if (!dir.n.allFinite() || dir.n.squaredNorm() == 0.0)
    {
      continue;
    }
    pss::Vec3 n = orientation.apply(dir.n.normalized(), x);
    if (dimension == 2)
    {
      const pss::Vec3 t(-n.y(), n.x(), 0.0);
      const pss::Vec3 a = x - half * t;
      const pss::Vec3 b = x + half * t;
      const vtkIdType seg[2] = { fitPoints->InsertNextPoint(a.data()), fitPoints->InsertNextPoint(b.data()) };
      fitCells->InsertNextCell(2, seg);
    }
    else
    {
      pss::Vec3 u;
      pss::Vec3 v;
      vtkMath::Perpendiculars(n.data(), u.data(), v.data(), 0.0);
      const pss::Vec3 corners[4] = { x - half * u - half * v, x + half * u - half * v, x + half * u + half * v,
        x - half * u + half * v };
      vtkIdType quad[4];
      for (int c = 0; c < 4; ++c)
      {
        quad[c] = fitPoints->InsertNextPoint(corners[c].data());
      }
      fitCells->InsertNextCell(4, quad);
    }
    fitNormal->InsertNextTuple(n.data());
    fitStability->InsertNextValue(dir.stability);
    fitSample->InsertNextValue(sampleIds[s]);
  }

  glyphs->SetPoints(glyphPoints);
  if (set.triangles.empty())
  {
    glyphs->SetLines(glyphCells);
  }
  else
  {
    glyphs->SetPolys(glyphCells);
  }
  glyphs->GetPointData()->SetScalars(energy);
  glyphs->GetCellData()->AddArray(glyphStability);
  glyphs->GetCellData()->AddArray(glyphSample);

  fits->SetPoints(fitPoints);
  if (dimension == 2)
  {
    fits->SetLines(fitCells);
  }
  else
  {
    fits->SetPolys(fitCells);
  }
  fits->GetCellData()->AddArray(fitNormal);
  fits->GetCellData()->AddArray(fitStability);
  fits->GetCellData()->AddArray(fitSample);
  run.AttachGhostFieldData(glyphs);
  run.AttachGhostFieldData(fits);
  return 1;
}

void vtkPointSetSurfaceEnergyGlyphs::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "GlyphSize: " << this->GlyphSize << " (h)\n";
  os << indent << "ScaleMode: " << (this->ScaleMode == SCALE_PER_GLYPH ? "PerGlyph" : "Global") << "\n";
  os << indent << "SegmentLength: " << this->SegmentLength << " (h)\n";
  os << indent << "GlyphScale: " << this->GlyphScale << "\n";
  os << indent << "GhostMargin: " << this->GhostMargin << "\n";
}

// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurface.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesVTKUtilities.h"

#include "pss/NormalOrientation.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <utility>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkPointSetSurface);

namespace
{
/// How many times estimated point scales are median-smoothed over their neighbours.
constexpr int ScaleSmoothing = 2;
}

vtkPointSetSurface::vtkPointSetSurface()
{
  this->SetScaleArrayName("Scale");
  this->SetNormalsArrayName("Normals");
}

vtkPointSetSurface::~vtkPointSetSurface()
{
  this->SetScaleArrayName(nullptr);
  this->SetNormalsArrayName(nullptr);
}

const char* vtkPointSetSurface::UseThreadedBackend()
{
  const char* chosen = std::getenv("VTK_SMP_BACKEND_IN_USE");
  if ((chosen == nullptr || *chosen == '\0') && std::strcmp(vtkSMPTools::GetBackend(), "Sequential") == 0)
  {
    vtkSMPTools::SetBackend("STDThread");
  }
  return vtkSMPTools::GetBackend();
}

bool vtkPointSetSurface::Fail(const std::string& message)
{
  this->LastError = message;
  this->Definition.reset();
  this->Index.reset();
  this->PreparedCloud = nullptr;
  return false;
}

bool vtkPointSetSurface::Prepare(vtkPointSet* cloud)
{
  return this->Prepare(cloud, false);
}

bool vtkPointSetSurface::Prepare(vtkPointSet* cloud, bool coordinateOrder)
{
  vtkMTimeType cloudTime = 0;
  if (cloud)
  {
    cloudTime = cloud->GetMTime();
    if (cloud->GetPoints())
    {
      cloudTime = std::max(cloudTime, cloud->GetPoints()->GetMTime());
    }
  }
  const vtkMTimeType stamp = std::max(cloudTime, this->GetMTime());
  if (this->Definition && cloud == this->PreparedCloud && stamp <= this->PreparedTime &&
    coordinateOrder == this->PreparedCoordinateOrder)
  {
    return true;
  }

  const vtkIdType n = cloud ? cloud->GetNumberOfPoints() : 0;
  if (n == 0)
  {
    return this->Fail("the point cloud is empty");
  }
  if (this->Dimension == 1)
  {
    return this->Fail("Dimension must be Auto (0), 2 or 3, not 1");
  }
  // The index is built, and h estimated, on the threads the application gave vtkSMPTools (the
  // result is the same for every count).
  const int threads = pss_vtk::CoreThreads();
  std::vector<double> arrayScales;
  if (this->AutomaticScale && this->PointScales == POINT_SCALES_FROM_ARRAY)
  {
    const char* name = this->ScaleArrayName ? this->ScaleArrayName : "";
    vtkDataArray* scales = cloud->GetPointData()->GetArray(name);
    if (!scales || scales->GetNumberOfComponents() != 1)
    {
      return this->Fail(std::string("PointScales is FromArray but the cloud has no one-component point array named \"") +
        name + "\"");
    }
    arrayScales.resize(static_cast<std::size_t>(scales->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < scales->GetNumberOfTuples(); ++i)
    {
      arrayScales[static_cast<std::size_t>(i)] = scales->GetComponent(i, 0);
    }
  }
  this->SensorFrame = pss_vtk::IsSensorFrame(cloud);
  std::vector<pss::Vec3> points = pss_vtk::ToVectors(cloud->GetPoints(), threads);
  const int dimension =
    this->Dimension == DIMENSION_AUTO ? pss::detectDimension(points, threads) : this->Dimension;
  std::unique_ptr<pss::PointIndex> index;
  try
  {
    index = std::make_unique<pss::PointIndex>(std::move(points), dimension, threads);
    index->setCoordinateOrder(coordinateOrder);
  }
  catch (const std::exception& e)
  {
    return this->Fail(std::string("invalid surface parameters: ") + e.what());
  }
  if (!this->Build(std::move(index), this->AutomaticScale ? 0.0 : this->ScaleFactor, arrayScales, cloud))
  {
    return false;
  }
  this->LastError.clear();
  this->PreparedCloud = cloud;
  this->PreparedTime = stamp;
  this->PreparedCoordinateOrder = coordinateOrder;
  return true;
}

bool vtkPointSetSurface::PreparePiece(
  const std::vector<double>& points, int dimension, const double lo[3], const double hi[3], double h)
{
  this->PreparedCloud = nullptr;
  this->SensorFrame = false;
  // The parameters first, so that every rank fails alike whatever its piece holds.
  if (!this->CheckParameters(dimension, h))
  {
    return this->Fail(this->LastError);
  }
  if (this->AutomaticScale && (this->PointScales == POINT_SCALES_ESTIMATED || this->PointScales == POINT_SCALES_FROM_ARRAY))
  {
    // The ghost margins would have to follow the largest scale a rank holds: not there yet.
    return this->Fail("a scale per point (PointScales Estimated or FromArray) is not supported in a distributed run "
                      "yet; use PointScales Off or Automatic (one h over the ranks) or a single process");
  }
  if (pss::needsNormals(static_cast<pss::Variant>(this->Variant)))
  {
    // The normals would have to travel with the ghost points: not there yet.
    return this->Fail("APSS and RIMLS are not supported in a distributed run yet (the cloud's normals do not travel "
                      "with the ghost points); run them in a single process");
  }
  std::unique_ptr<pss::PointIndex> index;
  try
  {
    if (points.empty())
    {
      // Nothing to define: the caller waits for ghost points.
      this->Definition.reset();
      this->Index.reset();
      this->LastError.clear();
      return true;
    }
    std::vector<pss::Vec3> vectors(points.size() / 3);
    for (std::size_t i = 0; i < vectors.size(); ++i)
    {
      vectors[i] = pss::Vec3(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
    }
    index = std::make_unique<pss::PointIndex>(std::move(vectors), dimension, pss_vtk::CoreThreads());
    index->setCompleteRegion(pss::Vec3(lo[0], lo[1], lo[2]), pss::Vec3(hi[0], hi[1], hi[2]));
    // Which points a rank holds must not change a bit of its sums.
    index->setCoordinateOrder(true);
  }
  catch (const std::exception& e)
  {
    return this->Fail(std::string("invalid surface parameters: ") + e.what());
  }
  if (!this->Build(std::move(index), h))
  {
    return false;
  }
  this->LastError.clear();
  return true;
}

bool vtkPointSetSurface::CheckParameters(int dimension, double h)
{
  if (dimension != 2 && dimension != 3)
  {
    this->LastError = "Dimension must be Auto (0), 2 or 3, not " + std::to_string(dimension);
    return false;
  }
  try
  {
    this->Parameters(h).validate();
  }
  catch (const std::exception& e)
  {
    this->LastError = std::string("invalid surface parameters: ") + e.what();
    return false;
  }
  return true;
}

pss::SurfaceParameters vtkPointSetSurface::Parameters(double h) const
{
  pss::SurfaceParameters params;
  params.h = h;
  params.cutoff = this->KernelCutoff;
  params.quadratureOrder = this->QuadratureOrder;
  params.deltaLattice = this->DeltaLatticeSpacing;
  params.minStability = this->MinimumStability;
  params.sphericity = this->Sphericity;
  params.sigmaNormal = this->SigmaNormal;
  params.sigmaResidual = this->SigmaResidual;
  params.robustRefits = this->RobustRefits;
  return params;
}

std::vector<double> vtkPointSetSurface::EstimatePointScales(const pss::PointIndex& index, int threads) const
{
  return pss::estimateLocalScales(
    index, this->ScaleNeighbors, this->ScaleMultiplier * this->PointScaleMultiplier, ScaleSmoothing, threads);
}

double vtkPointSetSurface::EstimateScaleSpread(const pss::PointIndex& index, int threads) const
{
  return pss::estimateScaleSpread(index, this->ScaleNeighbors, ScaleSmoothing, threads);
}

bool vtkPointSetSurface::AutomaticTakesPointScales(bool sensorFrame, double spread) const
{
  return sensorFrame || spread > this->ScaleSpreadThreshold;
}

double vtkPointSetSurface::ChooseScales(pss::PointIndex& index, const std::vector<double>& arrayScales)
{
  const int threads = pss_vtk::CoreThreads();
  std::vector<double> scales;
  this->ScaleSpread = 0.0;
  if (this->PointScales == POINT_SCALES_FROM_ARRAY)
  {
    scales = arrayScales;
    this->ScaleSpread = scales.empty() ? 0.0 : pss::scaleSpread(scales);
  }
  else if (this->PointScales != POINT_SCALES_OFF && index.size() > static_cast<std::size_t>(this->ScaleNeighbors))
  {
    // A large cloud in the automatic mode is judged on a sample first, so that an even one never
    // pays for every point's scale (at 10^7 points, 10 of the index stage's 13 s).
    const bool sampleFirst = this->PointScales == POINT_SCALES_AUTOMATIC && !this->SensorFrame &&
      index.size() > pss::ScaleSpreadSampledAbove;
    if (sampleFirst)
    {
      this->ScaleSpread = this->EstimateScaleSpread(index, threads);
    }
    if (!sampleFirst || this->AutomaticTakesPointScales(this->SensorFrame, this->ScaleSpread))
    {
      scales = this->EstimatePointScales(index, threads);
      this->ScaleSpread = pss::scaleSpread(scales);
    }
  }
  if (this->PointScales == POINT_SCALES_AUTOMATIC && !this->AutomaticTakesPointScales(this->SensorFrame, this->ScaleSpread))
  {
    scales.clear(); // even density: one h, exactly as with POINT_SCALES_OFF
  }
  if (scales.empty())
  {
    return pss::estimateScale(index, this->ScaleNeighbors, this->ScaleMultiplier, threads);
  }
  index.setScales(scales); // throws, naming the point, for a bad value
  this->UsesPointScales = true;
  std::vector<double> own(index.size());
  for (std::size_t i = 0; i < own.size(); ++i)
  {
    own[i] = index.scale(i);
  }
  std::nth_element(own.begin(), own.begin() + static_cast<std::ptrdiff_t>(own.size() / 2), own.end());
  return own[own.size() / 2];
}

bool vtkPointSetSurface::SetCloudNormals(pss::PointIndex& index, const pss::SurfaceParameters& params, vtkPointSet* cloud)
{
  const char* name = this->NormalsArrayName ? this->NormalsArrayName : "";
  vtkDataArray* given = cloud && *name ? cloud->GetPointData()->GetArray(name) : nullptr;
  std::vector<pss::Vec3> normals;
  std::optional<pss::Vec3> viewpoint;
  if (pss::Vec3 v; pss_vtk::CloudViewpoint(cloud, v.data()))
  {
    viewpoint = v;
  }
  if (given)
  {
    if (given->GetNumberOfComponents() != 3 || given->GetNumberOfTuples() != cloud->GetNumberOfPoints())
    {
      return this->Fail(std::string("the normals array \"") + name + "\" must have 3 components and one tuple per point");
    }
    normals.resize(static_cast<std::size_t>(given->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < given->GetNumberOfTuples(); ++i)
    {
      given->GetTuple(i, normals[static_cast<std::size_t>(i)].data());
    }
    this->NormalsSource = "array";
    if (this->ReorientNormals)
    {
      // setNormals checks them first (zero, NaN), then their signs are chosen again.
      index.setNormals(normals);
      std::vector<pss::Vec3> indexed(index.size());
      for (std::size_t i = 0; i < index.size(); ++i)
      {
        indexed[i] = index.normal(i);
      }
      pss::orientNormals(
        index, indexed, viewpoint, static_cast<std::size_t>(this->NormalNeighbors), pss_vtk::CoreThreads());
      for (std::size_t i = 0; i < index.size(); ++i)
      {
        normals[index.originalId(i)] = indexed[i];
      }
      this->NormalsSource = "reoriented";
    }
  }
  else
  {
    std::size_t borrowed = 0;
    normals = pss::estimateOrientedNormals(
      index, params, viewpoint, static_cast<std::size_t>(this->NormalNeighbors), pss_vtk::CoreThreads(), &borrowed);
    this->BorrowedNormals = static_cast<vtkIdType>(borrowed);
    this->NormalsSource = "estimated";
  }
  index.setNormals(normals); // throws, naming the point, for a zero or NaN normal
  return true;
}

bool vtkPointSetSurface::Build(
  std::unique_ptr<pss::PointIndex> index, double h, const std::vector<double>& arrayScales, vtkPointSet* cloud)
{
  this->SkippedPoints = static_cast<vtkIdType>(index->skippedCount());
  this->UsesPointScales = false;
  this->ScaleSpread = 0.0;
  this->NormalsSource.clear();
  this->BorrowedNormals = 0;
  if (index->empty())
  {
    return this->Fail("the point cloud has no point with finite coordinates");
  }
  try
  {
    pss::SurfaceParameters params = this->Parameters(h);
    if (this->AutomaticScale && !(h > 0.0))
    {
      params.h = this->PointScales == POINT_SCALES_OFF
        ? pss::estimateScale(*index, this->ScaleNeighbors, this->ScaleMultiplier, pss_vtk::CoreThreads())
        : this->ChooseScales(*index, arrayScales);
      if (!(params.h > 0.0))
      {
        std::ostringstream msg;
        msg << "the automatic scale is 0: the " << index->size() << " finite points have fewer than "
            << this->ScaleNeighbors + 1 << " distinct positions around most points (duplicates?); "
            << "set ScaleFactor and turn AutomaticScale off";
        return this->Fail(msg.str());
      }
    }
    if (pss::needsNormals(static_cast<pss::Variant>(this->Variant)) && !this->SetCloudNormals(*index, params, cloud))
    {
      return false;
    }
    this->Definition = pss::makeSurface(static_cast<pss::Variant>(this->Variant), *index, params);
    this->EffectiveScale = params.h;
    this->EffectiveDimension = index->dimension();
    this->Index = std::move(index);
  }
  catch (const std::exception& e)
  {
    return this->Fail(std::string("invalid surface parameters: ") + e.what());
  }
  return true;
}

void vtkPointSetSurface::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Variant: " << this->Variant << "\n";
  os << indent << "ScaleFactor: " << this->ScaleFactor << "\n";
  os << indent << "AutomaticScale: " << (this->AutomaticScale ? "On" : "Off") << "\n";
  os << indent << "ScaleNeighbors: " << this->ScaleNeighbors << "\n";
  os << indent << "ScaleMultiplier: " << this->ScaleMultiplier << "\n";
  os << indent << "PointScaleMultiplier: " << this->PointScaleMultiplier << "\n";
  os << indent << "PointScales: " << this->PointScales << "\n";
  os << indent << "ScaleSpreadThreshold: " << this->ScaleSpreadThreshold << "\n";
  os << indent << "ScaleArrayName: " << (this->ScaleArrayName ? this->ScaleArrayName : "(none)") << "\n";
  os << indent << "UsesPointScales: " << (this->UsesPointScales ? "On" : "Off") << "\n";
  os << indent << "ScaleSpread: " << this->ScaleSpread << "\n";
  os << indent << "SensorFrame: " << (this->SensorFrame ? "On" : "Off") << "\n";
  os << indent << "Dimension: " << this->Dimension << "\n";
  os << indent << "KernelCutoff: " << this->KernelCutoff << "\n";
  os << indent << "QuadratureOrder: " << this->QuadratureOrder << "\n";
  os << indent << "DeltaLatticeSpacing: " << this->DeltaLatticeSpacing << "\n";
  os << indent << "MinimumStability: " << this->MinimumStability << "\n";
  os << indent << "NormalsArrayName: " << (this->NormalsArrayName ? this->NormalsArrayName : "(none)") << "\n";
  os << indent << "NormalNeighbors: " << this->NormalNeighbors << "\n";
  os << indent << "ReorientNormals: " << (this->ReorientNormals ? "On" : "Off") << "\n";
  os << indent << "Sphericity: " << this->Sphericity << "\n";
  os << indent << "SigmaNormal: " << this->SigmaNormal << "\n";
  os << indent << "SigmaResidual: " << this->SigmaResidual << "\n";
  os << indent << "RobustRefits: " << this->RobustRefits << "\n";
  os << indent << "NormalsSource: " << this->NormalsSource << "\n";
  os << indent << "BorrowedNormals: " << this->BorrowedNormals << "\n";
  os << indent << "EffectiveScale: " << this->EffectiveScale << "\n";
  os << indent << "EffectiveDimension: " << this->EffectiveDimension << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->SkippedPoints << "\n";
}

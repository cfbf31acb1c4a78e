// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceDomainClassifier.h"

#include "PointSetSurfacesVTKUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include "pss/Domain.h"
#include "pss/ExtremalSurface.h"

#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkPointSetSurfaceDomainClassifier);

// The per-point evidence of the current update (the projection itself goes to the superclass).
struct vtkPointSetSurfaceDomainClassifier::vtkInternals
{
  struct Evidence
  {
    pss::DomainLabel label = pss::DomainLabel::Undefined;
    double distanceToCloud = 0.0;
    double normalAngle = 0.0;
    double startAngle = 0.0;
    double startStability = 0.0;
  };
  pss::DomainThresholds Thresholds;
  std::unique_ptr<pss::CloudNormals> Normals; ///< of the current update's cloud
  std::vector<Evidence> Points;
};

vtkPointSetSurfaceDomainClassifier::vtkPointSetSurfaceDomainClassifier()
  : Internals(new vtkInternals)
{
}

vtkPointSetSurfaceDomainClassifier::~vtkPointSetSurfaceDomainClassifier() = default;

bool vtkPointSetSurfaceDomainClassifier::BeginProjection(const pss::SurfaceDefinition& surface, vtkIdType numberOfStarts)
{
  pss::DomainThresholds thresholds;
  thresholds.maxDistance = this->MaxDistance;
  thresholds.maxNormalAngle = this->MaxNormalAngle;
  try
  {
    thresholds.validate();
  }
  catch (const std::invalid_argument& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  this->Internals->Thresholds = thresholds;
  this->Internals->Normals = std::make_unique<pss::CloudNormals>(surface);
  this->Internals->Points.assign(static_cast<std::size_t>(numberOfStarts), vtkInternals::Evidence());
  return true;
}

pss::ProjectionResult vtkPointSetSurfaceDomainClassifier::ProjectPoint(vtkIdType i, const double start[3],
  const pss::SurfaceDefinition& surface, const pss::ProjectionOptions& options, pss::Workspace& ws)
{
  pss::DomainEvidence ev =
    pss::classifyStart(surface, pss::Vec3(start[0], start[1], start[2]), options, this->Internals->Thresholds, ws,
      this->Internals->Normals.get());
  vtkInternals::Evidence& out = this->Internals->Points[static_cast<std::size_t>(i)];
  out.label = ev.label;
  out.distanceToCloud = ev.distanceToCloud;
  out.normalAngle = ev.normalAngle;
  out.startAngle = ev.startAngle;
  out.startStability = ev.startStability;
  return std::move(ev.projection);
}

bool vtkPointSetSurfaceDomainClassifier::AddPointArrays(
  vtkPointSet*, const std::vector<pss::ProjectionResult>& results, vtkPointData* outPD)
{
  const std::vector<vtkInternals::Evidence>& evidence = this->Internals->Points;
  if (evidence.size() != results.size())
  {
    vtkErrorMacro(<< "internal error: " << evidence.size() << " labels for " << results.size() << " projections");
    return false;
  }
  const vtkIdType n = static_cast<vtkIdType>(evidence.size());
  auto label = pss_vtk::NewArray<vtkIntArray>("DomainLabel", n, 1);
  auto distance = pss_vtk::NewArray<vtkDoubleArray>("DistanceToCloud", n, 1);
  auto normalAngle = pss_vtk::NewArray<vtkDoubleArray>("NormalAngle", n, 1);
  auto startAngle = pss_vtk::NewArray<vtkDoubleArray>("StartAngle", n, 1);
  auto startStability = pss_vtk::NewArray<vtkDoubleArray>("StartStability", n, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtkInternals::Evidence& ev = evidence[static_cast<std::size_t>(i)];
    // Only InDomain and Spurious points have a fixed point to measure (see the class description).
    const bool fixedPoint = ev.label == pss::DomainLabel::InDomain || ev.label == pss::DomainLabel::Spurious;
    label->SetValue(i, static_cast<int>(ev.label));
    distance->SetValue(i, fixedPoint ? ev.distanceToCloud : nan);
    normalAngle->SetValue(i, fixedPoint ? ev.normalAngle : nan);
    startAngle->SetValue(i, fixedPoint ? ev.startAngle : nan);
    startStability->SetValue(i, ev.startStability);
  }
  outPD->AddArray(label);
  outPD->AddArray(distance);
  outPD->AddArray(normalAngle);
  outPD->AddArray(startAngle);
  outPD->AddArray(startStability);
  outPD->SetActiveScalars("DomainLabel");
  this->Internals->Points.clear();
  return true;
}

void vtkPointSetSurfaceDomainClassifier::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaxDistance: " << this->MaxDistance << " (h)\n";
  os << indent << "MaxNormalAngle: " << this->MaxNormalAngle << " (degrees)\n";
}

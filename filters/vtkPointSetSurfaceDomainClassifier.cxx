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

// The per-point evidence of the current update, filled in place by the projections (the
// projection itself goes to the superclass).
struct vtkPointSetSurfaceDomainClassifier::vtkInternals
{
  pss::DomainThresholds Thresholds;
  std::unique_ptr<pss::CloudNormals> Normals; ///< of the current update's cloud
  vtkSmartPointer<vtkIntArray> Label;
  vtkSmartPointer<vtkDoubleArray> Distance;
  vtkSmartPointer<vtkDoubleArray> NormalAngle;
  vtkSmartPointer<vtkDoubleArray> StartAngle;
  vtkSmartPointer<vtkDoubleArray> StartStability;
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
  const vtkIdType n = numberOfStarts;
  if (this->Internals->Label && this->Internals->Label->GetNumberOfTuples() == n)
  {
    return true; // a later round of a run with ghost points: the first round's values stay
  }
  this->Internals->Label = pss_vtk::NewArray<vtkIntArray>("DomainLabel", n, 1);
  this->Internals->Distance = pss_vtk::NewArray<vtkDoubleArray>("DistanceToCloud", n, 1);
  this->Internals->NormalAngle = pss_vtk::NewArray<vtkDoubleArray>("NormalAngle", n, 1);
  this->Internals->StartAngle = pss_vtk::NewArray<vtkDoubleArray>("StartAngle", n, 1);
  this->Internals->StartStability = pss_vtk::NewArray<vtkDoubleArray>("StartStability", n, 1);
  return true;
}

pss::ProjectionResult vtkPointSetSurfaceDomainClassifier::ProjectPoint(vtkIdType i, const double start[3],
  const pss::SurfaceDefinition& surface, const pss::ProjectionOptions& options, pss::Workspace& ws)
{
  pss::DomainEvidence ev =
    pss::classifyStart(surface, pss::Vec3(start[0], start[1], start[2]), options, this->Internals->Thresholds, ws,
      this->Internals->Normals.get());
  // Only InDomain and Spurious points have a fixed point to measure (see the class description).
  const bool fixedPoint = ev.label == pss::DomainLabel::InDomain || ev.label == pss::DomainLabel::Spurious;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkInternals& out = *this->Internals;
  out.Label->GetPointer(i)[0] = static_cast<int>(ev.label);
  out.Distance->GetPointer(i)[0] = fixedPoint ? ev.distanceToCloud : nan;
  out.NormalAngle->GetPointer(i)[0] = fixedPoint ? ev.normalAngle : nan;
  out.StartAngle->GetPointer(i)[0] = fixedPoint ? ev.startAngle : nan;
  out.StartStability->GetPointer(i)[0] = ev.startStability;
  return std::move(ev.projection);
}

bool vtkPointSetSurfaceDomainClassifier::AddPointArrays(vtkPointSet*, vtkPointData* outPD)
{
  vtkInternals& in = *this->Internals;
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(in.Label), static_cast<vtkDataArray*>(in.Distance),
         static_cast<vtkDataArray*>(in.NormalAngle), static_cast<vtkDataArray*>(in.StartAngle),
         static_cast<vtkDataArray*>(in.StartStability) })
  {
    outPD->AddArray(a);
  }
  outPD->SetActiveScalars("DomainLabel");
  // The output holds them now; the next update allocates its own.
  in.Label = nullptr;
  in.Distance = in.NormalAngle = in.StartAngle = in.StartStability = nullptr;
  return true;
}

void vtkPointSetSurfaceDomainClassifier::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaxDistance: " << this->MaxDistance << " (h)\n";
  os << indent << "MaxNormalAngle: " << this->MaxNormalAngle << " (degrees)\n";
}

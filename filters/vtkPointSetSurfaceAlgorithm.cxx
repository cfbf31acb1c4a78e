// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceAlgorithm.h"

#include "PointSetSurfacesDistributedRun.h"
#include "PointSetSurfacesErrorWatch.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkPointSet.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>

vtkCxxSetObjectMacro(vtkPointSetSurfaceAlgorithm, Surface, vtkPointSetSurface);

vtkPointSetSurfaceAlgorithm::vtkPointSetSurfaceAlgorithm()
  : UpstreamWatch(std::make_unique<pss_vtk::UpstreamErrorWatch>())
{
  this->Surface = vtkPointSetSurface::New();
}

vtkPointSetSurfaceAlgorithm::~vtkPointSetSurfaceAlgorithm()
{
  this->SetSurface(nullptr);
}

double vtkPointSetSurfaceAlgorithm::GetEffectiveScale() const
{
  return this->Surface ? this->Surface->GetEffectiveScale() : 0.0;
}

vtkMTimeType vtkPointSetSurfaceAlgorithm::GetMTime()
{
  return pss_vtk::LatestMTime(this->Superclass::GetMTime(), this->Surface);
}

int vtkPointSetSurfaceAlgorithm::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  if (port > 0)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkPointSetSurfaceAlgorithm::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->UpstreamWatch->Arm();
  return this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
}

bool vtkPointSetSurfaceAlgorithm::PrepareRun(
  pss_vtk::DistributedRun& run, vtkInformationVector** inputVector, vtkPointSet* cloud)
{
  // The viewpoint first: an error in it fails the same way on every rank (the property, or the
  // field data every rank's piece of a reader's output carries).
  return this->ResolveViewpoint(cloud) &&
    run.Prepare(inputVector, *this->UpstreamWatch, cloud, "", this->GatheredCloud);
}

const double* vtkPointSetSurfaceAlgorithm::OrientationViewpoint() const
{
  return this->HasOrientationViewpoint ? this->ResolvedViewpoint : nullptr;
}

vtkMultiProcessController* vtkPointSetSurfaceAlgorithm::DistributedController() const
{
  return this->SupportsDistributedRun() ? pss_vtk::MultiProcessController() : nullptr;
}

void vtkPointSetSurfaceAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  pss_vtk::PrintSurface(os, indent, this->Surface);
  static const char* const modes[] = { "FromInput", "Given", "Off" };
  os << indent << "ViewpointMode: " << modes[this->ViewpointMode] << "\n";
  os << indent << "Viewpoint: " << this->Viewpoint[0] << " " << this->Viewpoint[1] << " " << this->Viewpoint[2] << "\n";
}

bool vtkPointSetSurfaceAlgorithm::ResolveViewpoint(vtkPointSet* cloud)
{
  double* viewpoint = this->ResolvedViewpoint;
  this->HasOrientationViewpoint = false;
  if (this->ViewpointMode == VIEWPOINT_OFF)
  {
    return true;
  }
  if (this->ViewpointMode == VIEWPOINT_GIVEN)
  {
    std::copy(this->Viewpoint, this->Viewpoint + 3, viewpoint);
  }
  else if (!pss_vtk::CloudViewpoint(cloud, viewpoint))
  {
    return true;
  }
  if (!(std::isfinite(viewpoint[0]) && std::isfinite(viewpoint[1]) && std::isfinite(viewpoint[2])))
  {
    vtkErrorMacro(<< "the viewpoint (" << viewpoint[0] << ", " << viewpoint[1] << ", " << viewpoint[2]
                  << ") is not finite");
    return false;
  }
  // At a cloud point the direction to the sensor is undefined there. Checked on a whole cloud
  // only: in a distributed run a rank cannot fail alone without leaving the others waiting.
  vtkMultiProcessController* controller = this->DistributedController();
  if (cloud && (!controller || controller->GetNumberOfProcesses() == 1))
  {
    const vtkIdType hit = pss_vtk::PointAt(cloud->GetPoints(), viewpoint);
    if (hit >= 0)
    {
      vtkErrorMacro(<< "the viewpoint (" << viewpoint[0] << ", " << viewpoint[1] << ", " << viewpoint[2]
                    << ") is cloud point " << hit << ": the direction to the sensor is undefined there");
      return false;
    }
  }
  this->HasOrientationViewpoint = true;
  return true;
}

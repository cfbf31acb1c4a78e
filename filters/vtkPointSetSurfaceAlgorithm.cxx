// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceAlgorithm.h"

#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkCxxSetObjectMacro(vtkPointSetSurfaceAlgorithm, Surface, vtkPointSetSurface);

vtkPointSetSurfaceAlgorithm::vtkPointSetSurfaceAlgorithm()
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

vtkMultiProcessController* vtkPointSetSurfaceAlgorithm::DistributedController() const
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return this->SupportsDistributedRun() && controller && controller->GetNumberOfProcesses() > 1 ? controller
                                                                                                 : nullptr;
}

bool vtkPointSetSurfaceAlgorithm::PrepareSurface(vtkPointSet* cloud, const char* what)
{
  vtkMultiProcessController* controller = this->DistributedController();
  if (!controller)
  {
    this->GatheredCloud = nullptr;
    return pss_vtk::PrepareSurface(this, this->Surface, cloud, what);
  }
  // The whole cloud on every rank makes h, centroid, bounds and every neighbourhood those of the
  // one-process run by construction, whatever the split.
  this->GatheredCloud = pss_vtk::GatherCloud(this, controller, cloud);
  return this->GatheredCloud && pss_vtk::PrepareSurface(this, this->Surface, this->GatheredCloud, what, true);
}

void vtkPointSetSurfaceAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  pss_vtk::PrintSurface(os, indent, this->Surface);
}

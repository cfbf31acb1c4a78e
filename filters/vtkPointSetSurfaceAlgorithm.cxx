// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceAlgorithm.h"

#include "PointSetSurfacesDistributedRun.h"
#include "PointSetSurfacesErrorWatch.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

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
  return run.Prepare(inputVector, *this->UpstreamWatch, cloud, "", this->GatheredCloud);
}

vtkMultiProcessController* vtkPointSetSurfaceAlgorithm::DistributedController() const
{
  return this->SupportsDistributedRun() ? pss_vtk::MultiProcessController() : nullptr;
}

void vtkPointSetSurfaceAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  pss_vtk::PrintSurface(os, indent, this->Surface);
}

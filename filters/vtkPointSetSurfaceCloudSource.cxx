// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceCloudSource.h"

#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesVTKUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "pss/PointIndex.h"
#include "pss/SyntheticClouds.h"

#include <cmath>
#include <functional>
#include <new>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkPointSetSurfaceCloudSource);

vtkPointSetSurfaceCloudSource::vtkPointSetSurfaceCloudSource()
{
  this->SetNumberOfInputPorts(0);
}

const char* vtkPointSetSurfaceCloudSource::GetSceneAsString() const
{
  return pss::sceneName(static_cast<pss::Scene>(this->Scene));
}

int vtkPointSetSurfaceCloudSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outInfo);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) &&
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0)
  {
    return 1; // the whole cloud goes to piece 0
  }

  pss::CloudSpec spec;
  spec.scene = static_cast<pss::Scene>(this->Scene);
  spec.count = static_cast<std::size_t>(this->NumberOfPoints);
  spec.size = this->Size;
  spec.noise = this->Noise;
  spec.seed = static_cast<unsigned>(this->Seed);
  spec.dimension = this->Dimension;
  spec.cornerAngle = this->CornerAngle;
  spec.gap = this->SheetGap;

  std::vector<pss::Vec3> cloud;
  try
  {
    cloud = pss::generateCloud(spec); // validates spec
  }
  catch (const std::invalid_argument& e)
  {
    vtkErrorMacro(<< "invalid " << this->GetSceneAsString() << " cloud (NumberOfPoints "
                  << this->NumberOfPoints << ", Size " << this->Size << ", Noise " << this->Noise
                  << ", SheetGap " << this->SheetGap << "): " << e.what());
    return 0;
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro(<< "not enough memory for " << this->NumberOfPoints << " points");
    return 0;
  }

  const vtkIdType n = static_cast<vtkIdType>(cloud.size());
  std::vector<double> distances;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  auto distance = pss_vtk::NewArray<vtkDoubleArray>("DistanceToShape", 0, 1);
  try
  {
    distances.resize(cloud.size());
    points->SetNumberOfPoints(n);
    distance->SetNumberOfTuples(n);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro(<< "not enough memory for " << n << " points");
    return 0;
  }
  if (!pss_vtk::ParallelFor(this, n, [&](vtkIdType i) {
        const auto k = static_cast<std::size_t>(i);
        distances[k] = pss::distanceToShape(spec, cloud[k]);
      }))
  {
    return 1; // aborted: leave the output empty
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const auto k = static_cast<std::size_t>(i);
    if (!pss::isFinite(cloud[k]) || !std::isfinite(distances[k]))
    {
      vtkErrorMacro(<< "the " << this->GetSceneAsString() << " cloud with Size " << this->Size << ", Noise "
                    << this->Noise << " and SheetGap " << this->SheetGap
                    << " has coordinates beyond double precision; use smaller values");
      return 0;
    }
    points->SetPoint(i, cloud[k].data());
    distance->SetValue(i, distances[k]);
  }

  output->SetPoints(points);
  output->SetVerts(pss_vtk::VertexCells(n));
  output->GetPointData()->SetScalars(distance);
  return 1;
}

void vtkPointSetSurfaceCloudSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->GetSceneAsString() << " (" << this->Scene << ")\n";
  os << indent << "NumberOfPoints: " << this->NumberOfPoints << "\n";
  os << indent << "Size: " << this->Size << "\n";
  os << indent << "Noise: " << this->Noise << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Dimension: " << this->Dimension << "\n";
  os << indent << "CornerAngle: " << this->CornerAngle << "\n";
  os << indent << "SheetGap: " << this->SheetGap << "\n";
}

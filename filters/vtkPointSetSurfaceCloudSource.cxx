// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceCloudSource.h"

#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesVTKUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "pss/PointIndex.h"
#include "pss/SyntheticClouds.h"

#include <cmath>
#include <functional>
#include <limits>
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
  if (this->Scene == DEPTH_CAMERA)
  {
    return this->RequestDepthCamera(output);
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

int vtkPointSetSurfaceCloudSource::RequestDepthCamera(vtkPolyData* output)
{
  pss::CloudSpec spec;
  spec.scene = pss::Scene::DepthCamera;
  spec.seed = static_cast<unsigned>(this->Seed);
  spec.camera.width = this->ImageWidth;
  spec.camera.height = this->ImageHeight;
  spec.camera.depthNoise = this->DepthNoise;
  pss::DepthFrame frame;
  try
  {
    frame = pss::generateDepthFrame(spec); // validates the camera
  }
  catch (const std::invalid_argument& e)
  {
    vtkErrorMacro(<< "invalid depth camera (ImageWidth " << this->ImageWidth << ", ImageHeight " << this->ImageHeight
                  << ", DepthNoise " << this->DepthNoise << "): " << e.what());
    return 0;
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro(<< "not enough memory for a " << this->ImageWidth << " x " << this->ImageHeight << " depth frame");
    return 0;
  }

  const vtkIdType n = static_cast<vtkIdType>(frame.points.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  auto distance = pss_vtk::NewArray<vtkDoubleArray>("DistanceToShape", 0, 1);
  auto pixel = pss_vtk::NewArray<vtkIntArray>("Pixel", 0, 2);
  auto surface = pss_vtk::NewArray<vtkIntArray>("SurfaceId", 0, 1);
  auto sigma = pss_vtk::NewArray<vtkDoubleArray>("NoiseSigma", 0, 1);
  try
  {
    points->SetNumberOfPoints(n);
    distance->SetNumberOfTuples(n);
    pixel->SetNumberOfTuples(n);
    surface->SetNumberOfTuples(n);
    sigma->SetNumberOfTuples(n);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro(<< "not enough memory for " << n << " points");
    return 0;
  }
  if (!pss_vtk::ParallelFor(this, n, [&](vtkIdType i) {
        const pss::Vec3& p = frame.points[static_cast<std::size_t>(i)];
        // A pixel the sensor did not measure has no distance to speak of.
        distance->SetValue(i, pss::isFinite(p) ? pss::distanceToShape(spec, p) : std::numeric_limits<double>::quiet_NaN());
      }))
  {
    return 1; // aborted: leave the output empty
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const pss::DepthPixel& px = frame.pixels[static_cast<std::size_t>(i)];
    points->SetPoint(i, frame.points[static_cast<std::size_t>(i)].data());
    pixel->SetTypedComponent(i, 0, px.column); // vtkPCDReader's layout: column, then row
    pixel->SetTypedComponent(i, 1, px.row);
    surface->SetValue(i, static_cast<int>(px.surface));
    sigma->SetValue(i, px.sigma);
  }

  output->SetPoints(points);
  output->SetVerts(pss_vtk::VertexCells(n));
  vtkPointData* pointData = output->GetPointData();
  pointData->SetScalars(distance);
  pointData->AddArray(pixel);
  pointData->AddArray(surface);
  pointData->AddArray(sigma);
  // The field data of an organized cloud read by vtkPCDReader, so that vtkPCDWriter writes an
  // organized file and the filters orient n toward the sensor.
  vtkNew<vtkIdTypeArray> grid;
  grid->SetName("GridDimensions");
  grid->InsertNextValue(frame.width);
  grid->InsertNextValue(frame.height);
  output->GetFieldData()->AddArray(grid);
  vtkNew<vtkDoubleArray> viewpoint;
  viewpoint->SetName("Viewpoint");
  for (double v : { frame.viewpoint.x(), frame.viewpoint.y(), frame.viewpoint.z(), 1.0, 0.0, 0.0, 0.0 })
  {
    viewpoint->InsertNextValue(v); // tx ty tz, then the identity quaternion qw qx qy qz
  }
  output->GetFieldData()->AddArray(viewpoint);
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
  os << indent << "ImageWidth: " << this->ImageWidth << "\n";
  os << indent << "ImageHeight: " << this->ImageHeight << "\n";
  os << indent << "DepthNoise: " << this->DepthNoise << "\n";
}

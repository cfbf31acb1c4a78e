// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceProjection.h"

#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "pss/ExtremalSurface.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"

vtkStandardNewMacro(vtkPointSetSurfaceProjection);

vtkPointSetSurfaceProjection::vtkPointSetSurfaceProjection()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkPointSetSurfaceProjection::~vtkPointSetSurfaceProjection() = default;

void vtkPointSetSurfaceProjection::SetStartPointsConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkPointSetSurfaceProjection::SetStartPointsData(vtkDataObject* data)
{
  this->SetInputData(1, data);
}

bool vtkPointSetSurfaceProjection::BeginProjection(const pss::SurfaceDefinition&, vtkIdType)
{
  return true;
}

pss::ProjectionResult vtkPointSetSurfaceProjection::ProjectPoint(vtkIdType, const double start[3],
  const pss::SurfaceDefinition& surface, const pss::ProjectionOptions& options, pss::Workspace& ws)
{
  return pss::project(surface, pss::Vec3(start[0], start[1], start[2]), options, ws);
}

bool vtkPointSetSurfaceProjection::AddPointArrays(
  vtkPointSet*, const std::vector<pss::ProjectionResult>&, vtkPointData*)
{
  return true;
}

int vtkPointSetSurfaceProjection::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* cloud = vtkPointSet::GetData(inputVector[0], 0);
  vtkPointSet* starts =
    inputVector[1]->GetNumberOfInformationObjects() > 0 ? vtkPointSet::GetData(inputVector[1], 0) : cloud;
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* lines = vtkPolyData::GetData(outputVector, 1);
  if (!this->PrepareSurface(cloud))
  {
    return 0;
  }
  if (!starts || starts->GetNumberOfPoints() == 0)
  {
    return 1; // nothing to project: empty outputs
  }

  const pss::SurfaceDefinition& surface = *this->Surface->GetDefinition();
  pss::ProjectionOptions options;
  options.procedure = this->Procedure == PLANE ? pss::Procedure::Plane : pss::Procedure::Extremal;
  options.seekMaxima = this->SeekMaxima;
  options.maxIterations = this->MaxIterations;
  options.tolerance = this->Tolerance;
  options.maxTravel = this->MaxTravel;

  const std::vector<pss::Vec3> startPoints = pss_vtk::ToVectors(starts->GetPoints());
  const vtkIdType n = static_cast<vtkIdType>(startPoints.size());
  if (!this->BeginProjection(surface, n))
  {
    return 0;
  }
  std::vector<pss::ProjectionResult> results(startPoints.size());
  const bool completed =
    pss::forEachStart(startPoints, pss_vtk::SMPLoop(this), [&](std::size_t i, pss::Workspace& ws) {
      results[i] = this->ProjectPoint(static_cast<vtkIdType>(i), startPoints[i].data(), surface, options, ws);
    });
  if (!completed)
  {
    return 1; // aborted: leave the outputs empty
  }

  const pss::PointIndex& index = *this->Surface->GetIndex();
  const pss::Orientation orientation = pss::Orientation::awayFromCentroid(index);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  auto normal = pss_vtk::NewArray<vtkDoubleArray>("Normal", n, 3);
  auto energy = pss_vtk::NewArray<vtkDoubleArray>("Energy", n, 1);
  auto displacement = pss_vtk::NewArray<vtkDoubleArray>("Displacement", n, 3);
  auto iterations = pss_vtk::NewArray<vtkIntArray>("Iterations", n, 1);
  auto converged = pss_vtk::NewArray<vtkUnsignedCharArray>("Converged", n, 1);
  auto stability = pss_vtk::NewArray<vtkDoubleArray>("Stability", n, 1);
  auto extremum = pss_vtk::NewArray<vtkIntArray>("ExtremumType", n, 1);
  auto reason = pss_vtk::NewArray<vtkIntArray>("StopReason", n, 1);
  vtkIdType invalid = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const pss::ProjectionResult& r = results[i];
    const bool valid = r.reason != pss::StopReason::InvalidInput;
    invalid += valid ? 0 : 1;
    points->SetPoint(i, r.point.data());
    const pss::Vec3 nrm = valid ? orientation.apply(r.direction.n, r.point) : pss::Vec3::Zero();
    normal->SetTypedTuple(i, nrm.data());
    energy->SetValue(i, r.energy);
    const pss::Vec3 d = valid ? pss::Vec3(r.point - index.restrict(startPoints[i])) : pss::Vec3::Zero();
    displacement->SetTypedTuple(i, d.data());
    iterations->SetValue(i, r.iterations);
    converged->SetValue(i, r.converged ? 1 : 0);
    stability->SetValue(i, r.direction.stability);
    extremum->SetValue(i, static_cast<int>(r.type));
    reason->SetValue(i, static_cast<int>(r.reason));
  }
  if (invalid > 0)
  {
    vtkWarningMacro(<< invalid << " start point(s) have NaN or infinite coordinates: left in place, StopReason 4");
  }

  output->SetPoints(points);
  output->SetVerts(pss_vtk::VertexCells(n));
  vtkPointData* outPD = output->GetPointData();
  outPD->PassData(starts->GetPointData());
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(normal), static_cast<vtkDataArray*>(energy),
         static_cast<vtkDataArray*>(displacement), static_cast<vtkDataArray*>(iterations),
         static_cast<vtkDataArray*>(converged), static_cast<vtkDataArray*>(stability),
         static_cast<vtkDataArray*>(extremum), static_cast<vtkDataArray*>(reason) })
  {
    outPD->AddArray(a);
  }
  outPD->SetNormals(normal);
  pss_vtk::AddSurfaceFieldData(output, this->Surface);
  if (!this->AddPointArrays(starts, results, outPD))
  {
    output->Initialize();
    return 0;
  }

  if (this->GenerateProjectionLines)
  {
    vtkNew<vtkPoints> ends;
    ends->SetDataTypeToDouble();
    vtkNew<vtkCellArray> segments;
    auto lineConverged = pss_vtk::NewArray<vtkUnsignedCharArray>("Converged", 0, 1);
    auto lineReason = pss_vtk::NewArray<vtkIntArray>("StopReason", 0, 1);
    auto lineStart = pss_vtk::NewArray<vtkIdTypeArray>("StartPointId", 0, 1);
    for (vtkIdType i = 0; i < n; ++i)
    {
      const pss::ProjectionResult& r = results[i];
      if (r.reason == pss::StopReason::InvalidInput)
      {
        continue;
      }
      const pss::Vec3 start = this->Surface->GetIndex()->restrict(startPoints[i]);
      const vtkIdType ids[2] = { ends->InsertNextPoint(start.data()), ends->InsertNextPoint(r.point.data()) };
      segments->InsertNextCell(2, ids);
      lineConverged->InsertNextValue(r.converged ? 1 : 0);
      lineReason->InsertNextValue(static_cast<int>(r.reason));
      lineStart->InsertNextValue(i);
    }
    lines->SetPoints(ends);
    lines->SetLines(segments);
    lines->GetCellData()->AddArray(lineConverged);
    lines->GetCellData()->AddArray(lineReason);
    lines->GetCellData()->AddArray(lineStart);
  }
  return 1;
}

void vtkPointSetSurfaceProjection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Procedure: " << (this->Procedure == PLANE ? "Plane" : "Extremal") << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaxTravel: " << this->MaxTravel << "\n";
  os << indent << "SeekMaxima: " << (this->SeekMaxima ? "On" : "Off") << "\n";
  os << indent << "GenerateProjectionLines: " << (this->GenerateProjectionLines ? "On" : "Off") << "\n";
}

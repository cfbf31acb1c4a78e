// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceProjection.h"

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
#include "vtkMultiProcessController.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <numeric>
#include <optional>
#include <vector>

#include "pss/ExtremalSurface.h"
#include "pss/NormalOrientation.h"
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

bool vtkPointSetSurfaceProjection::AddPointArrays(vtkPointSet*, vtkPointData*)
{
  return true;
}

namespace
{

// The output's standard arrays, allocated before the projections and filled by them in place:
// keeping every pss::ProjectionResult until the end would double the memory of a large run.
struct StandardArrays
{
  explicit StandardArrays(vtkIdType n)
    : N(n)
  {
    this->Points->SetData(this->Coordinates);
  }

  // Point i's tuples: called from several threads, each i once.
  void Set(vtkIdType i, const pss::ProjectionResult& r, const double start[3], const pss::PointIndex& index,
    const pss::Orientation& orientation)
  {
    const bool valid = r.reason != pss::StopReason::InvalidInput;
    const pss::Vec3 nrm = valid ? orientation.apply(r.direction.n, r.point) : pss::Vec3::Zero();
    const pss::Vec3 d =
      valid ? pss::Vec3(r.point - index.restrict(pss::Vec3(start[0], start[1], start[2]))) : pss::Vec3::Zero();
    std::copy(r.point.data(), r.point.data() + 3, this->Coordinates->GetPointer(3 * i));
    std::copy(nrm.data(), nrm.data() + 3, this->Normal->GetPointer(3 * i));
    this->Energy->GetPointer(i)[0] = r.energy;
    std::copy(d.data(), d.data() + 3, this->Displacement->GetPointer(3 * i));
    this->Iterations->GetPointer(i)[0] = r.iterations;
    this->Converged->GetPointer(i)[0] = r.converged ? 1 : 0;
    this->Stability->GetPointer(i)[0] = r.direction.stability;
    this->Extremum->GetPointer(i)[0] = static_cast<int>(r.type);
    this->Reason->GetPointer(i)[0] = static_cast<int>(r.reason);
  }

  void AddTo(vtkPointData* pd) const
  {
    for (vtkDataArray* a : { static_cast<vtkDataArray*>(this->Normal), static_cast<vtkDataArray*>(this->Energy),
           static_cast<vtkDataArray*>(this->Displacement), static_cast<vtkDataArray*>(this->Iterations),
           static_cast<vtkDataArray*>(this->Converged), static_cast<vtkDataArray*>(this->Stability),
           static_cast<vtkDataArray*>(this->Extremum), static_cast<vtkDataArray*>(this->Reason) })
    {
      pd->AddArray(a);
    }
    pd->SetNormals(this->Normal);
  }

  vtkIdType Size() const { return this->N; }

  const vtkIdType N; // declared first: the arrays below are sized from it
  vtkSmartPointer<vtkDoubleArray> Coordinates = pss_vtk::NewArray<vtkDoubleArray>("Points", N, 3);
  vtkNew<vtkPoints> Points; // holds Coordinates
  vtkSmartPointer<vtkDoubleArray> Normal = pss_vtk::NewArray<vtkDoubleArray>("Normal", N, 3);
  vtkSmartPointer<vtkDoubleArray> Energy = pss_vtk::NewArray<vtkDoubleArray>("Energy", N, 1);
  vtkSmartPointer<vtkDoubleArray> Displacement = pss_vtk::NewArray<vtkDoubleArray>("Displacement", N, 3);
  vtkSmartPointer<vtkIntArray> Iterations = pss_vtk::NewArray<vtkIntArray>("Iterations", N, 1);
  vtkSmartPointer<vtkUnsignedCharArray> Converged = pss_vtk::NewArray<vtkUnsignedCharArray>("Converged", N, 1);
  vtkSmartPointer<vtkDoubleArray> Stability = pss_vtk::NewArray<vtkDoubleArray>("Stability", N, 1);
  vtkSmartPointer<vtkIntArray> Extremum = pss_vtk::NewArray<vtkIntArray>("ExtremumType", N, 1);
  vtkSmartPointer<vtkIntArray> Reason = pss_vtk::NewArray<vtkIntArray>("StopReason", N, 1);
};

// A segment from each valid start point to where its projection stopped (Figure 1).
void FillProjectionLines(vtkPoints* startPoints, const StandardArrays& arrays, const pss::PointIndex& index,
  vtkPolyData* lines)
{
  vtkNew<vtkPoints> ends;
  ends->SetDataTypeToDouble();
  vtkNew<vtkCellArray> segments;
  auto lineConverged = pss_vtk::NewArray<vtkUnsignedCharArray>("Converged", 0, 1);
  auto lineReason = pss_vtk::NewArray<vtkIntArray>("StopReason", 0, 1);
  auto lineStart = pss_vtk::NewArray<vtkIdTypeArray>("StartPointId", 0, 1);
  for (vtkIdType i = 0; i < arrays.Size(); ++i)
  {
    const int reason = arrays.Reason->GetValue(i);
    if (reason == static_cast<int>(pss::StopReason::InvalidInput))
    {
      continue;
    }
    double start[3];
    startPoints->GetPoint(i, start);
    const pss::Vec3 from = index.restrict(pss::Vec3(start[0], start[1], start[2]));
    const vtkIdType ids[2] = { ends->InsertNextPoint(from.data()), ends->InsertNextPoint(arrays.Points->GetPoint(i)) };
    segments->InsertNextCell(2, ids);
    lineConverged->InsertNextValue(arrays.Converged->GetValue(i));
    lineReason->InsertNextValue(reason);
    lineStart->InsertNextValue(i);
  }
  lines->SetPoints(ends);
  lines->SetLines(segments);
  lines->GetCellData()->AddArray(lineConverged);
  lines->GetCellData()->AddArray(lineReason);
  lines->GetCellData()->AddArray(lineStart);
}

} // namespace

int vtkPointSetSurfaceProjection::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* cloud = vtkPointSet::GetData(inputVector[0], 0);
  vtkPointSet* starts =
    inputVector[1]->GetNumberOfInformationObjects() > 0 ? vtkPointSet::GetData(inputVector[1], 0) : cloud;
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* lines = vtkPolyData::GetData(outputVector, 1);
  this->GhostRounds = 0;
  const vtkIdType n = starts ? starts->GetNumberOfPoints() : 0;
  vtkPoints* startPoints = n > 0 ? starts->GetPoints() : nullptr;

  // Refused on every rank alike, before anything collective: no rank is left waiting.
  if (vtkMultiProcessController* controller = this->DistributedController(); controller && this->PropagateNormals)
  {
    vtkErrorMacro(<< "PropagateNormals needs every end point on one process, and this run has "
                  << controller->GetNumberOfProcesses() << " (MPI): turn it off, or run in one process");
    return 0;
  }
  // Prepare: the surface (gathered cloud or ghost run) and this rank's first global id.
  pss_vtk::DistributedRun run(this, this->Surface, this->DistributedController(), this->GhostMargin);
  if (!this->PrepareRun(run, inputVector, cloud))
  {
    return 0;
  }
  const vtkIdType firstGlobalId = run.FirstGlobalId(n); // collective: before any early return
  // A start set too thin to share the delta lattice's nodes is projected on the exact path.
  const bool exactDelta = !run.LatticeServes(startPoints); // collective too
  if (n == 0 && !run.HasGhosts())
  {
    return 1; // nothing to project: empty outputs
  }
  std::vector<std::uint32_t> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0u);
  std::vector<std::uint32_t> positions; // where each start of order sits in the index, when they are its cloud
  const bool ordered =
    this->OrderStartPoints(starts, cloud, startPoints, run.GetController() != nullptr, order, positions);
  if (!ordered && !run.HasGhosts())
  {
    return 0;
  }

  // Evaluate: every start point projected in place into the output arrays.
  pss::ProjectionOptions options;
  options.procedure = this->Procedure == PLANE ? pss::Procedure::Plane : pss::Procedure::Extremal;
  options.seekMaxima = this->SeekMaxima;
  options.maxIterations = this->MaxIterations;
  options.tolerance = this->Tolerance;
  options.maxTravel = this->MaxTravel;
  StandardArrays arrays(n);
  // Projects the starts @p ks on the surface as prepared; with ghost points, flags those whose
  // projection read beyond this rank's complete region. False: this rank cannot project (its
  // error reported), or the run was aborted (one process only: with ghosts every rank goes on
  // to the end, so that none waits for it).
  bool aborted = false;
  auto project = [&](const std::vector<std::uint32_t>& ks, std::vector<unsigned char>& escaped) {
    const pss::SurfaceDefinition* surface = this->Surface->GetDefinition();
    if (!ordered || !this->BeginProjection(*surface, n))
    {
      return false;
    }
    const pss::PointIndex& index = *this->Surface->GetIndex();
    const pss::Orientation orientation = pss_vtk::OrientationFor(this->OrientationViewpoint(), run.GetCentroid());
    // The indexed cloud's own starts are read from the index, near the neighbours just fetched
    // for the previous start, rather than from the input array, where the visiting order jumps
    // all over memory (3D only: in 2D the index holds them restricted to the plane).
    const bool fromIndex = !positions.empty() && index.dimension() == 3 && ks.size() == static_cast<std::size_t>(n);
    const bool completed =
      pss::forEachPosition(ks.size(), pss_vtk::SMPLoop(this), [&](std::size_t position, pss::Workspace& ws) {
        const vtkIdType i = static_cast<vtkIdType>(ks[position]);
        double start[3];
        if (fromIndex && position < positions.size()) // after them: the skipped non-finite starts
        {
          const pss::Vec3& p = index.point(positions[position]);
          std::copy(p.data(), p.data() + 3, start);
        }
        else
        {
          startPoints->GetPoint(i, start);
        }
        ws.leftCompleteRegion = false;
        ws.exactDelta = exactDelta;
        arrays.Set(i, this->ProjectPoint(i, start, *surface, options, ws), start, index, orientation);
        if (run.HasGhosts())
        {
          escaped[static_cast<std::size_t>(i)] = ws.leftCompleteRegion ? 1 : 0;
        }
      });
    aborted = !completed;
    return completed || run.HasGhosts();
  };
  const auto startAt = [startPoints](std::uint32_t k, double x[3]) {
    startPoints->GetPoint(static_cast<vtkIdType>(k), x);
  };
  if (!run.Evaluate(std::move(order), static_cast<std::size_t>(n), startAt, project))
  {
    return aborted && !run.HasGhosts() ? 1 : 0; // aborted: leave the outputs empty
  }
  this->GhostRounds = run.GetRounds();
  if (n == 0)
  {
    return 1;
  }

  // Attach: the arrays, the surface's field data, global ids and the projection lines.
  vtkIdType invalid = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    invalid += arrays.Reason->GetValue(i) == static_cast<int>(pss::StopReason::InvalidInput) ? 1 : 0;
  }
  if (invalid > 0)
  {
    vtkWarningMacro(<< invalid << " start point(s) have NaN or infinite coordinates: left in place, StopReason 4");
  }
  if (this->PropagateNormals && !this->OrientOutputNormals(arrays.Points, arrays.Normal->GetPointer(0)))
  {
    return 0;
  }
  output->SetPoints(arrays.Points);
  output->SetVerts(pss_vtk::VertexCells(n));
  vtkPointData* outPD = output->GetPointData();
  outPD->PassData(starts->GetPointData());
  arrays.AddTo(outPD);
  pss_vtk::AddSurfaceFieldData(output, this->Surface);
  run.AttachGhostFieldData(output);
  if (!this->AddPointArrays(starts, outPD))
  {
    output->Initialize();
    return 0;
  }
  run.AttachGlobalIds(outPD, firstGlobalId, n);
  if (this->GenerateProjectionLines)
  {
    FillProjectionLines(startPoints, arrays, *this->Surface->GetIndex(), lines);
  }
  return 1;
}

bool vtkPointSetSurfaceProjection::OrderStartPoints(vtkPointSet* starts, vtkPointSet* cloud, vtkPoints* startPoints,
  bool distributed, std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& positions)
{
  positions.clear();
  try
  {
    // Neighbours are visited together so that they share cached neighbourhoods. The indexed
    // cloud's own points are sorted as the index holds them (not in a distributed run: the index
    // holds the gathered cloud or a piece with ghosts); other start points are copied and sorted.
    const pss::PointIndex* index = this->Surface->GetIndex();
    const vtkIdType n = startPoints ? startPoints->GetNumberOfPoints() : 0;
    const bool startsAreIndexed = starts == cloud && !distributed && index &&
      static_cast<vtkIdType>(index->size() + index->skippedCount()) == n;
    const int threads = pss_vtk::CoreThreads();
    if (startsAreIndexed)
    {
      pss::PointIndex::VisitingOrder visiting = index->visitingOrder(threads);
      order = std::move(visiting.ids);
      positions = std::move(visiting.positions);
    }
    else
    {
      order = pss::spatialOrder(pss_vtk::ToVectors(startPoints, threads), threads);
    }
    return true;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "cannot order the start points: " << e.what());
    return false;
  }
}

bool vtkPointSetSurfaceProjection::OrientOutputNormals(vtkPoints* endPoints, double* normals)
{
  try
  {
    const int threads = pss_vtk::CoreThreads();
    const pss::PointIndex index(pss_vtk::ToVectors(endPoints, threads), this->Surface->GetIndex()->dimension(), threads);
    std::vector<pss::Vec3> oriented(index.size());
    for (std::size_t i = 0; i < index.size(); ++i)
    {
      oriented[i] = Eigen::Map<const pss::Vec3>(normals + 3 * index.originalId(i));
    }
    const double* viewpoint = this->OrientationViewpoint();
    pss::orientNormals(index, oriented,
      viewpoint ? std::optional<pss::Vec3>(pss::Vec3(viewpoint[0], viewpoint[1], viewpoint[2])) : std::nullopt,
      static_cast<std::size_t>(this->NormalNeighbors), threads);
    for (std::size_t i = 0; i < index.size(); ++i)
    {
      std::copy(oriented[i].data(), oriented[i].data() + 3, normals + 3 * index.originalId(i));
    }
    return true;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "cannot orient the normals: " << e.what());
    return false;
  }
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
  os << indent << "PropagateNormals: " << (this->PropagateNormals ? "On" : "Off") << "\n";
  os << indent << "NormalNeighbors: " << this->NormalNeighbors << "\n";
  os << indent << "GhostMargin: " << this->GhostMargin << "\n";
}

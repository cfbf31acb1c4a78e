// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceMesher.h"

#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesDistributedRun.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "pss/SurfaceMesh.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <climits>
#include <optional>
#include <sstream>
#include <vector>
#include <stdexcept>

vtkStandardNewMacro(vtkPointSetSurfaceMesher);

vtkPointSetSurfaceMesher::vtkPointSetSurfaceMesher()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

vtkPointSetSurfaceMesher::~vtkPointSetSurfaceMesher() = default;

namespace
{

// The mesh's points, cells and per-point arrays as a vtkPolyData.
void WriteMesh(const pss::SurfaceMesh& mesh, vtkPolyData* output)
{
  const auto n = static_cast<vtkIdType>(mesh.points.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  auto normals = pss_vtk::NewArray<vtkDoubleArray>("Normals", n, 3);
  auto stability = pss_vtk::NewArray<vtkDoubleArray>("Stability", n, 1);
  auto energy = pss_vtk::NewArray<vtkDoubleArray>("Energy", n, 1);
  auto label = pss_vtk::NewArray<vtkIntArray>("DomainLabel", n, 1);
  auto distance = pss_vtk::NewArray<vtkDoubleArray>("DistanceToCloud", n, 1);
  auto normalAngle = pss_vtk::NewArray<vtkDoubleArray>("NormalAngle", n, 1);
  auto startAngle = pss_vtk::NewArray<vtkDoubleArray>("StartAngle", n, 1);
  auto startStability = pss_vtk::NewArray<vtkDoubleArray>("StartStability", n, 1);
  auto displacement = pss_vtk::NewArray<vtkDoubleArray>("Displacement", n, 3);
  auto iterations = pss_vtk::NewArray<vtkIntArray>("Iterations", n, 1);
  auto reason = pss_vtk::NewArray<vtkIntArray>("StopReason", n, 1);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const pss::DomainEvidence& ev = mesh.evidence[i];
    points->SetPoint(i, mesh.points[i].data());
    normals->SetTypedTuple(i, mesh.normals[i].data());
    stability->SetValue(i, ev.projection.direction.stability);
    energy->SetValue(i, ev.projection.energy);
    label->SetValue(i, static_cast<int>(ev.label));
    distance->SetValue(i, ev.distanceToCloud);
    normalAngle->SetValue(i, ev.normalAngle);
    startAngle->SetValue(i, ev.startAngle);
    startStability->SetValue(i, ev.startStability);
    const pss::Vec3 d = mesh.points[i] - mesh.crossings[i];
    displacement->SetTypedTuple(i, d.data());
    iterations->SetValue(i, ev.projection.iterations);
    reason->SetValue(i, static_cast<int>(ev.projection.reason));
  }
  // The connectivity written straight into VTK's arrays (offsets and point ids).
  const bool surface = mesh.dimension == 3;
  const vtkIdType cellCount = static_cast<vtkIdType>(surface ? mesh.triangles.size() : mesh.segments.size());
  const int corners = surface ? 3 : 2;
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(cellCount + 1);
  connectivity->SetNumberOfValues(cellCount * corners);
  for (vtkIdType c = 0; c < cellCount; ++c)
  {
    offsets->SetValue(c, c * corners);
    for (int k = 0; k < corners; ++k)
    {
      const std::uint32_t id = surface ? mesh.triangles[c][k] : mesh.segments[c][k];
      connectivity->SetValue(c * corners + k, static_cast<vtkIdType>(id));
    }
  }
  offsets->SetValue(cellCount, cellCount * corners);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  if (surface)
  {
    output->SetPolys(cells);
  }
  else
  {
    output->SetLines(cells);
  }
  output->SetPoints(points);
  vtkPointData* pd = output->GetPointData();
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(normals), static_cast<vtkDataArray*>(stability),
         static_cast<vtkDataArray*>(energy), static_cast<vtkDataArray*>(label),
         static_cast<vtkDataArray*>(distance), static_cast<vtkDataArray*>(normalAngle),
         static_cast<vtkDataArray*>(startAngle), static_cast<vtkDataArray*>(startStability),
         static_cast<vtkDataArray*>(displacement), static_cast<vtkDataArray*>(iterations),
         static_cast<vtkDataArray*>(reason) })
  {
    pd->AddArray(a);
  }
  pd->SetNormals(normals);
}

// What the mesher did, as one-value field arrays, so a written mesh says how it was made.
void AddStatistics(const pss::MeshStatistics& st, vtkFieldData* fd)
{
  const std::pair<const char*, long long> counts[] = {
    { "BandCells", static_cast<long long>(st.bandCells) },
    { "CellLevels", static_cast<long long>(st.cellLevels) },
    { "HangingVertices", static_cast<long long>(st.hangingVertices) },
    { "GridVertices", static_cast<long long>(st.gridVertices) },
    { "Crossings", static_cast<long long>(st.crossings) },
    { "DroppedVertices", static_cast<long long>(st.droppedVertices) },
    { "MaximumCrossings", static_cast<long long>(st.maximumCrossings) },
    { "SeamSimplices", static_cast<long long>(st.seamSimplices) },
    { "FoldedTriangles", static_cast<long long>(st.foldedSimplices) },
    { "RemovedPieces", static_cast<long long>(st.removedPieces) },
    { "CoveredPieces", static_cast<long long>(st.coveredPieces) },
    { "ClosedHoles", static_cast<long long>(st.closedHoles) },
    { "DanglingTriangles", static_cast<long long>(st.danglingTriangles) },
    { "TrimmedTriangles", static_cast<long long>(st.trimmedSimplices) },
    { "UndefinedGridVertices", static_cast<long long>(st.undefinedVertices) },
    { "Components", static_cast<long long>(st.components) },
    { "BoundaryEdges", static_cast<long long>(st.boundaryEdges) },
    { "NonManifoldEdges", static_cast<long long>(st.nonManifoldEdges) },
    { "EulerCharacteristic", st.eulerCharacteristic },
  };
  for (const auto& entry : counts)
  {
    auto a = pss_vtk::NewArray<vtkIdTypeArray>(entry.first, 1, 1);
    a->SetValue(0, static_cast<vtkIdType>(entry.second));
    fd->AddArray(a);
  }
}

} // namespace

namespace
{
// Keeps this rank's block of the cells of @p mesh (triangles, or polylines in 2D; the blocks of
// @p split, as for the corners and crossings) and the points they use, with their point data and
// `GlobalPointIds`, the points' ids in the whole mesh: the ranks' shares, merged by global id, are
// the whole mesh again.
void KeepShareOfCells(vtkPolyData* mesh, const pss::StageSplit& split)
{
  const bool triangles = mesh->GetNumberOfPolys() > 0;
  vtkCellArray* cells = triangles ? mesh->GetPolys() : mesh->GetLines();
  const std::size_t n = cells ? static_cast<std::size_t>(cells->GetNumberOfCells()) : 0;
  const vtkIdType first = static_cast<vtkIdType>(split.begin(n));
  const vtkIdType last = static_cast<vtkIdType>(split.end(n));
  std::vector<vtkIdType> newId(static_cast<std::size_t>(mesh->GetNumberOfPoints()), -1);
  auto globalIds = pss_vtk::NewArray<vtkIdTypeArray>("GlobalPointIds", 0, 1);
  vtkNew<vtkCellArray> kept;
  std::vector<vtkIdType> ids;
  for (vtkIdType c = first; c < last; ++c)
  {
    vtkIdType size = 0;
    const vtkIdType* pts = nullptr;
    cells->GetCellAtId(c, size, pts);
    ids.assign(pts, pts + size);
    for (vtkIdType& id : ids)
    {
      vtkIdType& mapped = newId[static_cast<std::size_t>(id)];
      if (mapped < 0)
      {
        mapped = globalIds->InsertNextValue(id);
      }
      id = mapped;
    }
    kept->InsertNextCell(size, ids.data());
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(mesh->GetPoints()->GetDataType());
  points->SetNumberOfPoints(globalIds->GetNumberOfTuples());
  vtkNew<vtkPointData> pointData;
  pointData->CopyAllocate(mesh->GetPointData(), globalIds->GetNumberOfTuples());
  for (vtkIdType i = 0; i < globalIds->GetNumberOfTuples(); ++i)
  {
    const vtkIdType old = globalIds->GetValue(i);
    points->SetPoint(i, mesh->GetPoint(old));
    pointData->CopyData(mesh->GetPointData(), old, i);
  }
  mesh->SetPoints(points);
  mesh->GetPointData()->ShallowCopy(pointData);
  mesh->GetPointData()->SetGlobalIds(globalIds);
  mesh->SetPolys(triangles ? kept.Get() : nullptr);
  mesh->SetLines(triangles ? nullptr : kept.Get());
}
}

int vtkPointSetSurfaceMesher::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* cloud = vtkPointSet::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->GhostRounds = 0;
  pss_vtk::DistributedRun run(this, this->Surface, this->DistributedController(), this->GhostMargin);
  if (!this->PrepareRun(run, inputVector, cloud))
  {
    return 0;
  }
  vtkMultiProcessController* controller = run.GetController();
  pss::MeshOptions options;
  if (const double* viewpoint = this->OrientationViewpoint())
  {
    options.viewpoint = pss::Vec3(viewpoint[0], viewpoint[1], viewpoint[2]);
  }
  // The cloud's own normals orient each piece: the input's normals in one process, where the
  // surface's points are the input's in its order; with the gathered cloud, its array of the
  // surface's NormalsArrayName (what PLY and PCD readers call their normals); with ghost points,
  // none (a rank's points are not the whole cloud's).
  const char* normalsName = this->Surface->GetNormalsArrayName();
  vtkPointSet* normalsCloud = !controller ? cloud : run.HasGhosts() ? nullptr : this->GatheredCloud.Get();
  vtkDataArray* cloudNormals = !normalsCloud ? nullptr
    : !controller                           ? normalsCloud->GetPointData()->GetNormals()
    : normalsName                           ? normalsCloud->GetPointData()->GetArray(normalsName)
                                            : nullptr;
  if (cloudNormals && cloudNormals->GetNumberOfComponents() == 3 &&
    cloudNormals->GetNumberOfTuples() == normalsCloud->GetNumberOfPoints())
  {
    options.cloudNormals.resize(static_cast<std::size_t>(cloudNormals->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < cloudNormals->GetNumberOfTuples(); ++i)
    {
      double n[3];
      cloudNormals->GetTuple(i, n);
      options.cloudNormals[static_cast<std::size_t>(i)] = pss::Vec3(n[0], n[1], n[2]);
    }
  }
  options.cellSize = this->CellSize;
  options.adaptiveCells = this->AdaptiveCells;
  options.band = this->Band;
  options.projectVertices = this->ProjectVertices;
  options.maxVertexTravel = this->MaxVertexTravel;
  options.maxSeamAngle = this->MaxSeamAngle;
  options.maxFoldAngle = this->MaxFoldAngle;
  options.maxHoleEdges = static_cast<std::size_t>(this->MaxHoleEdges);
  options.minPieceArea = this->MinPieceArea;
  options.coveredPieceArea = this->CoveredPieceArea;
  options.maxBandCells = static_cast<std::size_t>(this->MaximumNumberOfBandCells);
  // APSS's and RIMLS's plane procedure is their own projection onto their fit (the same zero set
  // as the extremal one, without a line search).
  const int variant = this->Surface->GetVariant();
  const bool ownStep = pss::needsNormals(static_cast<pss::Variant>(variant));
  this->UsedProcedure = this->Procedure != AUTOMATIC ? this->Procedure
    : ownStep || (this->Surface->GetUsesPointScales() && variant == vtkPointSetSurface::CENTER_OF_MASS)
    ? PLANE
    : EXTREMAL;
  options.projection.procedure = this->UsedProcedure == PLANE ? pss::Procedure::Plane : pss::Procedure::Extremal;
  // The automatic distance and border criteria (see the header) were measured on depth frames:
  // with a scale per point, 1 h_i and a border offset of 0.6 left 0.6% (a Kinect frame) to 3.7%
  // (a room scan) of the mesh farther than three spacings from the scan.
  const bool pointScales = this->Surface->GetUsesPointScales();
  options.domain.maxDistance = this->MaxDistance > 0.0 ? this->MaxDistance : pointScales ? 0.6 : 1.0;
  options.domain.maxNormalAngle = this->MaxNormalAngle;
  options.domain.maxBorderOffset = this->MaxBorderOffset != BORDER_OFFSET_AUTOMATIC ? std::max(0.0, this->MaxBorderOffset)
    : pointScales                                                                    ? 0.6
                                                                                     : 0.0;
  // The automatic trim (see the header) was measured on depth frames; it needs the whole cloud, so
  // a run with ghost points (GhostMargin > 0, also in one process: the same mesh) goes without.
  options.trimDistance = this->TrimDistance >= 0.0 ? this->TrimDistance
    : pointScales && this->GhostMargin == 0.0                         ? 2.5
                                                                      : 0.0;
  this->UsedMaxDistance = options.domain.maxDistance;
  this->UsedMaxBorderOffset = options.domain.maxBorderOffset;
  // In a distributed run every rank builds the same band; each computes its block of the corners,
  // of the crossings and of the holes' centres, and the blocks are exchanged after each stage.
  bool tooLarge = false;
  const pss::StageSplit split = controller ? pss_vtk::SplitAcrossRanks(controller, tooLarge) : pss::StageSplit();
  std::optional<pss::SurfaceMesh> mesh;
  pss::MeshTimings t;
  bool failed = false;
  try
  {
    if (run.HasGhosts() && options.trimDistance > 0.0)
    {
      vtkErrorMacro("TrimDistance needs every cloud point's neighbours, which a distributed run with ghost points "
                    "does not have: set GhostMargin to 0 (the gathered cloud) or TrimDistance to 0 or automatic (-1)");
      failed = true;
    }
    else if (run.HasGhosts())
    {
      mesh = this->MeshWithGhostPoints(run, options, split, t, tooLarge, failed);
    }
    else
    {
      mesh = pss::extractSurfaceMesh(
        *this->Surface->GetDefinition(), options, pss_vtk::SMPLoop(this), &t, controller ? &split : nullptr);
    }
  }
  catch (const std::invalid_argument& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  if (tooLarge)
  {
    vtkErrorMacro(<< "the band's cells, grid corners or crossings exceed one MPI exchange (2^31 - 1 values): use a "
                     "larger CellSize or a smaller Band");
    return 0;
  }
  if (failed)
  {
    return 0;
  }
  if (!mesh)
  {
    return 1; // aborted: empty output
  }
  this->UsedTrimDistance = mesh->dimension == 3 ? options.trimDistance : 0.0; // no trim in 2D
  const auto start = std::chrono::steady_clock::now();
  WriteMesh(*mesh, output);
  const double write = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream timing;
  timing << "band " << t.band << " s, corners " << t.corners << " s, orient " << t.orient << " s, contour "
         << t.contour << " s, projection " << t.projection << " s, finish " << t.finish << " s, output " << write
         << " s";
  this->TimingReport = timing.str();
  // With ghost points, the one-process h and dimension: a rank whose last block was empty
  // prepared no surface.
  run.AttachSurfaceFieldData(output);
  run.AttachGhostFieldData(output);
  for (const auto& entry : { std::make_pair("CellSize", this->CellSize), std::make_pair("Band", this->Band),
         std::make_pair("MaxDistance", this->UsedMaxDistance),
         std::make_pair("MaxBorderOffset", this->UsedMaxBorderOffset),
         std::make_pair("TrimDistance", this->UsedTrimDistance) })
  {
    auto a = pss_vtk::NewArray<vtkDoubleArray>(entry.first, 1, 1);
    a->SetValue(0, entry.second);
    output->GetFieldData()->AddArray(a);
  }
  // The procedure the vertices were projected with (0 extremal, 1 plane), AUTOMATIC resolved.
  auto procedure = pss_vtk::NewArray<vtkIntArray>("Procedure", 1, 1);
  procedure->SetValue(0, this->UsedProcedure);
  output->GetFieldData()->AddArray(procedure);
  AddStatistics(mesh->statistics, output->GetFieldData());
  if (controller)
  {
    KeepShareOfCells(output, split);
  }
  return 1;
}

std::optional<pss::SurfaceMesh> vtkPointSetSurfaceMesher::MeshWithGhostPoints(pss_vtk::DistributedRun& run,
  const pss::MeshOptions& options, const pss::StageSplit& split, pss::MeshTimings& t, bool& tooLarge, bool& failed)
{
  const auto start = std::chrono::steady_clock::now();
  const pss_vtk::GhostRun& ghost = run.GetGhostRun();
  // Sized from the reduced bounds and h (the same frame on every rank), so it throws alike.
  const pss::MeshFrame frame{ ghost.Dimension, ghost.H, pss::Vec3(ghost.Lo[0], ghost.Lo[1], ghost.Lo[2]),
    pss::Vec3(ghost.Hi[0], ghost.Hi[1], ghost.Hi[2]), run.GetCentroid() };
  pss::SurfaceMesher mesher(frame, options);
  std::vector<pss::Vec3> own(ghost.Own.size() / 3);
  for (std::size_t i = 0; i < own.size(); ++i)
  {
    own[i] = pss::Vec3(ghost.Own[3 * i], ghost.Own[3 * i + 1], ghost.Own[3 * i + 2]);
  }
  std::vector<std::uint64_t> occupied;
  if (!pss_vtk::GatherCellKeys(run.GetController(), mesher.cellKeysOf(own), occupied, tooLarge))
  {
    return std::nullopt;
  }
  own = {};
  mesher.buildBand(std::move(occupied)); // the same union on every rank: throws alike
  t.band = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Each split stage: this rank's block evaluated with ghost points in rounds, then every rank's
  // blocks exchanged.
  return pss::runMeshStages(
    mesher,
    [&](const pss::MeshStage& stage) {
      std::vector<std::uint32_t> ks;
      for (std::size_t k = split.begin(stage.count); k < split.end(stage.count); ++k)
      {
        ks.push_back(static_cast<std::uint32_t>(k));
      }
      const auto positionAt = [&](std::uint32_t k, double x[3]) {
        const pss::Vec3 p = stage.position(k);
        std::copy(p.data(), p.data() + 3, x);
      };
      const auto evaluate = [&](const std::vector<std::uint32_t>& todo, std::vector<unsigned char>& escaped) {
        // Aborting is not offered: every rank goes on, so that none waits.
        mesher.useSurface(*this->Surface->GetDefinition());
        pss::forEachInOrder(todo, pss_vtk::SMPLoop(this), [&](std::size_t k, pss::Workspace& ws) {
          ws.leftCompleteRegion = false;
          (mesher.*stage.evaluate)(k, ws);
          escaped[k] = ws.leftCompleteRegion ? 1 : 0;
        });
        return true;
      };
      if (!run.Evaluate(std::move(ks), stage.count, positionAt, evaluate))
      {
        failed = true;
        return false;
      }
      this->GhostRounds = run.GetRounds();
      std::vector<double> items = (mesher.*stage.get)();
      if (!split.share(items, stage.width, stage.count, true))
      {
        failed = !tooLarge;
        return false;
      }
      (mesher.*stage.set)(items);
      return true;
    },
    t);
}

void vtkPointSetSurfaceMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "AdaptiveCells: " << (this->AdaptiveCells ? "On" : "Off") << "\n";
  os << indent << "Band: " << this->Band << "\n";
  os << indent << "ProjectVertices: " << (this->ProjectVertices ? "On" : "Off") << "\n";
  const char* procedures[] = { "Extremal", "Plane", "Automatic" };
  os << indent << "Procedure: " << procedures[this->Procedure] << "\n";
  os << indent << "UsedProcedure: " << procedures[this->UsedProcedure] << "\n";
  os << indent << "MaxDistance: " << this->MaxDistance << " (used " << this->UsedMaxDistance << ")\n";
  os << indent << "MaxNormalAngle: " << this->MaxNormalAngle << "\n";
  os << indent << "MaxVertexTravel: " << this->MaxVertexTravel << "\n";
  os << indent << "MaxSeamAngle: " << this->MaxSeamAngle << "\n";
  os << indent << "MaxFoldAngle: " << this->MaxFoldAngle << "\n";
  os << indent << "MaxHoleEdges: " << this->MaxHoleEdges << "\n";
  os << indent << "MinPieceArea: " << this->MinPieceArea << "\n";
  os << indent << "MaxBorderOffset: " << this->MaxBorderOffset << " (used " << this->UsedMaxBorderOffset << ")\n";
  os << indent << "TrimDistance: " << this->TrimDistance << " (used " << this->UsedTrimDistance << ")\n";
  os << indent << "CoveredPieceArea: " << this->CoveredPieceArea << "\n";
  os << indent << "MaximumNumberOfBandCells: " << this->MaximumNumberOfBandCells << "\n";
  os << indent << "GhostMargin: " << this->GhostMargin << "\n";
}

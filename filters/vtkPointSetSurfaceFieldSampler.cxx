// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceFieldSampler.h"

#include "PointSetSurfacesFieldEvaluation.h"
#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesDistributedRun.h"
#include "PointSetSurfacesErrorWatch.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkPoints.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "pss/Domain.h"
#include "pss/ExtremalSurface.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPointSetSurfaceFieldSampler);
vtkCxxSetObjectMacro(vtkPointSetSurfaceFieldSampler, Surface, vtkPointSetSurface);

namespace
{
// Limits of the generated grid: vtkIdType-safe counts and a memory ceiling for the output arrays.
constexpr std::uint64_t kMaxSamples = std::uint64_t(1) << 31;
constexpr std::uint64_t kMaxOutputBytes = std::uint64_t(4) << 30;
// Normal (3 doubles), Energy, Delta, ImplicitG, Stability (doubles), ExtremumType (int), Valid
// (byte), DomainLabel (int).
constexpr std::uint64_t kBytesPerSample = 3 * 8 + 4 * 8 + 4 + 1 + 4;
}

namespace
{
// Asks the producer on @p info for piece @p piece of @p pieces, without ghost levels (a structured
// producer for its whole extent, which a piece request does not translate).
void RequestPiece(vtkInformation* info, int piece, int pieces)
{
  info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), piece);
  info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), pieces);
  info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  if (info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    info->Set(
      vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
}
}

vtkPointSetSurfaceFieldSampler::vtkPointSetSurfaceFieldSampler()
  : UpstreamWatch(std::make_unique<pss_vtk::UpstreamErrorWatch>())
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
  this->Surface = vtkPointSetSurface::New();
}

vtkPointSetSurfaceFieldSampler::~vtkPointSetSurfaceFieldSampler()
{
  this->SetSurface(nullptr);
}

void vtkPointSetSurfaceFieldSampler::SetSourceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkPointSetSurfaceFieldSampler::SetSourceData(vtkDataObject* data)
{
  this->SetInputData(1, data);
}

vtkDataObject* vtkPointSetSurfaceFieldSampler::GetSource()
{
  if (this->GetNumberOfInputConnections(1) < 1)
  {
    return nullptr;
  }
  return this->GetExecutive()->GetInputData(1, 0);
}

double vtkPointSetSurfaceFieldSampler::GetEffectiveScale() const
{
  return this->Surface ? this->Surface->GetEffectiveScale() : 0.0;
}

vtkMTimeType vtkPointSetSurfaceFieldSampler::GetMTime()
{
  return pss_vtk::LatestMTime(this->Superclass::GetMTime(), this->Surface);
}

int vtkPointSetSurfaceFieldSampler::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1); // not needed with GenerateSamplingGrid
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  }
  return 1;
}

bool vtkPointSetSurfaceFieldSampler::CheckSampleDimensions()
{
  const int* d = this->SampleDimensions;
  if (d[0] < 1 || d[1] < 1 || d[2] < 1)
  {
    vtkErrorMacro(<< "SampleDimensions must all be >= 1, not " << d[0] << " x " << d[1] << " x " << d[2]);
    return false;
  }
  // In floating point: the product of three ints can overflow 64 bits (2^30 cubed is 2^90).
  const double count = double(d[0]) * double(d[1]) * double(d[2]);
  if (count > double(kMaxSamples) || count * double(kBytesPerSample) > double(kMaxOutputBytes))
  {
    vtkErrorMacro(<< "SampleDimensions " << d[0] << " x " << d[1] << " x " << d[2] << " ask for " << count
                  << " samples (about " << count * double(kBytesPerSample) / double(1u << 20)
                  << " MiB of output); the limit is 2^31 samples and 4 GiB");
    return false;
  }
  return true;
}

bool vtkPointSetSurfaceFieldSampler::ComputeGridGeometry(
  vtkPointSet* cloud, double origin[3], double spacing[3], bool quiet)
{
  // Bounds of the finite cloud points (the surface skips the others too).
  double lo[3] = { std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double hi[3] = { -lo[0], -lo[1], -lo[2] };
  const vtkIdType n = cloud->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    cloud->GetPoint(i, p);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    }
  }
  if (!(lo[0] <= hi[0]))
  {
    if (!quiet)
    {
      vtkErrorMacro(<< "the point cloud has no point with finite coordinates");
    }
    return false;
  }
  return this->ComputeGridGeometry(lo, hi, this->Surface->GetEffectiveScale(), origin, spacing, quiet);
}

bool vtkPointSetSurfaceFieldSampler::ComputeGridGeometry(
  const double lo[3], const double hi[3], double h, double origin[3], double spacing[3], bool quiet)
{
  const double margin = this->SamplingMargin * h;
  double largest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const int d = this->SampleDimensions[a];
    if (d == 1)
    {
      origin[a] = 0.5 * (lo[a] + hi[a]); // the mid-plane (for a planar cloud, its plane)
      spacing[a] = 0.0;                  // set below
      continue;
    }
    origin[a] = lo[a] - margin;
    spacing[a] = (hi[a] + margin - origin[a]) / (d - 1);
    if (!std::isfinite(origin[a]) || !std::isfinite(spacing[a]) || !(spacing[a] > 0.0))
    {
      if (!quiet)
      {
        vtkErrorMacro(<< "the sampling grid is degenerate along axis " << a << " (cloud from " << lo[a] << " to "
                      << hi[a] << ", margin " << margin
                      << "): use a SamplingMargin > 0 or a SampleDimension of 1 there");
      }
      return false;
    }
    largest = std::max(largest, spacing[a]);
  }
  for (int a = 0; a < 3; ++a)
  {
    if (this->SampleDimensions[a] == 1)
    {
      spacing[a] = largest > 0.0 ? largest : 1.0; // any positive value: one layer of samples
    }
  }
  return true;
}

int vtkPointSetSurfaceFieldSampler::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* output = outInfo->Get(vtkDataObject::DATA_OBJECT());
  vtkDataSet* input =
    inputVector[0]->GetNumberOfInformationObjects() > 0 ? vtkDataSet::GetData(inputVector[0], 0) : nullptr;
  if (this->GenerateSamplingGrid || !input)
  {
    // Without input 0 and without the grid RequestData reports the error; an image is a
    // harmless placeholder until then.
    if (!output || !output->IsA("vtkImageData"))
    {
      vtkNew<vtkImageData> image;
      outInfo->Set(vtkDataObject::DATA_OBJECT(), image);
    }
    return 1;
  }
  if (!output || !output->IsA(input->GetClassName()))
  {
    vtkDataObject* copy = input->NewInstance();
    outInfo->Set(vtkDataObject::DATA_OBJECT(), copy);
    copy->Delete();
  }
  return 1;
}

int vtkPointSetSurfaceFieldSampler::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->GenerateSamplingGrid)
  {
    return 1; // the executive has copied input 0's information
  }
  if (!this->CheckSampleDimensions())
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int* d = this->SampleDimensions;
  int whole[6] = { 0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(CAN_PRODUCE_SUB_EXTENT(), 1);

  // The origin and spacing depend on the cloud and on h: announce them when the cloud is already
  // there; RequestData sets the definitive ones from the cloud it samples.
  double origin[3] = { 0.0, 0.0, 0.0 };
  double spacing[3] = { 1.0, 1.0, 1.0 };
  // In a distributed run this rank's piece would give a provisional geometry of its own (and an
  // index built for nothing): the one of the gathered cloud comes in RequestData.
  vtkPointSet* cloud = pss_vtk::MultiProcessController() ? nullptr : vtkPointSet::GetData(inputVector[1], 0);
  if (cloud && cloud->GetNumberOfPoints() > 0 && this->Surface && this->Surface->Prepare(cloud))
  {
    double o[3], s[3];
    if (this->ComputeGridGeometry(cloud, o, s, true))
    {
      std::copy(o, o + 3, origin);
      std::copy(s, s + 3, spacing);
    }
  }
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  return 1;
}

int vtkPointSetSurfaceFieldSampler::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The whole cloud, always: every sample may depend on any cloud point. One process reads all
  // of it; in a distributed run each rank reads its piece and RequestData gathers the pieces (or,
  // with GhostMargin, exchanges the ghost points its samples need).
  this->UpstreamWatch->Arm(); // errors from here to RequestData are the pipeline upstream's
  vtkMultiProcessController* controller = pss_vtk::MultiProcessController();
  const int piece = controller ? controller->GetLocalProcessId() : 0;
  const int pieces = controller ? controller->GetNumberOfProcesses() : 1;
  if (vtkInformation* sourceInfo = inputVector[1]->GetInformationObject(0))
  {
    RequestPiece(sourceInfo, piece, pieces);
  }
  // With the generated grid, input 0 (if connected) is ignored: ask for as little as possible
  // in a form any producer accepts, i.e. a piece, not our image extent.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (this->GenerateSamplingGrid && inInfo)
  {
    RequestPiece(inInfo, piece, pieces);
  }
  return 1;
}

bool vtkPointSetSurfaceFieldSampler::SetUpSamplingGrid(
  vtkImageData* image, const double origin[3], const double spacing[3], vtkInformation* outInfo)
{
  if (!image)
  {
    vtkErrorMacro(<< "the output is not a vtkImageData");
    return false;
  }
  const int* d = this->SampleDimensions;
  int extent[6] = { 0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1 };
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int requested[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), requested);
    for (int a = 0; a < 3; ++a)
    {
      extent[2 * a] = std::max(extent[2 * a], requested[2 * a]);
      extent[2 * a + 1] = std::min(extent[2 * a + 1], requested[2 * a + 1]);
    }
  }
  image->Initialize();
  image->SetExtent(extent);
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  // Correct the announcement too if RequestInformation saw an older cloud (or none yet).
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  return true;
}

int vtkPointSetSurfaceFieldSampler::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input =
    inputVector[0]->GetNumberOfInformationObjects() > 0 ? vtkDataSet::GetData(inputVector[0], 0) : nullptr;
  vtkPointSet* cloud = vtkPointSet::GetData(inputVector[1], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataSet* output = vtkDataSet::GetData(outInfo);
  if (!output)
  {
    vtkErrorMacro(<< "no output data object");
    return 0;
  }
  if (!this->GenerateSamplingGrid && !input)
  {
    vtkErrorMacro(<< "no dataset to sample: connect input 0 or turn GenerateSamplingGrid on");
    return 0;
  }
  vtkMultiProcessController* controller = this->SupportsDistributedRun() ? pss_vtk::MultiProcessController() : nullptr;
  // Refused on every rank alike, before anything collective: no rank is left waiting.
  if (controller && this->OrientationMode == PROPAGATE)
  {
    vtkErrorMacro(<< "OrientationMode PROPAGATE needs every sample on one process, and this run has "
                  << controller->GetNumberOfProcesses()
                  << " (MPI): use AWAY_FROM_CENTROID or ALONG_DIRECTION, or run in one process");
    return 0;
  }
  // Prepare: the surface (gathered cloud or ghost run), the global id of this rank's first probe
  // point, the orientation and where the samples are.
  this->GhostRounds = 0;
  pss_vtk::DistributedRun run(this, this->Surface, controller, this->GhostMargin);
  if (!run.Prepare(inputVector, *this->UpstreamWatch, cloud, " from the source", this->GatheredCloud))
  {
    return 0;
  }
  if (this->GatheredCloud)
  {
    cloud = this->GatheredCloud;
  }
  // Collective, so taken before any rank may stop.
  const vtkIdType firstGlobalId =
    this->GenerateSamplingGrid ? 0 : run.FirstGlobalId(input ? input->GetNumberOfPoints() : 0);
  const bool ghosts = run.HasGhosts();
  const pss_vtk::GhostRun& ghost = run.GetGhostRun();

  pss::Orientation orientation;
  std::string error;
  const int rule = this->OrientationMode == PROPAGATE ? pss_vtk::ORIENT_AWAY_FROM_CENTROID : this->OrientationMode;
  if (!pss_vtk::MakeOrientation(
        rule, this->ReferencePoint, this->ReferenceDirection, run.GetCentroid(), orientation, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  // The two modes differ only in where the samples are: the grid's points or the probe's.
  if (this->GenerateSamplingGrid)
  {
    double origin[3], spacing[3];
    const bool geometry = ghosts ? this->ComputeGridGeometry(ghost.Lo, ghost.Hi, ghost.H, origin, spacing, false)
                                 : this->ComputeGridGeometry(cloud, origin, spacing, false);
    if (!this->CheckSampleDimensions() || !geometry ||
      !this->SetUpSamplingGrid(vtkImageData::SafeDownCast(output), origin, spacing, outInfo))
    {
      return 0;
    }
  }
  else
  {
    output->ShallowCopy(input);
  }

  // The output arrays are filled in place by the threads (each writes its own tuples): no
  // per-sample buffer beyond them, so the 4 GiB check above is the memory used.
  const vtkIdType n = output->GetNumberOfPoints();
  auto normal = pss_vtk::NewArray<vtkDoubleArray>("Normal", n, 3);
  auto energy = pss_vtk::NewArray<vtkDoubleArray>("Energy", n, 1);
  auto delta = pss_vtk::NewArray<vtkDoubleArray>("Delta", n, 1);
  auto g = pss_vtk::NewArray<vtkDoubleArray>("ImplicitG", n, 1);
  auto stability = pss_vtk::NewArray<vtkDoubleArray>("Stability", n, 1);
  auto extremum = pss_vtk::NewArray<vtkIntArray>("ExtremumType", n, 1);
  auto valid = pss_vtk::NewArray<vtkUnsignedCharArray>("Valid", n, 1);
  vtkSmartPointer<vtkIntArray> label;
  if (this->ComputeDomainLabels)
  {
    label = pss_vtk::NewArray<vtkIntArray>("DomainLabel", n, 1);
  }
  double* normalOut = normal->GetPointer(0);
  double* energyOut = energy->GetPointer(0);
  double* deltaOut = delta->GetPointer(0);
  double* gOut = g->GetPointer(0);
  double* stabilityOut = stability->GetPointer(0);
  int* extremumOut = extremum->GetPointer(0);
  unsigned char* validOut = valid->GetPointer(0);
  int* labelOut = label ? label->GetPointer(0) : nullptr;

  pss::ProjectionOptions projection;
  projection.maxIterations = this->MaxIterations;
  projection.tolerance = this->Tolerance;
  pss::DomainThresholds thresholds;
  thresholds.maxDistance = this->MaxDistance;
  thresholds.maxNormalAngle = this->MaxNormalAngle;

  if (n > 0)
  {
    double first[3];
    output->GetPoint(0, first); // vtkDataSet::GetPoint(id, x) is thread-safe once called serially
  }
  // Samples the points @p ks (all of them in one process) on the surface as prepared; with ghost
  // points, flags those whose evaluation read beyond this rank's complete region. False after an
  // error. An abort leaves the output empty; with ghosts the rank still takes part in every round.
  bool aborted = false;
  auto sample = [&](const std::vector<std::uint32_t>& ks, std::vector<unsigned char>& escaped) {
    try
    {
      if (labelOut)
      {
        projection.validate();
        thresholds.validate();
      }
      const pss::SurfaceDefinition& surface = *this->Surface->GetDefinition();
      const pss_vtk::FieldEvaluator evaluator(surface, orientation);
      const pss::CloudNormals cloudNormals(surface);
      auto body = [&](std::size_t k, pss::Workspace& ws) {
        const vtkIdType i = static_cast<vtkIdType>(k);
        double x[3];
        output->GetPoint(i, x);
        ws.leftCompleteRegion = false;
        const pss_vtk::FieldValues v = evaluator.Evaluate(x, ws);
        std::copy(v.normal.data(), v.normal.data() + 3, normalOut + 3 * i);
        energyOut[i] = v.energy;
        deltaOut[i] = v.delta;
        gOut[i] = v.g;
        stabilityOut[i] = v.stability;
        extremumOut[i] = v.extremumType;
        validOut[i] = v.valid ? 1 : 0;
        if (labelOut)
        {
          const pss::DomainEvidence ev =
            pss::classifyStart(surface, pss::Vec3(x[0], x[1], x[2]), projection, thresholds, ws, &cloudNormals);
          labelOut[i] = static_cast<int>(ev.label);
        }
        if (ghosts)
        {
          escaped[k] = ws.leftCompleteRegion ? 1 : 0;
        }
      };
      const bool completed = ghosts
        ? pss::forEachInOrder(ks, pss_vtk::SMPLoop(this), body)
        : pss_vtk::ParallelFor(this, n, [&](vtkIdType i, pss::Workspace& ws) { body(static_cast<std::size_t>(i), ws); },
            0.0, this->OrientationMode == PROPAGATE ? 0.95 : 1.0);
      aborted = aborted || !completed;
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro(<< "field sampling failed: " << e.what());
      return false;
    }
    return true;
  };
  const auto sampleAt = [output](std::uint32_t k, double x[3]) { output->GetPoint(static_cast<vtkIdType>(k), x); };
  if (!run.EvaluateAll(static_cast<std::size_t>(n), sampleAt, sample))
  {
    output->Initialize();
    return 0;
  }
  this->GhostRounds = run.GetRounds();
  if (aborted)
  {
    output->Initialize(); // aborted: leave the output empty
    return 1;
  }
  if (this->OrientationMode == PROPAGATE)
  {
    pss_vtk::PropagateOrientation(output, normalOut, gOut, stabilityOut);
    this->UpdateProgress(1.0);
  }

  const vtkIdType invalid = n - std::count(validOut, validOut + n, static_cast<unsigned char>(1));
  if (invalid > 0)
  {
    vtkWarningMacro(<< invalid << " sample point(s) have NaN or infinite coordinates (or values): Valid = 0, "
                    << "every other array 0 there");
  }
  vtkPointData* outPD = output->GetPointData();
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(normal), static_cast<vtkDataArray*>(energy),
         static_cast<vtkDataArray*>(delta), static_cast<vtkDataArray*>(g),
         static_cast<vtkDataArray*>(stability), static_cast<vtkDataArray*>(extremum),
         static_cast<vtkDataArray*>(valid) })
  {
    outPD->AddArray(a);
  }
  if (label)
  {
    outPD->AddArray(label);
  }
  // SetActive* only moves the flags: SetScalars/SetVectors would drop the probe's own active
  // arrays, which are passed through.
  outPD->SetActiveVectors(normal->GetName());
  outPD->SetActiveScalars(g->GetName());
  if (!this->GenerateSamplingGrid)
  {
    run.AttachGlobalIds(outPD, firstGlobalId, n);
  }
  run.AttachGhostFieldData(output);
  return 1;
}

void vtkPointSetSurfaceFieldSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  static const char* const modes[] = { "AwayFromCentroid", "AwayFromPoint", "AlongDirection", "Propagate" };
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrientationMode: " << modes[this->OrientationMode] << "\n";
  os << indent << "ReferencePoint: (" << this->ReferencePoint[0] << ", " << this->ReferencePoint[1] << ", "
     << this->ReferencePoint[2] << ")\n";
  os << indent << "ReferenceDirection: (" << this->ReferenceDirection[0] << ", " << this->ReferenceDirection[1]
     << ", " << this->ReferenceDirection[2] << ")\n";
  os << indent << "GenerateSamplingGrid: " << (this->GenerateSamplingGrid ? "On" : "Off") << "\n";
  os << indent << "SampleDimensions: (" << this->SampleDimensions[0] << ", " << this->SampleDimensions[1] << ", "
     << this->SampleDimensions[2] << ")\n";
  os << indent << "SamplingMargin: " << this->SamplingMargin << "\n";
  os << indent << "ComputeDomainLabels: " << (this->ComputeDomainLabels ? "On" : "Off") << "\n";
  os << indent << "MaxDistance: " << this->MaxDistance << "\n";
  os << indent << "MaxNormalAngle: " << this->MaxNormalAngle << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "GhostMargin: " << this->GhostMargin << "\n";
  pss_vtk::PrintSurface(os, indent, this->Surface);
}

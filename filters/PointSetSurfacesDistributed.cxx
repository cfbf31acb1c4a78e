// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesDistributed.h"
#include "PointSetSurfacesErrorWatch.h"
#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesVTKUtilities.h"

#include "vtkAlgorithm.h"
#include "vtkCommunicator.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPolyData.h"

#include "pss/PointIndex.h"
#include "pss/Types.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>

namespace pss_vtk
{

bool PrepareSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkPointSet* cloud, const char* what,
  bool gathered, bool coordinateOrder)
{
  if (!surface)
  {
    vtkErrorWithObjectMacro(algorithm, << "no vtkPointSetSurface is set");
    return false;
  }
  // A filter that does not gather the cloud would take each rank's piece as the whole cloud (its
  // own h, centroid and neighbours) and silently differ from a one-process run near every piece's
  // border: refuse instead.
  vtkMultiProcessController* controller = MultiProcessController();
  if (!gathered && controller)
  {
    vtkErrorWithObjectMacro(algorithm, << "runs in one process only (it does not run distributed yet), and this "
                                          "run has "
                                       << controller->GetNumberOfProcesses()
                                       << " (MPI): each rank would see only its piece of the cloud. Run it in one "
                                          "process (pvpython, or pvbatch without mpiexec), or on the merged cloud");
    return false;
  }
  if (!surface->Prepare(cloud, coordinateOrder))
  {
    vtkErrorWithObjectMacro(algorithm, << "cannot define the surface" << what << ": " << surface->GetLastError());
    return false;
  }
  const vtkIdType skipped = surface->GetNumberOfSkippedPoints();
  if (skipped > 0)
  {
    vtkWarningWithObjectMacro(algorithm, << skipped
                                         << " cloud point(s) with NaN or infinite coordinates were left out of the surface");
  }
  return true;
}

vtkMultiProcessController* MultiProcessController()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

bool PrepareDistributedSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface,
  vtkMultiProcessController* controller, vtkPointSet* cloud, const char* what, vtkSmartPointer<vtkPolyData>& gathered,
  bool coordinateOrder)
{
  if (!controller)
  {
    gathered = nullptr;
    return PrepareSurface(algorithm, surface, cloud, what, false, coordinateOrder);
  }
  // The whole cloud on every rank makes h, centroid, bounds and every neighbourhood those of the
  // one-process run by construction, whatever the split; with the point arrays the surface reads.
  // The normals also when the definition does not read them: the mesher orients by them.
  std::vector<std::string> arrays;
  const char* normals = surface->GetNormalsArrayName();
  if (normals && *normals)
  {
    arrays.emplace_back(normals);
  }
  const char* scales = surface->GetScaleArrayName();
  if (surface->GetPointScales() == vtkPointSetSurface::POINT_SCALES_FROM_ARRAY && scales && *scales)
  {
    arrays.emplace_back(scales);
  }
  gathered = GatherCloud(algorithm, controller, cloud, arrays);
  return gathered && PrepareSurface(algorithm, surface, gathered, what, true, coordinateOrder);
}

GatherLayout LayoutOfAllGather(vtkMultiProcessController* controller, vtkIdType length)
{
  GatherLayout layout;
  layout.Lengths.resize(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  controller->AllGather(&length, layout.Lengths.data(), 1);
  layout.Offsets.resize(layout.Lengths.size());
  for (std::size_t r = 0; r < layout.Lengths.size(); ++r)
  {
    layout.Offsets[r] = layout.Total;
    layout.Total += layout.Lengths[r];
  }
  return layout;
}

namespace
{

// Every rank's values of point array @p name (as doubles, ranks in order) into @p whole, when
// the ranks' points carry it. False (collectively, after an error) when some do and some do not.
bool GatherPointArray(vtkAlgorithm* algorithm, vtkMultiProcessController* controller, vtkPointSet* cloud,
  const std::string& name, vtkPolyData* whole)
{
  const vtkIdType n = cloud ? cloud->GetNumberOfPoints() : 0;
  vtkDataArray* local = n > 0 ? cloud->GetPointData()->GetArray(name.c_str()) : nullptr;
  const int components = local && local->GetNumberOfTuples() == n ? local->GetNumberOfComponents() : 0;
  // A rank without points has no say; the others must agree.
  const int mine[2] = { n > 0 ? components : -1, n > 0 ? -components : -VTK_INT_MAX };
  int agreed[2] = { 0, 0 };
  controller->AllReduce(mine, agreed, 2, vtkCommunicator::MAX_OP);
  const int most = agreed[0];
  const int least = -agreed[1];
  if (most <= 0)
  {
    return true; // no rank's points carry it (or no points at all): Prepare reports what is missing
  }
  if (least != most)
  {
    vtkErrorWithObjectMacro(algorithm, << "the point array \"" << name
                                       << "\" is on some ranks' pieces of the cloud only (or with other component "
                                          "counts): every piece needs it");
    return false;
  }
  std::vector<double> values(static_cast<std::size_t>(n) * static_cast<std::size_t>(components));
  for (vtkIdType i = 0; i < n; ++i)
  {
    local->GetTuple(i, values.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(components));
  }
  const vtkIdType sendLength = static_cast<vtkIdType>(values.size());
  GatherLayout layout = LayoutOfAllGather(controller, sendLength);
  auto all = vtkSmartPointer<vtkDoubleArray>::New();
  all->SetName(name.c_str());
  all->SetNumberOfComponents(components);
  all->SetNumberOfTuples(layout.Total / components);
  controller->AllGatherV(values.data(), all->GetPointer(0), sendLength, layout.Lengths.data(), layout.Offsets.data());
  whole->GetPointData()->AddArray(all);
  return true;
}

// The field data array @p name of the lowest rank whose cloud has it (at most 16 values), into
// @p whole.
void GatherFieldArray(vtkMultiProcessController* controller, vtkPointSet* cloud, const char* name, vtkPolyData* whole)
{
  constexpr int most = 16;
  double mine[most + 2] = {};
  vtkDataArray* a = cloud ? cloud->GetFieldData()->GetArray(name) : nullptr;
  if (a && a->GetNumberOfValues() > 0 && a->GetNumberOfValues() <= most)
  {
    mine[0] = a->GetNumberOfComponents();
    mine[1] = static_cast<double>(a->GetNumberOfTuples());
    for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k)
    {
      mine[2 + k] = a->GetComponent(k / a->GetNumberOfComponents(), static_cast<int>(k % a->GetNumberOfComponents()));
    }
  }
  std::vector<double> all(static_cast<std::size_t>((most + 2) * controller->GetNumberOfProcesses()));
  controller->AllGather(mine, all.data(), most + 2);
  for (std::size_t r = 0; r < all.size(); r += most + 2)
  {
    if (all[r] > 0.0)
    {
      auto copy = vtkSmartPointer<vtkDoubleArray>::New();
      copy->SetName(name);
      copy->SetNumberOfComponents(static_cast<int>(all[r]));
      copy->SetNumberOfTuples(static_cast<vtkIdType>(all[r + 1]));
      std::copy(all.begin() + static_cast<std::ptrdiff_t>(r + 2),
        all.begin() + static_cast<std::ptrdiff_t>(r + 2) + copy->GetNumberOfValues(), copy->GetPointer(0));
      whole->GetFieldData()->AddArray(copy);
      return;
    }
  }
}

} // namespace

vtkSmartPointer<vtkPolyData> GatherCloud(vtkAlgorithm* algorithm, vtkMultiProcessController* controller,
  vtkPointSet* cloud, const std::vector<std::string>& arrays)
{
  const vtkIdType n = cloud ? cloud->GetNumberOfPoints() : 0;
  std::vector<double> local(static_cast<std::size_t>(3 * n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    cloud->GetPoint(i, local.data() + 3 * i);
  }
  const vtkIdType sendLength = 3 * n;
  GatherLayout layout = LayoutOfAllGather(controller, sendLength);
  if (!layout.FitsOneMessage())
  {
    vtkErrorWithObjectMacro(algorithm, << "the cloud of all ranks (" << layout.Total / 3
                                       << " points) exceeds one MPI message (2^31 - 1 coordinates)");
    return nullptr;
  }
  auto coordinates = vtkSmartPointer<vtkDoubleArray>::New();
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(layout.Total / 3);
  if (layout.Total > 0)
  {
    controller->AllGatherV(
      local.data(), coordinates->GetPointer(0), sendLength, layout.Lengths.data(), layout.Offsets.data());
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  auto whole = vtkSmartPointer<vtkPolyData>::New();
  whole->SetPoints(points);
  for (const std::string& name : arrays)
  {
    if (!GatherPointArray(algorithm, controller, cloud, name, whole))
    {
      return nullptr;
    }
  }
  for (const char* name : { "Viewpoint", "GridDimensions" })
  {
    GatherFieldArray(controller, cloud, name, whole);
  }
  return whole;
}

namespace
{

// The centroid of the finite points of every rank as one process computes it: one sum over the
// points in rank order, each rank carrying on from the previous rank's partial sum (a chain of
// N - 1 messages), so the result is bitwise the one-process PointIndex::centroid().
void ChainedCentroid(vtkMultiProcessController* controller, const GhostRun& run, double count, double centroid[3])
{
  constexpr int tag = 916016;
  const int ranks = controller->GetNumberOfProcesses();
  const int me = controller->GetLocalProcessId();
  double sum[3] = { 0.0, 0.0, 0.0 };
  if (me > 0)
  {
    controller->Receive(sum, 3, me - 1, tag);
  }
  const int axes = run.Dimension == 2 ? 2 : 3; // PointIndex sums 2D points with z = 0
  for (std::size_t i = 0; i < run.Own.size(); i += 3)
  {
    for (int a = 0; a < axes; ++a)
    {
      sum[a] += run.Own[i + static_cast<std::size_t>(a)];
    }
  }
  if (me + 1 < ranks)
  {
    controller->Send(sum, 3, me + 1, tag);
  }
  controller->Broadcast(sum, 3, ranks - 1);
  for (int a = 0; a < 3; ++a)
  {
    centroid[a] = sum[a] / count;
  }
}

// The automatic h of the one-process run: the finite points gathered on rank 0 in rank order
// (the order one process indexes them in), its index and estimateScale there, broadcast. Rank 0
// holds the whole cloud meanwhile. h is 0 on every rank when the estimate is 0, -1 when the
// cloud is too large for one message. With PointScales Automatic, spread is the spread of the
// scales per point one process would estimate (0 otherwise): what decides whether it takes them.
struct RootScale
{
  double h = 0.0;
  double spread = 0.0;
};

RootScale RootAutomaticScale(vtkMultiProcessController* controller, vtkPointSetSurface* surface, const GhostRun& run)
{
  const vtkIdType length = static_cast<vtkIdType>(run.Own.size());
  GatherLayout layout = LayoutOfAllGather(controller, length);
  if (!layout.FitsOneMessage())
  {
    return { -1.0, 0.0 };
  }
  const bool root = controller->GetLocalProcessId() == 0;
  std::vector<double> all(root ? static_cast<std::size_t>(layout.Total) : 0);
  controller->GatherV(run.Own.data(), all.data(), length, layout.Lengths.data(), layout.Offsets.data(), 0);
  double result[2] = { 0.0, 0.0 }; // h, spread
  if (root)
  {
    std::vector<pss::Vec3> points(all.size() / 3);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      points[i] = pss::Vec3(all[3 * i], all[3 * i + 1], all[3 * i + 2]);
    }
    all = std::vector<double>();
    const int threads = CoreThreads();
    const pss::PointIndex index(std::move(points), run.Dimension, threads);
    result[0] = pss::estimateScale(index, surface->GetScaleNeighbors(), surface->GetScaleMultiplier(), threads);
    const int k = surface->GetScaleNeighbors();
    if (surface->GetPointScales() == vtkPointSetSurface::POINT_SCALES_AUTOMATIC && index.size() > static_cast<std::size_t>(k))
    {
      result[1] = surface->EstimateScaleSpread(index, threads);
    }
  }
  controller->Broadcast(result, 2, 0);
  return { result[0], result[1] };
}

} // namespace

bool BeginGhostRun(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkMultiProcessController* controller,
  vtkPointSet* cloud, GhostRun& run)
{
  if (!surface)
  {
    vtkErrorWithObjectMacro(algorithm, << "no vtkPointSetSurface is set");
    return false;
  }
  run.Own.clear();
  const vtkIdType n = cloud ? cloud->GetNumberOfPoints() : 0;
  run.Own.reserve(static_cast<std::size_t>(3 * n));
  // Counts (all, finite) and bounds: one reduction each.
  double counts[2] = { static_cast<double>(n), 0.0 };
  double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    cloud->GetPoint(i, p);
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      continue;
    }
    run.Own.insert(run.Own.end(), p, p + 3);
    counts[1] += 1.0;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  double total[2];
  controller->AllReduce(counts, total, 2, vtkCommunicator::SUM_OP);
  controller->AllReduce(lo, run.Lo, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(hi, run.Hi, 3, vtkCommunicator::MAX_OP);
  if (total[0] == 0.0 || total[1] == 0.0)
  {
    vtkErrorWithObjectMacro(algorithm, << "cannot define the surface: "
                                       << (total[0] == 0.0 ? "the point cloud is empty"
                                                           : "the point cloud has no point with finite coordinates"));
    return false;
  }
  const int asked = surface->GetDimension();
  run.Dimension = asked == vtkPointSetSurface::DIMENSION_AUTO
    ? pss::detectDimension(pss::Vec3(run.Lo[0], run.Lo[1], run.Lo[2]), pss::Vec3(run.Hi[0], run.Hi[1], run.Hi[2]))
    : asked;
  ChainedCentroid(controller, run, total[1], run.Centroid);
  run.H = surface->GetScaleFactor();
  if (surface->GetAutomaticScale() && (run.Dimension == 2 || run.Dimension == 3))
  {
    const RootScale scale = RootAutomaticScale(controller, surface, run);
    run.H = scale.h;
    if (!(run.H > 0.0))
    {
      if (run.H < 0.0)
      {
        vtkErrorWithObjectMacro(algorithm, << "cannot define the surface: the automatic scale needs the whole cloud ("
                                           << static_cast<vtkIdType>(total[1])
                                           << " points) on rank 0, more than one MPI message holds (2^31 - 1 "
                                              "coordinates): turn AutomaticScale off and set ScaleFactor");
      }
      else
      {
        vtkErrorWithObjectMacro(algorithm, << "cannot define the surface: the automatic scale is 0: the "
                                           << static_cast<vtkIdType>(total[1]) << " finite points have fewer than "
                                           << surface->GetScaleNeighbors() + 1
                                           << " distinct positions around most points (duplicates?); set "
                                              "ScaleFactor and turn AutomaticScale off");
      }
      return false;
    }
    // Where one process would take a scale per point, one h would be another surface (a depth
    // frame's mesh in hundreds of pieces): refused alike on every rank, as Estimated is.
    int sensor = pss_vtk::IsSensorFrame(cloud) ? 1 : 0;
    int anySensor = 0;
    controller->AllReduce(&sensor, &anySensor, 1, vtkCommunicator::MAX_OP);
    if (surface->GetPointScales() == vtkPointSetSurface::POINT_SCALES_AUTOMATIC &&
      surface->AutomaticTakesPointScales(anySensor != 0, scale.spread))
    {
      std::ostringstream why;
      if (anySensor)
        why << "it is a sensor frame: field data GridDimensions or Viewpoint";
      else
        why << "its scales spread " << scale.spread << " times, above ScaleSpreadThreshold "
            << surface->GetScaleSpreadThreshold();
      vtkErrorWithObjectMacro(algorithm, << "cannot define the surface: one process would take a scale per point here ("
                                         << why.str()
                                         << "), which a run with ghost points (GhostMargin > 0) does not support "
                                            "yet: set GhostMargin 0 (the gathered cloud, which does) or PointScales "
                                            "Off (one h)");
      return false;
    }
  }
  // Every rank, whatever it holds: a rank that asks for no ghost points never prepares a surface,
  // and must not wait in a collective that the ranks refusing the parameters never reach.
  if (!surface->CheckParameters(run.Dimension, run.H))
  {
    vtkErrorWithObjectMacro(algorithm, << "cannot define the surface: " << surface->GetLastError());
    return false;
  }
  const double skipped = total[0] - total[1];
  if (skipped > 0.0)
  {
    vtkWarningWithObjectMacro(algorithm, << static_cast<vtkIdType>(skipped)
                                         << " cloud point(s) with NaN or infinite coordinates were left out of the surface");
  }
  return true;
}

bool PrepareGhostSurface(vtkAlgorithm* algorithm, vtkPointSetSurface* surface,
  vtkMultiProcessController* controller, GhostRun& run, const double lo[3], const double hi[3])
{
  if (!surface)
  {
    vtkErrorWithObjectMacro(algorithm, << "no vtkPointSetSurface is set");
    return false;
  }
  const int ranks = controller->GetNumberOfProcesses();
  const int me = controller->GetLocalProcessId();
  const double box[6] = { lo[0], lo[1], lo[2], hi[0], hi[1], hi[2] };
  std::vector<double> boxes(static_cast<std::size_t>(6 * ranks));
  controller->AllGather(box, boxes.data(), 6);
  // What this rank sends each other rank: its own points inside that rank's box.
  std::vector<std::vector<double>> outgoing(static_cast<std::size_t>(ranks));
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
  for (int r = 0; r < ranks; ++r)
  {
    const double* b = &boxes[static_cast<std::size_t>(6 * r)];
    if (r == me || !(b[0] <= b[3]))
    {
      continue;
    }
    std::vector<double>& out = outgoing[static_cast<std::size_t>(r)];
    for (std::size_t i = 0; i < run.Own.size(); i += 3)
    {
      const double* p = &run.Own[i];
      if (p[0] >= b[0] && p[0] <= b[3] && p[1] >= b[1] && p[1] <= b[4] && p[2] >= b[2] && p[2] <= b[5])
      {
        out.insert(out.end(), p, p + 3);
      }
    }
    lengths[static_cast<std::size_t>(r)] = static_cast<vtkIdType>(out.size());
  }
  std::vector<vtkIdType> all(static_cast<std::size_t>(ranks * ranks));
  controller->AllGather(lengths.data(), all.data(), ranks);
  // Row s of all: what rank s sends to each rank. MPI counts are ints: every rank sees the sums.
  for (int r = 0; r < ranks; ++r)
  {
    vtkIdType incoming = 0;
    for (int s2 = 0; s2 < ranks; ++s2)
    {
      incoming += all[static_cast<std::size_t>(s2 * ranks + r)];
    }
    if (incoming > vtkIdType(INT_MAX))
    {
      vtkErrorWithObjectMacro(algorithm, << "rank " << r << "'s ghost points (" << incoming / 3
                                         << ") exceed one MPI message (2^31 - 1 coordinates): lower GhostMargin");
      return false;
    }
  }
  std::vector<double> local = run.Own;
  for (int r = 0; r < ranks; ++r)
  {
    std::vector<vtkIdType> counts(static_cast<std::size_t>(ranks));
    std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks));
    vtkIdType total = 0;
    for (int s2 = 0; s2 < ranks; ++s2)
    {
      counts[static_cast<std::size_t>(s2)] = all[static_cast<std::size_t>(s2 * ranks + r)];
      offsets[static_cast<std::size_t>(s2)] = total;
      total += counts[static_cast<std::size_t>(s2)];
    }
    if (total == 0)
    {
      continue; // every rank knows it: no message at all
    }
    std::vector<double> received(r == me ? static_cast<std::size_t>(total) : 0);
    const std::vector<double>& out = outgoing[static_cast<std::size_t>(r)];
    controller->GatherV(out.data(), received.data(), static_cast<vtkIdType>(out.size()), counts.data(),
      offsets.data(), r);
    local.insert(local.end(), received.begin(), received.end());
  }
  if (!(lo[0] <= hi[0]))
  {
    return true; // this rank asked for nothing: its surface stays as it is
  }
  run.Ghosts = static_cast<vtkIdType>((local.size() - run.Own.size()) / 3);
  // The box is complete; a side beyond the cloud's bounds is open (no point lies past it).
  const double inf = std::numeric_limits<double>::infinity();
  double regionLo[3];
  double regionHi[3];
  for (int a = 0; a < 3; ++a)
  {
    regionLo[a] = lo[a] <= run.Lo[a] ? -inf : lo[a];
    regionHi[a] = hi[a] >= run.Hi[a] ? inf : hi[a];
  }
  if (!surface->PreparePiece(local, run.Dimension, regionLo, regionHi, run.H))
  {
    vtkErrorWithObjectMacro(algorithm, << "cannot define the surface: " << surface->GetLastError());
    return false;
  }
  return true;
}

namespace
{
// The box of the finite points @p ks, grown by @p margin (lo > hi: none).
void GrownBounds(const GhostPointAt& pointAt, const std::vector<std::uint32_t>& ks, double margin, double lo[3],
  double hi[3])
{
  std::fill(lo, lo + 3, VTK_DOUBLE_MAX);
  std::fill(hi, hi + 3, -VTK_DOUBLE_MAX);
  for (std::uint32_t k : ks)
  {
    double p[3];
    pointAt(k, p);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], p[a] - margin);
        hi[a] = std::max(hi[a], p[a] + margin);
      }
    }
  }
}
} // namespace

int RunGhostRounds(vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkMultiProcessController* controller,
  GhostRun& run, double margin, std::vector<std::uint32_t> ks, std::size_t n, const GhostPointAt& pointAt,
  const GhostEvaluation& evaluate)
{
  std::vector<unsigned char> escaped(n, 0);
  double lo[3];
  double hi[3];
  GrownBounds(pointAt, ks, margin, lo, hi);
  for (int round = 1;; ++round)
  {
    // A rank that fails (to build its piece's surface, or to evaluate) still takes part in the
    // round's reduction, so that every rank stops with it.
    bool failed = !PrepareGhostSurface(algorithm, surface, controller, run, lo, hi);
    if (!failed && surface->GetDefinition() && !ks.empty())
    {
      failed = !evaluate(ks, escaped);
    }
    else if (!failed)
    {
      for (std::uint32_t k : ks)
      {
        escaped[k] = 1; // no cloud point within reach yet
      }
    }
    std::vector<std::uint32_t> again;
    for (std::uint32_t k : ks)
    {
      if (escaped[k])
      {
        again.push_back(k);
      }
    }
    const vtkIdType local[2] = { failed ? 0 : static_cast<vtkIdType>(again.size()), failed ? 1 : 0 };
    vtkIdType total[2] = { 0, 0 };
    controller->AllReduce(local, total, 2, vtkCommunicator::SUM_OP);
    if (total[1] > 0)
    {
      if (!failed)
      {
        vtkErrorWithObjectMacro(algorithm, << "another rank failed (see its error)");
      }
      return 0;
    }
    if (total[0] == 0)
    {
      return round;
    }
    margin *= 2.0;
    GrownBounds(pointAt, again, margin, lo, hi);
    if (!(lo[0] <= hi[0]) && !again.empty())
    {
      // Only NaN/Inf points are left, on a rank without a surface yet: they need one to be
      // flagged as such, so this rank takes the whole cloud (rare: no cloud point within reach).
      std::copy(run.Lo, run.Lo + 3, lo);
      std::copy(run.Hi, run.Hi + 3, hi);
    }
    ks = std::move(again);
  }
}

void AddGhostFieldData(vtkDataObject* output, int rounds, const GhostRun& run)
{
  auto roundsArray = NewArray<vtkIntArray>("GhostRounds", 1, 1);
  roundsArray->SetValue(0, rounds);
  output->GetFieldData()->AddArray(roundsArray);
  auto count = NewArray<vtkIdTypeArray>("GhostPoints", 1, 1);
  count->SetValue(0, run.Ghosts);
  output->GetFieldData()->AddArray(count);
}

void AddGlobalPointIds(vtkPointData* pd, vtkIdType first, vtkIdType n)
{
  if (pd->GetGlobalIds())
  {
    return;
  }
  auto ids = NewArray<vtkIdTypeArray>("GlobalPointIds", n, 1);
  for (vtkIdType i = 0; i < n; ++i)
  {
    ids->SetValue(i, first + i);
  }
  pd->SetGlobalIds(ids);
}

vtkIdType GlobalOffset(vtkMultiProcessController* controller, vtkIdType count)
{
  return LayoutOfAllGather(controller, count).Offsets[static_cast<std::size_t>(controller->GetLocalProcessId())];
}

bool AgreeOnInputs(vtkAlgorithm* algorithm, vtkMultiProcessController* controller, const std::string& upstreamError)
{
  const int local = upstreamError.empty() ? 0 : 1;
  std::vector<int> failed(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  controller->AllGather(&local, failed.data(), 1);
  std::ostringstream ranks;
  for (std::size_t r = 0; r < failed.size(); ++r)
  {
    if (failed[r])
    {
      ranks << (ranks.tellp() > 0 ? ", " : "") << r;
    }
  }
  if (ranks.tellp() == 0)
  {
    return true;
  }
  // The same words on every rank; the upstream error itself is in the log of the rank(s) named.
  vtkErrorWithObjectMacro(algorithm, << "the pipeline upstream reported an error on rank(s) " << ranks.str()
                                     << " during this update, so their pieces of the input may be incomplete: every "
                                        "rank stops (see the error in those ranks' log)");
  return false;
}

bool UpstreamSucceededEverywhere(vtkAlgorithm* algorithm, vtkInformationVector** inputVector,
  vtkMultiProcessController* controller, UpstreamErrorWatch& watch)
{
  std::vector<vtkDataObject*> inputs;
  for (int port = 0; port < algorithm->GetNumberOfInputPorts(); ++port)
  {
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
    {
      inputs.push_back(inputVector[port]->GetInformationObject(c)->Get(vtkDataObject::DATA_OBJECT()));
    }
  }
  // Checked in every run (also in one process), so that the watch is disarmed and what it saw is
  // recorded; only a distributed run refuses on it.
  const std::string error = watch.Check(inputs);
  return !controller || AgreeOnInputs(algorithm, controller, error);
}

pss::StageSplit SplitAcrossRanks(vtkMultiProcessController* controller, bool& tooLarge)
{
  pss::StageSplit split;
  split.part = controller->GetLocalProcessId();
  split.parts = controller->GetNumberOfProcesses();
  const int me = split.part;
  const int parts = split.parts;
  split.share = [controller, &tooLarge, me, parts](
                  std::vector<double>& items, std::size_t width, std::size_t count, bool completed) {
    int mine = completed ? 1 : 0;
    int all = 0;
    controller->AllReduce(&mine, &all, 1, vtkCommunicator::MIN_OP);
    if (!all)
    {
      return false;
    }
    if (count * width > static_cast<std::size_t>(INT_MAX)) // the same count on every rank
    {
      tooLarge = true;
      return false;
    }
    std::vector<vtkIdType> lengths(static_cast<std::size_t>(parts));
    std::vector<vtkIdType> offsets(lengths.size());
    for (int r = 0; r < parts; ++r)
    {
      const pss::StageSplit part{ r, parts, nullptr };
      offsets[static_cast<std::size_t>(r)] = static_cast<vtkIdType>(part.begin(count) * width);
      lengths[static_cast<std::size_t>(r)] = static_cast<vtkIdType>((part.end(count) - part.begin(count)) * width);
    }
    const auto first = items.begin() + offsets[static_cast<std::size_t>(me)];
    const std::vector<double> own(first, first + lengths[static_cast<std::size_t>(me)]);
    controller->AllGatherV(
      own.data(), items.data(), static_cast<vtkIdType>(own.size()), lengths.data(), offsets.data());
    return true;
  };
  return split;
}

bool GatherCellKeys(vtkMultiProcessController* controller, const std::vector<std::uint64_t>& own,
  std::vector<std::uint64_t>& all, bool& tooLarge)
{
  const vtkIdType length = static_cast<vtkIdType>(own.size());
  GatherLayout layout = LayoutOfAllGather(controller, length);
  if (!layout.FitsOneMessage())
  {
    tooLarge = true;
    return false;
  }
  // Keys are below 2^60, so they travel as vtkIdType (64-bit) unchanged.
  const std::vector<vtkIdType> mine(own.begin(), own.end());
  std::vector<vtkIdType> received(static_cast<std::size_t>(layout.Total));
  controller->AllGatherV(mine.data(), received.data(), length, layout.Lengths.data(), layout.Offsets.data());
  all.assign(received.begin(), received.end());
  return true;
}

}

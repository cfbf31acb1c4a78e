// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesDistributedRun.h"
#include "PointSetSurfacesSMP.h"
#include "PointSetSurfacesVTKUtilities.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkPoints.h"
#include "vtkPointSetSurface.h"

#include "pss/DeltaLattice.h"
#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace pss_vtk
{

DistributedRun::DistributedRun(
  vtkAlgorithm* algorithm, vtkPointSetSurface* surface, vtkMultiProcessController* controller, double ghostMargin)
  : Algorithm(algorithm)
  , Surface(surface)
  , Controller(controller)
  , Margin(ghostMargin)
  , Ghosts(controller && ghostMargin > 0.0)
{
}

bool DistributedRun::Prepare(vtkInformationVector** inputVector, UpstreamErrorWatch& watch, vtkPointSet* cloud,
  const char* what, vtkSmartPointer<vtkPolyData>& gathered)
{
  if (!UpstreamSucceededEverywhere(this->Algorithm, inputVector, this->Controller, watch))
  {
    return false;
  }
  if (this->Ghosts)
  {
    return BeginGhostRun(this->Algorithm, this->Surface, this->Controller, cloud, this->Ghost);
  }
  return PrepareDistributedSurface(
    this->Algorithm, this->Surface, this->Controller, cloud, what, gathered, this->Margin > 0.0);
}

vtkIdType DistributedRun::FirstGlobalId(vtkIdType count)
{
  return this->Controller ? GlobalOffset(this->Controller, count) : 0;
}

bool DistributedRun::Evaluate(
  std::vector<std::uint32_t> order, std::size_t n, const GhostPointAt& pointAt, const GhostEvaluation& evaluate)
{
  if (!this->Ghosts)
  {
    std::vector<unsigned char> none;
    return evaluate(order, none);
  }
  const int rounds = RunGhostRounds(this->Algorithm, this->Surface, this->Controller, this->Ghost,
    this->Margin * this->Ghost.H, std::move(order), n, pointAt, evaluate);
  this->Rounds = std::max(this->Rounds, rounds);
  return rounds > 0;
}

bool DistributedRun::EvaluateAll(std::size_t n, const GhostPointAt& pointAt, const GhostEvaluation& evaluate)
{
  std::vector<std::uint32_t> all(this->Ghosts ? n : 0);
  std::iota(all.begin(), all.end(), 0u);
  return this->Evaluate(std::move(all), n, pointAt, evaluate);
}

double DistributedRun::MaximumOverRanks(double value)
{
  double all = value;
  if (this->Controller)
  {
    this->Controller->AllReduce(&value, &all, 1, vtkCommunicator::MAX_OP);
  }
  return all;
}

bool DistributedRun::LatticeServes(vtkPoints* starts)
{
  const int variant = this->Surface->GetVariant();
  if (!(this->Surface->GetDeltaLatticeSpacing() > 0.0) ||
    (variant != vtkPointSetSurface::INTEGRAL && variant != vtkPointSetSurface::DELTA))
  {
    return true; // the same answer on every rank: no collective needed
  }
  const pss::SurfaceDefinition* definition = this->Surface->GetDefinition();
  vtkIdType count = starts ? starts->GetNumberOfPoints() : 0;
  std::vector<std::uint64_t> keys;
  if (definition && count > 0)
  {
    keys = pss::latticeBrickKeys(ToVectors(starts, CoreThreads()), definition->index(), definition->parameters());
  }
  if (this->Controller)
  {
    bool tooLarge = false;
    std::vector<std::uint64_t> all;
    if (!GatherCellKeys(this->Controller, keys, all, tooLarge))
    {
      return true; // beyond one message on every rank alike: far more starts than a scattered set
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    keys = std::move(all);
    vtkIdType total = count;
    this->Controller->AllReduce(&count, &total, 1, vtkCommunicator::SUM_OP);
    count = total;
  }
  return pss::latticeServes(static_cast<std::size_t>(count), keys.size());
}

double DistributedRun::GetScale() const
{
  return this->Ghosts ? this->Ghost.H : this->Surface->GetEffectiveScale();
}

int DistributedRun::GetDimension() const
{
  return this->Ghosts ? this->Ghost.Dimension : this->Surface->GetDefinition()->dimension();
}

pss::Vec3 DistributedRun::GetCentroid() const
{
  return this->Ghosts ? pss::Vec3(this->Ghost.Centroid[0], this->Ghost.Centroid[1], this->Ghost.Centroid[2])
                      : this->Surface->GetIndex()->centroid();
}

void DistributedRun::AttachSurfaceFieldData(vtkDataObject* output) const
{
  if (this->Ghosts)
  {
    AddSurfaceFieldData(output, this->Ghost.H, this->Ghost.Dimension);
  }
  else
  {
    AddSurfaceFieldData(output, this->Surface);
  }
}

void DistributedRun::AttachGhostFieldData(vtkDataObject* output) const
{
  if (this->Ghosts)
  {
    AddGhostFieldData(output, this->Rounds, this->Ghost);
  }
}

void DistributedRun::AttachGlobalIds(vtkPointData* pd, vtkIdType first, vtkIdType n) const
{
  if (this->Controller)
  {
    AddGlobalPointIds(pd, first, n);
  }
}

}

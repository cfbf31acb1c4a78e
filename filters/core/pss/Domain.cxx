// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Domain.h"

#include "pss/Kernel.h"
#include "pss/Workspace.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pss
{

const char* domainLabelName(DomainLabel label)
{
  switch (label)
  {
    case DomainLabel::InDomain:
      return "InDomain";
    case DomainLabel::Spurious:
      return "Spurious";
    case DomainLabel::Undefined:
      return "Undefined";
    case DomainLabel::NotConverged:
      return "NotConverged";
  }
  return "Unknown";
}

void DomainThresholds::validate() const
{
  if (!(maxDistance > 0.0) || !std::isfinite(maxDistance))
  {
    throw std::invalid_argument("the domain distance threshold must be a positive finite multiple of h");
  }
  if (!(maxNormalAngle >= 0.0 && maxNormalAngle <= 90.0))
  {
    throw std::invalid_argument("the domain normal-angle threshold must be in [0, 90] degrees");
  }
  if (!(maxBorderOffset >= 0.0) || !std::isfinite(maxBorderOffset))
  {
    throw std::invalid_argument("the domain border-offset threshold must be 0 (off) or a positive multiple of h");
  }
}

double unorientedAngleDegrees(const Vec3& a, const Vec3& b)
{
  const double na = a.norm();
  const double nb = b.norm();
  if (na == 0.0 || nb == 0.0)
  {
    return 90.0;
  }
  const double c = std::min(1.0, std::abs(a.dot(b)) / (na * nb));
  return std::acos(c) * 180.0 / M_PI;
}

Direction cloudNormalAt(const SurfaceDefinition& s, std::size_t point, Workspace& ws)
{
  if (s.index().hasNormals())
  {
    // A cloud with normals (APSS, RIMLS) brings its own.
    Direction given;
    given.n = s.index().normal(point);
    given.stability = 1.0;
    given.defined = true;
    return given;
  }
  return centreOfMassNormal(s.index(), s.parameters(), s.index().point(point), ws);
}

Direction centreOfMassNormal(const PointIndex& index, const SurfaceParameters& params, const Vec3& x, Workspace& ws)
{
  // The weighted total-least-squares plane of the neighbours.
  Neighbourhood& nb = ws.local;
  gatherNeighbourhood(index, params, x, nb, ws);
  return smallestEigenDirection(covarianceAboutCentroid(nb), index.dimension(), params.minStability);
}

CloudNormals::CloudNormals(const SurfaceDefinition& s)
  : Surface(s)
  , Normal(s.index().size())
  , State(std::make_unique<std::atomic<std::uint8_t>[]>(s.index().size()))
{
  for (std::size_t i = 0; i < s.index().size(); ++i)
  {
    State[i].store(0, std::memory_order_relaxed);
  }
}

Direction CloudNormals::at(std::size_t point, Workspace& ws) const
{
  std::atomic<std::uint8_t>& state = State[point];
  const std::uint8_t stored = state.load(std::memory_order_acquire);
  if (stored >= 2)
  {
    ws.leftCompleteRegion = ws.leftCompleteRegion || stored == 3;
    return Normal[point];
  }
  // Whether this normal's own reads left the region, apart from what ws had flagged before.
  const bool flaggedBefore = ws.leftCompleteRegion;
  ws.leftCompleteRegion = false;
  const Direction d = cloudNormalAt(Surface, point, ws);
  const bool escaped = ws.leftCompleteRegion;
  ws.leftCompleteRegion = flaggedBefore || escaped;
  std::uint8_t expected = 0;
  // Only the thread that claims the slot writes it; one that finds it being written keeps its own
  // copy (the same value).
  if (state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel))
  {
    Normal[point] = d;
    state.store(escaped ? 3 : 2, std::memory_order_release);
  }
  return d;
}

DomainEvidence classifyStart(const SurfaceDefinition& s, const Vec3& start, const ProjectionOptions& options,
  const DomainThresholds& thresholds, Workspace& ws, const CloudNormals* normals)
{
  DomainEvidence ev;
  ev.projection = project(s, start, options, ws);
  const ProjectionResult& r = ev.projection;
  ev.startStability = r.startDirection.stability;
  switch (r.reason)
  {
    case StopReason::InvalidInput:
    case StopReason::UndefinedDirection:
      ev.label = DomainLabel::Undefined;
      return ev;
    case StopReason::MaxIterations:
    case StopReason::NoExtremum:
      ev.label = DomainLabel::NotConverged;
      return ev;
    case StopReason::Converged:
      break;
  }

  const PointIndex& index = s.index();
  const auto nearest = index.nearest(r.point);
  noteReach(index, index.restrict(r.point), nearest.second, ws);
  ev.distanceToCloud = std::sqrt(nearest.second);
  ev.startAngle = unorientedAngleDegrees(r.startDirection.n, r.direction.n);

  // The cloud's own normal where the projection landed, at the nearest cloud point.
  const Direction cloudNormal = normals ? normals->at(nearest.first, ws) : cloudNormalAt(s, nearest.first, ws);
  ev.normalAngle = unorientedAngleDegrees(r.direction.n, cloudNormal.n);

  // In units of the nearest point's own scale when the cloud has one per point.
  const double h = index.hasScales() ? index.scale(nearest.first) : s.h();
  const bool far = ev.distanceToCloud > thresholds.maxDistance * h;
  const bool misaligned = cloudNormal.defined && ev.normalAngle > thresholds.maxNormalAngle;
  bool past = false;
  if (thresholds.maxBorderOffset > 0.0 && !far)
  {
    gatherNeighbourhood(index, s.parameters(), r.point, ws.local, ws);
    const Vec3 offset = centroidOffset(ws.local);
    const Vec3& n = r.direction.n;
    ev.borderOffset = (offset - offset.dot(n) * n).norm() / (index.hasScales() ? ws.local.localScale : s.h());
    past = ev.borderOffset > thresholds.maxBorderOffset;
  }
  ev.label = far || misaligned || past ? DomainLabel::Spurious : DomainLabel::InDomain;
  return ev;
}

} // namespace pss

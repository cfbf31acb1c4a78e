// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Domain.h"

#include "pss/Kernel.h"

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

DomainEvidence classifyStart(
  const SurfaceDefinition& s, const Vec3& start, const ProjectionOptions& options, const DomainThresholds& thresholds)
{
  DomainEvidence ev;
  ev.projection = project(s, start, options);
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
  ev.distanceToCloud = std::sqrt(nearest.second);
  ev.startAngle = unorientedAngleDegrees(r.startDirection.n, r.direction.n);

  // The cloud's own normal where the projection landed: the weighted total-least-squares plane
  // of the neighbours of the nearest cloud point.
  thread_local Neighbourhood nb;
  gatherNeighbourhood(index, s.parameters(), index.point(nearest.first), nb);
  const Direction cloudNormal =
    smallestEigenDirection(covarianceAboutCentroid(nb), s.dimension(), s.parameters().minStability);
  ev.normalAngle = unorientedAngleDegrees(r.direction.n, cloudNormal.n);

  const bool far = ev.distanceToCloud > thresholds.maxDistance * s.h();
  const bool misaligned = cloudNormal.defined && ev.normalAngle > thresholds.maxNormalAngle;
  ev.label = far || misaligned ? DomainLabel::Spurious : DomainLabel::InDomain;
  return ev;
}

} // namespace pss

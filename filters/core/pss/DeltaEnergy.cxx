// SPDX-License-Identifier: BSD-3-Clause
#include "pss/DirectionRulesAndEnergies.h"

namespace pss
{

DeltaEnergy::DeltaEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Field(index, params)
{
}

LineSample DeltaEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  LineSample out;
  const DeltaJet jet = Field.jet(y, a, ws, &out.nearestSqDist);
  out.value = jet.value;
  out.slope = a.dot(jet.gradient);
  out.curvature = jet.curvature;
  return out;
}

} // namespace pss

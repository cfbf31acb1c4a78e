// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

DeltaEnergy::DeltaEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Field(index, params)
{
}

LineSample DeltaEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  Vec3 gradient;
  LineSample out;
  out.value = Field.deltaAndGradient(y, ws, gradient, &out.nearestSqDist);
  out.slope = a.dot(gradient);
  return out;
}

} // namespace pss

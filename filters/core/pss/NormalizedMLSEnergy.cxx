// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"
#include "pss/Workspace.h"

namespace pss
{

NormalizedMLSEnergy::NormalizedMLSEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
}

LineSample NormalizedMLSEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  Neighbourhood& nb = ws.query;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  // e = N / W with N = sum w_i s_i^2 and W = sum w_i; quotient rule with the derivatives of
  // MLSEnergy::lineSample, dW/dt = sum w_i 2 s_i / h^2 and d2W/dt2 = sum w_i (4 s_i^2 / h^4 - 2 / h^2).
  const LineMoments m = lineMoments(nb, a);
  const double k = nb.invH2;
  const double w = nb.weightSum;
  const double n = m.s2;
  const double dn = 2.0 * k * m.s3 - 2.0 * m.s1;
  const double ddn = 4.0 * k * k * m.s4 - 10.0 * k * m.s2 + 2.0 * w;
  const double dw = 2.0 * k * m.s1;
  const double ddw = 4.0 * k * k * m.s2 - 2.0 * k * w;
  LineSample out;
  out.value = n / w;
  out.slope = dn / w - n * dw / (w * w);
  out.curvature = ddn / w - 2.0 * dn * dw / (w * w) - n * ddw / (w * w) + 2.0 * n * dw * dw / (w * w * w);
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss

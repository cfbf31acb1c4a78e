// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

LineSample NormalizedMLS::lineSample(const Vec3& y, const Vec3& a) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, y, nb);
  // e = N / W with N = sum w_i s_i^2 and W = sum w_i; quotient rule with the derivatives of
  // LevinMLS::lineSample, dW/dt = sum w_i 2 s_i / h^2 and d2W/dt2 = sum w_i (4 s_i^2 / h^4 - 2 / h^2).
  const auto s = nb.along(a);
  const double k = nb.invH2;
  const double n = (nb.w() * s.square()).sum();
  const double dn = (nb.w() * (2.0 * k * s.cube() - 2.0 * s)).sum();
  const double ddn = (nb.w() * (4.0 * k * k * s.square().square() - 10.0 * k * s.square() + 2.0)).sum();
  const double dw = 2.0 * k * (nb.w() * s).sum();
  const double ddw = (nb.w() * (4.0 * k * k * s.square() - 2.0 * k)).sum();
  const double w = nb.weightSum;
  LineSample out;
  out.value = n / w;
  out.slope = dn / w - n * dw / (w * w);
  out.curvature = ddn / w - 2.0 * dn * dw / (w * w) - n * ddw / (w * w) + 2.0 * n * dw * dw / (w * w * w);
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss

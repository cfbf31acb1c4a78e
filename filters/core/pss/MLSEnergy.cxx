// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"
#include "pss/Workspace.h"

namespace pss
{

MLSEnergy::MLSEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
}

LineSample MLSEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  Neighbourhood& nb = ws.query;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  // Eq. 1 along y + t a: with s_i = <a, p_i - y>, d theta_i/dt = theta_i 2 s_i / h^2 and
  // d s_i/dt = -1, so d/dt sum theta_i s_i^2 = sum theta_i (2 s_i^3 / h^2 - 2 s_i), and once more
  // d2/dt2 = sum theta_i (4 s_i^4 / h^4 - 10 s_i^2 / h^2 + 2).
  LineSample out;
  const LineMoments m = lineMoments(nb, a);
  const double k = nb.invH2;
  out.value = m.s2;
  out.slope = 2.0 * k * m.s3 - 2.0 * m.s1;
  out.curvature = 4.0 * k * k * m.s4 - 10.0 * k * m.s2 + 2.0 * nb.weightSum;
  out.logScale = nb.logScale();
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss

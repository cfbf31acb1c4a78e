// SPDX-License-Identifier: BSD-3-Clause
// The energy of Eq. 1 with the plain Gaussian weights (Levin) and with normalized ones.
#include "pss/DirectionRulesAndEnergies.h"
#include "pss/Workspace.h"

namespace pss
{

MLSEnergy::MLSEnergy(const PointIndex& index, const SurfaceParameters& params, Weights weights)
  : Index(index)
  , Params(params)
  , Weighting(weights)
{
}

LineSample MLSEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  Neighbourhood& nb = ws.query;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  // N(t) = sum theta_i s_i^2 along y + t a, in the shifted weights: with s_i = <a, p_i - y>,
  // d theta_i/dt = theta_i 2 s_i / h^2 and d s_i/dt = -1, so dN/dt = sum theta_i (2 s_i^3 / h^2 - 2 s_i)
  // and d2N/dt2 = sum theta_i (4 s_i^4 / h^4 - 10 s_i^2 / h^2 + 2).
  const LineMoments m = lineMoments(nb, a);
  const double w = nb.weightSum;
  const double n = m.s2;
  double dn = 0.0, ddn = 0.0, dw = 0.0, ddw = 0.0;
  if (nb.scaled)
  {
    // The same derivatives with each point's own k_i = 1 / h_i^2 inside the sums, in one pass.
    double ks1 = 0.0, ks2 = 0.0, ks3 = 0.0, kks2 = 0.0, kks4 = 0.0, k0 = 0.0;
    for (Eigen::Index i = 0; i < nb.count; ++i)
    {
      const double si = a.x() * nb.dx[i] + a.y() * nb.dy[i] + a.z() * nb.dz[i];
      const double wk = nb.weight[i] * nb.inverseSqScale[i];
      const double wkk = wk * nb.inverseSqScale[i];
      const double s2 = si * si;
      k0 += wk;
      ks1 += wk * si;
      ks2 += wk * s2;
      ks3 += wk * s2 * si;
      kks2 += wkk * s2;
      kks4 += wkk * s2 * s2;
    }
    dn = 2.0 * ks3 - 2.0 * m.s1;
    ddn = 4.0 * kks4 - 10.0 * ks2 + 2.0 * w;
    dw = 2.0 * ks1;
    ddw = 4.0 * kks2 - 2.0 * k0;
  }
  else
  {
    const double k = nb.invH2;
    dn = 2.0 * k * m.s3 - 2.0 * m.s1;
    ddn = 4.0 * k * k * m.s4 - 10.0 * k * m.s2 + 2.0 * w;
    dw = 2.0 * k * m.s1;
    ddw = 4.0 * k * k * m.s2 - 2.0 * k * w;
  }
  LineSample out;
  out.nearestSqDist = nb.minSqDist;
  if (Weighting == Weights::Plain)
  {
    out.value = n;
    out.slope = dn;
    out.curvature = ddn;
    out.logScale = nb.logScale();
    return out;
  }
  // e = N / W with W = sum w_i: the quotient rule, with dW/dt = sum w_i 2 s_i / h^2 and
  // d2W/dt2 = sum w_i (4 s_i^2 / h^4 - 2 / h^2) (dw, ddw above).
  out.value = n / w;
  out.slope = dn / w - n * dw / (w * w);
  out.curvature = ddn / w - 2.0 * dn * dw / (w * w) - n * ddw / (w * w) + 2.0 * n * dw * dw / (w * w * w);
  return out;
}

} // namespace pss

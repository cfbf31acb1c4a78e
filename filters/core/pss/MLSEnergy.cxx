// SPDX-License-Identifier: BSD-3-Clause
// The two energies of Eq. 1: with the plain Gaussian weights (Levin) and with normalized ones.
#include "pss/Variants.h"
#include "pss/Workspace.h"

namespace pss
{

namespace
{

// N(t) = sum theta_i s_i^2 along y + t a and its first two derivatives at t = 0, in the shifted
// weights: with s_i = <a, p_i - y>, d theta_i/dt = theta_i 2 s_i / h^2 and d s_i/dt = -1, so
// dN/dt = sum theta_i (2 s_i^3 / h^2 - 2 s_i) and d2N/dt2 = sum theta_i (4 s_i^4 / h^4 - 10 s_i^2 / h^2 + 2).
struct Numerator
{
  double value, slope, curvature;
};

Numerator numeratorAlong(const Neighbourhood& nb, const LineMoments& m)
{
  const double k = nb.invH2;
  return { m.s2, 2.0 * k * m.s3 - 2.0 * m.s1, 4.0 * k * k * m.s4 - 10.0 * k * m.s2 + 2.0 * nb.weightSum };
}

} // namespace

MLSEnergy::MLSEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
}

LineSample MLSEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  Neighbourhood& nb = ws.query;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  const Numerator n = numeratorAlong(nb, lineMoments(nb, a));
  LineSample out;
  out.value = n.value;
  out.slope = n.slope;
  out.curvature = n.curvature;
  out.logScale = nb.logScale();
  out.nearestSqDist = nb.minSqDist;
  return out;
}

NormalizedMLSEnergy::NormalizedMLSEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
}

LineSample NormalizedMLSEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  Neighbourhood& nb = ws.query;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  // e = N / W with W = sum w_i: the quotient rule, with dW/dt = sum w_i 2 s_i / h^2 and
  // d2W/dt2 = sum w_i (4 s_i^2 / h^4 - 2 / h^2).
  const LineMoments m = lineMoments(nb, a);
  const Numerator n = numeratorAlong(nb, m);
  const double k = nb.invH2;
  const double w = nb.weightSum;
  const double dw = 2.0 * k * m.s1;
  const double ddw = 4.0 * k * k * m.s2 - 2.0 * k * w;
  LineSample out;
  out.value = n.value / w;
  out.slope = n.slope / w - n.value * dw / (w * w);
  out.curvature = n.curvature / w - 2.0 * n.slope * dw / (w * w) - n.value * ddw / (w * w) +
    2.0 * n.value * dw * dw / (w * w * w);
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss

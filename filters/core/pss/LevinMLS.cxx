// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction LevinMLS::direction(const Vec3& x) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, x, nb);
  // The shift factor exp(logScale) scales C(x) and cannot move its eigenvectors.
  return smallestEigenDirection(covarianceAboutQuery(nb), dimension(), Params.minStability);
}

LineSample LevinMLS::lineSample(const Vec3& y, const Vec3& a) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, y, nb);
  // Eq. 1 along y + t a: with s_i = <a, p_i - y>, d theta_i/dt = theta_i 2 s_i / h^2 and
  // d s_i/dt = -1, so d/dt sum theta_i s_i^2 = sum theta_i (2 s_i^3 / h^2 - 2 s_i).
  LineSample out;
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    const double s = a.dot(nb.offsets[i]);
    const double s2 = s * s;
    out.value += nb.weight[i] * s2;
    out.slope += nb.weight[i] * (2.0 * s2 * s * nb.invH2 - 2.0 * s);
  }
  out.logScale = nb.logScale();
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss

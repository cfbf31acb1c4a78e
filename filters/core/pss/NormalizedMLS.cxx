// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction NormalizedMLS::direction(const Vec3& x) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, x, nb);
  // Normalizing divides C(x) by a positive number: same eigenvectors as Levin's.
  return smallestEigenDirection(covarianceAboutQuery(nb), dimension(), Params.minStability);
}

LineSample NormalizedMLS::lineSample(const Vec3& y, const Vec3& a) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, y, nb);
  // e = N / W with N = sum w_i s_i^2 and W = sum w_i; quotient rule with the derivatives of
  // LevinMLS::lineSample (dW/dt = sum w_i 2 s_i / h^2).
  double n = 0.0;
  double dn = 0.0;
  double dw = 0.0;
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    const double s = a.dot(nb.offsets[i]);
    const double s2 = s * s;
    n += nb.weight[i] * s2;
    dn += nb.weight[i] * (2.0 * s2 * s * nb.invH2 - 2.0 * s);
    dw += nb.weight[i] * 2.0 * s * nb.invH2;
  }
  const double w = nb.weightSum;
  LineSample out;
  out.value = n / w;
  out.slope = dn / w - n * dw / (w * w);
  out.nearestSqDist = nb.minSqDist;
  return out;
}

} // namespace pss

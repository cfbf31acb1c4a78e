// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction CenterOfMass::direction(const Vec3& x) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, x, nb);
  return smallestEigenDirection(covarianceAboutCentroid(nb), dimension(), Params.minStability);
}

} // namespace pss

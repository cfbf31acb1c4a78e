// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction CenterOfMass::directionNear(const Vec3& x, DirectionMemory& memory) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, x, nb);
  return smallestEigenDirection(covarianceAboutCentroid(nb), dimension(), Params.minStability, &memory.frame);
}

} // namespace pss

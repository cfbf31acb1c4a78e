// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction CenterOfMass::direction(const Vec3& x) const
{
  DirectionMemory none; // no earlier fit: the decomposition starts from scratch
  return directionNear(x, none);
}

Direction CenterOfMass::directionNear(const Vec3& x, DirectionMemory& memory) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, x, nb);
  return smallestEigenDirection(covarianceAboutCentroid(nb), dimension(), Params.minStability, &memory.frame);
}

} // namespace pss

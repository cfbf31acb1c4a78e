// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

namespace pss
{

Direction CenterOfMass::direction(const Vec3& x) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, x, nb);
  return smallestEigenDirection(covarianceAboutCentroid(nb), dimension(), Params.minStability);
}

Direction CenterOfMass::planeFit(const Vec3& x, Vec3& offset, EigenFrame& frame) const
{
  Neighbourhood& nb = threadNeighbourhood();
  gatherNeighbourhood(Index, Params, x, nb);
  offset = centroidOffset(nb);
  return smallestEigenDirection(covarianceAboutCentroid(nb), dimension(), Params.minStability, &frame);
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
#include "pss/DirectionRulesAndEnergies.h"
#include "pss/Workspace.h"

namespace pss
{

CovarianceDirection::CovarianceDirection(const PointIndex& index, const SurfaceParameters& params, About about)
  : Index(index)
  , Params(params)
  , Centre(about)
{
}

DirectionFit CovarianceDirection::fit(const Vec3& x, DirectionMemory& memory, Workspace& ws) const
{
  Neighbourhood& nb = ws.query;
  gatherNeighbourhood(Index, Params, x, nb, ws);
  // The shift factor exp(logScale) scales C(x) and cannot move its eigenvectors.
  const Mat3 c = Centre == About::Query ? covarianceAboutQuery(nb) : covarianceAboutCentroid(nb);
  return { smallestEigenDirection(c, Index.dimension(), Params.minStability, &memory.frame), &nb };
}

} // namespace pss

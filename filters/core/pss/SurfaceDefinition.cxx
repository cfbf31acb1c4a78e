// SPDX-License-Identifier: BSD-3-Clause
#include "pss/SurfaceDefinition.h"

#include "pss/VariantCatalog.h"
#include "pss/Workspace.h"

#include <limits>
#include <stdexcept>

namespace pss
{

namespace
{

// The parameters, once checked: the rules are built from them, so the checks come first.
const SurfaceParameters& validated(const SurfaceParameters& params, const PointIndex& index)
{
  params.validate();
  if (index.empty())
  {
    throw std::invalid_argument("the point cloud is empty (no finite points)");
  }
  return params;
}

} // namespace

double Energy::value(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  return lineSample(y, a, ws).trueValue();
}

SurfaceDefinition::SurfaceDefinition(
  const VariantInfo& recipe, const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(validated(params, index))
  , Kind(recipe.variant)
  , Directions(recipe.direction(Index, Params))
  , Energies(recipe.energy(Index, Params))
{
}

Direction SurfaceDefinition::direction(const Vec3& x, Workspace& ws) const
{
  DirectionMemory none; // no earlier fit: a cold start
  return Directions->fit(x, none, ws).direction;
}

Direction SurfaceDefinition::directionNear(const Vec3& x, DirectionMemory& memory, Workspace& ws) const
{
  return Directions->fit(x, memory, ws).direction;
}

LineSample SurfaceDefinition::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  return Energies->lineSample(y, a, ws);
}

double SurfaceDefinition::energy(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  return Energies->value(y, a, ws);
}

Direction SurfaceDefinition::planeFit(
  const Vec3& x, Vec3& offset, DirectionMemory& memory, Workspace& ws, double* contraction) const
{
  const DirectionFit fit = Directions->fit(x, memory, ws);
  if (contraction)
  {
    *contraction = std::numeric_limits<double>::quiet_NaN();
  }
  if (fit.hasStep)
  {
    offset = fit.step;
    return fit.direction;
  }
  const Neighbourhood* nb = fit.neighbourhood;
  if (!nb)
  {
    gatherNeighbourhood(Index, Params, x, ws.local, ws);
    nb = &ws.local;
  }
  offset = centroidOffset(*nb);
  if (contraction && fit.direction.defined)
  {
    *contraction = centroidContraction(*nb, fit.direction.n);
  }
  return fit.direction;
}

double SurfaceDefinition::scaleAt(const Vec3& x, Workspace& ws) const
{
  if (!Index.hasScales() || !isFinite(x))
  {
    return Params.h;
  }
  // Most callers have just fitted n at x: that neighbourhood's scale is the one asked for.
  const Neighbourhood& fitted = ws.query;
  if (fitted.indexSerial == Index.serial() && fitted.h == Params.h && fitted.cutoff == Params.cutoff &&
    fitted.origin == Index.restrict(x))
  {
    return fitted.localScale;
  }
  gatherNeighbourhood(Index, Params, x, ws.scale, ws);
  return ws.scale.localScale;
}

} // namespace pss

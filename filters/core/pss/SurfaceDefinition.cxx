// SPDX-License-Identifier: BSD-3-Clause
#include "pss/SurfaceDefinition.h"

#include "pss/Variants.h"

#include <stdexcept>

namespace pss
{

SurfaceDefinition::SurfaceDefinition(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
  Params.validate();
  if (Index.empty())
  {
    throw std::invalid_argument("the point cloud is empty (no finite points)");
  }
}

double SurfaceDefinition::energy(const Vec3& y, const Vec3& a) const
{
  return lineSample(y, a).trueValue();
}

Direction SurfaceDefinition::directionNear(const Vec3& x, DirectionMemory&) const
{
  return direction(x);
}

Direction SurfaceDefinition::planeFit(const Vec3& x, Vec3& offset, DirectionMemory& memory) const
{
  thread_local Neighbourhood nb;
  const Direction d = directionNear(x, memory);
  gatherNeighbourhood(Index, Params, x, nb);
  offset = centroidOffset(nb);
  return d;
}

std::unique_ptr<SurfaceDefinition> makeSurface(
  Variant v, const PointIndex& index, const SurfaceParameters& params)
{
  switch (v)
  {
    case Variant::LevinMLS:
      return std::make_unique<LevinMLS>(index, params);
    case Variant::NormalizedMLS:
      return std::make_unique<NormalizedMLS>(index, params);
    case Variant::CenterOfMass:
      return std::make_unique<CenterOfMass>(index, params);
    case Variant::Integral:
      return std::make_unique<IntegralEnergy>(index, params);
    case Variant::Delta:
      return std::make_unique<DeltaEnergy>(index, params);
  }
  throw std::invalid_argument("unknown surface variant " + std::to_string(static_cast<int>(v)));
}

} // namespace pss

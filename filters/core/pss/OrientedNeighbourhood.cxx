// SPDX-License-Identifier: BSD-3-Clause
// The cloud's oriented normals (PointIndex::setNormals) and neighbourhoods that carry them, for
// the definitions that fit points with normals (APSS, RIMLS).
#include "pss/Kernel.h"
#include "pss/PointIndex.h"
#include "pss/Workspace.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pss
{

void PointIndex::setNormals(const std::vector<Vec3>& normals)
{
  renewSerial();
  Normals.clear();
  if (normals.empty())
  {
    return;
  }
  if (normals.size() != Points.size() + Skipped)
  {
    throw std::invalid_argument("the normal array has " + std::to_string(normals.size()) + " vectors for " +
      std::to_string(Points.size() + Skipped) + " points");
  }
  std::vector<Vec3> ordered(Points.size());
  for (std::size_t i = 0; i < Points.size(); ++i)
  {
    const Vec3 n = restrict(normals[OriginalIds[i]]);
    const double length = n.norm();
    if (!(length > 0.0) || !std::isfinite(length))
    {
      throw std::invalid_argument("the normal of point " + std::to_string(OriginalIds[i]) +
        " must be a nonzero finite vector" + (Dimension == 2 ? " in the xy-plane" : "") + ", got (" +
        std::to_string(n.x()) + ", " + std::to_string(n.y()) + ", " + std::to_string(n.z()) + ")");
    }
    ordered[i] = n / length;
  }
  Normals = std::move(ordered);
}

void gatherOrientedNeighbourhood(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& y, Neighbourhood& nb, Workspace& ws)
{
  if (!index.hasNormals())
  {
    throw std::invalid_argument("this definition needs an oriented normal at every cloud point");
  }
  // The candidate caches carry the normals of an index that has them, and every neighbourhood
  // gathered from them compacts the normals with the coordinates.
  gatherNeighbourhood(index, params, y, nb, ws);
  if (!nb.withNormals)
  {
    throw std::logic_error("gatherOrientedNeighbourhood: the neighbourhood came without normals");
  }
}

} // namespace pss

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
  const Vec3 origin = index.restrict(y);
  const bool kept = nb.indexSerial == index.serial() && nb.h == params.h && nb.cutoff == params.cutoff &&
    nb.origin == origin;
  gatherNeighbourhood(index, params, y, nb, ws);
  if (nb.withNormals)
  {
    return;
  }
  // The neighbourhood is the selection gatherNeighbourhood made from the cache that served it
  // (the focused one when it covers the query, else the wide one, fetched anew when needed); pick
  // the same candidates again, by the same test (compactTail's and compactScaledTail's in
  // KernelDispatch.cxx), to know which points they are.
  auto served = [&]() -> const CandidateCache* {
    return ws.focused.covers(index, params, nb.origin) ? &ws.focused : &ws.wide;
  };
  const CandidateCache* cache = served();
  if (kept && !cache->covers(index, params, nb.origin))
  {
    // Kept from an earlier gather whose candidates have moved on since: gather it again.
    nb.indexSerial = 0;
    gatherNeighbourhood(index, params, y, nb, ws);
    cache = served();
  }
  const Eigen::Index m = cache->count;
  const auto sq = cache->squaredDistances(nb.origin, ws.candidateSq);
  const Eigen::Index capacity = nb.dx.size();
  if (nb.nx.size() < capacity)
  {
    for (Eigen::ArrayXd* a : { &nb.nx, &nb.ny, &nb.nz, &nb.robust })
    {
      a->resize(capacity);
    }
  }
  Eigen::Index n = 0;
  auto keep = [&](Eigen::Index k) {
    const Vec3& normal = index.normal(cache->ids[static_cast<std::size_t>(k)]);
    nb.nx[n] = normal.x();
    nb.ny[n] = normal.y();
    nb.nz[n] = normal.z();
    ++n;
  };
  if (nb.scaled)
  {
    const double bound = nb.minScaledSqDist + params.cutoff * params.cutoff;
    for (Eigen::Index k = 0; k < m; ++k)
    {
      if (sq[k] * cache->pk[k] < bound)
      {
        keep(k);
      }
    }
  }
  else
  {
    const double limit = nb.minSqDist + cache->band;
    for (Eigen::Index k = 0; k < m; ++k)
    {
      if (sq[k] < limit || sq[k] == nb.minSqDist)
      {
        keep(k);
      }
    }
  }
  if (n != nb.count)
  {
    throw std::logic_error("gatherOrientedNeighbourhood: the normals do not match the neighbourhood");
  }
  nb.withNormals = true;
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
// Stage 3 of the mesher (SurfaceMesh.h): one orientation of n over the band's corners.
#include "pss/SurfaceMesh.h"

#include <cmath>
#include <queue>
#include <tuple>

namespace pss
{

signed char SurfaceMesher::seedSign(std::size_t seed, const Orientation& away) const
{
  const Vec3& ns = Values[seed].n;
  const Vec3 x = positionOf(Keys[seed]);
  // The cloud's own normal nearest to the seed decides when there is one; a zero (unknown) normal
  // leaves it to the viewpoint or the centroid.
  if (!Options.cloudNormals.empty())
  {
    const PointIndex& index = Surface->index();
    const double along = Options.cloudNormals[index.originalId(index.nearest(x).first)].dot(ns);
    if (along != 0.0 && std::isfinite(along))
    {
      return along < 0.0 ? -1 : 1;
    }
  }
  return away.apply(ns, x).dot(ns) < 0.0 ? -1 : 1;
}

void SurfaceMesher::orient()
{
  const std::size_t n = Keys.size();
  Sign.assign(n, 0);
  const Orientation away = Options.viewpoint ? Orientation::toward(*Options.viewpoint) : Orientation::awayFrom(Frame.centroid);
  // Max-heap of (|n_a . n_b|, b, a): the most parallel edge out of the oriented set goes first.
  using Edge = std::tuple<double, std::uint32_t, std::uint32_t>;
  std::priority_queue<Edge> heap;
  auto pushNeighbours = [&](std::size_t v) {
    for (int k = 0; k < 2 * Dimension; ++k)
    {
      const std::uint32_t w = Step[k][v];
      if (w != NoIndex && Values[w].defined && Sign[w] == 0)
      {
        heap.emplace(std::abs(Values[v].n.dot(Values[w].n)), w, static_cast<std::uint32_t>(v));
      }
    }
  };
  for (std::size_t seed = 0; seed < n; ++seed)
  {
    if (!Values[seed].defined || Sign[seed] != 0)
    {
      continue;
    }
    Sign[seed] = seedSign(seed, away);
    pushNeighbours(seed);
    while (!heap.empty())
    {
      const auto [weight, to, from] = heap.top();
      heap.pop();
      (void)weight;
      if (Sign[to] != 0)
      {
        continue;
      }
      Sign[to] = static_cast<signed char>(Values[to].n.dot(Values[from].n) * Sign[from] < 0.0 ? -1 : 1);
      pushNeighbours(to);
    }
  }
  interpolateHanging();
}

void SurfaceMesher::interpolateHanging()
{
  // Coarser cells' hanging corners come first: a hanging corner may be the end of a finer cell's
  // edge whose midpoint hangs in turn.
  const double seamCos = std::cos(Options.maxSeamAngle * M_PI / 180.0);
  for (const HangingCorner& h : HangingCorners)
  {
    CornerValue& v = Values[h.corner];
    v = CornerValue{};
    Sign[h.corner] = 0;
    const CornerValue& a = Values[h.a];
    const CornerValue& b = Values[h.b];
    if (!a.defined || !b.defined || Sign[h.a] == 0 || Sign[h.b] == 0)
    {
      continue;
    }
    const Vec3 na = a.n * Sign[h.a];
    const Vec3 nb = b.n * Sign[h.b];
    const Vec3 sum = na + nb;
    // Across a seam the coarser cell's simplices are skipped; so are the finer ones at this corner.
    if (na.dot(nb) < seamCos || !(sum.norm() > 1e-6))
    {
      continue;
    }
    v.n = sum.normalized();
    v.g = (a.g * Sign[h.a] + b.g * Sign[h.b]) / 2.0;
    v.defined = true;
    Sign[h.corner] = 1;
  }
}

} // namespace pss

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
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
#include "pss/NormalOrientation.h"

#include "pss/Domain.h"
#include "pss/Parallel.h"
#include "pss/Workspace.h"

#include <algorithm>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace pss
{

NeighbourGraph nearestNeighbourGraph(const PointIndex& index, std::size_t k, int threads)
{
  const std::size_t n = index.size();
  if (k == 0)
  {
    throw std::invalid_argument("a neighbour graph needs k >= 1");
  }
  // Each point's k nearest others (itself comes first), then both directions of every link.
  const std::size_t kk = std::min(k, n > 0 ? n - 1 : 0);
  std::vector<std::uint32_t> nearest(n * kk, 0);
  parallelFor(n, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::uint32_t, double>> found;
    for (std::size_t i = begin; i < end; ++i)
    {
      index.kNearest(index.point(i), kk + 1, found);
      std::size_t m = 0;
      for (const auto& [j, d2] : found)
      {
        (void)d2;
        if (j != i && m < kk)
        {
          nearest[i * kk + m++] = j;
        }
      }
      for (; m < kk; ++m)
      {
        nearest[i * kk + m] = static_cast<std::uint32_t>(i); // fewer distinct neighbours: a self link, dropped below
      }
    }
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> links;
  links.reserve(2 * nearest.size());
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t m = 0; m < kk; ++m)
    {
      const std::uint32_t j = nearest[i * kk + m];
      if (j != i)
      {
        links.emplace_back(static_cast<std::uint32_t>(i), j);
        links.emplace_back(j, static_cast<std::uint32_t>(i));
      }
    }
  }
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  NeighbourGraph graph;
  graph.start.assign(n + 1, 0);
  graph.adjacent.resize(links.size());
  for (std::size_t e = 0; e < links.size(); ++e)
  {
    ++graph.start[links[e].first + 1];
    graph.adjacent[e] = links[e].second;
  }
  std::partial_sum(graph.start.begin(), graph.start.end(), graph.start.begin());
  return graph;
}

std::size_t propagateOrientation(const NeighbourGraph& graph, double* normals, const std::vector<std::uint32_t>& seeds,
  const std::function<bool(std::uint32_t)>& flipSeed, const std::function<void(std::uint32_t)>& flipped)
{
  const std::size_t n = graph.size();
  auto normal = [&](std::uint32_t i) { return Eigen::Map<Vec3>(normals + 3 * static_cast<std::size_t>(i)); };
  auto usable = [&](std::uint32_t i) { return normal(i).squaredNorm() > 0.0; };
  std::size_t count = 0;
  auto flip = [&](std::uint32_t i) {
    normal(i) *= -1.0;
    ++count;
    if (flipped)
    {
      flipped(i);
    }
  };
  std::vector<char> done(n, 0);
  // (|n_i . n_j|, point to orient, its oriented neighbour): the most parallel link first; the
  // indices break ties, so the tree does not depend on the order links are pushed in.
  using Link = std::tuple<double, std::uint32_t, std::uint32_t>;
  std::priority_queue<Link> front;
  auto pushNeighbours = [&](std::uint32_t i) {
    for (std::size_t e = graph.start[i]; e < graph.start[i + 1]; ++e)
    {
      const std::uint32_t j = graph.adjacent[e];
      if (!done[j] && usable(j))
      {
        front.emplace(std::abs(normal(i).dot(normal(j))), j, i);
      }
    }
  };
  for (const std::uint32_t seed : seeds)
  {
    if (seed >= n || done[seed] || !usable(seed))
    {
      continue;
    }
    done[seed] = 1;
    if (flipSeed(seed))
    {
      flip(seed);
    }
    pushNeighbours(seed);
    while (!front.empty())
    {
      const auto [weight, j, parent] = front.top();
      (void)weight;
      front.pop();
      if (done[j])
      {
        continue;
      }
      done[j] = 1;
      if (normal(j).dot(normal(parent)) < 0.0)
      {
        flip(j);
      }
      pushNeighbours(j);
    }
  }
  return count;
}

std::size_t orientNormals(const PointIndex& index, std::vector<Vec3>& normals, const std::optional<Vec3>& viewpoint,
  std::size_t k, int threads)
{
  const std::size_t n = index.size();
  if (normals.size() != n)
  {
    throw std::invalid_argument("orientNormals: " + std::to_string(normals.size()) + " normals for " +
      std::to_string(n) + " indexed points");
  }
  if (viewpoint)
  {
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (normals[i].dot(*viewpoint - index.point(i)) < 0.0)
      {
        normals[i] = -normals[i];
        ++count;
      }
    }
    return count;
  }
  const int up = index.dimension() - 1;
  std::vector<std::uint32_t> seeds(n);
  std::iota(seeds.begin(), seeds.end(), 0u);
  std::stable_sort(seeds.begin(), seeds.end(),
    [&](std::uint32_t a, std::uint32_t b) { return index.point(a)[up] > index.point(b)[up]; });
  const NeighbourGraph graph = nearestNeighbourGraph(index, k, threads);
  return propagateOrientation(graph, normals.empty() ? nullptr : normals.front().data(), seeds,
    [&](std::uint32_t seed) { return normals[seed][up] < 0.0; });
}

std::vector<Vec3> estimateOrientedNormals(const PointIndex& index, const SurfaceParameters& params,
  const std::optional<Vec3>& viewpoint, std::size_t k, int threads, std::size_t* borrowed)
{
  const std::size_t n = index.size();
  params.validate();
  std::vector<Vec3> normals(n, Vec3::Zero());
  // In Morton order, so that consecutive fits share candidate fetches (PointIndex::visitingOrder).
  const std::vector<std::uint32_t> order = spatialOrder(index.points(), threads);
  parallelFor(n, threads, [&](std::size_t begin, std::size_t end, Workspace& ws) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const std::uint32_t i = order[k];
      const Direction d = centreOfMassNormal(index, params, index.point(i), ws);
      normals[i] = d.defined ? d.n : Vec3::Zero();
    }
  });
  // Orientation skips the zero normals; they borrow from their nearest oriented neighbour after.
  std::vector<Vec3> known;
  std::vector<std::size_t> knownId;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (normals[i].squaredNorm() > 0.0)
    {
      known.push_back(index.point(i));
      knownId.push_back(i);
    }
  }
  if (known.empty())
  {
    throw std::invalid_argument("no cloud point has a normal: every neighbourhood is a single point or a line "
                                "(isolated points?); give a Normals array or a larger scale");
  }
  orientNormals(index, normals, viewpoint, k, threads);
  std::size_t lent = 0;
  if (known.size() < n)
  {
    const PointIndex withNormal(known, index.dimension());
    for (std::size_t i = 0; i < n; ++i)
    {
      if (normals[i].squaredNorm() == 0.0)
      {
        normals[i] = normals[knownId[withNormal.originalId(withNormal.nearest(index.point(i)).first)]];
        ++lent;
      }
    }
  }
  if (borrowed)
  {
    *borrowed = lent;
  }
  std::vector<Vec3> inInputOrder(index.size() + index.skippedCount(), Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i)
  {
    inInputOrder[index.originalId(i)] = normals[i];
  }
  return inInputOrder;
}

} // namespace pss

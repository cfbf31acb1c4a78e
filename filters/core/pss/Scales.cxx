// SPDX-License-Identifier: BSD-3-Clause
// The automatic scales: one h for a cloud of even density (estimateScale), or one per point for a
// cloud whose density varies (estimateLocalScales: depth-camera and LiDAR frames).
#include "pss/PointIndex.h"

#include "pss/Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace pss
{

namespace
{

// The last step of the local scales, in place: a point without a scale of its own (its k
// neighbours all coincide with it) takes the smallest positive one (none in a cloud of one
// repeated point, which setScales refuses), and no scale exceeds maxRatio times their median.
void settleScales(std::vector<double>& scales, double maxRatio)
{
  double smallest = std::numeric_limits<double>::infinity();
  for (const double r : scales)
  {
    smallest = r > 0.0 ? std::min(smallest, r) : smallest;
  }
  std::vector<double> sorted(scales);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double cap = maxRatio * sorted[sorted.size() / 2];
  for (double& r : scales)
  {
    r = std::min(r > 0.0 ? r : smallest, cap);
  }
}

} // namespace

double estimateScale(const PointIndex& index, int k, double multiplier, int threads)
{
  if (k < 1 || index.size() < static_cast<std::size_t>(k) + 1)
  {
    return 0.0;
  }
  const std::size_t samples = std::min<std::size_t>(index.size(), 2000);
  // Each sample's distance goes to its own slot, so that the distances are kept in sample order
  // (the order nth_element sees) whichever thread measured them.
  std::vector<double> measured(samples, 0.0);
  std::vector<std::uint8_t> kept(samples, 0);
  parallelFor(samples, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::uint32_t, double>> found;
    for (std::size_t s = begin; s < end; ++s)
    {
      const std::size_t i = s * index.size() / samples;
      index.kNearest(index.point(i), static_cast<std::size_t>(k) + 1, found); // the point itself is first
      if (found.size() == static_cast<std::size_t>(k) + 1)
      {
        measured[s] = std::sqrt(found.back().second);
        kept[s] = 1;
      }
    }
  });
  std::vector<double> distances;
  distances.reserve(samples);
  for (std::size_t s = 0; s < samples; ++s)
  {
    if (kept[s])
    {
      distances.push_back(measured[s]);
    }
  }
  if (distances.empty())
  {
    return 0.0;
  }
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return multiplier * distances[distances.size() / 2];
}

std::vector<double> estimateLocalScales(
  const PointIndex& index, int k, double multiplier, int smoothing, int threads, double maxRatio)
{
  if (k < 1 || smoothing < 0 || !(multiplier > 0.0) || !std::isfinite(multiplier) || !(maxRatio > 0.0))
  {
    throw std::invalid_argument(
      "local scales need k >= 1, smoothing >= 0, a positive finite multiplier and a positive maxRatio");
  }
  const std::size_t n = index.size();
  const auto kk = static_cast<std::size_t>(k);
  if (n < kk + 1)
  {
    throw std::invalid_argument("local scales need at least k + 1 = " + std::to_string(kk + 1) +
      " finite points, the cloud has " + std::to_string(n));
  }
  // Each point's k nearest others (the point itself comes first and is left out), and the raw
  // scale: the distance to the k-th of them.
  std::vector<std::uint32_t> neighbours(n * kk);
  std::vector<double> raw(n);
  parallelFor(n, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::uint32_t, double>> found;
    for (std::size_t i = begin; i < end; ++i)
    {
      index.kNearest(index.point(i), kk + 1, found);
      for (std::size_t j = 0; j < kk; ++j)
      {
        neighbours[i * kk + j] = found[j + 1].first;
      }
      raw[i] = std::sqrt(found.back().second);
    }
  });
  // Smoothing: the median over the point and its neighbours, repeated. A median, not a mean, so
  // that a duplicate (distance 0) or a stray point does not pull its neighbours' scales along.
  std::vector<double> next(n);
  for (int pass = 0; pass < smoothing; ++pass)
  {
    parallelFor(n, threads, [&](std::size_t begin, std::size_t end) {
      std::vector<double> values(kk + 1);
      for (std::size_t i = begin; i < end; ++i)
      {
        values[0] = raw[i];
        for (std::size_t j = 0; j < kk; ++j)
        {
          values[j + 1] = raw[neighbours[i * kk + j]];
        }
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(kk / 2), values.end());
        next[i] = values[kk / 2];
      }
    });
    raw.swap(next);
  }
  settleScales(raw, maxRatio);
  std::vector<double> out(n + index.skippedCount(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < n; ++i)
  {
    out[index.originalId(i)] = multiplier * raw[i];
  }
  return out;
}

double rawSpacing(const PointIndex& index, std::size_t i, std::size_t k, std::vector<std::uint32_t>& neighbours,
  std::vector<std::pair<std::uint32_t, double>>& scratch)
{
  index.kNearest(index.point(i), k + 1, scratch); // the point itself comes first
  neighbours.clear();
  for (std::size_t j = 1; j < scratch.size(); ++j)
  {
    neighbours.push_back(scratch[j].first);
  }
  if (scratch.size() < k + 1)
  {
    return 0.0;
  }
  return std::sqrt(M_PI / static_cast<double>(k)) * std::sqrt(scratch.back().second);
}

double smoothedSpacing(const std::vector<double>& raw, std::size_t i, const std::uint32_t* neighbours, std::size_t k,
  std::vector<double>& scratch)
{
  scratch.assign(1, raw[i]);
  for (std::size_t j = 0; j < k; ++j)
  {
    scratch.push_back(raw[neighbours[j]]);
  }
  const auto middle = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
  std::nth_element(scratch.begin(), middle, scratch.end());
  return *middle;
}

std::vector<double> estimateLocalSpacings(const PointIndex& index, std::size_t k, int threads)
{
  const std::size_t n = index.size();
  if (k < 1 || n < k + 1)
  {
    return std::vector<double>(n, 0.0);
  }
  std::vector<double> raw(n);
  std::vector<std::uint32_t> neighbours(n * k);
  parallelFor(n, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> near;
    std::vector<std::pair<std::uint32_t, double>> scratch;
    for (std::size_t i = begin; i < end; ++i)
    {
      raw[i] = rawSpacing(index, i, k, near, scratch);
      std::copy(near.begin(), near.end(), neighbours.begin() + static_cast<std::ptrdiff_t>(i * k));
    }
  });
  std::vector<double> out(n);
  parallelFor(n, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> scratch;
    for (std::size_t i = begin; i < end; ++i)
    {
      out[i] = smoothedSpacing(raw, i, neighbours.data() + i * k, k, scratch);
    }
  });
  return out;
}

double scaleSpread(const std::vector<double>& scales)
{
  std::vector<double> finite;
  finite.reserve(scales.size());
  for (const double s : scales)
  {
    if (std::isfinite(s) && s > 0.0)
    {
      finite.push_back(s);
    }
  }
  if (finite.empty())
  {
    return 1.0;
  }
  const auto at = [&](double q) {
    auto it = finite.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(finite.size() - 1));
    std::nth_element(finite.begin(), it, finite.end());
    return *it;
  };
  const double low = at(0.1);
  const double high = at(0.9);
  return high / low;
}

double estimateScaleSpread(const PointIndex& index, int k, int smoothing, int threads, double maxRatio)
{
  const std::size_t n = index.size();
  if (n <= ScaleSpreadSampledAbove)
  {
    return scaleSpread(estimateLocalScales(index, k, 1.0, smoothing, threads, maxRatio));
  }
  if (k < 1 || smoothing < 0 || !(maxRatio > 0.0))
  {
    throw std::invalid_argument("a scale spread needs k >= 1, smoothing >= 0 and a positive maxRatio");
  }
  const auto kk = static_cast<std::size_t>(k);
  std::vector<double> sampled(ScaleSpreadSamples);
  parallelFor(ScaleSpreadSamples, threads, [&](std::size_t begin, std::size_t end) {
    // Per point of a sample's reach: its k nearest others and its raw scale, found once.
    std::unordered_map<std::uint32_t, std::pair<std::vector<std::uint32_t>, double>> known;
    std::vector<std::pair<std::uint32_t, double>> found;
    auto near = [&](std::uint32_t i) -> const std::pair<std::vector<std::uint32_t>, double>& {
      auto [it, added] = known.try_emplace(i);
      if (added)
      {
        index.kNearest(index.point(i), kk + 1, found); // the point itself comes first
        for (std::size_t j = 1; j < found.size(); ++j)
        {
          it->second.first.push_back(found[j].first);
        }
        it->second.second = found.size() == kk + 1 ? std::sqrt(found.back().second) : 0.0;
      }
      return it->second;
    };
    // The scale of point i after `pass` smoothings, as estimateLocalScales computes it.
    auto smoothed = [&](auto&& self, std::uint32_t i, int pass) -> double {
      if (pass == 0)
      {
        return near(i).second;
      }
      const std::vector<std::uint32_t> neighbours = near(i).first;
      std::vector<double> own{ self(self, i, pass - 1) };
      for (const std::uint32_t j : neighbours)
      {
        own.push_back(self(self, j, pass - 1));
      }
      std::nth_element(own.begin(), own.begin() + static_cast<std::ptrdiff_t>(kk / 2), own.end());
      return own[kk / 2];
    };
    for (std::size_t s = begin; s < end; ++s)
    {
      known.clear();
      sampled[s] = smoothed(smoothed, static_cast<std::uint32_t>(s * n / ScaleSpreadSamples), smoothing);
    }
  });
  settleScales(sampled, maxRatio);
  return scaleSpread(sampled);
}

} // namespace pss

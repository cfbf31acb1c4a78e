// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include "pss/PointIndex.h"
#include "pss/Workspace.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace pss
{

namespace
{

// Sorts words (rank << 32 | index) by rank, ranks below @p bound: a least-significant-digit radix
// sort of 8-bit digits, as many as the bound needs. A few hundred candidates per fetch: a
// comparison sort of them mispredicted half its branches and made the fetch several times slower.
void sortByRank(std::vector<std::uint64_t>& items, std::vector<std::uint64_t>& scratch, std::size_t bound)
{
  int bits = 0;
  while (bits < 32 && (std::uint64_t(bound - 1) >> bits) != 0)
  {
    ++bits;
  }
  scratch.resize(items.size());
  for (int shift = 32; shift < 32 + std::max(bits, 1); shift += 8)
  {
    std::array<std::uint32_t, 257> start{};
    for (const std::uint64_t v : items)
    {
      ++start[((v >> shift) & 0xffu) + 1];
    }
    for (std::size_t d = 1; d < start.size(); ++d)
    {
      start[d] += start[d - 1];
    }
    for (const std::uint64_t v : items)
    {
      scratch[start[(v >> shift) & 0xffu]++] = v;
    }
    items.swap(scratch);
  }
}

} // namespace

// True when every point within sqrt(dmin(y)^2 + band) of y is among the candidates:
// dmin(y) <= centerMinDist + |y - center|, and that ball around y lies in the fetched one.
bool CandidateCache::covers(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, double extra) const
{
  if (!reusable || indexSerial != index.serial() || h != params.h || band != params.cutoff * params.cutoff * h * h)
  {
    return false;
  }
  if (scaled)
  {
    return (y - center).norm() + extra <= margin;
  }
  const double shift = (y - center).norm() + extra;
  const double reach = centerMinDist + shift;
  return std::sqrt(reach * reach + band) + shift <= radius;
}

void CandidateCache::fetch(const PointIndex& index, const SurfaceParameters& params, const Vec3& y,
  PointIndex::LeafRanges& leaves, double minMargin)
{
  indexSerial = index.serial();
  h = params.h;
  band = params.cutoff * params.cutoff * h * h;
  cutoffSq = params.cutoff * params.cutoff;
  center = y;
  const auto nearest = index.nearest(y);
  centerMinDist = std::sqrt(nearest.second);
  scaled = index.hasScales();
  if (scaled)
  {
    fetchScaled(index, y, nearest.first, leaves, minMargin);
    fetchNormals(index);
    return;
  }
  const double margin = std::max({ 0.5 * h, std::min(0.05 * centerMinDist, 2.0 * h), minMargin });
  const double reach = centerMinDist + margin;
  radius = std::sqrt(reach * reach + band) + margin;
  const double sqRadius = radius * radius;
  // The leaves come in index order, so the candidates do too: every later neighbourhood is
  // then independent of where this fetch was made. (The count and the arrays are locals in
  // the loop, which keeps them in registers.)
  Eigen::Index n = 0;
  if (index.coordinateOrder())
  {
    // The same candidates, in the order of their coordinates instead of their indices. Each
    // is sorted as (rank, index) in one word, so that no lookup of the rank's point is needed.
    std::size_t kept = 0;
    index.forEachLeafInBall(y, sqRadius, leaves, [&](std::uint32_t begin, std::uint32_t end) {
      if (ranks.size() < kept + (end - begin))
      {
        ranks.resize(std::max<std::size_t>(kept + (end - begin), 2 * ranks.size()));
      }
      std::uint64_t* out = ranks.data();
      for (std::uint32_t i = begin; i < end; ++i)
      {
        out[kept] = std::uint64_t(index.coordinateRank(i)) << 32 | i;
        kept += (index.point(i) - y).squaredNorm() < sqRadius ? 1 : 0;
      }
    });
    ranks.resize(kept);
    sortByRank(ranks, rankScratch, index.size());
    n = static_cast<Eigen::Index>(ranks.size());
    reserve(n);
    for (Eigen::Index k = 0; k < n; ++k)
    {
      const auto i = static_cast<std::uint32_t>(ranks[static_cast<std::size_t>(k)]);
      const Vec3& p = index.point(i);
      px[k] = p.x();
      py[k] = p.y();
      pz[k] = p.z();
      ids[static_cast<std::size_t>(k)] = i;
    }
  }
  else
  {
    index.forEachLeafInBall(y, sqRadius, leaves, [&](std::uint32_t begin, std::uint32_t end) {
      reserve(n + (end - begin));
      double* x = px.data();
      double* yy = py.data();
      double* z = pz.data();
      std::uint32_t* id = ids.data();
      for (std::uint32_t i = begin; i < end; ++i)
      {
        const Vec3& p = index.point(i);
        x[n] = p.x();
        yy[n] = p.y();
        z[n] = p.z();
        id[n] = i;
        n += (p - y).squaredNorm() < sqRadius ? 1 : 0;
      }
    });
  }
  count = n;
  // The ball holds every point within radius only while the squared distances are finite.
  reusable = count > 0 && std::isfinite(sqRadius);
  if (count == 0)
  {
    // Only when the radius rounds below the nearest distance (absurd scale ratios, or squared
    // distances beyond double's range). Such candidates are good for this query alone: reusing
    // them for the next one made results depend on which query came first (found by
    // tests/fuzz/FuzzCore.cxx: 1 vs 2 threads differed for a start 1e300 from the cloud).
    reserve(1);
    const Vec3& p = index.point(nearest.first);
    px[0] = p.x();
    py[0] = p.y();
    pz[0] = p.z();
    ids[0] = static_cast<std::uint32_t>(nearest.first);
    count = 1;
  }
  fetchNormals(index);
}

void CandidateCache::fetchNormals(const PointIndex& index)
{
  withNormals = index.hasNormals();
  if (!withNormals)
  {
    return;
  }
  if (nx.size() < px.size())
  {
    nx.resize(px.size());
    ny.resize(px.size());
    nz.resize(px.size());
  }
  for (Eigen::Index k = 0; k < count; ++k)
  {
    const Vec3& n = index.normal(ids[static_cast<std::size_t>(k)]);
    nx[k] = n.x();
    ny[k] = n.y();
    nz[k] = n.z();
  }
}

Eigen::VectorBlock<Eigen::ArrayXd> CandidateCache::squaredDistances(const Vec3& y, Eigen::ArrayXd& out) const
{
  if (out.size() < count)
  {
    out.resize(count);
  }
  auto sq = out.head(count);
  sq = (px.head(count) - y.x()).square() + (py.head(count) - y.y()).square() + (pz.head(count) - y.z()).square();
  return sq;
}

// With a scale per point. For a query y' within margin m of y, some point j (here y's nearest,
// at distance d_j) bounds the smallest scaled distance: s(y') <= (d_j + m)^2 / h_j^2, so every
// point y' can need has |p_i - y'| < sigma h_i with sigma^2 = (d_j + m)^2 / h_j^2 + cutoff^2, and
// so |p_i - y| < m + sigma h_i: the fetch keeps those (the tree's walk skips the nodes whose
// largest scale cannot reach). Exact whatever the scales are, smooth or not.
void CandidateCache::fetchScaled(
  const PointIndex& index, const Vec3& y, std::size_t nearest, PointIndex::LeafRanges& leaves, double minMargin)
{
  const double hj = index.scale(nearest);
  margin = std::max({ 0.5 * hj, std::min(0.05 * centerMinDist, 2.0 * hj), minMargin });
  const double reach = centerMinDist + margin;
  const double sigma = std::sqrt(reach * reach * index.inverseSqScale(nearest) + cutoffSq);
  radius = std::numeric_limits<double>::infinity(); // not used: covers() reads margin
  const bool ranked = index.coordinateOrder();
  std::size_t kept = 0;
  Eigen::Index n = 0;
  // As in fetch(): every point of a leaf is written, and the count moves on for those kept.
  index.forEachLeafInScaledBall(y, margin, sigma, leaves, [&](std::uint32_t begin, std::uint32_t end) {
    if (ranked)
    {
      ranks.resize(std::max<std::size_t>(kept + (end - begin), ranks.size()));
    }
    else
    {
      reserve(n + (end - begin));
    }
    for (std::uint32_t i = begin; i < end; ++i)
    {
      const double r = margin + sigma * index.scale(i);
      const bool inside = (index.point(i) - y).squaredNorm() < r * r;
      if (ranked)
      {
        ranks[kept] = std::uint64_t(index.coordinateRank(i)) << 32 | i;
        kept += inside ? 1 : 0;
      }
      else
      {
        const Vec3& p = index.point(i);
        px[n] = p.x();
        py[n] = p.y();
        pz[n] = p.z();
        pk[n] = index.inverseSqScale(i);
        ph[n] = index.scale(i);
        ids[static_cast<std::size_t>(n)] = i;
        n += inside ? 1 : 0;
      }
    }
  });
  if (ranked)
  {
    ranks.resize(kept);
    sortByRank(ranks, rankScratch, index.size());
    n = static_cast<Eigen::Index>(kept);
    reserve(n);
    for (Eigen::Index k = 0; k < n; ++k)
    {
      const auto i = static_cast<std::uint32_t>(ranks[static_cast<std::size_t>(k)]);
      const Vec3& p = index.point(i);
      px[k] = p.x();
      py[k] = p.y();
      pz[k] = p.z();
      pk[k] = index.inverseSqScale(i);
      ph[k] = index.scale(i);
      ids[static_cast<std::size_t>(k)] = i;
    }
  }
  count = n;
  // The nearest point is always kept (sigma h_j > d_j + margin), unless the arithmetic overflowed.
  reusable = count > 0 && std::isfinite(sigma);
  if (count == 0)
  {
    reserve(1);
    const Vec3& p = index.point(nearest);
    px[0] = p.x();
    py[0] = p.y();
    pz[0] = p.z();
    pk[0] = index.inverseSqScale(nearest);
    ph[0] = index.scale(nearest);
    ids[0] = static_cast<std::uint32_t>(nearest);
    count = 1;
  }
}

// The same guarantee as a fetch at c with margin reach, from a scan of wider's candidates
// instead of a k-d tree query.
void CandidateCache::focus(const CandidateCache& wider, const Vec3& c, double reach, Eigen::ArrayXd& sq)
{
  indexSerial = wider.indexSerial;
  h = wider.h;
  band = wider.band;
  cutoffSq = wider.cutoffSq;
  scaled = wider.scaled;
  withNormals = wider.withNormals;
  center = c;
  const Eigen::Index m = wider.count;
  if (scaled)
  {
    focusScaled(wider, c, reach, sq);
    return;
  }
  centerMinDist = std::sqrt(wider.squaredDistances(c, sq).minCoeff());
  const double outer = centerMinDist + reach;
  radius = std::sqrt(outer * outer + band) + reach;
  const double sqRadius = radius * radius;
  reserve(m);
  const double* wx = wider.px.data();
  const double* wy = wider.py.data();
  const double* wz = wider.pz.data();
  const double* ds = sq.data();
  double* x = px.data();
  double* y = py.data();
  double* z = pz.data();
  std::uint32_t* id = ids.data();
  const std::uint32_t* wid = wider.ids.data();
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < m; ++i)
  {
    x[n] = wx[i];
    y[n] = wy[i];
    z[n] = wz[i];
    id[n] = wid[i];
    copyNormal(wider, i, n);
    n += ds[i] < sqRadius ? 1 : 0;
  }
  count = n;
  reusable = wider.reusable && n > 0 && std::isfinite(sqRadius);
}

// focus() with a scale per point: fetchScaled's bound, from the candidate nearest to c.
void CandidateCache::focusScaled(const CandidateCache& wider, const Vec3& c, double reach, Eigen::ArrayXd& sq)
{
  const Eigen::Index m = wider.count;
  const auto d2 = wider.squaredDistances(c, sq);
  Eigen::Index j = 0;
  const double minSq = d2.minCoeff(&j);
  centerMinDist = std::sqrt(minSq);
  margin = reach;
  const double outer = centerMinDist + reach;
  const double sigma = std::sqrt(outer * outer * wider.pk[j] + cutoffSq);
  radius = std::numeric_limits<double>::infinity();
  reserve(m);
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < m; ++i)
  {
    const double r = reach + sigma * wider.ph[i];
    px[n] = wider.px[i];
    py[n] = wider.py[i];
    pz[n] = wider.pz[i];
    pk[n] = wider.pk[i];
    ph[n] = wider.ph[i];
    ids[static_cast<std::size_t>(n)] = wider.ids[static_cast<std::size_t>(i)];
    copyNormal(wider, i, n);
    n += d2[i] < r * r ? 1 : 0;
  }
  count = n;
  reusable = wider.reusable && n > 0 && std::isfinite(sigma);
}

void CandidateCache::reserve(Eigen::Index n)
{
  if (px.size() < n)
  {
    const Eigen::Index capacity = std::max<Eigen::Index>(n, 2 * px.size());
    px.conservativeResize(capacity);
    py.conservativeResize(capacity);
    pz.conservativeResize(capacity);
    ids.resize(static_cast<std::size_t>(capacity));
    if (scaled)
    {
      pk.conservativeResize(capacity);
      ph.conservativeResize(capacity);
    }
  }
  if (scaled && pk.size() < px.size())
  {
    pk.conservativeResize(px.size());
    ph.conservativeResize(px.size());
  }
  if (withNormals && nx.size() < px.size())
  {
    nx.conservativeResize(px.size());
    ny.conservativeResize(px.size());
    nz.conservativeResize(px.size());
  }
}

void CandidateCache::copyNormal(const CandidateCache& wider, Eigen::Index from, Eigen::Index to)
{
  if (withNormals)
  {
    nx[to] = wider.nx[from];
    ny[to] = wider.ny[from];
    nz[to] = wider.nz[from];
  }
}
} // namespace pss

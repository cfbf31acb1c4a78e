// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pss
{

void SurfaceParameters::validate() const
{
  if (!(h > 0.0) || !std::isfinite(h))
  {
    throw std::invalid_argument("the scale h must be a positive finite number, got " + std::to_string(h));
  }
  if (!(cutoff > 0.0) || !std::isfinite(cutoff))
  {
    throw std::invalid_argument("the kernel cutoff must be a positive finite number of h, got " + std::to_string(cutoff));
  }
  if (quadratureOrder < 1 || quadratureOrder > 32)
  {
    throw std::invalid_argument(
      "the quadrature order must be in [1, 32], got " + std::to_string(quadratureOrder));
  }
  if (integrandPower != 1 && integrandPower != 2)
  {
    throw std::invalid_argument("the integrand power must be 1 or 2, got " + std::to_string(integrandPower));
  }
  if (!(minStability >= 0.0 && minStability < 1.0))
  {
    throw std::invalid_argument("the minimum stability must be in [0, 1), got " + std::to_string(minStability));
  }
}

void Neighbourhood::resize(Eigen::Index n)
{
  if (dx.size() < n)
  {
    const Eigen::Index capacity = std::max<Eigen::Index>(n, 2 * dx.size());
    for (Eigen::ArrayXd* a : { &dx, &dy, &dz, &sqDist, &weight })
    {
      a->resize(capacity);
    }
  }
  count = n;
}

namespace
{

// The candidates of a thread's last k-d tree query: absolute coordinates, ordered by index.
struct CandidateCache
{
  std::uint64_t indexSerial = 0; // 0: empty
  double h = 0.0;
  double band = 0.0;
  Vec3 center = Vec3::Zero();
  double centerMinDist = 0.0;
  double radius = 0.0;
  Eigen::ArrayXd px, py, pz;
  Eigen::Index count = 0;
  bool reusable = false; // the fetched ball is exact, so later queries may rely on it

  // True when every point within sqrt(dmin(y)^2 + band) of y is among the candidates:
  // dmin(y) <= centerMinDist + |y - center|, and that ball around y lies in the fetched one.
  // (With @p extra > 0: for every query within extra of y.)
  bool covers(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, double extra = 0.0) const
  {
    if (!reusable || indexSerial != index.serial() || h != params.h ||
      band != params.cutoff * params.cutoff * h * h)
    {
      return false;
    }
    const double shift = (y - center).norm() + extra;
    const double reach = centerMinDist + shift;
    return std::sqrt(reach * reach + band) + shift <= radius;
  }

  // Fetches the candidates around y with a margin of at least @p minMargin.
  void fetch(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, double minMargin = 0.0)
  {
    indexSerial = index.serial();
    h = params.h;
    band = params.cutoff * params.cutoff * h * h;
    center = y;
    const auto nearest = index.nearest(y);
    centerMinDist = std::sqrt(nearest.second);
    const double margin = std::max({ 0.25 * h, 0.05 * centerMinDist, minMargin });
    const double reach = centerMinDist + margin;
    radius = std::sqrt(reach * reach + band) + margin;
    const double sqRadius = radius * radius;
    count = 0;
    // The leaves come in index order, so the candidates do too: every later neighbourhood is
    // then independent of where this fetch was made.
    index.forEachLeafInBall(y, sqRadius, [&](std::uint32_t begin, std::uint32_t end) {
      reserve(count + (end - begin));
      for (std::uint32_t i = begin; i < end; ++i)
      {
        const Vec3& p = index.point(i);
        px[count] = p.x();
        py[count] = p.y();
        pz[count] = p.z();
        count += (p - y).squaredNorm() < sqRadius ? 1 : 0;
      }
    });
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
      count = 1;
    }
  }

  // Room for @p n candidates, keeping the first count.
  void reserve(Eigen::Index n)
  {
    if (px.size() < n)
    {
      const Eigen::Index capacity = std::max<Eigen::Index>(n, 2 * px.size());
      px.conservativeResize(capacity);
      py.conservativeResize(capacity);
      pz.conservativeResize(capacity);
    }
  }
};

thread_local CandidateCache ThreadCache;

} // namespace

void prefetchNeighbourhoods(const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach)
{
  const Vec3 c = index.restrict(center);
  if (!ThreadCache.covers(index, params, c, reach))
  {
    ThreadCache.fetch(index, params, c, reach);
  }
}

void gatherNeighbourhood(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, Neighbourhood& nb)
{
  CandidateCache& cache = ThreadCache;
  thread_local Eigen::ArrayXd candidateSq;

  const Vec3 origin = index.restrict(y);
  if (nb.indexSerial == index.serial() && nb.h == params.h && nb.cutoff == params.cutoff && nb.origin == origin)
  {
    return;
  }
  nb.indexSerial = 0; // until the new contents are complete
  nb.origin = origin;
  nb.invH2 = 1.0 / (params.h * params.h);
  if (!cache.covers(index, params, nb.origin))
  {
    cache.fetch(index, params, nb.origin);
  }
  const Eigen::Index m = cache.count;
  if (candidateSq.size() < m)
  {
    candidateSq.resize(m);
  }
  // Offsets are p - y from absolute coordinates: for large coordinates this subtraction is the
  // only place digits can go, and it is exact to one rounding whatever the cache centre was.
  auto sq = candidateSq.head(m);
  sq = (cache.px.head(m) - nb.origin.x()).square() + (cache.py.head(m) - nb.origin.y()).square() +
    (cache.pz.head(m) - nb.origin.z()).square();
  const double minSq = sq.minCoeff();
  const double limit = minSq + cache.band;

  nb.resize(m);
  Eigen::Index n = 0;
  // Branch-free compaction: every candidate is written, only those inside the band advance n.
  for (Eigen::Index i = 0; i < m; ++i)
  {
    nb.dx[n] = cache.px[i] - nb.origin.x();
    nb.dy[n] = cache.py[i] - nb.origin.y();
    nb.dz[n] = cache.pz[i] - nb.origin.z();
    nb.sqDist[n] = sq[i];
    n += (sq[i] < limit || sq[i] == minSq) ? 1 : 0;
  }
  nb.count = n;
  nb.minSqDist = minSq;
  nb.weight.head(n) = (-(nb.sqDist.head(n) - minSq) * nb.invH2).exp();
  nb.weightSum = nb.w().sum();
  nb.indexSerial = index.serial();
  nb.h = params.h;
  nb.cutoff = params.cutoff;
}

Neighbourhood& threadNeighbourhood()
{
  thread_local Neighbourhood nb;
  return nb;
}

Vec3 centroidOffset(const Neighbourhood& nb)
{
  const auto w = nb.w();
  return Vec3((w * nb.x()).sum(), (w * nb.y()).sum(), (w * nb.z()).sum()) / nb.weightSum;
}

// sum_i w_i (p_i - y - m)(p_i - y - m)^T: the six distinct entries, as lazy array expressions
// (no temporaries are allocated; each entry is one vectorized pass over the neighbours).
Mat3 weightedScatter(const Neighbourhood& nb, const Vec3& m)
{
  const auto w = nb.w();
  const auto cx = nb.x() - m.x();
  const auto cy = nb.y() - m.y();
  const auto cz = nb.z() - m.z();
  Mat3 c;
  c(0, 0) = (w * cx * cx).sum();
  c(1, 1) = (w * cy * cy).sum();
  c(2, 2) = (w * cz * cz).sum();
  c(0, 1) = c(1, 0) = (w * cx * cy).sum();
  c(0, 2) = c(2, 0) = (w * cx * cz).sum();
  c(1, 2) = c(2, 1) = (w * cy * cz).sum();
  return c;
}

Mat3 covarianceAboutQuery(const Neighbourhood& nb)
{
  return weightedScatter(nb, Vec3::Zero());
}

Mat3 covarianceAboutCentroid(const Neighbourhood& nb)
{
  // Two passes: far from the cloud the offsets are large and nearly equal, and the one-pass
  // form E[r r^T] - m m^T would cancel away the digits that matter.
  return weightedScatter(nb, centroidOffset(nb)) / nb.weightSum;
}

Direction smallestEigenDirection(const Mat3& C, int dimension, double minStability)
{
  Direction out;
  if (!C.allFinite())
  {
    return out;
  }
  double l0 = 0.0;
  double l1 = 0.0;
  double lmax = 0.0;
  if (dimension == 2)
  {
    const Eigen::Matrix2d c2 = C.topLeftCorner<2, 2>();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(c2);
    const Eigen::Vector2d v = solver.eigenvectors().col(0);
    out.n = Vec3(v.x(), v.y(), 0.0);
    l0 = solver.eigenvalues()(0);
    l1 = lmax = solver.eigenvalues()(1);
  }
  else
  {
    Eigen::SelfAdjointEigenSolver<Mat3> solver(C);
    out.n = solver.eigenvectors().col(0);
    l0 = solver.eigenvalues()(0);
    l1 = solver.eigenvalues()(1);
    lmax = solver.eigenvalues()(2);
  }
  // Eigenvalues within rounding of zero are zero: a rank-deficient matrix (all weight on one
  // point, or a collinear neighbourhood in 3D) has no unique smallest direction.
  const double floor = 64.0 * std::numeric_limits<double>::epsilon() * std::abs(lmax);
  l0 = l0 > floor ? l0 : 0.0;
  l1 = l1 > floor ? l1 : 0.0;
  out.stability = (l1 + l0) > 0.0 ? (l1 - l0) / (l1 + l0) : 0.0;
  out.n.normalize();
  out.defined = out.stability > minStability && out.n.allFinite();
  return out;
}

double approximateSqDistance(const Neighbourhood& nb)
{
  return (nb.w() * nb.d2()).sum() / nb.weightSum;
}

Vec3 approximateSqDistanceGradient(const Neighbourhood& nb, double delta)
{
  const auto w = nb.w();
  const auto spread = w * (nb.d2() - delta);
  const Vec3 centroid((w * nb.x()).sum(), (w * nb.y()).sum(), (w * nb.z()).sum());
  const Vec3 moment((spread * nb.x()).sum(), (spread * nb.y()).sum(), (spread * nb.z()).sum());
  return (-2.0 * centroid + 2.0 * nb.invH2 * moment) / nb.weightSum;
}

DistanceField::DistanceField(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
{
  Params.validate();
  if (Index.empty())
  {
    throw std::invalid_argument("the point cloud is empty (no finite points)");
  }
}

double DistanceField::delta(const Vec3& y) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, y, nb);
  return approximateSqDistance(nb);
}

double DistanceField::deltaAndGradient(const Vec3& y, Vec3& gradient, double* nearestSqDist) const
{
  thread_local Neighbourhood nb;
  gatherNeighbourhood(Index, Params, y, nb);
  if (nearestSqDist)
  {
    *nearestSqDist = nb.minSqDist;
  }
  const double d = approximateSqDistance(nb);
  gradient = approximateSqDistanceGradient(nb, d);
  return d;
}

} // namespace pss

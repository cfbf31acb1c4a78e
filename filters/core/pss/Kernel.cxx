// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include <Eigen/Eigenvalues>

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

void gatherNeighbourhood(const PointIndex& index, const SurfaceParameters& params, const Vec3& y, Neighbourhood& nb)
{
  // Reused across calls on the same thread: the search buffer is the only allocation per query.
  thread_local std::vector<std::pair<std::uint32_t, double>> found;

  nb.origin = index.restrict(y);
  nb.invH2 = 1.0 / (params.h * params.h);
  const auto nearest = index.nearest(nb.origin);
  const double band = params.cutoff * params.cutoff * params.h * params.h;
  index.withinSqRadius(nb.origin, nearest.second + band, found);
  if (found.empty())
  {
    // Only when dmin^2 + band rounds to dmin^2 (absurd scale ratios): keep the nearest point.
    found.emplace_back(static_cast<std::uint32_t>(nearest.first), nearest.second);
  }

  const std::size_t n = found.size();
  nb.offsets.resize(n);
  nb.sqDist.resize(n);
  nb.weight.resize(n);
  double minSq = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
  {
    // Offsets relative to the query keep covariances exact for large coordinates.
    nb.offsets[i] = index.point(found[i].first) - nb.origin;
    nb.sqDist[i] = nb.offsets[i].squaredNorm();
    minSq = std::min(minSq, nb.sqDist[i]);
  }
  nb.minSqDist = minSq;
  nb.weightSum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    nb.weight[i] = std::exp(-(nb.sqDist[i] - minSq) * nb.invH2);
    nb.weightSum += nb.weight[i];
  }
}

Vec3 centroidOffset(const Neighbourhood& nb)
{
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    sum += nb.weight[i] * nb.offsets[i];
  }
  return sum / nb.weightSum;
}

Mat3 covarianceAboutQuery(const Neighbourhood& nb)
{
  Mat3 c = Mat3::Zero();
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    c.noalias() += nb.weight[i] * nb.offsets[i] * nb.offsets[i].transpose();
  }
  return c;
}

Mat3 covarianceAboutCentroid(const Neighbourhood& nb)
{
  // Two passes: far from the cloud the offsets are large and nearly equal, and the one-pass
  // form E[r r^T] - m m^T would cancel away the digits that matter.
  const Vec3 m = centroidOffset(nb);
  Mat3 c = Mat3::Zero();
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    const Vec3 d = nb.offsets[i] - m;
    c.noalias() += nb.weight[i] * d * d.transpose();
  }
  return c / nb.weightSum;
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
  double sum = 0.0;
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    sum += nb.weight[i] * nb.sqDist[i];
  }
  return sum / nb.weightSum;
}

Vec3 approximateSqDistanceGradient(const Neighbourhood& nb, double delta)
{
  Vec3 centroid = Vec3::Zero();
  Vec3 spread = Vec3::Zero();
  for (std::size_t i = 0; i < nb.size(); ++i)
  {
    centroid += nb.weight[i] * nb.offsets[i];
    spread += nb.weight[i] * (nb.sqDist[i] - delta) * nb.offsets[i];
  }
  return (-2.0 * centroid + 2.0 * nb.invH2 * spread) / nb.weightSum;
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

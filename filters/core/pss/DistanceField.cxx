// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include "pss/PointIndex.h"
#include "pss/Workspace.h"

#include <cmath>

namespace pss
{

double approximateSqDistance(const Neighbourhood& nb)
{
  return (nb.w() * nb.d2()).sum() / nb.weightSum;
}

namespace
{

// What delta's jet and Hessian share (approximateSqDistanceJet's formulas): delta, the weighted
// mean offset m, T = sum theta_N (d_i^2 - delta) r_i, and grad delta.
struct DeltaFirstOrder
{
  double value = 0.0;
  Vec3 m = Vec3::Zero();
  Vec3 t = Vec3::Zero();
  Vec3 gradient = Vec3::Zero();
};

DeltaFirstOrder deltaFirstOrder(const Neighbourhood& nb)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  DeltaFirstOrder out;
  out.value = (w * nb.d2()).sum() / weightSum;
  const auto spread = w * (nb.d2() - out.value);
  out.m = Vec3((w * nb.x()).sum(), (w * nb.y()).sum(), (w * nb.z()).sum()) / weightSum;
  out.t = Vec3((spread * nb.x()).sum(), (spread * nb.y()).sum(), (spread * nb.z()).sum()) / weightSum;
  out.gradient = -2.0 * out.m + 2.0 * nb.invH2 * out.t;
  return out;
}

} // namespace

DeltaJet approximateSqDistanceJet(const Neighbourhood& nb, const Vec3& a)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  const DeltaFirstOrder first = deltaFirstOrder(nb);
  DeltaJet out;
  out.value = first.value;
  out.gradient = first.gradient;
  const Vec3& m = first.m;
  const Vec3& t = first.t;
  const auto spread = w * (nb.d2() - out.value);
  const auto along = a.x() * nb.x() + a.y() * nb.y() + a.z() * nb.z(); // <a, r_i>
  const double k = nb.invH2;
  const double am = a.dot(m);
  const double alongCovariance = (w * along.square()).sum() / weightSum - am * am;
  const double alongSpread = (spread * along.square()).sum() / weightSum;
  out.curvature = 2.0 - 8.0 * k * alongCovariance + 4.0 * k * k * (alongSpread - 2.0 * a.dot(t) * am);
  return out;
}

DeltaHessian approximateSqDistanceHessian(const Neighbourhood& nb)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  const DeltaFirstOrder first = deltaFirstOrder(nb);
  DeltaHessian out;
  out.value = first.value;
  out.gradient = first.gradient;
  const Vec3& m = first.m;
  const Vec3& t = first.t;
  const auto spread = w * (nb.d2() - out.value);
  const double k = nb.invH2;
  // Second moments about y, weighted by w and by the spread, one entry of the upper triangle at a time.
  Mat3 second, spreadSecond;
  const std::array<decltype(nb.x()), 3> r{ nb.x(), nb.y(), nb.z() };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = i; j < 3; ++j)
    {
      const auto rr = r[i] * r[j];
      second(i, j) = second(j, i) = (w * rr).sum() / weightSum;
      spreadSecond(i, j) = spreadSecond(j, i) = (spread * rr).sum() / weightSum;
    }
  }
  const Mat3 covariance = second - m * m.transpose();
  out.hessian = 2.0 * Mat3::Identity() - 8.0 * k * covariance +
    4.0 * k * k * (spreadSecond - t * m.transpose() - m * t.transpose());
  return out;
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

double DistanceField::delta(const Vec3& y, Workspace& ws) const
{
  Neighbourhood& nb = ws.field;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  return approximateSqDistance(nb);
}

DeltaJet DistanceField::jet(const Vec3& y, const Vec3& a, Workspace& ws, double* nearestSqDist) const
{
  Neighbourhood& nb = ws.field;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  if (nearestSqDist)
  {
    *nearestSqDist = nb.minSqDist;
  }
  return approximateSqDistanceJet(nb, a);
}

DeltaHessian DistanceField::hessian(const Vec3& y, Workspace& ws) const
{
  Neighbourhood& nb = ws.field;
  gatherNeighbourhood(Index, Params, y, nb, ws);
  return approximateSqDistanceHessian(nb);
}

} // namespace pss

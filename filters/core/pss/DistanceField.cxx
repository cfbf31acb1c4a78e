// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include "pss/PointIndex.h"
#include "pss/Workspace.h"

#include <array>
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

// delta's derivatives with a scale per point. With k_i = 1 / h_i^2, grad theta_i = 2 k_i theta_i r_i,
// so (theta_N the normalized weights, r_i = p_i - y, m = sum theta_N r_i):
//   grad delta = -2 m + 2 T_k,            T_k = sum theta_N k_i (d_i^2 - delta) r_i,
//   H = 2 (1 - s_k) I + 4 S_kk - 8 R_k - 2 (m_k g^T + g m_k^T),
// with g = grad delta, s_k = sum theta_N k_i (d_i^2 - delta), S_kk = sum theta_N k_i^2 (d_i^2 - delta)
// r_i r_i^T, R_k = sum theta_N k_i r_i r_i^T and m_k = sum theta_N k_i r_i. With every k_i = k this
// is the single scale's formula (s_k = 0, m_k = k m).
struct ScaledDelta
{
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  Vec3 mk = Vec3::Zero();
  double sk = 0.0;
};

ScaledDelta scaledFirstOrder(const Neighbourhood& nb)
{
  const auto w = nb.w();
  const double weightSum = nb.weightSum;
  ScaledDelta out;
  out.value = (w * nb.d2()).sum() / weightSum;
  const auto wk = (w * nb.k()).eval();
  const auto spreadK = (wk * (nb.d2() - out.value)).eval();
  const Vec3 m = Vec3((w * nb.x()).sum(), (w * nb.y()).sum(), (w * nb.z()).sum()) / weightSum;
  const Vec3 tk = Vec3((spreadK * nb.x()).sum(), (spreadK * nb.y()).sum(), (spreadK * nb.z()).sum()) / weightSum;
  out.mk = Vec3((wk * nb.x()).sum(), (wk * nb.y()).sum(), (wk * nb.z()).sum()) / weightSum;
  out.sk = spreadK.sum() / weightSum;
  out.gradient = -2.0 * m + 2.0 * tk;
  return out;
}

// a^T H a (the formula above) and, when @p hessian is given, the whole H.
double scaledSecondOrder(const Neighbourhood& nb, const ScaledDelta& first, const Vec3& a, Mat3* hessian)
{
  const double weightSum = nb.weightSum;
  const auto wk = (nb.w() * nb.k()).eval();
  const auto spreadKK = (wk * nb.k() * (nb.d2() - first.value)).eval();
  const auto along = (a.x() * nb.x() + a.y() * nb.y() + a.z() * nb.z()).eval();
  const double curvature = 2.0 * (1.0 - first.sk) + (4.0 * (spreadKK * along.square()).sum() -
    8.0 * (wk * along.square()).sum()) / weightSum - 4.0 * a.dot(first.mk) * a.dot(first.gradient);
  if (hessian)
  {
    const std::array<decltype(nb.x()), 3> r{ nb.x(), nb.y(), nb.z() };
    Mat3 h;
    for (int i = 0; i < 3; ++i)
    {
      for (int j = i; j < 3; ++j)
      {
        const auto rr = r[i] * r[j];
        h(i, j) = h(j, i) = (4.0 * (spreadKK * rr).sum() - 8.0 * (wk * rr).sum()) / weightSum;
      }
    }
    const Mat3 outer = first.mk * first.gradient.transpose();
    *hessian = 2.0 * (1.0 - first.sk) * Mat3::Identity() + h - 2.0 * (outer + outer.transpose());
  }
  return curvature;
}

} // namespace

DeltaJet approximateSqDistanceJet(const Neighbourhood& nb, const Vec3& a)
{
  if (nb.scaled)
  {
    const ScaledDelta first = scaledFirstOrder(nb);
    DeltaJet out;
    out.value = first.value;
    out.gradient = first.gradient;
    out.curvature = scaledSecondOrder(nb, first, a, nullptr);
    return out;
  }
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
  if (nb.scaled)
  {
    const ScaledDelta first = scaledFirstOrder(nb);
    DeltaHessian out;
    out.value = first.value;
    out.gradient = first.gradient;
    scaledSecondOrder(nb, first, Vec3::UnitX(), &out.hessian);
    return out;
  }
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

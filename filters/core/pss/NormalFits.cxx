// SPDX-License-Identifier: BSD-3-Clause
// APSS and RIMLS: the fits of points with oriented normals (DirectionRulesAndEnergies.h).
#include "pss/DirectionRulesAndEnergies.h"

#include "pss/Workspace.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pss
{

namespace
{

double clampedStability(double s)
{
  return s > 0.0 ? std::min(s, 1.0) : 0.0;
}

NormalFit undefinedFit(double stability)
{
  NormalFit out;
  out.stability = stability;
  return out;
}

// Guennebaud and Gross's closed form (their Sec. 3.2): with normalized weights, P the weighted
// mean of r, N of n, and the means <r . n> and <|r|^2>,
//   uq = 1/2 (<r . n> - P . N) / (<|r|^2> - |P|^2),  ul = N - 2 uq P,  u0 = -ul . P - uq <|r|^2>,
// then divided by sqrt(|ul|^2 - 4 u0 uq) (Pratt), so that u0, the value at x, is about the
// signed distance and |grad| = 1 on the sphere. The nearest zero along the gradient's line
// (which passes through the centre) is t = -2 u0 / (1 + |ul|).
NormalFit sphereFit(const Neighbourhood& nb, const SurfaceParameters& params)
{
  const double W = nb.weightSum;
  const OrientedMoments sums = orientedMoments(nb);
  const Vec3 P = nb.moment / W;
  const Vec3 N = sums.normal / W;
  // Within [0, 1] (rounding can carry a mean of unit vectors a hair past 1); NaN counts as 0.
  const double stability = clampedStability(N.norm());
  const double meanRN = sums.offsetAlongNormal / W;
  const double meanRR = sums.squaredOffset / W;
  const double spread = meanRR - P.squaredNorm(); // the weighted variance of the positions
  const double scale = nb.localScale;
  // No spread (a single point, coincident points): the plane through them, normal to N.
  const double uq = spread > 1e-12 * scale * scale ? 0.5 * params.sphericity * (meanRN - P.dot(N)) / spread : 0.0;
  Vec3 ul = N - 2.0 * uq * P;
  double u0 = -ul.dot(P) - uq * meanRR;
  const double pratt = ul.squaredNorm() - 4.0 * u0 * uq;
  if (!(pratt > 0.0) || !std::isfinite(pratt) || !(stability > params.minStability))
  {
    return undefinedFit(stability);
  }
  const double norm = std::sqrt(pratt);
  u0 /= norm;
  ul /= norm;
  const double g = ul.norm();
  if (!(g > 0.0) || !std::isfinite(g))
  {
    return undefinedFit(stability);
  }
  NormalFit out;
  out.value = u0;
  out.gradient = ul;
  out.step = (-2.0 * u0 / (1.0 + g)) * (ul / g);
  out.secondDerivative = 2.0 * uq / norm;
  out.stability = stability;
  out.defined = true;
  return out;
}

// Oztireli, Guennebaud and Gross's Algorithm 1 with Gaussian weights w_i = exp(-|x - p_i|^2 k_i)
// (k_i = 1 / h_i^2), whose gradient is 2 k_i w_i r_i. Each refit multiplies the weights by
// exp(-((f_i - f) / (sigma_r h))^2 - (|n_i - grad f| / sigma_n)^2) with f_i = (x - p_i) . n_i and
// f, grad f of the previous fit: points far off the others' surface, and normals across a sharp
// edge, count less. A fixed number of refits keeps f continuous in x. Each fit is one pass over
// the neighbours; @p inverseSqScale(i) is k_i.
template <class InverseSqScale>
NormalFit robustFit(Neighbourhood& nb, const SurfaceParameters& params, InverseSqScale inverseSqScale)
{
  const Eigen::Index c = nb.count;
  const double* rx = nb.dx.data();
  const double* ry = nb.dy.data();
  const double* rz = nb.dz.data();
  const double* nx = nb.nx.data();
  const double* ny = nb.ny.data();
  const double* nz = nb.nz.data();
  const double* w = nb.weight.data();
  // The refits' weights: their exponents (never positive) then expNonPositive, several at a time.
  double* robust = nb.robust.data();
  const double sigmaR = params.sigmaResidual * nb.localScale;
  const double residualFactor = 1.0 / (sigmaR * sigmaR);
  const double normalFactor = 1.0 / (params.sigmaNormal * params.sigmaNormal);
  double f = 0.0;
  Vec3 grad = Vec3::Zero();
  double W = 0.0;
  Vec3 sumN = Vec3::Zero();
  for (int refit = 0; refit <= params.robustRefits; ++refit)
  {
    const double gg = grad.squaredNorm();
    if (refit > 0)
    {
      for (Eigen::Index i = 0; i < c; ++i)
      {
        const double residual = -(rx[i] * nx[i] + ry[i] * ny[i] + rz[i] * nz[i]) - f;
        const double normalGap = 1.0 - 2.0 * (nx[i] * grad.x() + ny[i] * grad.y() + nz[i] * grad.z()) + gg;
        robust[i] = std::min(0.0, -residual * residual * residualFactor - normalGap * normalFactor);
      }
      expNonPositive(robust, robust, c);
    }
    double sumW = 0.0, sumF = 0.0;
    double sumG[3] = { 0.0, 0.0, 0.0 }, sumGF[3] = { 0.0, 0.0, 0.0 }, sumNormal[3] = { 0.0, 0.0, 0.0 };
    for (Eigen::Index i = 0; i < c; ++i)
    {
      const double fi = -(rx[i] * nx[i] + ry[i] * ny[i] + rz[i] * nz[i]); // (x - p_i) . n_i
      const double wi = refit > 0 ? w[i] * robust[i] : w[i];
      const double wk = 2.0 * wi * inverseSqScale(i);
      sumW += wi;
      sumF += wi * fi;
      sumG[0] += wk * rx[i];
      sumG[1] += wk * ry[i];
      sumG[2] += wk * rz[i];
      sumGF[0] += wk * fi * rx[i];
      sumGF[1] += wk * fi * ry[i];
      sumGF[2] += wk * fi * rz[i];
      sumNormal[0] += wi * nx[i];
      sumNormal[1] += wi * ny[i];
      sumNormal[2] += wi * nz[i];
    }
    W = sumW;
    if (!(W > 0.0) || !std::isfinite(W))
    {
      return undefinedFit(0.0);
    }
    f = sumF / W;
    sumN = Vec3(sumNormal[0], sumNormal[1], sumNormal[2]);
    grad = (Vec3(sumGF[0], sumGF[1], sumGF[2]) - f * Vec3(sumG[0], sumG[1], sumG[2]) + sumN) / W;
  }
  const double stability = clampedStability(sumN.norm() / W);
  const double g = grad.norm();
  if (!(g > 0.0) || !std::isfinite(g) || !std::isfinite(f) || !(stability > params.minStability))
  {
    return undefinedFit(stability);
  }
  NormalFit out;
  out.value = f;
  out.gradient = grad;
  out.step = (-f / g) * (grad / g);
  out.stability = stability;
  out.defined = true;
  return out;
}

} // namespace

NormalFit fitWithNormals(
  NormalFitKind kind, const PointIndex& index, const SurfaceParameters& params, const Vec3& x, Workspace& ws)
{
  Neighbourhood& nb = ws.query;
  gatherOrientedNeighbourhood(index, params, x, nb, ws);
  if (kind == NormalFitKind::AlgebraicSphere)
  {
    return sphereFit(nb, params);
  }
  if (nb.scaled)
  {
    const double* k = nb.inverseSqScale.data();
    return robustFit(nb, params, [k](Eigen::Index i) { return k[i]; });
  }
  const double k = nb.invH2;
  return robustFit(nb, params, [k](Eigen::Index) { return k; });
}

NormalFitDirection::NormalFitDirection(const PointIndex& index, const SurfaceParameters& params, NormalFitKind kind)
  : Index(index)
  , Params(params)
  , Kind(kind)
{
  if (!index.hasNormals())
  {
    throw std::invalid_argument(std::string(kind == NormalFitKind::AlgebraicSphere ? "APSS" : "RIMLS") +
      " needs an oriented normal at every cloud point (a Normals array, or normals estimated and oriented)");
  }
}

DirectionFit NormalFitDirection::fit(const Vec3& x, DirectionMemory&, Workspace& ws) const
{
  const NormalFit f = fitWithNormals(Kind, Index, Params, x, ws);
  DirectionFit out;
  out.direction.stability = f.stability;
  out.direction.defined = f.defined;
  if (f.defined)
  {
    out.direction.n = f.gradient.normalized();
    out.hasStep = true;
    out.step = f.step;
  }
  out.neighbourhood = &ws.query;
  return out;
}

NormalFitEnergy::NormalFitEnergy(const PointIndex& index, const SurfaceParameters& params, NormalFitKind kind)
  : Index(index)
  , Params(params)
  , Kind(kind)
{
}

LineSample NormalFitEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  const NormalFit f = fitWithNormals(Kind, Index, Params, y, ws);
  LineSample out;
  out.nearestSqDist = ws.query.minSqDist;
  const double along = f.gradient.dot(a);
  out.value = f.value * f.value;
  out.slope = 2.0 * f.value * along;
  out.curvature = 2.0 * (along * along + f.value * f.secondDerivative * a.squaredNorm());
  return out;
}

} // namespace pss

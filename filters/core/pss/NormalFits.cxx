// SPDX-License-Identifier: BSD-3-Clause
// APSS and RIMLS: the fits of points with oriented normals (DirectionRulesAndEnergies.h).
#include "pss/DirectionRulesAndEnergies.h"

#include "pss/Workspace.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pss
{

namespace
{

// Sums over the neighbourhood in local coordinates (r_i = p_i - x); the shifted weights suffice,
// every quantity below being a ratio of sums.
Vec3 weightedNormalSum(const Neighbourhood& nb, const Eigen::Ref<const Eigen::ArrayXd>& w)
{
  const Eigen::Index c = nb.count;
  return Vec3((w * nb.nx.head(c)).sum(), (w * nb.ny.head(c)).sum(), (w * nb.nz.head(c)).sum());
}

// The neighbours' (p_i - x) . n_i.
auto normalOffsets(const Neighbourhood& nb)
{
  const Eigen::Index c = nb.count;
  return nb.x() * nb.nx.head(c) + nb.y() * nb.ny.head(c) + nb.z() * nb.nz.head(c);
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
  const auto w = nb.w();
  const Vec3 P = nb.moment / W;
  const Vec3 N = weightedNormalSum(nb, w) / W;
  const double stability = N.norm();
  const double meanRN = (w * normalOffsets(nb)).sum() / W;
  const double meanRR = (w * nb.d2()).sum() / W;
  const double spread = meanRR - P.squaredNorm(); // the weighted variance of the positions
  const double scale = nb.localScale;
  // No spread (a single point, coincident points): the plane through them, normal to N.
  const double uq = spread > 1e-12 * scale * scale ? 0.5 * params.sphericity * (meanRN - P.dot(N)) / spread : 0.0;
  Vec3 ul = N - 2.0 * uq * P;
  double u0 = -ul.dot(P) - uq * meanRR;
  const double pratt = ul.squaredNorm() - 4.0 * u0 * uq;
  if (!(pratt > 0.0) || !std::isfinite(pratt) || !(stability >= params.minStability))
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
  out.stability = stability;
  out.defined = true;
  return out;
}

// Oztireli, Guennebaud and Gross's Algorithm 1 with Gaussian weights w_i = exp(-|x - p_i|^2 k_i)
// (k_i = 1 / h_i^2), whose gradient is 2 k_i w_i r_i. Each refit multiplies the weights by
// exp(-((f_i - f) / (sigma_r h))^2 - (|n_i - grad f| / sigma_n)^2) with f_i = (x - p_i) . n_i and
// f, grad f of the previous fit: points far off the others' surface, and normals across a sharp
// edge, count less. A fixed number of refits keeps f continuous in x.
template <class InverseSqScale>
NormalFit robustFit(Neighbourhood& nb, const SurfaceParameters& params, const InverseSqScale& k)
{
  const Eigen::Index c = nb.count;
  auto ww = nb.robust.head(c);
  const auto residual = -normalOffsets(nb); // f_i = (x - p_i) . n_i
  const double sigmaR = params.sigmaResidual * nb.localScale;
  double f = 0.0;
  Vec3 grad = Vec3::Zero();
  double W = 0.0;
  Vec3 sumN = Vec3::Zero();
  for (int refit = 0; refit <= params.robustRefits; ++refit)
  {
    if (refit == 0)
    {
      ww = nb.w();
    }
    else
    {
      const double gg = grad.squaredNorm();
      const auto normalGap = 1.0 - 2.0 * (nb.nx.head(c) * grad.x() + nb.ny.head(c) * grad.y() + nb.nz.head(c) * grad.z()) + gg;
      ww = nb.w() *
        (-(residual - f).square() / (sigmaR * sigmaR) - normalGap / (params.sigmaNormal * params.sigmaNormal)).exp();
    }
    W = ww.sum();
    if (!(W > 0.0) || !std::isfinite(W))
    {
      return undefinedFit(0.0);
    }
    f = (ww * residual).sum() / W;
    const auto wk = ww * k;
    const Vec3 sumG(2.0 * (wk * nb.x()).sum(), 2.0 * (wk * nb.y()).sum(), 2.0 * (wk * nb.z()).sum());
    const auto wkf = wk * residual;
    const Vec3 sumGF(2.0 * (wkf * nb.x()).sum(), 2.0 * (wkf * nb.y()).sum(), 2.0 * (wkf * nb.z()).sum());
    sumN = weightedNormalSum(nb, ww);
    grad = (sumGF - f * sumG + sumN) / W;
  }
  const double stability = sumN.norm() / W;
  const double g = grad.norm();
  if (!(g > 0.0) || !std::isfinite(g) || !std::isfinite(f) || !(stability >= params.minStability))
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
  return nb.scaled ? robustFit(nb, params, nb.k()) : robustFit(nb, params, nb.invH2);
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
  out.value = f.value * f.value;
  out.slope = 2.0 * f.value * f.gradient.dot(a);
  return out;
}

} // namespace pss

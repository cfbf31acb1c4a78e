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
// edge, count less. A fixed number of refits keeps f continuous in x. Each fit is one vector pass
// over the neighbours (robustSums), each refit's factors another (robustFactors).
NormalFit robustFit(Neighbourhood& nb, const SurfaceParameters& params)
{
  const double sigmaR = params.sigmaResidual * nb.localScale;
  const double residualFactor = 1.0 / (sigmaR * sigmaR);
  const double normalFactor = 1.0 / (params.sigmaNormal * params.sigmaNormal);
  double f = 0.0;
  Vec3 grad = Vec3::Zero();
  RobustSums sums;
  for (int refit = 0; refit <= params.robustRefits; ++refit)
  {
    const double* robust = nullptr;
    if (refit > 0)
    {
      robustFactors(nb, f, grad, residualFactor, normalFactor, nb.robust.data());
      robust = nb.robust.data();
    }
    sums = robustSums(nb, robust);
    const double W = sums.weight;
    if (!(W > 0.0) || !std::isfinite(W))
    {
      return undefinedFit(0.0);
    }
    f = sums.value / W;
    grad = (sums.valueOffset - f * sums.offset + sums.normal) / W;
  }
  const double stability = clampedStability(sums.normal.norm() / sums.weight);
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
  return kind == NormalFitKind::AlgebraicSphere ? sphereFit(nb, params) : robustFit(nb, params);
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

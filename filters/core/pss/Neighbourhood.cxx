// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Kernel.h"

#include "pss/KernelDispatch.h"
#include "pss/PointIndex.h"
#include "pss/Workspace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pss
{

using dispatch::kernels;
using dispatch::SimdLanes;

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
  if (!(deltaLattice == 0.0 || (deltaLattice >= 0.05 && deltaLattice <= 1.0)))
  {
    throw std::invalid_argument(
      "the delta lattice spacing must be 0 (exact) or in [0.05, 1] h, got " + std::to_string(deltaLattice));
  }
  if (!(sphericity >= 0.0 && sphericity <= 1.0))
  {
    throw std::invalid_argument("the APSS sphericity must be in [0, 1], got " + std::to_string(sphericity));
  }
  if (!(sigmaNormal > 0.0) || !std::isfinite(sigmaNormal) || !(sigmaResidual > 0.0) || !std::isfinite(sigmaResidual))
  {
    throw std::invalid_argument("the RIMLS sigma_n and sigma_r must be positive finite numbers, got " +
      std::to_string(sigmaNormal) + " and " + std::to_string(sigmaResidual));
  }
  if (robustRefits < 0 || robustRefits > 100)
  {
    throw std::invalid_argument("the RIMLS refits must be in [0, 100], got " + std::to_string(robustRefits));
  }
}

void Neighbourhood::resize(Eigen::Index n)
{
  // Room for a whole vector past the end: the loops below read and write in whole vectors.
  const Eigen::Index needed = n + SimdLanes;
  if (dx.size() < needed)
  {
    const Eigen::Index capacity = std::max<Eigen::Index>(needed, 2 * dx.size());
    for (Eigen::ArrayXd* a : { &dx, &dy, &dz, &sqDist, &weight, &inverseSqScale, &pointScale, &nx, &ny, &nz, &robust })
    {
      a->resize(capacity);
    }
  }
  count = n;
}

void prefetchNeighbourhoods(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach, Workspace& ws)
{
  const Vec3 c = index.restrict(center);
  if (!ws.wide.covers(index, params, c, reach))
  {
    // Half an h of slack beyond the reach asked for, so that nearby centres (the steps of a
    // projection, the samples of a line search) reuse the same fetch.
    // (With a scale per point the fetch adds half the nearest point's own scale.)
    ws.wide.fetch(index, params, c, ws.leaves, reach + (index.hasScales() ? 0.0 : 0.5 * params.h));
  }
}

void focusNeighbourhoods(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& center, double reach, Workspace& ws)
{
  const Vec3 c = index.restrict(center);
  if (ws.focused.covers(index, params, c, reach))
  {
    return;
  }
  prefetchNeighbourhoods(index, params, c, reach, ws);
  ws.focused.focus(ws.wide, c, reach, ws.focusSq);
}

void noteReach(const PointIndex& index, const Vec3& y, double sqRadius, Workspace& ws)
{
  if (!index.holdsBall(y, std::sqrt(sqRadius)))
  {
    ws.leftCompleteRegion = true;
  }
}

namespace
{

// The ball an evaluation at y reads with a scale per point: every point with
// d^2 / h_i^2 < s + cutoff^2 lies within the largest scale times sqrt(s + cutoff^2).
double scaledReachSq(const PointIndex& index, const Neighbourhood& nb, double cutoff)
{
  return index.maxScale() * index.maxScale() * (nb.minScaledSqDist + cutoff * cutoff);
}

// The kernels' view of @p cache's first count candidates, whose squared distances are @p sq.
dispatch::Candidates candidatesOf(const CandidateCache& cache, const double* sq)
{
  const bool normals = cache.withNormals;
  return { cache.px.data(), cache.py.data(), cache.pz.data(), sq, normals ? cache.nx.data() : nullptr,
    normals ? cache.ny.data() : nullptr, normals ? cache.nz.data() : nullptr, cache.count };
}

// The padding after the last of @p n neighbours (up to @p padded) holds zero normals.
void padNormals(Neighbourhood& nb, Eigen::Index n, Eigen::Index padded)
{
  if (nb.withNormals)
  {
    for (Eigen::Index i = n; i < padded; ++i)
    {
      nb.nx[i] = nb.ny[i] = nb.nz[i] = 0.0;
    }
  }
}

// gatherNeighbourhood with a scale per point (the file comment of Kernel.h): the scaled squared
// distances s_i = d_i^2 / h_i^2 take the place of d_i^2 / h^2, per candidate.
void gatherScaled(const PointIndex& index, const SurfaceParameters& params, const CandidateCache& cache,
  Neighbourhood& nb, Workspace& ws)
{
  const Eigen::Index m = cache.count;
  const auto sq = cache.squaredDistances(nb.origin, ws.candidateSq);
  if (ws.scaledSq.size() < m)
  {
    ws.scaledSq.resize(m);
  }
  auto scaledSq = ws.scaledSq.head(m);
  scaledSq = sq * cache.pk.head(m);
  const double minScaled = scaledSq.minCoeff();
  const double bound = minScaled + params.cutoff * params.cutoff;
  nb.resize(m);
  // The exponents go to weight, for expNonPositive below.
  const dispatch::ScaledCandidates candidates{ candidatesOf(cache, sq.data()), scaledSq.data(), cache.pk.data(),
    cache.ph.data() };
  const Eigen::Index n = kernels().compactScaled(candidates, nb.origin, bound, minScaled, nb);
  // The last vector is padded with neighbours of weight 0 at offset 0, which add nothing.
  const Eigen::Index padded = (n + SimdLanes - 1) / SimdLanes * SimdLanes;
  for (Eigen::Index i = n; i < padded; ++i)
  {
    nb.dx[i] = nb.dy[i] = nb.dz[i] = 0.0;
    nb.sqDist[i] = std::numeric_limits<double>::infinity();
    nb.inverseSqScale[i] = nb.pointScale[i] = 0.0;
    nb.weight[i] = -std::numeric_limits<double>::infinity();
  }
  padNormals(nb, n, padded);
  // Weights, their sum, the first moments and the weighted scale in one pass.
  double sums[5];
  kernels().scaledWeights(
    nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.pointScale.data(), nb.weight.data(), padded, sums);
  nb.count = n;
  nb.minSqDist = nb.d2().minCoeff();
  nb.minScaledSqDist = minScaled;
  nb.weightSum = sums[0];
  nb.moment = Vec3(sums[1], sums[2], sums[3]);
  nb.localScale = sums[4] / nb.weightSum;
  noteReach(index, nb.origin, scaledReachSq(index, nb, params.cutoff), ws);
}

} // namespace

void gatherNeighbourhood(
  const PointIndex& index, const SurfaceParameters& params, const Vec3& y, Neighbourhood& nb, Workspace& ws)
{
  const Vec3 origin = index.restrict(y);
  if (nb.indexSerial == index.serial() && nb.h == params.h && nb.cutoff == params.cutoff && nb.origin == origin)
  {
    noteReach(index, origin,
      nb.scaled ? scaledReachSq(index, nb, params.cutoff)
                : nb.minSqDist + params.cutoff * params.cutoff * params.h * params.h,
      ws);
    return;
  }
  nb.indexSerial = 0; // until the new contents are complete
  nb.withNormals = false;
  nb.origin = origin;
  nb.invH2 = 1.0 / (params.h * params.h);
  nb.scaled = index.hasScales();
  nb.localScale = params.h;
  // Either cache holds, in index order, every point the neighbourhood can need, so which one
  // serves the query does not change a bit of the result.
  const bool focused = ws.focused.covers(index, params, nb.origin);
  CandidateCache& cache = focused ? ws.focused : ws.wide;
  if (!focused && !cache.covers(index, params, nb.origin))
  {
    cache.fetch(index, params, nb.origin, ws.leaves, index.hasScales() ? 0.0 : ws.fetchSlack * params.h);
  }
  nb.withNormals = cache.withNormals;
  if (nb.scaled)
  {
    gatherScaled(index, params, cache, nb, ws);
    nb.indexSerial = index.serial();
    nb.h = params.h;
    nb.cutoff = params.cutoff;
    return;
  }
  const Eigen::Index m = cache.count;
  // Offsets are p - y from absolute coordinates: for large coordinates this subtraction is the
  // only place digits can go, and it is exact to one rounding whatever the cache centre was.
  const auto sq = cache.squaredDistances(nb.origin, ws.candidateSq);
  const double minSq = sq.minCoeff();
  nb.resize(m);
  const Eigen::Index n = kernels().compact(candidatesOf(cache, sq.data()), nb.origin, minSq + cache.band, minSq, nb);
  nb.count = n;
  nb.minSqDist = minSq;
  noteReach(index, origin, minSq + cache.band, ws);
  // The last vector is padded with neighbours of weight 0 at offset 0, which add nothing.
  const Eigen::Index padded = (n + SimdLanes - 1) / SimdLanes * SimdLanes;
  for (Eigen::Index i = n; i < padded; ++i)
  {
    nb.dx[i] = nb.dy[i] = nb.dz[i] = 0.0;
    nb.sqDist[i] = std::numeric_limits<double>::infinity();
  }
  padNormals(nb, n, padded);
  // Weights, their sum and the first moments in one pass.
  double sums[4];
  kernels().weights(nb.sqDist.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.weight.data(), padded, minSq,
    nb.invH2, sums);
  nb.weightSum = sums[0];
  nb.moment = Vec3(sums[1], sums[2], sums[3]);
  nb.indexSerial = index.serial();
  nb.h = params.h;
  nb.cutoff = params.cutoff;
}
Vec3 localScaleGradient(const Neighbourhood& nb)
{
  if (!nb.scaled)
  {
    return Vec3::Zero();
  }
  const auto wk = nb.w() * nb.k() * (nb.pointScale.head(nb.count) - nb.localScale);
  return 2.0 * Vec3((wk * nb.x()).sum(), (wk * nb.y()).sum(), (wk * nb.z()).sum()) / nb.weightSum;
}

Vec3 centroidOffset(const Neighbourhood& nb)
{
  return nb.moment / nb.weightSum;
}

double centroidContraction(const Neighbourhood& nb, const Vec3& a)
{
  const auto z = a.x() * nb.x() + a.y() * nb.y() + a.z() * nb.z();
  const double mean = (nb.w() * z).sum() / nb.weightSum;
  // Cov(z, k z) = E[(z - mean) k z]: centred, so no difference of large sums.
  const double sum =
    nb.scaled ? (nb.w() * (z - mean) * nb.k() * z).sum() : nb.invH2 * (nb.w() * (z - mean) * z).sum();
  return 2.0 * sum / nb.weightSum;
}

// sum_i w_i (p_i - y - m)(p_i - y - m)^T: the six distinct entries in one pass over the
// neighbours (the padding after the last one weighs 0).
Mat3 weightedScatter(const Neighbourhood& nb, const Vec3& m)
{
  double s[6];
  kernels().scatter(nb.weight.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.count, m.x(), m.y(), m.z(), s);
  Mat3 c;
  c(0, 0) = s[0];
  c(1, 1) = s[3];
  c(2, 2) = s[5];
  c(0, 1) = c(1, 0) = s[1];
  c(0, 2) = c(2, 0) = s[2];
  c(1, 2) = c(2, 1) = s[4];
  return c;
}

OrientedMoments orientedMoments(const Neighbourhood& nb)
{
  double s[5];
  kernels().orientedMoments(nb.weight.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.nx.data(), nb.ny.data(),
    nb.nz.data(), nb.count, s);
  OrientedMoments out;
  out.normal = Vec3(s[0], s[1], s[2]);
  out.offsetAlongNormal = s[3];
  out.squaredOffset = s[4];
  return out;
}

void robustFactors(const Neighbourhood& nb, double f, const Vec3& g, double residualFactor, double normalFactor,
  double* robust)
{
  const double fit[7] = { f, g.x(), g.y(), g.z(), g.squaredNorm(), residualFactor, normalFactor };
  kernels().robustFactors(
    nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.nx.data(), nb.ny.data(), nb.nz.data(), nb.count, fit, robust);
}

RobustSums robustSums(const Neighbourhood& nb, const double* robust)
{
  double s[11];
  kernels().robustSums(nb.weight.data(), robust, nb.scaled ? nb.inverseSqScale.data() : nullptr, nb.invH2,
    nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.nx.data(), nb.ny.data(), nb.nz.data(), nb.count, s);
  RobustSums out;
  out.weight = s[0];
  out.value = s[1];
  out.offset = Vec3(s[2], s[3], s[4]);
  out.valueOffset = Vec3(s[5], s[6], s[7]);
  out.normal = Vec3(s[8], s[9], s[10]);
  return out;
}

LineMoments lineMoments(const Neighbourhood& nb, const Vec3& a)
{
  double s[4];
  kernels().moments(nb.weight.data(), nb.dx.data(), nb.dy.data(), nb.dz.data(), nb.count, a.x(), a.y(), a.z(), s);
  LineMoments out;
  out.s1 = s[0];
  out.s2 = s[1];
  out.s3 = s[2];
  out.s4 = s[3];
  return out;
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
} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Variants.h"

#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace pss
{

namespace
{

// Golden-section search for a minimum of f on [lo, hi]; f is smooth and unimodal there because
// the bracket comes from a fine scan. Returns the abscissa and stores the value in fBest.
template <class F>
double goldenMinimum(const F& f, double lo, double hi, double tol, double& fBest)
{
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = hi - r * (hi - lo);
  double d = lo + r * (hi - lo);
  double fc = f(c);
  double fd = f(d);
  while (hi - lo > tol)
  {
    if (fc < fd)
    {
      hi = d;
      d = c;
      fd = fc;
      c = hi - r * (hi - lo);
      fc = f(c);
    }
    else
    {
      lo = c;
      c = d;
      fc = fd;
      d = lo + r * (hi - lo);
      fd = f(d);
    }
  }
  if (fc < fd)
  {
    fBest = fc;
    return c;
  }
  fBest = fd;
  return d;
}

// Orthonormal basis (b1, b2) of the plane with unit normal a (Duff et al.'s branch-free frame).
// The unoriented a is first flipped to a.z >= 0, away from the frame's only singularity.
void planeBasis(Vec3 a, Vec3& b1, Vec3& b2)
{
  if (a.z() < 0.0)
  {
    a = -a;
  }
  const double k = -1.0 / (1.0 + a.z());
  const double m = a.x() * a.y() * k;
  b1 = Vec3(1.0 + a.x() * a.x() * k, m, -a.x());
  b2 = Vec3(m, 1.0 + a.y() * a.y() * k, -a.y());
}

// Unit vector in the plane orthogonal to n at angle phi from b1.
Vec3 inPlane(const Vec3& b1, const Vec3& b2, double phi)
{
  return std::cos(phi) * b1 + std::sin(phi) * b2;
}

constexpr double AngularTolerance = 1e-9;

} // namespace

IntegralEnergy::IntegralEnergy(const PointIndex& index, const SurfaceParameters& params)
  : SurfaceDefinition(index, params)
  , Rule(gaussHermite(params.quadratureOrder))
  , Field(index, params)
{
}

double IntegralEnergy::integrate(const Vec3& x, const Vec3& a, const Vec3* slopeDirection, double* slope) const
{
  const double h = Params.h;
  const int p = Params.integrandPower;
  const Vec3 origin = Index.restrict(x);
  const std::size_t n = Rule.nodes.size();
  double value = 0.0;
  double derivative = 0.0;
  Vec3 gradient;
  // One term of the Gauss-Hermite sum: weight * delta^p at y, plus weight * d(delta^p)/dt.
  auto accumulate = [&](const Vec3& y, double weight) {
    const double d = slopeDirection ? Field.deltaAndGradient(y, gradient) : Field.delta(y);
    value += weight * (p == 2 ? d * d : d);
    if (slopeDirection)
    {
      derivative += weight * (p == 2 ? 2.0 * d : 1.0) * slopeDirection->dot(gradient);
    }
  };
  // Every node lies within h * max|node| (times sqrt(2) in 3D) of x: one candidate fetch serves all.
  const double spread = h * Rule.nodes.back() * (dimension() == 2 ? 1.0 : std::sqrt(2.0));
  prefetchNeighbourhoods(Index, Params, origin, spread);
  double jacobian = h;
  if (dimension() == 2)
  {
    const Vec3 b(-a.y(), a.x(), 0.0);
    for (std::size_t j = 0; j < n; ++j)
    {
      accumulate(origin + h * Rule.nodes[j] * b, Rule.weights[j]);
    }
  }
  else
  {
    Vec3 b1;
    Vec3 b2;
    planeBasis(a, b1, b2);
    for (std::size_t j = 0; j < n; ++j)
    {
      for (std::size_t k = 0; k < n; ++k)
      {
        accumulate(origin + h * (Rule.nodes[j] * b1 + Rule.nodes[k] * b2), Rule.weights[j] * Rule.weights[k]);
      }
    }
    jacobian = h * h;
  }
  if (slope)
  {
    *slope = jacobian * derivative;
  }
  return jacobian * value;
}

double IntegralEnergy::energy(const Vec3& y, const Vec3& a) const
{
  return integrate(y, a, nullptr, nullptr);
}

LineSample IntegralEnergy::lineSample(const Vec3& y, const Vec3& a) const
{
  // Moving the plane along its own normal a moves every node by the same t a, so the slope is
  // the quadrature of d(delta^p)/dt = p delta^(p-1) a . grad delta.
  LineSample out;
  out.value = integrate(y, a, &a, &out.slope);
  out.nearestSqDist = Index.nearest(y).second;
  return out;
}

Direction IntegralEnergy::direction(const Vec3& x) const
{
  return dimension() == 2 ? direction2D(x) : direction3D(x);
}

double IntegralEnergy::leastEnergyOrthogonalTo(const Vec3& x, const Vec3& n) const
{
  if (dimension() == 2)
  {
    return energy(x, Vec3(-n.y(), n.x(), 0.0));
  }
  Vec3 b1;
  Vec3 b2;
  planeBasis(n, b1, b2);
  constexpr int samples = 12;
  int best = 0;
  double bestValue = std::numeric_limits<double>::infinity();
  for (int k = 0; k < samples; ++k)
  {
    const double e = energy(x, inPlane(b1, b2, M_PI * k / samples));
    if (e < bestValue)
    {
      bestValue = e;
      best = k;
    }
  }
  const double step = M_PI / samples;
  double refined = bestValue;
  goldenMinimum([&](double phi) { return energy(x, inPlane(b1, b2, phi)); }, (best - 1) * step,
    (best + 1) * step, 1e-6, refined);
  return std::min(refined, bestValue);
}

namespace
{

Direction finishDirection(const Vec3& n, double eMin, double ePerp, double minStability)
{
  Direction out;
  out.n = n.normalized();
  const double sum = ePerp + eMin;
  out.stability = sum > 0.0 && std::isfinite(sum) ? std::max(0.0, (ePerp - eMin) / sum) : 0.0;
  out.defined = out.stability > minStability && out.n.allFinite();
  return out;
}

} // namespace

Direction IntegralEnergy::direction2D(const Vec3& x) const
{
  // Scan the half circle of unoriented directions, then refine the best sample's bracket.
  constexpr int samples = 36;
  const double step = M_PI / samples;
  auto energyAt = [&](double phi) { return energy(x, Vec3(std::cos(phi), std::sin(phi), 0.0)); };
  int best = 0;
  double bestValue = std::numeric_limits<double>::infinity();
  for (int k = 0; k < samples; ++k)
  {
    const double e = energyAt(k * step);
    if (e < bestValue)
    {
      bestValue = e;
      best = k;
    }
  }
  double eMin = bestValue;
  const double phi = goldenMinimum(energyAt, (best - 1) * step, (best + 1) * step, AngularTolerance, eMin);
  const Vec3 n(std::cos(phi), std::sin(phi), 0.0);
  return finishDirection(n, eMin, leastEnergyOrthogonalTo(x, n), Params.minStability);
}

Direction IntegralEnergy::direction3D(const Vec3& x) const
{
  // Candidates: the 13 directions of a cube's axes, face and body diagonals (every unoriented
  // direction is within 35 degrees of one), plus the centre-of-mass eigenvectors, which are
  // usually within a few degrees of n_I near the cloud.
  std::vector<Vec3> candidates;
  candidates.reserve(16);
  for (int i = -1; i <= 1; ++i)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int k = 0; k <= 1; ++k)
      {
        const Vec3 v(i, j, k);
        const bool canonical = k == 1 || j == 1 || (j == 0 && i == 1);
        if (canonical)
        {
          candidates.push_back(v.normalized());
        }
      }
    }
  }
  {
    thread_local Neighbourhood nb;
    gatherNeighbourhood(Index, Params, x, nb);
    Eigen::SelfAdjointEigenSolver<Mat3> solver(covarianceAboutCentroid(nb));
    for (int c = 0; c < 3; ++c)
    {
      if (solver.eigenvectors().col(c).allFinite())
      {
        candidates.push_back(solver.eigenvectors().col(c).normalized());
      }
    }
  }
  Vec3 n = candidates.front();
  double eMin = std::numeric_limits<double>::infinity();
  for (const Vec3& c : candidates)
  {
    const double e = energy(x, c);
    if (e < eMin)
    {
      eMin = e;
      n = c;
    }
  }

  // Pattern search on the sphere: rotate n by +-sigma towards the two tangent axes, accept any
  // decrease, halve sigma when none helps. It takes about 40 steps; the budget stops it where the
  // minima form a ring (e_I equal along a great circle, to a slow drift): there it once crawled
  // 490,000 steps of 1.5e-6 rad along the ring (half a second for one n, found by
  // tests/fuzz/FuzzCore.cxx), and n is not unique there anyway (stability ~0).
  double sigma = 0.2;
  for (int step = 0; sigma > 1e-7 && step < 1000; ++step)
  {
    Vec3 b1;
    Vec3 b2;
    planeBasis(n, b1, b2);
    bool improved = false;
    for (const Vec3& t : { b1, b2, Vec3(-b1), Vec3(-b2) })
    {
      const Vec3 trial = (std::cos(sigma) * n + std::sin(sigma) * t).normalized();
      const double e = energy(x, trial);
      if (e < eMin)
      {
        eMin = e;
        n = trial;
        improved = true;
        break;
      }
    }
    if (!improved)
    {
      sigma *= 0.5;
    }
  }
  return finishDirection(n, eMin, leastEnergyOrthogonalTo(x, n), Params.minStability);
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
#include "pss/ExtremalSurface.h"

#include "pss/Kernel.h"
#include "pss/Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pss
{

namespace
{
// The plane procedure's Workspace::fetchSlack: on the bunny (h = 1 mm) 1 h ran the com plane rows
// 3-16% faster than 0.5 h, 0.35 h and 1.5-2 h slower; the extremal rows ran 6% slower at 1 h.
constexpr double PlaneFetchSlack = 1.0;
} // namespace

Orientation Orientation::awayFromCentroid(const PointIndex& index)
{
  return awayFrom(index.centroid());
}

Orientation Orientation::awayFrom(const Vec3& point)
{
  Orientation o;
  o.rule = Rule::AwayFromPoint;
  o.reference = point;
  return o;
}

Orientation Orientation::toward(const Vec3& viewpoint)
{
  Orientation o;
  o.rule = Rule::TowardPoint;
  o.reference = viewpoint;
  return o;
}

Vec3 Orientation::apply(const Vec3& n, const Vec3& x) const
{
  const double side = rule == Rule::AwayFromPoint ? n.dot(x - reference)
    : rule == Rule::TowardPoint                   ? n.dot(reference - x)
                                                  : n.dot(reference);
  return side < 0.0 ? Vec3(-n) : n;
}

namespace
{

// A slope sample kept as mantissa and log-scale, so Levin's underflowing energies still compare.
struct ScaledSlope
{
  double t = 0.0;
  double mantissa = 0.0;  ///< slope (signed for the kind of extremum sought), at exp(logScale)
  double curvature = 0.0; ///< second derivative at the same scale, NaN when unknown
  double logScale = 0.0;
  double nearestSqDist = 0.0;
  double illinois = 1.0;  ///< Illinois down-weighting of this end in false-position steps
};

// The two mantissas brought to the larger of their scales (the smaller may underflow to zero,
// never overflow).
void commonScale(const ScaledSlope& a, const ScaledSlope& b, double& fa, double& fb)
{
  const double l = std::max(a.logScale, b.logScale);
  fa = a.illinois * a.mantissa * std::exp(a.logScale - l);
  fb = b.illinois * b.mantissa * std::exp(b.logScale - l);
}

// Second derivative of t -> e(x + t n, n) at 0, expressed at the scale of @p at (multiply by
// exp(at.logScale) for the true value): the definition's own when it has one, else a central
// difference of the analytic slope.
double scaledCurvature(const SurfaceDefinition& s, const Vec3& x, const Vec3& n, const LineSample& at, Workspace& ws)
{
  if (!std::isnan(at.curvature))
  {
    return at.curvature;
  }
  const double eps = 1e-4 * s.scaleAt(x, ws);
  const LineSample plus = s.lineSample(x + eps * n, n, ws);
  const LineSample minus = s.lineSample(x - eps * n, n, ws);
  const double sp = plus.slope * std::exp(plus.logScale - at.logScale);
  const double sm = minus.slope * std::exp(minus.logScale - at.logScale);
  return (sp - sm) / (2.0 * eps);
}

ExtremumType typeFromCurvature(double curvature)
{
  if (curvature > 0.0)
  {
    return ExtremumType::Minimum;
  }
  return curvature < 0.0 ? ExtremumType::Maximum : ExtremumType::None;
}

} // namespace

ImplicitSample evaluateImplicit(const SurfaceDefinition& s, const Vec3& xIn, const Orientation& o, Workspace& ws)
{
  ImplicitSample out;
  if (!isFinite(xIn))
  {
    return out;
  }
  const Vec3 x = s.index().restrict(xIn);
  out.direction = s.direction(x, ws);
  if (!out.direction.n.allFinite() || out.direction.n.squaredNorm() == 0.0)
  {
    out.direction.defined = false;
    return out;
  }
  const Vec3 n = o.apply(out.direction.n, x);
  out.direction.n = n;
  const LineSample at = s.lineSample(x, n, ws);
  const double scale = std::exp(at.logScale);
  out.energy = at.value * scale;
  if (!out.direction.defined)
  {
    return out; // n(x) is not unique: g and curvature 0, type None (see the header)
  }
  out.g = at.slope * scale;
  const double curvature = scaledCurvature(s, x, n, at, ws);
  out.curvature = curvature * scale;
  out.type = typeFromCurvature(curvature);
  return out;
}

LineExtremum nearestExtremumOnLine(
  const SurfaceDefinition& s, const Vec3& x, const Vec3& a, bool seekMaximum, double maxTravel, Workspace& ws)
{
  LineExtremum out;
  // Seeking a maximum of e is seeking a minimum of -e: flip the derivatives' signs once, here.
  const double sign = seekMaximum ? -1.0 : 1.0;
  const ExtremumType wanted = seekMaximum ? ExtremumType::Maximum : ExtremumType::Minimum;
  const double h = s.scaleAt(x, ws);
  auto sample = [&](double t) {
    const LineSample ls = s.lineSample(x + t * a, a, ws);
    ScaledSlope p;
    p.t = t;
    p.mantissa = sign * ls.slope;
    p.curvature = sign * ls.curvature; // NaN when the definition has no closed form
    p.logScale = ls.logScale;
    p.nearestSqDist = ls.nearestSqDist;
    return p;
  };
  // Newton's step towards the root of the slope, when the curvature says we are in a basin.
  auto newton = [](const ScaledSlope& p) {
    return p.curvature > 0.0 ? -p.mantissa / p.curvature : std::numeric_limits<double>::quiet_NaN();
  };

  const ScaledSlope start = sample(0.0);
  if (!std::isfinite(start.mantissa))
  {
    return out;
  }
  double travel = 1.0;
  if (start.mantissa > 0.0)
  {
    travel = -1.0;
  }
  else if (start.mantissa == 0.0)
  {
    const LineSample at = s.lineSample(x, a, ws);
    if (sign * scaledCurvature(s, x, a, at, ws) > 0.0)
    {
      out.found = true;
      out.type = wanted;
      return out;
    }
  }

  // March downhill (of sign * e) until the slope turns. Steps grow geometrically from 0.02 h but
  // stay below half the distance to the cloud (and 0.25 h near it): the energy has no structure
  // finer than that, so no pair of extrema hides inside one step. Where the curvature is known
  // and positive and Newton's estimate of the minimum lies beyond the step, the step goes just
  // past it, which usually brackets the minimum at once.
  double step = 0.02 * h;
  ScaledSlope previous = start;
  ScaledSlope next;
  bool bracketed = false;
  while (std::abs(previous.t) < maxTravel)
  {
    const double cap = std::max(0.25 * h, 0.5 * std::sqrt(previous.nearestSqDist));
    // Newton may lengthen a step (to land just past a minimum it sees farther on), never shorten
    // it: a shrinking sequence of Newton steps that never brackets would stall the march.
    const double guess = newton(previous) * travel;
    const double trial = std::min(std::max(step, guess > 0.0 ? 1.1 * guess : 0.0), cap);
    next = sample(previous.t + travel * trial);
    if (!std::isfinite(next.mantissa))
    {
      return out;
    }
    if (travel * next.mantissa >= 0.0)
    {
      bracketed = true;
      break;
    }
    previous = next;
    step *= 1.6;
  }
  if (!bracketed)
  {
    return out;
  }

  // Refine the root of the slope inside [lo, hi]: Newton from the better end when its step stays
  // inside the bracket, else Illinois false position. Both keep the bracket, so the search cannot
  // wander to another extremum.
  ScaledSlope lo = previous; // travel * slope < 0
  ScaledSlope hi = next;     // travel * slope >= 0
  const double tol = 1e-12 * h;
  int lastMoved = 0;
  double root = hi.t;
  double lastStep = std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < 200 && std::abs(hi.t - lo.t) > tol && hi.mantissa != 0.0 && lastStep > tol; ++iter)
  {
    const double left = std::min(lo.t, hi.t);
    const double right = std::max(lo.t, hi.t);
    const ScaledSlope& best = std::abs(lo.mantissa) * std::exp(lo.logScale - hi.logScale) < std::abs(hi.mantissa) ? lo : hi;
    double t = best.t + newton(best);
    const bool newtonStep = t > left && t < right;
    if (!newtonStep)
    {
      double flo = 0.0;
      double fhi = 0.0;
      commonScale(lo, hi, flo, fhi);
      t = (lo.t * fhi - hi.t * flo) / (fhi - flo);
      if (!(t > left && t < right))
      {
        t = 0.5 * (lo.t + hi.t);
      }
    }
    const ScaledSlope mid = sample(t);
    if (!std::isfinite(mid.mantissa))
    {
      return out;
    }
    lastStep = newtonStep ? std::abs(t - best.t) : std::numeric_limits<double>::infinity();
    root = t;
    if (travel * mid.mantissa >= 0.0)
    {
      hi = mid;
      if (lastMoved == 1 && !newtonStep)
      {
        lo.illinois *= 0.5;
      }
      lastMoved = 1;
    }
    else
    {
      lo = mid;
      if (lastMoved == -1 && !newtonStep)
      {
        hi.illinois *= 0.5;
      }
      lastMoved = -1;
    }
  }
  if (hi.mantissa == 0.0)
  {
    root = hi.t;
  }
  // The root is known to tol only: an extremum exactly maxTravel away (a start 1000 h above a
  // plane) must not be lost to the rounding of its last digits.
  if (std::abs(root) > maxTravel + tol)
  {
    return out;
  }
  out.found = true;
  out.t = root;
  out.type = wanted;
  return out;
}

void ProjectionOptions::validate() const
{
  if (maxIterations < 1)
  {
    throw std::invalid_argument("MaxIterations must be at least 1, got " + std::to_string(maxIterations));
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
  {
    throw std::invalid_argument("the tolerance must be a positive finite multiple of h");
  }
  if (!(maxTravel > 0.0) || !std::isfinite(maxTravel))
  {
    throw std::invalid_argument("the maximum travel must be a positive finite multiple of h");
  }
}

ProjectionResult project(const SurfaceDefinition& s, const Vec3& startIn, const ProjectionOptions& opt, Workspace& ws)
{
  ProjectionResult res;
  res.point = startIn;
  if (!isFinite(startIn))
  {
    res.reason = StopReason::InvalidInput;
    return res;
  }
  const PointIndex& index = s.index();
  Vec3 x = index.restrict(startIn);
  // Travel and tolerance in units of the scale at the start (h itself without a scale per point).
  const double h = s.scaleAt(x, ws);
  const bool plane = opt.procedure == Procedure::Plane;
  // One gather per step: wider candidate fetches pay (Workspace::fetchSlack), for this call only.
  struct Slack
  {
    Workspace& ws;
    double saved;
    ~Slack() { ws.fetchSlack = saved; }
  } slack{ ws, ws.fetchSlack };
  if (plane)
  {
    ws.fetchSlack = PlaneFetchSlack;
  }
  // The plane procedure needs n(x) and c(x) - x at every iterate; planeFit gets both from one
  // neighbourhood. Each iterate's fit starts from what the previous one left in memory.
  Vec3 centroid = Vec3::Zero();
  double contraction = std::numeric_limits<double>::quiet_NaN();
  DirectionMemory memory;
  auto fitAt = [&](const Vec3& p, double* contractionOut = nullptr) {
    return plane ? s.planeFit(p, centroid, memory, ws, contractionOut) : s.directionNear(p, memory, ws);
  };
  Vec3 fitted = x; // where dir was fitted
  Direction dir = fitAt(x, &contraction);
  res.startDirection = dir;
  res.reason = StopReason::MaxIterations;
  ExtremumType lastType = ExtremumType::None;
  Vec3 previousStep = Vec3::Zero();
  Vec3 previousPlainStep = Vec3::Zero(); // t n, before the extrapolation
  for (int it = 0;; ++it)
  {
    if (!dir.defined)
    {
      res.reason = StopReason::UndefinedDirection;
      break;
    }
    if (it == opt.maxIterations)
    {
      break;
    }
    double t = 0.0;
    double move = 0.0;
    if (plane)
    {
      // Move x onto the plane through c(x) with normal n(x): the zero set of <n, x - c>.
      t = dir.n.dot(centroid);
      // The iteration contracts linearly: a step onto the plane leaves a fraction r of the
      // distance e to the fixed point along n (t = (1 - r) e; r ~ 2 sigma^2 / h^2 for noise
      // sigma along n), so t / (1 - r) steps onto the fixed point itself: the same fixed
      // points in fewer iterations. The first step takes r from the fit (planeFit's
      // contraction), the later ones from how much the last move changed t (a secant).
      move = t;
      const double moved = dir.n.dot(previousStep);
      const double r = moved != 0.0 ? 1.0 - (dir.n.dot(previousPlainStep) - t) / moved : contraction;
      if (r > 0.0 && r < 0.5)
      {
        move = t / (1.0 - r);
      }
      previousPlainStep = t * dir.n;
    }
    else
    {
      const LineExtremum le = nearestExtremumOnLine(s, x, dir.n, opt.seekMaxima, opt.maxTravel * h, ws);
      if (!le.found)
      {
        res.reason = StopReason::NoExtremum;
        break;
      }
      t = le.t;
      move = t;
      lastType = le.type;
    }
    previousStep = move * dir.n;
    res.iterations = it + 1;
    res.lastStep = std::abs(t);
    x = index.restrict(x + previousStep);
    const bool converged = std::abs(t) < opt.tolerance * h;
    if (converged && plane)
    {
      // The plane procedure's last step, below the tolerance, lands on the plane just fitted; it
      // is taken without another fit, and that plane's normal is the direction reported (energy
      // and type at its fit point, at most tolerance * h away): one neighbourhood fewer per
      // projection. The extremal procedure fits again: its n is n at the point itself.
      res.reason = StopReason::Converged;
      break;
    }
    fitted = x;
    // The iterates' stability only decides whether to go on; the one reported is the final
    // fit's, and that is never an estimate (below).
    memory.estimateStability = !converged;
    dir = fitAt(x);
    if (converged)
    {
      res.reason = dir.defined ? StopReason::Converged : StopReason::UndefinedDirection;
      break;
    }
  }
  if (memory.stabilityEstimated)
  {
    // Stopped at an intermediate iterate (iteration limit, no extremum) or on the plane of one:
    // fit it again in full.
    memory.estimateStability = false;
    dir = fitAt(fitted);
    if (!dir.defined && res.reason == StopReason::Converged)
    {
      // The full fit finds no direction where the estimate did (found by the fuzzer only, with
      // coordinates near 1e303, where squared distances overflow): not a converged projection.
      res.reason = StopReason::UndefinedDirection;
    }
  }
  res.point = x;
  res.direction = dir;
  res.converged = res.reason == StopReason::Converged;
  if (dir.n.allFinite() && dir.n.squaredNorm() > 0.0)
  {
    const LineSample at = s.lineSample(fitted, dir.n, ws);
    res.energy = at.trueValue();
    res.type = opt.procedure == Procedure::Extremal && res.converged
      ? lastType
      : typeFromCurvature(scaledCurvature(s, fitted, dir.n, at, ws));
  }
  return res;
}

bool forEachStart(const std::vector<Vec3>& starts, const ParallelLoop& loop,
  const std::function<void(std::size_t, Workspace&)>& work)
{
  return forEachInOrder(spatialOrder(starts), loop, work);
}

bool forEachInOrder(const std::vector<std::uint32_t>& order, const ParallelLoop& loop,
  const std::function<void(std::size_t, Workspace&)>& work)
{
  return forEachPosition(order.size(), loop, [&](std::size_t k, Workspace& ws) { work(order[k], ws); });
}

bool forEachPosition(std::size_t count, const ParallelLoop& loop, const std::function<void(std::size_t, Workspace&)>& work)
{
  return loop(count, LoopShare(0.0, 1.0), [&](std::size_t begin, std::size_t end, Workspace& ws) {
    for (std::size_t k = begin; k < end; ++k)
    {
      work(k, ws);
    }
  });
}

void projectEach(const SurfaceDefinition& s, const std::vector<Vec3>& starts, const ProjectionOptions& opt,
  int threads, const std::function<void(std::size_t, const ProjectionResult&)>& sink)
{
  opt.validate();
  forEachStart(starts, threadLoop(threads), [&](std::size_t i, Workspace& ws) { sink(i, project(s, starts[i], opt, ws)); });
}

std::vector<ProjectionResult> projectAll(
  const SurfaceDefinition& s, const std::vector<Vec3>& starts, const ProjectionOptions& opt, int threads)
{
  std::vector<ProjectionResult> results(starts.size());
  projectEach(s, starts, opt, threads, [&](std::size_t i, const ProjectionResult& r) { results[i] = r; });
  return results;
}

} // namespace pss

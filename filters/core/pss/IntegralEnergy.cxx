// SPDX-License-Identifier: BSD-3-Clause
#include "pss/DirectionRulesAndEnergies.h"
#include "pss/Workspace.h"

#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace pss
{

namespace
{

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

} // namespace

namespace
{

// The quadrature's sums times the rule's Jacobian (h per in-plane axis).
IntegralEnergy::PlaneIntegral scaled(IntegralEnergy::PlaneIntegral sums, double jacobian)
{
  sums.value *= jacobian;
  sums.slope *= jacobian;
  sums.radial *= jacobian;
  sums.tilt *= jacobian;
  sums.curvature *= jacobian;
  sums.tiltHessian *= jacobian;
  return sums;
}

} // namespace

IntegralEnergy::IntegralEnergy(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
  , Rule(gaussHermite(params.quadratureOrder))
  , RoughRule(gaussHermite(std::min(params.quadratureOrder, 3)))
  , Field(index, params)
  , Lattice(Field)
{
}

IntegralEnergy::Frame IntegralEnergy::frameOf(const Vec3& a) const
{
  Frame f;
  f.a = a;
  if (Index.dimension() == 2)
  {
    f.b1 = Vec3(-a.y(), a.x(), 0.0);
    f.b2 = Vec3::Zero();
  }
  else
  {
    planeBasis(a, f.b1, f.b2);
  }
  return f;
}

// The frame turned by the tangent step s (radians, in b1/b2 coordinates): a moves along the great
// circle towards s1 b1 + s2 b2 and the in-plane axes are carried along it (parallel transport),
// so a step's coordinates mean the same in the frame it ends in.
IntegralEnergy::Frame IntegralEnergy::tilted(const Frame& f, const Eigen::Vector2d& s)
{
  const double angle = s.norm();
  if (angle == 0.0)
  {
    return f;
  }
  const Vec3 toward = (s.x() * f.b1 + s.y() * f.b2) / angle;
  const Vec3 across = f.a.cross(toward); // the pivot axis: in both planes, unmoved
  const Vec3 towardTurned = std::cos(angle) * toward - std::sin(angle) * f.a;
  Frame out;
  out.a = (std::cos(angle) * f.a + std::sin(angle) * toward).normalized();
  auto carried = [&](const Vec3& b) { return b.dot(toward) * towardTurned + b.dot(across) * across; };
  // Gram-Schmidt against rounding drift; the axes keep their signs (the frame may be left-handed:
  // frameOf's a is unoriented).
  out.b1 = carried(f.b1);
  out.b1 = (out.b1 - out.b1.dot(out.a) * out.a).normalized();
  out.b2 = carried(f.b2);
  out.b2 = (out.b2 - out.b2.dot(out.a) * out.a - out.b2.dot(out.b1) * out.b1).normalized();
  return out;
}

IntegralEnergy::PlaneIntegral IntegralEnergy::integrate(
  const Vec3& x, const Frame& f, Derivatives order, Workspace& ws) const
{
  return sum(x, f, order, Rule, ws);
}

double IntegralEnergy::roughValue(const Vec3& x, const Vec3& a, Workspace& ws) const
{
  return sum(x, frameOf(a), Derivatives::None, RoughRule, ws).value;
}

IntegralEnergy::PlaneIntegral IntegralEnergy::sum(
  const Vec3& x, const Frame& f, Derivatives order, const GaussHermiteRule& rule, Workspace& ws) const
{
  const int p = Params.integrandPower;
  const Vec3 origin = Index.restrict(x);
  // The Gaussian window over the plane has the scale at x (Neighbourhood::localScale); with a
  // scale per point it moves with x, which adds a term to the slope below.
  Vec3 windowGradient = Vec3::Zero();
  const double h = windowScale(origin, windowGradient, ws);
  const bool planar = Index.dimension() == 2;
  const bool lattice = Params.deltaLattice > 0.0 && !ws.exactDelta;
  PlaneIntegral out;
  // The node at in-plane coordinates w = (u, v) (units of h) adds weight * F(delta), F = delta^p.
  // Moving the plane by t along a moves every node by t a; tilting a by s (tilted()'s
  // coordinates) moves the node by -h (s . w) a to first order and by -h (s . w) / 2 (s1 b1 + s2 b2)
  // to second. With ga = a . grad delta, gb its in-plane components and c = a^T H a:
  //   slope = F' ga,  curvature = F'' ga^2 + F' c,  tilt = -h w F' ga,
  //   tiltHessian = h^2 w w^T (F'' ga^2 + F' c) - (h / 2) F' (w gb^T + gb w^T).
  auto accumulate = [&](double u, double v, double weight) {
    const Vec3 y = origin + h * (u * f.b1 + v * f.b2);
    if (order == Derivatives::None)
    {
      const double d = lattice ? Lattice.value(y, ws) : Field.delta(y, ws);
      out.value += weight * (p == 2 ? d * d : d);
      return;
    }
    const DeltaJet jet = lattice ? Lattice.jet(y, f.a, ws) : Field.jet(y, f.a, ws);
    const double d = jet.value;
    const double dF = p == 2 ? 2.0 * d : 1.0;
    const double ddF = p == 2 ? 2.0 : 0.0;
    const double ga = f.a.dot(jet.gradient);
    const double s = weight * dF * ga;
    const Eigen::Vector2d w(u, v);
    out.value += weight * (p == 2 ? d * d : d);
    out.slope += s;
    out.radial += weight * dF * (u * f.b1.dot(jet.gradient) + v * f.b2.dot(jet.gradient));
    out.tilt -= (s * h) * w;
    const double alongA = weight * (ddF * ga * ga + dF * jet.curvature);
    const Eigen::Vector2d gb(f.b1.dot(jet.gradient), f.b2.dot(jet.gradient));
    const Eigen::Matrix2d cross = w * gb.transpose();
    out.curvature += alongA;
    out.tiltHessian += (alongA * h * h) * (w * w.transpose()) - (0.5 * h * weight * dF) * (cross + cross.transpose());
  };
  const std::size_t n = rule.nodes.size();
  auto vAt = [&](std::size_t k) { return planar ? 0.0 : rule.nodes[k]; };
  auto weightAt = [&](std::size_t j, std::size_t k) { return planar ? rule.weights[j] : rule.weights[j] * rule.weights[k]; };
  const double jacobian = planar ? h : h * h;
  if (lattice)
  {
    // The lattice's nodes gather their own neighbourhoods, a block of nodes at a time
    // (DeltaLattice::nodeIn).
    for (std::size_t j = 0; j < n; ++j)
    {
      for (std::size_t k = 0; k < (planar ? 1 : n); ++k)
      {
        accumulate(rule.nodes[j], vAt(k), weightAt(j, k));
      }
    }
    return withWindow(scaled(out, jacobian), h, f.a.dot(windowGradient), planar);
  }
  // Every node lies within h * max|node| (times sqrt(2) in 3D) of x: one candidate fetch serves
  // all. The nodes are then visited by halves of the line, quarters of the plane, each with
  // the part of the fetch its nodes can need (a node's own gather then scans a few hundred
  // candidates instead of some 1,500).
  const double spread = h * rule.nodes.back() * (planar ? 1.0 : std::sqrt(2.0));
  prefetchNeighbourhoods(Index, Params, origin, spread, ws);
  // Node index ranges: the two halves of the u axis, and of the v axis in 3D (the line has one
  // "v" node, at 0). With one node per axis a half is empty.
  using Range = std::array<std::size_t, 2>;
  const std::array<Range, 2> halves{ Range{ 0, n / 2 }, Range{ n / 2, n } };
  const std::array<Range, 2> vRanges = planar ? std::array<Range, 2>{ Range{ 0, 1 }, Range{ 1, 1 } } : halves;
  for (const Range& us : halves)
  {
    for (const Range& vs : vRanges)
    {
      if (us[0] == us[1] || vs[0] == vs[1])
      {
        continue;
      }
      // The block's centre and its corners' distance from it, in units of h.
      const double cu = 0.5 * (rule.nodes[us[0]] + rule.nodes[us[1] - 1]);
      const double cv = 0.5 * (vAt(vs[0]) + vAt(vs[1] - 1));
      const double corner = std::hypot(rule.nodes[us[1] - 1] - cu, vAt(vs[1] - 1) - cv);
      focusNeighbourhoods(Index, Params, origin + h * (cu * f.b1 + cv * f.b2), h * corner, ws);
      for (std::size_t j = us[0]; j < us[1]; ++j)
      {
        for (std::size_t k = vs[0]; k < vs[1]; ++k)
        {
          accumulate(rule.nodes[j], vAt(k), weightAt(j, k));
        }
      }
    }
  }
  return withWindow(scaled(out, jacobian), h, f.a.dot(windowGradient), planar);
}

double IntegralEnergy::windowScale(const Vec3& x, Vec3& gradient, Workspace& ws) const
{
  if (!Index.hasScales())
  {
    return Params.h;
  }
  gatherNeighbourhood(Index, Params, x, ws.scale, ws);
  gradient = localScaleGradient(ws.scale);
  return ws.scale.localScale;
}

// e = J(h) sum_w weight F(delta(x + h w)), J = h^2 (h on a line), so with the window's scale
// moving at the rate dh along a the slope gains dh de/dh = dh (J'/J e + J sum weight F' <grad delta, w>).
IntegralEnergy::PlaneIntegral IntegralEnergy::withWindow(PlaneIntegral sums, double h, double dh, bool planar)
{
  if (dh != 0.0)
  {
    sums.slope += dh * ((planar ? 1.0 : 2.0) / h * sums.value + sums.radial);
  }
  return sums;
}

double IntegralEnergy::value(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  return integrate(y, frameOf(a), Derivatives::None, ws).value;
}

LineSample IntegralEnergy::lineSample(const Vec3& y, const Vec3& a, Workspace& ws) const
{
  // Moving the plane along its own normal a moves every node by the same t a: the slope and the
  // curvature are quadratures of the first two derivatives of delta^p along a.
  const PlaneIntegral sums = integrate(y, frameOf(a), Derivatives::UpToSecond, ws);
  LineSample out;
  out.value = sums.value;
  out.slope = sums.slope;
  out.curvature = sums.curvature;
  out.nearestSqDist = Index.nearest(y).second;
  noteReach(Index, Index.restrict(y), out.nearestSqDist, ws);
  return out;
}

IntegralDirection::IntegralDirection(const PointIndex& index, const SurfaceParameters& params)
  : Index(index)
  , Params(params)
  , Integral(index, params)
{
}

IntegralDirection::Across IntegralDirection::leastEnergyOrthogonalTo(
  const Vec3& x, const Vec3& n, const Vec3* near, bool rough, Workspace& ws) const
{
  auto energy = [&](const Vec3& a) { return rough ? Integral.roughValue(x, a, ws) : Integral.value(x, a, ws); };
  if (dimension() == 2)
  {
    const Vec3 b(-n.y(), n.x(), 0.0);
    return { energy(b), b };
  }
  // Twelve samples of the half circle of directions orthogonal to n (a and -a are the same, so
  // the samples wrap around), then one more at the vertex of the parabola through the best
  // sample and its neighbours. Given a guess (@p near: the last iterate's answer, or the tilt
  // Hessian's softest direction), the samples start around it and walk downhill instead: usually
  // three or four samples instead of twelve.
  Vec3 b1;
  Vec3 b2;
  planeBasis(n, b1, b2);
  constexpr int samples = 12;
  const double step = M_PI / samples;
  auto sampleAt = [&](double phi) { return energy(inPlane(b1, b2, phi)); };
  double centre = 0.0;
  double before = 0.0;
  double best = 0.0;
  double after = 0.0;
  bool bracketed = false;
  if (near)
  {
    centre = std::atan2(near->dot(b2), near->dot(b1));
    before = sampleAt(centre - step);
    best = sampleAt(centre);
    after = sampleAt(centre + step);
    // Walk downhill a step at a time until the middle sample is the least. e_I is periodic in
    // the angle (period pi, 12 steps), so a strictly falling walk cannot last a whole period.
    const double direction = after < before ? 1.0 : -1.0;
    for (int k = 0; k < samples && !(best <= before && best <= after); ++k)
    {
      centre += direction * step;
      double& behind = direction > 0.0 ? before : after;
      double& ahead = direction > 0.0 ? after : before;
      behind = best;
      best = ahead;
      ahead = sampleAt(centre + direction * step);
    }
    bracketed = best <= before && best <= after;
  }
  if (!bracketed)
  {
    std::array<double, samples> e;
    int k0 = 0;
    for (int k = 0; k < samples; ++k)
    {
      e[k] = sampleAt(k * step);
      k0 = e[k] < e[k0] ? k : k0;
    }
    centre = k0 * step;
    before = e[(k0 + samples - 1) % samples];
    best = e[k0];
    after = e[(k0 + 1) % samples];
  }
  const double curvature = before - 2.0 * best + after;
  if (!(curvature > 0.0))
  {
    return { best, inPlane(b1, b2, centre) };
  }
  const double offset = 0.5 * (before - after) / curvature; // in [-1/2, 1/2] steps
  const double vertex = centre + offset * step;
  const double atVertex = sampleAt(vertex);
  return atVertex < best ? Across{ atVertex, inPlane(b1, b2, vertex) } : Across{ best, inPlane(b1, b2, centre) };
}

IntegralDirection::Minimum IntegralDirection::refineDirection(const Vec3& x, const Vec3& start, Workspace& ws) const
{
  // Newton's method on the sphere, with the analytic tilt gradient and Hessian (integrate()).
  // The step uses |eigenvalues|, so it goes downhill at saddles too, is capped at maxTurn (beyond
  // that the quadratic model means little), and is halved until e_I decreases. Where e_I is
  // constant along a ring of directions (n is not unique there, stability ~0) the steps stop
  // decreasing it and the iteration ends.
  // A step is taken when it lowers e_I, which values tell only down to about sqrt(epsilon), so
  // the last step, once the tilt Hessian is positive definite and the step below finalStep, is
  // taken without evaluating it: the quadratic model holds there to far below rounding. Every
  // search then ends at the minimiser to rounding, not anywhere within the band that values
  // cannot resolve (two sums of the same terms in another order, such as one h and every h_i = h,
  // give the same n_I to about 1e-14 rad).
  constexpr double maxTurn = 0.2;
  constexpr double finalStep = 1e-7;
  constexpr int maxIterations = 30;
  using Frame = IntegralEnergy::Frame;
  using PlaneIntegral = IntegralEnergy::PlaneIntegral;
  constexpr auto second = IntegralEnergy::Derivatives::UpToSecond;
  Minimum out;
  Frame f = Integral.frameOf(start);
  PlaneIntegral at = Integral.integrate(x, f, second, ws);
  for (int it = 0; it < maxIterations && at.tilt.allFinite(); ++it)
  {
    const Eigen::Matrix2d symmetric = 0.5 * (at.tiltHessian + at.tiltHessian.transpose());
    if (!symmetric.allFinite())
    {
      break;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(symmetric);
    const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
    if (!(largest > 0.0))
    {
      break;
    }
    const Eigen::Vector2d lambda = eigen.eigenvalues().cwiseAbs().cwiseMax(1e-9 * largest);
    Eigen::Vector2d step =
      -(eigen.eigenvectors() * (eigen.eigenvectors().transpose() * at.tilt).cwiseQuotient(lambda));
    if (step.norm() > maxTurn)
    {
      step *= maxTurn / step.norm();
    }
    if (step.norm() < finalStep)
    {
      if (eigen.eigenvalues().minCoeff() > 0.0)
      {
        f = IntegralEnergy::tilted(f, step);
      }
      break;
    }
    bool moved = false;
    for (int halving = 0; halving < 10 && step.norm() >= finalStep; ++halving, step *= 0.5)
    {
      const Frame trialFrame = IntegralEnergy::tilted(f, step);
      const PlaneIntegral trial = Integral.integrate(x, trialFrame, second, ws);
      if (trial.value < at.value)
      {
        f = trialFrame;
        at = trial;
        moved = true;
        break;
      }
    }
    if (!moved)
    {
      break;
    }
  }
  out.n = f.a;
  out.value = at.value;
  // The tilt towards which e_I grows least: where the search for e_perp starts (in 3D).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(0.5 * (at.tiltHessian + at.tiltHessian.transpose()));
  const Eigen::Vector2d soft = eigen.eigenvectors().col(0);
  out.softest = (soft.x() * f.b1 + soft.y() * f.b2).normalized();
  out.softCurvature = eigen.eigenvalues()(0);
  return out;
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

IntegralDirection::Minimum IntegralDirection::minimum2D(const Vec3& x, const Vec3* near, Workspace& ws) const
{
  // From the last iterate's n_I, Newton's method (refineDirection; in 2D the tilt has one
  // component) as in 3D. Else 18 samples of the half circle of unoriented directions, 10 degrees
  // apart, ranked by the rough e_I (the minima of e_I over directions that a projection must tell
  // apart, such as a corner's two normals, lie much farther apart), and Newton from the best.
  if (near)
  {
    return refineDirection(x, *near, ws);
  }
  constexpr int samples = 18;
  auto direction = [](double phi) { return Vec3(std::cos(phi), std::sin(phi), 0.0); };
  int best = 0;
  double bestValue = std::numeric_limits<double>::infinity();
  for (int k = 0; k < samples; ++k)
  {
    const double e = Integral.roughValue(x, direction(k * M_PI / samples), ws);
    if (e < bestValue)
    {
      bestValue = e;
      best = k;
    }
  }
  return refineDirection(x, direction(best * M_PI / samples), ws);
}

IntegralDirection::Minimum IntegralDirection::minimum3D(const Vec3& x, const Vec3* near, Workspace& ws) const
{
  if (near)
  {
    return refineDirection(x, *near, ws);
  }
  // Candidates: the 13 directions of a cube's axes, face and body diagonals (every unoriented
  // direction is within 35 degrees of one), plus the centre-of-mass eigenvectors, which are
  // usually within a few degrees of n_I near the cloud. They are ranked by the rough e_I (a
  // quarter of the nodes): the best only has to lie in the right basin, Newton does the rest.
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
    Neighbourhood& nb = ws.local;
    gatherNeighbourhood(Index, Params, x, nb, ws);
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
    const double e = Integral.roughValue(x, c, ws);
    if (e < eMin)
    {
      eMin = e;
      n = c;
    }
  }
  return refineDirection(x, n, ws);
}

DirectionFit IntegralDirection::fit(const Vec3& x, DirectionMemory& memory, Workspace& ws) const
{
  // The last n_I is where the search starts only while the iterates stay within a tenth of h:
  // n_I turns little over such a step, so the search stays in the same basin, while a longer
  // step (a projection's first, from a noisy start) may cross to where another direction wins,
  // and gets the full scan.
  constexpr double warmReach = 0.1;
  const bool warm = memory.valid && (x - memory.point).norm() <= warmReach * Params.h;
  const Minimum least = dimension() == 2 ? minimum2D(x, warm ? &memory.n : nullptr, ws)
                                         : minimum3D(x, warm ? &memory.n : nullptr, ws);
  // For a quadratic form e(a) = a^T M a the tilt Hessian at its least eigenvector is
  // 2 (M - lambda_0) on the tangent plane, so e_perp = e_min + (least Hessian eigenvalue) / 2, in
  // the direction of its eigenvector. e_I is not quadratic: the estimate serves only where the
  // caller wants to know whether n is defined and it is clearly so (at 0.05, 5000 times the
  // default threshold; the exact search decides below that).
  const bool soft = least.softest.allFinite() && least.softest.squaredNorm() > 0.0;
  constexpr double clearlyDefined = 0.05;
  if (memory.estimateStability && soft && std::isfinite(least.softCurvature))
  {
    const Direction estimate =
      finishDirection(least.n, least.value, least.value + 0.5 * least.softCurvature, Params.minStability);
    if (estimate.stability >= std::max(clearlyDefined, Params.minStability))
    {
      memory.valid = least.n.allFinite();
      memory.point = x;
      memory.n = least.n;
      memory.across = least.softest;
      memory.stabilityEstimated = true;
      return { estimate, nullptr };
    }
  }
  // e_perp's search starts from the last iterate's answer, else from where the tilt Hessian
  // says e_I grows least.
  const Vec3* acrossStart = warm ? &memory.across : soft ? &least.softest : nullptr;
  // The fast path first takes e_perp, and e_min for the ratio, from the rough rule (9 nodes in
  // 3D, 36 at the default order): the plane orthogonal to n_I crosses the surface, where delta^2
  // grows about as the fourth power of the distance from it, a polynomial the rough rule
  // integrates exactly, and one rule for both keeps the ratio 0 where they are equal. Where
  // that stability is not clearly above the threshold (below 0.05, as for the estimate above)
  // the full rule decides, as on the exact path. Measured: docs/paper.md, "Reading: the integral
  // energy's fast path".
  Across across;
  Direction result;
  bool decided = false;
  if (Params.deltaLattice > 0.0 && !ws.exactDelta)
  {
    across = leastEnergyOrthogonalTo(x, least.n, acrossStart, true, ws);
    result = finishDirection(least.n, Integral.roughValue(x, least.n, ws), across.value, Params.minStability);
    decided = result.stability >= std::max(clearlyDefined, Params.minStability);
  }
  if (!decided)
  {
    across = leastEnergyOrthogonalTo(x, least.n, acrossStart, false, ws);
    result = finishDirection(least.n, least.value, across.value, Params.minStability);
  }
  memory.stabilityEstimated = false;
  memory.valid = least.n.allFinite() && across.direction.allFinite();
  memory.point = x;
  memory.n = least.n;
  memory.across = across.direction;
  // No neighbourhood of x to hand on: only a cold 3D search gathers one (in Workspace::local,
  // where a plane fit's own gather of x then finds it).
  return { result, nullptr };
}

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
/**
 * libFuzzer target over the VTK-free core: the bytes choose a cloud (random, duplicated,
 * collinear, coplanar, perturbed points; coordinates from 1e-300 to 1e300, NaN and Inf), a scale
 * h (also 0, negative, NaN, Inf), a variant, a procedure, kernel parameters and start points
 * (near the cloud, 1000 h away, NaN). Everything the core offers is then called on them.
 *
 * Beyond ASan/UBSan, the run aborts (a crash for libFuzzer) when a contract of the core breaks:
 * - PointIndex keeps exactly the finite points; makeSurface throws std::invalid_argument exactly
 *   for an empty index or invalid parameters, and nothing else escapes;
 * - a projection reports InvalidInput exactly for a non-finite start, never leaves a finite start
 *   at a non-finite point, keeps its counters in range, and `converged` agrees with its reason;
 * - n is a unit vector (or zero) with stability in [0, 1]; no NaN in n, e, g, delta or the domain
 *   evidence of a converged projection ("per-point trouble is a flag, never a silent NaN");
 * - where n is undefined, g and the curvature are 0 and the extremum type None;
 * - projectAll on 1 and 2 threads gives the same bits as project() one point at a time.
 * The value checks apply where the arithmetic is representable: coordinates and h within
 * [1e-100, 1e100] in magnitude (squared distances of larger numbers overflow double).
 */
#include "FuzzContract.h"
#include "pss/Core.h"

#include <Eigen/Geometry>
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

const char* const FuzzTargetName = "pss_fuzz_core";

namespace
{

using pss::Vec3;


constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A number that is often special: the edges of double, 0, NaN, Inf, or a plain value.
double Number(FuzzedDataProvider& in, double typical)
{
  static const double special[] = { 0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, kNaN, kInf, -kInf, 1e6,
    -1e6, 1e-8, std::numeric_limits<double>::max(), std::numeric_limits<double>::min(),
    std::numeric_limits<double>::denorm_min(), 1e15, 0.5, 3.0 };
  switch (in.ConsumeIntegralInRange<int>(0, 4))
  {
    case 0:
      return special[in.ConsumeIntegralInRange<std::size_t>(0, sizeof(special) / sizeof(special[0]) - 1)];
    case 1:
      return in.ConsumeFloatingPoint<double>();
    case 2:
      return in.ConsumeIntegralInRange<int>(-20, 20) * typical * 0.25;
    default:
      return in.ConsumeFloatingPointInRange<double>(-10.0 * typical, 10.0 * typical);
  }
}

Vec3 Point(FuzzedDataProvider& in, double typical)
{
  const double x = Number(in, typical);
  const double y = Number(in, typical);
  const double z = Number(in, typical);
  return Vec3(x, y, z);
}

// A unit-ish direction from small integers (never all zero).
Vec3 Direction(FuzzedDataProvider& in)
{
  Vec3 d(in.ConsumeIntegralInRange<int>(-3, 3), in.ConsumeIntegralInRange<int>(-3, 3),
    in.ConsumeIntegralInRange<int>(-3, 3));
  if (d.squaredNorm() == 0.0)
  {
    d = Vec3(1.0, 0.0, 0.0);
  }
  return d.normalized();
}

bool Representable(double v)
{
  return std::isfinite(v) && std::abs(v) <= 1e100 && (v == 0.0 || std::abs(v) >= 1e-100);
}

bool Representable(const Vec3& p)
{
  return Representable(p.x()) && Representable(p.y()) && Representable(p.z());
}

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

bool SameBits(const Vec3& a, const Vec3& b)
{
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

bool SameResult(const pss::ProjectionResult& a, const pss::ProjectionResult& b)
{
  return SameBits(a.point, b.point) && SameBits(a.direction.n, b.direction.n) &&
    SameBits(a.direction.stability, b.direction.stability) && SameBits(a.energy, b.energy) &&
    a.iterations == b.iterations && a.reason == b.reason && a.type == b.type && a.converged == b.converged &&
    SameBits(a.lastStep, b.lastStep);
}

void CheckDirection(const pss::Direction& d, double minStability)
{
  PSS_FUZZ_CHECK(d.n.allFinite());
  PSS_FUZZ_CHECK(d.n.squaredNorm() == 0.0 || std::abs(d.n.norm() - 1.0) < 1e-9);
  PSS_FUZZ_CHECK(d.stability >= 0.0 && d.stability <= 1.0);
  PSS_FUZZ_CHECK(!d.defined || d.stability > minStability);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  FuzzedDataProvider in(data, size);

  // The surface and the procedure.
  const int dimension = in.ConsumeBool() ? 3 : 2;
  const auto variant = static_cast<pss::Variant>(in.ConsumeIntegralInRange<int>(0, pss::VariantCount - 1));
  pss::SurfaceParameters params;
  const bool explicitScale = in.ConsumeBool();
  params.h = explicitScale ? Number(in, 1.0) : 1.0;
  params.cutoff = in.ConsumeBool() ? 3.0 : in.ConsumeFloatingPointInRange<double>(0.5, 6.0);
  params.quadratureOrder = in.ConsumeIntegralInRange<int>(1, 8);
  params.integrandPower = in.ConsumeBool() ? 2 : 1;
  params.minStability = in.ConsumeBool() ? 1e-5 : in.ConsumeFloatingPointInRange<double>(0.0, 0.9);
  // Both ways of evaluating e_I's delta, without a byte of its own (the corpus keeps its meaning).
  params.deltaLattice = params.quadratureOrder % 2 == 0 ? 0.5 : 0.0;
  pss::ProjectionOptions options;
  options.procedure = in.ConsumeBool() ? pss::Procedure::Plane : pss::Procedure::Extremal;
  options.seekMaxima = in.ConsumeBool();
  options.maxIterations = in.ConsumeIntegralInRange<int>(1, 12);
  options.maxTravel = in.ConsumeBool() ? 1000.0 : in.ConsumeFloatingPointInRange<double>(0.01, 2000.0);
  // n_I in 3D is a search over the sphere of directions (tens of e_I quadratures per step): keep
  // those inputs to a few projections so that each input stays well within the time limit.
  const bool expensive = dimension == 3 && (variant == pss::Variant::Integral || variant == pss::Variant::Delta);
  if (expensive)
  {
    params.quadratureOrder = std::min(params.quadratureOrder, 4);
    options.maxIterations = std::min(options.maxIterations, 2);
  }
  const double typical = std::abs(params.h) > 0.0 && std::isfinite(params.h) && std::abs(params.h) < 1e100
    ? std::abs(params.h)
    : 1.0;

  // The cloud: each point new, or built from earlier ones (duplicates, lines, planes, jitter).
  const std::size_t count = in.ConsumeIntegralInRange<std::size_t>(0, 40);
  std::vector<Vec3> cloud;
  const Vec3 lineDirection = Direction(in);
  const Vec3 planeU = Direction(in);
  const Vec3 planeV = planeU.cross(Direction(in)).normalized();
  for (std::size_t i = 0; i < count && in.remaining_bytes() > 0; ++i)
  {
    const int kind = cloud.empty() ? 0 : in.ConsumeIntegralInRange<int>(0, 5);
    const Vec3 base = cloud.empty() ? Vec3(Vec3::Zero()) : cloud[in.ConsumeIntegralInRange<std::size_t>(0, cloud.size() - 1)];
    const double s = in.ConsumeIntegralInRange<int>(-40, 40) * typical * 0.1;
    const double t = in.ConsumeIntegralInRange<int>(-40, 40) * typical * 0.1;
    switch (kind)
    {
      case 0:
        cloud.push_back(Point(in, typical));
        break;
      case 1: // an exact duplicate
        cloud.push_back(base);
        break;
      case 2: // collinear with the first point
        cloud.push_back(cloud.front() + s * lineDirection);
        break;
      case 3: // coplanar with the first point
        cloud.push_back(cloud.front() + s * planeU + t * (planeV.allFinite() ? planeV : planeU));
        break;
      case 4: // a near-duplicate, one ulp-ish away
        cloud.push_back(base + Vec3(std::nextafter(base.x(), kInf) - base.x(), 0.0, 0.0));
        break;
      default: // a plain lattice point
        cloud.push_back(Vec3(s, t, dimension == 3 ? 0.1 * s * t / typical : 0.0));
        break;
    }
  }

  pss::PointIndex index(cloud, dimension);
  std::size_t finite = 0;
  bool representable = Representable(params.h) && params.h > 0.0;
  for (const Vec3& p : cloud)
  {
    finite += pss::isFinite(p) ? 1 : 0;
    representable = representable && (!pss::isFinite(p) || Representable(p));
  }
  PSS_FUZZ_CHECK(index.size() == finite);
  PSS_FUZZ_CHECK(index.skippedCount() == cloud.size() - finite);
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    PSS_FUZZ_CHECK(pss::isFinite(index.point(i)));
    PSS_FUZZ_CHECK(index.originalId(i) < cloud.size());
  }
  const int detected = pss::detectDimension(cloud);
  PSS_FUZZ_CHECK(detected == 2 || detected == 3);
  const double estimated = pss::estimateScale(index, in.ConsumeIntegralInRange<int>(1, 12), 1.0);
  PSS_FUZZ_CHECK(estimated >= 0.0); // 0 when there are too few distinct points; never NaN
  if (!explicitScale && estimated > 0.0 && std::isfinite(estimated))
  {
    params.h = estimated;
    representable = representable && Representable(params.h);
  }

  // APSS and RIMLS need normals: the plane's normal, flipped at every third point, so that some
  // neighbourhoods' normals agree and some cancel. In 2D a normal along z has no xy part and is
  // refused; that refusal is checked too.
  if (pss::needsNormals(variant))
  {
    const Vec3 up = planeU.cross(planeV.allFinite() ? planeV : lineDirection);
    std::vector<Vec3> normals(cloud.size());
    for (std::size_t i = 0; i < normals.size(); ++i)
    {
      normals[i] = i % 3 == 0 ? Vec3(-up) : up;
    }
    try
    {
      index.setNormals(normals);
    }
    catch (const std::invalid_argument&)
    {
      PSS_FUZZ_CHECK(!index.empty() && !(index.restrict(up).norm() > 0.0));
      return 0;
    }
  }

  bool paramsValid = true;
  try
  {
    params.validate();
  }
  catch (const std::invalid_argument&)
  {
    paramsValid = false;
  }
  std::unique_ptr<pss::SurfaceDefinition> surface;
  try
  {
    surface = pss::makeSurface(variant, index, params);
  }
  catch (const std::invalid_argument&)
  {
    PSS_FUZZ_CHECK(index.empty() || !paramsValid);
    return 0;
  }
  PSS_FUZZ_CHECK(surface && !index.empty() && paramsValid);
  const double h = params.h;

  // Start points: anywhere, near a cloud point, or far (up to 1000 h) from it.
  std::vector<Vec3> starts;
  const std::size_t startCount = in.ConsumeIntegralInRange<std::size_t>(0, expensive ? 1 : 4);
  for (std::size_t i = 0; i < startCount; ++i)
  {
    const Vec3 near = index.point(in.ConsumeIntegralInRange<std::size_t>(0, index.size() - 1));
    switch (in.ConsumeIntegralInRange<int>(0, 3))
    {
      case 0:
        starts.push_back(Point(in, typical));
        break;
      case 1:
        starts.push_back(near + in.ConsumeFloatingPointInRange<double>(-2.0, 2.0) * h * Direction(in));
        break;
      case 2:
        starts.push_back(near + in.ConsumeFloatingPointInRange<double>(-1000.0, 1000.0) * h * Direction(in));
        break;
      default:
        starts.push_back(near);
        break;
    }
  }
  // Sums over the Gaussian band are representable when the starts are, and not too far out.
  for (const Vec3& s : starts)
  {
    representable = representable && (!pss::isFinite(s) || Representable(s));
  }

  // PSS_FUZZ_DEBUG=1 prints what an input decodes to (for replaying an artifact).
  static const bool debug = std::getenv("PSS_FUZZ_DEBUG") != nullptr;
  if (debug)
  {
    std::fprintf(stderr, "dimension %d variant %s h %.17g cutoff %g order %d power %d deltaLattice %g minStability %g "
                         "procedure %s%s maxIterations %d maxTravel %g\n",
      dimension, pss::variantName(variant), h, params.cutoff, params.quadratureOrder, params.integrandPower,
      params.deltaLattice, params.minStability, options.procedure == pss::Procedure::Plane ? "plane" : "extremal",
      options.seekMaxima ? " (maxima)" : "", options.maxIterations, options.maxTravel);
    for (const Vec3& p : cloud)
    {
      std::fprintf(stderr, "  point %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    }
    for (const Vec3& p : starts)
    {
      std::fprintf(stderr, "  start %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    }
  }

  const pss::Orientation orientation = pss::Orientation::awayFromCentroid(index);
  const pss::DistanceField field(index, params);
  pss::DomainThresholds thresholds;
  pss::Workspace ws; // one for every query below, as a caller's loop would keep it
  for (const Vec3& x : starts)
  {
    const bool finiteStart = pss::isFinite(x);
    if (finiteStart)
    {
      const pss::Direction d = surface->direction(x, ws);
      if (representable)
      {
        CheckDirection(d, params.minStability);
        PSS_FUZZ_CHECK(!std::isnan(field.delta(x, ws)) && field.delta(x, ws) >= 0.0);
        PSS_FUZZ_CHECK(!std::isnan(surface->energy(x, d.n.squaredNorm() > 0.0 ? d.n : Vec3(1, 0, 0), ws)));
      }
    }
    const pss::ImplicitSample sample = pss::evaluateImplicit(*surface, x, orientation, ws);
    if (representable)
    {
      CheckDirection(sample.direction, params.minStability);
      PSS_FUZZ_CHECK(!std::isnan(sample.energy) && !std::isnan(sample.g) && !std::isnan(sample.curvature));
    }
    if (!finiteStart)
    {
      PSS_FUZZ_CHECK(!sample.direction.defined && sample.energy == 0.0 && sample.g == 0.0);
    }
    if (!sample.direction.defined)
    {
      PSS_FUZZ_CHECK(sample.g == 0.0 && sample.curvature == 0.0 && sample.type == pss::ExtremumType::None);
    }

    const pss::ProjectionResult r = pss::project(*surface, x, options, ws);
    PSS_FUZZ_CHECK((r.reason == pss::StopReason::InvalidInput) == !finiteStart);
    PSS_FUZZ_CHECK(r.converged == (r.reason == pss::StopReason::Converged));
    PSS_FUZZ_CHECK(r.iterations >= 0 && r.iterations <= options.maxIterations);
    PSS_FUZZ_CHECK(!r.converged || r.direction.defined);
    PSS_FUZZ_CHECK(r.reason != pss::StopReason::MaxIterations || r.iterations == options.maxIterations);
    if (finiteStart)
    {
      PSS_FUZZ_CHECK(pss::isFinite(r.point));
    }
    if (representable && finiteStart)
    {
      CheckDirection(r.direction, params.minStability);
      CheckDirection(r.startDirection, params.minStability);
      PSS_FUZZ_CHECK(!std::isnan(r.energy));
      PSS_FUZZ_CHECK(std::isfinite(r.lastStep));
    }

    const pss::DomainEvidence ev = pss::classifyStart(*surface, x, options, thresholds, ws);
    PSS_FUZZ_CHECK(SameResult(ev.projection, r)); // the same projection, whatever ran before it
    if (ev.projection.converged)
    {
      PSS_FUZZ_CHECK(ev.label == pss::DomainLabel::InDomain || ev.label == pss::DomainLabel::Spurious);
      if (representable)
      {
        PSS_FUZZ_CHECK(std::isfinite(ev.distanceToCloud) && ev.normalAngle >= 0.0 && ev.normalAngle <= 90.0 &&
          ev.startAngle >= 0.0 && ev.startAngle <= 90.0);
      }
    }
    else
    {
      PSS_FUZZ_CHECK(ev.label == pss::DomainLabel::Undefined || ev.label == pss::DomainLabel::NotConverged);
    }
  }

  // Determinism: the threaded batch gives the bits of the one-at-a-time projections.
  if (!starts.empty() && !expensive && in.ConsumeBool())
  {
    std::vector<pss::ProjectionResult> single;
    for (const Vec3& x : starts)
    {
      single.push_back(pss::project(*surface, x, options, ws));
    }
    for (int threads : { 1, 2 })
    {
      const std::vector<pss::ProjectionResult> batch = pss::projectAll(*surface, starts, options, threads);
      PSS_FUZZ_CHECK(batch.size() == single.size());
      for (std::size_t i = 0; i < batch.size(); ++i)
      {
        PSS_FUZZ_CHECK(SameResult(batch[i], single[i]));
      }
    }
  }
  return 0;
}

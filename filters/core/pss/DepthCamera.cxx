// SPDX-License-Identifier: BSD-3-Clause
#include "pss/DepthCamera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pss
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();

double radians(double degrees)
{
  return degrees * M_PI / 180.0;
}

// The scene in the table frame (X across, Y away from the sensor, Z up, the top at Z = 0), and
// the rigid motion between that frame and the sensor's. Everything is intersected and measured
// in the table frame, where the objects are axis-aligned or nearly so; distances and ray
// parameters do not change under a rigid motion.
struct TableScene
{
  // Sensor pose: height above the table, pitch down and roll about the optical axis.
  static constexpr double height = 0.52;
  static constexpr double pitchDegrees = 30.0;
  static constexpr double rollDegrees = 4.0;
  // Table rectangle.
  static constexpr double tableHalfX = 0.9;
  static constexpr double tableNearY = 0.2;
  static constexpr double tableFarY = 3.15;
  // Box: centre, half sizes, turn about Z.
  static constexpr double boxX = -0.28, boxY = 1.05;
  static constexpr double boxHalf[3] = { 0.16, 0.12, 0.15 };
  static constexpr double boxYawDegrees = 30.0;
  // Cylinder: axis, radius, height.
  static constexpr double cylinderX = 0.30, cylinderY = 0.80, cylinderRadius = 0.08, cylinderHeight = 0.28;
  // Sphere resting on the table.
  static constexpr double sphereX = 0.08, sphereY = 1.45, sphereRadius = 0.14;

  Vec3 axes[3];   // the table frame's X, Y, Z in sensor coordinates
  Vec3 sensor;    // the sensor's position in the table frame
  double boxCos, boxSin;

  TableScene()
  {
    const double sp = std::sin(radians(pitchDegrees)), cp = std::cos(radians(pitchDegrees));
    const double sr = std::sin(radians(rollDegrees)), cr = std::cos(radians(rollDegrees));
    // Unrolled: X = x; Y (level, away) = cos(pitch) z - sin(pitch) y; Z (up) = -cos(pitch) y -
    // sin(pitch) z. The roll turns all three about the optical axis z.
    auto roll = [&](double x, double y, double z) { return Vec3(cr * x - sr * y, sr * x + cr * y, z); };
    axes[0] = roll(1.0, 0.0, 0.0);
    axes[1] = roll(0.0, -sp, cp);
    axes[2] = roll(0.0, -cp, -sp);
    sensor = Vec3(0.0, 0.0, height);
    boxCos = std::cos(radians(boxYawDegrees));
    boxSin = std::sin(radians(boxYawDegrees));
  }

  Vec3 pointToTable(const Vec3& p) const { return sensor + directionToTable(p); }
  Vec3 directionToTable(const Vec3& d) const { return Vec3(axes[0].dot(d), axes[1].dot(d), axes[2].dot(d)); }

  // Box coordinates: centred, along the box's edges.
  Vec3 toBox(const Vec3& p) const
  {
    const double x = p.x() - boxX, y = p.y() - boxY, z = p.z() - boxHalf[2];
    return Vec3(boxCos * x + boxSin * y, -boxSin * x + boxCos * y, z);
  }
  Vec3 directionToBox(const Vec3& d) const
  {
    return Vec3(boxCos * d.x() + boxSin * d.y(), -boxSin * d.x() + boxCos * d.y(), d.z());
  }
};

const TableScene& scene()
{
  static const TableScene s;
  return s;
}

// Distance from q to the boundary of the box [-half, half] (n axes), inside or outside.
double boxBoundaryDistance(const double* q, const double* half, int n)
{
  double outside = 0.0;
  double inside = Infinity;
  bool isOutside = false;
  for (int i = 0; i < n; ++i)
  {
    const double excess = std::abs(q[i]) - half[i];
    if (excess > 0.0)
    {
      outside += excess * excess;
      isOutside = true;
    }
    inside = std::min(inside, -excess);
  }
  return isOutside ? std::sqrt(outside) : inside;
}

// The smaller positive root below tMax of a t^2 + b t + c = 0 whose point passes @p accept, or
// +infinity. The roots are computed without cancellation.
template <class Accept>
double quadraticHit(double a, double b, double c, double tMax, Accept&& accept)
{
  const double disc = b * b - 4.0 * a * c;
  if (!(a > 0.0) || disc < 0.0)
  {
    return Infinity;
  }
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double t1 = q / a;
  double t2 = q != 0.0 ? c / q : t1;
  if (t1 > t2)
  {
    std::swap(t1, t2);
  }
  for (double t : { t1, t2 })
  {
    if (t > 0.0 && t < tMax && accept(t))
    {
      return t;
    }
  }
  return Infinity;
}

// Ray parameters of each surface's nearest hit in the table frame (+infinity: none).
double tableHit(const Vec3& o, const Vec3& d, double tMax)
{
  if (d.z() == 0.0)
  {
    return Infinity;
  }
  const double t = -o.z() / d.z();
  if (!(t > 0.0 && t < tMax))
  {
    return Infinity;
  }
  const Vec3 p = o + t * d;
  return std::abs(p.x()) <= TableScene::tableHalfX && p.y() >= TableScene::tableNearY && p.y() <= TableScene::tableFarY ? t : Infinity;
}

double boxHit(const Vec3& oTable, const Vec3& dTable, double tMax)
{
  const TableScene& s = scene();
  const Vec3 o = s.toBox(oTable);
  const Vec3 d = s.directionToBox(dTable);
  double tNear = -Infinity, tFar = Infinity;
  for (int i = 0; i < 3; ++i)
  {
    const double h = TableScene::boxHalf[i];
    if (d[i] == 0.0)
    {
      if (std::abs(o[i]) > h)
      {
        return Infinity;
      }
      continue;
    }
    double t1 = (-h - o[i]) / d[i];
    double t2 = (h - o[i]) / d[i];
    if (t1 > t2)
    {
      std::swap(t1, t2);
    }
    tNear = std::max(tNear, t1);
    tFar = std::min(tFar, t2);
  }
  if (tNear > tFar)
  {
    return Infinity;
  }
  // From outside the first face crossed is the entry; from inside, the exit.
  const double t = tNear > 0.0 ? tNear : tFar;
  return t > 0.0 && t < tMax ? t : Infinity;
}

double cylinderHit(const Vec3& o, const Vec3& d, double tMax)
{
  const double ex = o.x() - TableScene::cylinderX, ey = o.y() - TableScene::cylinderY;
  const double r2 = TableScene::cylinderRadius * TableScene::cylinderRadius;
  double best = quadraticHit(d.x() * d.x() + d.y() * d.y(), 2.0 * (ex * d.x() + ey * d.y()), ex * ex + ey * ey - r2,
    tMax, [&](double t) {
      const double z = o.z() + t * d.z();
      return z >= 0.0 && z <= TableScene::cylinderHeight;
    });
  if (d.z() != 0.0)
  {
    for (double level : { 0.0, TableScene::cylinderHeight })
    {
      const double t = (level - o.z()) / d.z();
      const double x = ex + t * d.x(), y = ey + t * d.y();
      if (t > 0.0 && t < std::min(best, tMax) && x * x + y * y <= r2)
      {
        best = t;
      }
    }
  }
  return best;
}

Vec3 sphereCentre()
{
  return Vec3(TableScene::sphereX, TableScene::sphereY, TableScene::sphereRadius);
}

double sphereHit(const Vec3& o, const Vec3& d, double tMax)
{
  const Vec3 e = o - sphereCentre();
  return quadraticHit(d.squaredNorm(), 2.0 * e.dot(d), e.squaredNorm() - TableScene::sphereRadius * TableScene::sphereRadius,
    tMax, [](double) { return true; });
}

double tableFrameDistance(DepthSurface surface, const Vec3& p)
{
  switch (surface)
  {
    case DepthSurface::Table:
    {
      const double dx = std::max(0.0, std::abs(p.x()) - TableScene::tableHalfX);
      const double dy = std::max({ 0.0, TableScene::tableNearY - p.y(), p.y() - TableScene::tableFarY });
      return std::sqrt(dx * dx + dy * dy + p.z() * p.z());
    }
    case DepthSurface::Box:
    {
      const Vec3 q = scene().toBox(p);
      return boxBoundaryDistance(q.data(), TableScene::boxHalf, 3);
    }
    case DepthSurface::Cylinder:
    {
      // A solid of revolution: the distance in the half-plane through the axis and p.
      const double q[2] = { std::hypot(p.x() - TableScene::cylinderX, p.y() - TableScene::cylinderY),
        p.z() - 0.5 * TableScene::cylinderHeight };
      const double half[2] = { TableScene::cylinderRadius, 0.5 * TableScene::cylinderHeight };
      return boxBoundaryDistance(q, half, 2);
    }
    case DepthSurface::Sphere:
      return std::abs((p - sphereCentre()).norm() - TableScene::sphereRadius);
    case DepthSurface::None:
      break;
  }
  return Infinity;
}

} // namespace

const char* depthSurfaceName(DepthSurface s)
{
  switch (s)
  {
    case DepthSurface::None:
      return "none";
    case DepthSurface::Table:
      return "table";
    case DepthSurface::Box:
      return "box";
    case DepthSurface::Cylinder:
      return "cylinder";
    case DepthSurface::Sphere:
      return "sphere";
  }
  return "unknown";
}

void DepthCameraSpec::validate() const
{
  if (width < 1 || height < 1 || static_cast<double>(width) * static_cast<double>(height) > 1e8)
  {
    throw std::invalid_argument("the depth image needs at least one pixel and at most 1e8");
  }
  if (!(horizontalFov > 0.0 && horizontalFov < 180.0))
  {
    throw std::invalid_argument("the depth camera's field of view must be in (0, 180) degrees");
  }
  if (!(depthNoise >= 0.0) || !std::isfinite(depthNoise))
  {
    throw std::invalid_argument("the depth noise must be a finite number >= 0");
  }
  if (!(baseline > 0.0) || !std::isfinite(baseline))
  {
    throw std::invalid_argument("the projector baseline must be a positive finite number");
  }
  if (!(disparityStep >= 0.0) || !std::isfinite(disparityStep))
  {
    throw std::invalid_argument("the disparity step must be a finite number >= 0");
  }
  if (!(maxRange > 0.0))
  {
    throw std::invalid_argument("the depth camera's range must be positive");
  }
}

double DepthCameraSpec::focalLength() const
{
  return 0.5 * width / std::tan(0.5 * radians(horizontalFov));
}

Vec3 DepthCameraSpec::pixelRay(int row, int column) const
{
  const double f = focalLength();
  return Vec3((column + 0.5 - 0.5 * width) / f, (row + 0.5 - 0.5 * height) / f, 1.0);
}

double DepthCameraSpec::depthStep(double z) const
{
  return z * z * disparityStep / (focalLength() * baseline);
}

double DepthCameraSpec::quantizeDepth(double z) const
{
  if (!(z > 0.0))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (disparityStep == 0.0)
  {
    return z;
  }
  const double fb = focalLength() * baseline;
  const double disparity = std::round(fb / z / disparityStep) * disparityStep;
  return disparity > 0.0 ? fb / disparity : std::numeric_limits<double>::quiet_NaN();
}

DepthHit castDepthSceneRay(const Vec3& origin, const Vec3& direction, double tMax)
{
  const TableScene& s = scene();
  const Vec3 o = s.pointToTable(origin);
  const Vec3 d = s.directionToTable(direction);
  DepthHit hit;
  double best = tMax;
  auto consider = [&](DepthSurface surface, double t) {
    if (t < best)
    {
      best = t;
      hit.surface = surface;
    }
  };
  consider(DepthSurface::Table, tableHit(o, d, best));
  consider(DepthSurface::Box, boxHit(o, d, best));
  consider(DepthSurface::Cylinder, cylinderHit(o, d, best));
  consider(DepthSurface::Sphere, sphereHit(o, d, best));
  if (hit.surface != DepthSurface::None)
  {
    hit.t = best;
    hit.point = origin + best * direction;
  }
  return hit;
}

double distanceToDepthSurface(DepthSurface s, const Vec3& x)
{
  return tableFrameDistance(s, scene().pointToTable(x));
}

double distanceToDepthScene(const Vec3& x)
{
  const Vec3 p = scene().pointToTable(x);
  double d = Infinity;
  for (int s = 1; s < DepthSurfaceCount; ++s)
  {
    d = std::min(d, tableFrameDistance(static_cast<DepthSurface>(s), p));
  }
  return d;
}

std::vector<DepthPixelTruth> traceDepthImage(const DepthCameraSpec& camera)
{
  camera.validate();
  std::vector<DepthPixelTruth> image(static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height));
  const Vec3 projector = camera.projector();
  // A hit of the projector's ray this close to the point itself is the point (rounding), not a
  // surface in front of it.
  constexpr double selfHit = 1.0 - 1e-9;
  for (int row = 0; row < camera.height; ++row)
  {
    for (int column = 0; column < camera.width; ++column)
    {
      DepthPixelTruth& pixel = image[static_cast<std::size_t>(row) * static_cast<std::size_t>(camera.width) +
        static_cast<std::size_t>(column)];
      // The ray has z = 1, so its parameter is the depth.
      const DepthHit hit = castDepthSceneRay(Vec3::Zero(), camera.pixelRay(row, column), Infinity);
      pixel.surface = hit.surface;
      if (hit.surface == DepthSurface::None)
      {
        pixel.state = PixelState::NoHit;
        continue;
      }
      pixel.depth = hit.t;
      if (hit.t > camera.maxRange)
      {
        pixel.state = PixelState::OutOfRange;
      }
      else if (camera.projectorShadows &&
        castDepthSceneRay(projector, hit.point - projector, selfHit).surface != DepthSurface::None)
      {
        pixel.state = PixelState::Shadow;
      }
      else
      {
        pixel.state = PixelState::Valid;
      }
    }
  }
  return image;
}

} // namespace pss

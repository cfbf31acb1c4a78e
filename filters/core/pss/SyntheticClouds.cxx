// SPDX-License-Identifier: BSD-3-Clause
#include "pss/SyntheticClouds.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace pss
{

namespace
{

struct SceneName
{
  Scene scene;
  const char* name;
};

constexpr SceneName SceneNames[] = { { Scene::Line, "line" }, { Scene::Circle, "circle" },
  { Scene::Corner, "corner" }, { Scene::NoisyCurve, "noisy-curve" }, { Scene::Plane, "plane" },
  { Scene::Sphere, "sphere" }, { Scene::TwoSheets, "two-sheets" },
  { Scene::DepthCamera, "depth-camera" } };

// std::normal_distribution differs between standard libraries; this does not.
class PortableRandom
{
public:
  explicit PortableRandom(unsigned seed)
    : Engine(seed)
  {
  }
  double uniform() { return (static_cast<double>(Engine()) + 0.5) / 4294967296.0; }
  double normal()
  {
    // Box-Muller; uniform() never returns 0, so the logarithm is finite.
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    return r * std::cos(2.0 * M_PI * uniform());
  }

private:
  std::mt19937 Engine;
};

double segmentDistance(const Vec3& x, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm();
}

// Distance to the axis-aligned square [-half, half]^2 at height z = level.
double squareDistance(const Vec3& x, double half, double level)
{
  const double dx = std::max(0.0, std::abs(x.x()) - half);
  const double dy = std::max(0.0, std::abs(x.y()) - half);
  const double dz = x.z() - level;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// The NoisyCurve's centre line, parameter u in [0, 1].
Vec3 sineArc(double size, double u)
{
  return Vec3(size * u, 0.15 * size * std::sin(2.0 * M_PI * u), 0.0);
}

// Its derivative d/du.
Vec3 sineArcTangent(double size, double u)
{
  return Vec3(size, 0.3 * M_PI * size * std::cos(2.0 * M_PI * u), 0.0);
}

// The NoisyCurve's noise grows from a fifth of spec.noise at u = 0 to all of it at u = 1.
double noisyCurveNoiseScale(double u)
{
  return 0.2 + 0.8 * u;
}

void cornerEnds(const CloudSpec& s, Vec3& left, Vec3& right)
{
  const double half = 0.5 * s.cornerAngle * M_PI / 180.0;
  left = 0.5 * s.size * Vec3(-std::sin(half), std::cos(half), 0.0);
  right = 0.5 * s.size * Vec3(std::sin(half), std::cos(half), 0.0);
}

// A point of the noise-free shape drawn uniformly (NoisyCurve: with falling density).
Vec3 shapePoint(const CloudSpec& s, PortableRandom& rng, double& noiseScale)
{
  const bool flat = s.dimension == 2;
  const double half = 0.5 * s.size;
  noiseScale = 1.0;
  switch (s.scene)
  {
    case Scene::Line:
      return Vec3(s.size * (rng.uniform() - 0.5), 0.0, 0.0);
    case Scene::Circle:
    {
      const double phi = 2.0 * M_PI * rng.uniform();
      return half * Vec3(std::cos(phi), std::sin(phi), 0.0);
    }
    case Scene::Corner:
    {
      Vec3 left;
      Vec3 right;
      cornerEnds(s, left, right);
      return rng.uniform() * (rng.uniform() < 0.5 ? left : right);
    }
    case Scene::NoisyCurve:
    {
      // Density 1.5 - u by inverting its cumulative distribution 1.5 u - u^2 / 2; the noise
      // grows from a fifth of its value at u = 0 to all of it at u = 1.
      const double u = 1.5 - std::sqrt(2.25 - 2.0 * rng.uniform());
      noiseScale = noisyCurveNoiseScale(u);
      return sineArc(s.size, u);
    }
    case Scene::Plane:
      return flat ? Vec3(s.size * (rng.uniform() - 0.5), 0.0, 0.0)
                  : Vec3(s.size * (rng.uniform() - 0.5), s.size * (rng.uniform() - 0.5), 0.0);
    case Scene::Sphere:
    {
      if (flat)
      {
        const double phi = 2.0 * M_PI * rng.uniform();
        return half * Vec3(std::cos(phi), std::sin(phi), 0.0);
      }
      Vec3 v(rng.normal(), rng.normal(), rng.normal());
      return half * v.normalized();
    }
    case Scene::TwoSheets:
    {
      const double level = (rng.uniform() < 0.5 ? -0.5 : 0.5) * s.gap;
      return flat ? Vec3(s.size * (rng.uniform() - 0.5), level, 0.0)
                  : Vec3(s.size * (rng.uniform() - 0.5), s.size * (rng.uniform() - 0.5), level);
    }
    case Scene::DepthCamera:
      break; // generateDepthFrame
  }
  return Vec3::Zero();
}

} // namespace

const char* sceneName(Scene s)
{
  for (const SceneName& n : SceneNames)
  {
    if (n.scene == s)
    {
      return n.name;
    }
  }
  return "unknown";
}

bool parseScene(const std::string& text, Scene& out)
{
  std::string key;
  for (char c : text)
  {
    key.push_back(c == '_' || c == ' ' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  for (const SceneName& n : SceneNames)
  {
    if (key == n.name)
    {
      out = n.scene;
      return true;
    }
  }
  return false;
}

void CloudSpec::validate() const
{
  if (scene == Scene::DepthCamera)
  {
    camera.validate(); // the other fields do not apply to it
    return;
  }
  if (dimension != 2 && dimension != 3)
  {
    throw std::invalid_argument("the cloud dimension must be 2 or 3");
  }
  if (!(size > 0.0) || !std::isfinite(size))
  {
    throw std::invalid_argument("the scene size must be a positive finite number");
  }
  if (!(noise >= 0.0) || !std::isfinite(noise))
  {
    throw std::invalid_argument("the noise must be a finite number >= 0");
  }
  if (!(cornerAngle > 0.0 && cornerAngle < 180.0))
  {
    throw std::invalid_argument("the corner angle must be in (0, 180) degrees");
  }
  if (!(gap >= 0.0) || !std::isfinite(gap))
  {
    throw std::invalid_argument("the sheet gap must be a finite number >= 0");
  }
  if (count > 100000000)
  {
    throw std::invalid_argument("refusing to generate more than 1e8 points");
  }
}

std::vector<Vec3> generateCloud(const CloudSpec& spec)
{
  if (spec.scene == Scene::DepthCamera)
  {
    return generateDepthFrame(spec).points;
  }
  spec.validate();
  PortableRandom rng(spec.seed);
  std::vector<Vec3> points;
  points.reserve(spec.count);
  for (std::size_t i = 0; i < spec.count; ++i)
  {
    double noiseScale = 1.0;
    Vec3 p = shapePoint(spec, rng, noiseScale);
    if (spec.noise > 0.0)
    {
      const double sigma = spec.noise * noiseScale;
      p.x() += sigma * rng.normal();
      p.y() += sigma * rng.normal();
      if (spec.dimension == 3)
      {
        p.z() += sigma * rng.normal();
      }
    }
    points.push_back(p);
  }
  return points;
}

double distanceToShape(const CloudSpec& s, const Vec3& xIn)
{
  if (s.scene == Scene::DepthCamera)
  {
    return distanceToDepthScene(xIn);
  }
  const bool flat = s.dimension == 2;
  const Vec3 x = flat ? Vec3(xIn.x(), xIn.y(), 0.0) : xIn;
  const double half = 0.5 * s.size;
  switch (s.scene)
  {
    case Scene::Line:
      return segmentDistance(x, Vec3(-half, 0, 0), Vec3(half, 0, 0));
    case Scene::Circle:
    {
      const double rho = std::hypot(x.x(), x.y());
      return std::hypot(rho - half, x.z());
    }
    case Scene::Corner:
    {
      Vec3 left;
      Vec3 right;
      cornerEnds(s, left, right);
      return std::min(segmentDistance(x, Vec3::Zero(), left), segmentDistance(x, Vec3::Zero(), right));
    }
    case Scene::NoisyCurve:
    {
      // Closest polyline vertex of a fine sampling, then a golden-section refinement on the
      // two neighbouring parameter intervals.
      constexpr int samples = 4096;
      int best = 0;
      double bestDist = std::numeric_limits<double>::infinity();
      for (int i = 0; i <= samples; ++i)
      {
        const double d = (x - sineArc(s.size, double(i) / samples)).squaredNorm();
        if (d < bestDist)
        {
          bestDist = d;
          best = i;
        }
      }
      double lo = std::max(0.0, double(best - 1) / samples);
      double hi = std::min(1.0, double(best + 1) / samples);
      const double r = 0.5 * (std::sqrt(5.0) - 1.0);
      auto f = [&](double u) { return (x - sineArc(s.size, u)).squaredNorm(); };
      for (int it = 0; it < 60; ++it)
      {
        const double c = hi - r * (hi - lo);
        const double d = lo + r * (hi - lo);
        if (f(c) < f(d))
        {
          hi = d;
        }
        else
        {
          lo = c;
        }
      }
      return std::sqrt(std::min(bestDist, f(0.5 * (lo + hi))));
    }
    case Scene::Plane:
      return flat ? segmentDistance(x, Vec3(-half, 0, 0), Vec3(half, 0, 0)) : squareDistance(x, half, 0.0);
    case Scene::Sphere:
      return std::abs(x.norm() - half);
    case Scene::DepthCamera:
      break; // handled above
    case Scene::TwoSheets:
    {
      const double g = 0.5 * s.gap;
      if (flat)
      {
        return std::min(segmentDistance(x, Vec3(-half, -g, 0), Vec3(half, -g, 0)),
          segmentDistance(x, Vec3(-half, g, 0), Vec3(half, g, 0)));
      }
      return std::min(squareDistance(x, half, -g), squareDistance(x, half, g));
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

CurveFrame noisyCurveFrame(const CloudSpec& spec, double u)
{
  if (spec.scene != Scene::NoisyCurve)
  {
    throw std::invalid_argument("noisyCurveFrame: the scene is not the noisy curve");
  }
  if (!(u >= 0.0 && u <= 1.0))
  {
    throw std::invalid_argument("noisyCurveFrame: the parameter must be in [0, 1]");
  }
  CurveFrame f;
  f.point = sineArc(spec.size, u);
  const Vec3 t = sineArcTangent(spec.size, u).normalized();
  f.normal = Vec3(-t.y(), t.x(), 0.0);
  f.sigma = spec.noise * noisyCurveNoiseScale(u);
  return f;
}

DepthFrame generateDepthFrame(const CloudSpec& spec)
{
  if (spec.scene != Scene::DepthCamera)
  {
    throw std::invalid_argument("generateDepthFrame: the scene is not the depth camera");
  }
  const DepthCameraSpec& camera = spec.camera;
  const std::vector<DepthPixelTruth> truth = traceDepthImage(camera); // validates the camera
  DepthFrame frame;
  frame.width = camera.width;
  frame.height = camera.height;
  frame.focalLength = camera.focalLength();
  frame.points.assign(truth.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  frame.pixels.resize(truth.size());
  PortableRandom rng(spec.seed);
  for (std::size_t k = 0; k < truth.size(); ++k)
  {
    // Drawn for every pixel, so that a pixel's noise does not depend on which others are valid.
    const double draw = rng.normal();
    DepthPixel& pixel = frame.pixels[k];
    pixel.row = static_cast<int>(k / static_cast<std::size_t>(camera.width));
    pixel.column = static_cast<int>(k % static_cast<std::size_t>(camera.width));
    pixel.surface = truth[k].surface;
    pixel.state = truth[k].state;
    const double z = truth[k].depth;
    pixel.sigma = pixel.surface == DepthSurface::None ? 0.0 : camera.depthNoise * z * z;
    if (pixel.state != PixelState::Valid)
    {
      continue;
    }
    const double measured = camera.quantizeDepth(z + pixel.sigma * draw);
    if (!(measured > 0.0) || !std::isfinite(measured))
    {
      pixel.state = PixelState::OutOfRange;
      continue;
    }
    frame.points[k] = measured * camera.pixelRay(pixel.row, pixel.column);
  }
  return frame;
}

} // namespace pss

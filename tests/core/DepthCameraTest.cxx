// SPDX-License-Identifier: BSD-3-Clause
// The simulated depth camera (DepthCamera.h, generateDepthFrame) against truths it does not
// compute itself: sphere tracing with the exact distance functions finds the same hits and the
// same projector shadows as the analytic ray intersections; every measured point lies within its
// noise and quantization of its own surface; disparities are exact multiples of 1/8 pixel; the
// noise, without quantization, is Gaussian with sigma0 z^2; same seed, same bytes.

#include "pss/DepthCamera.h"
#include "pss/SyntheticClouds.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

using namespace pss;

namespace
{

CloudSpec cameraSpec(int width = 640, int height = 480)
{
  CloudSpec spec;
  spec.scene = Scene::DepthCamera;
  spec.camera.width = width;
  spec.camera.height = height;
  return spec;
}

bool finite(const Vec3& p)
{
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

// Sphere tracing along from + t u (u a unit vector) with the exact distance to the scene: the
// first t in (0, length) where the distance falls below eps, or +infinity. It knows nothing of
// the ray intersections it checks.
double sphereTrace(const Vec3& from, const Vec3& u, double length, double start, double eps = 1e-8)
{
  double t = start;
  for (int step = 0; step < 100000 && t < length; ++step)
  {
    const double d = distanceToDepthScene(from + t * u);
    if (d < eps)
    {
      return t;
    }
    t += d;
  }
  return std::numeric_limits<double>::infinity();
}

// The surface nearest to x.
DepthSurface nearestSurface(const Vec3& x)
{
  DepthSurface best = DepthSurface::None;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int s = 1; s < DepthSurfaceCount; ++s)
  {
    const double d = distanceToDepthSurface(static_cast<DepthSurface>(s), x);
    if (d < bestDistance)
    {
      bestDistance = d;
      best = static_cast<DepthSurface>(s);
    }
  }
  return best;
}

} // namespace

// The defaults are the documented Kinect-like sensor: f = 320 / tan(29 degrees) = 577.3 px, and
// the depth step at 1 m is 1 / (8 f b) = 2.9 mm.
TEST(DepthCamera, SensorGeometry)
{
  const DepthCameraSpec camera;
  EXPECT_NEAR(camera.focalLength(), 320.0 / std::tan(29.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(camera.focalLength(), 577.3, 0.05);
  EXPECT_NEAR(camera.depthStep(1.0), 0.125 / (camera.focalLength() * 0.075), 1e-15);
  EXPECT_NEAR(camera.depthStep(1.0), 0.00289, 0.00001);
  EXPECT_NEAR(camera.depthStep(2.0), 4.0 * camera.depthStep(1.0), 1e-15);
  // The corner pixels' rays point at +-29 degrees across, through the pixel centres.
  EXPECT_NEAR(camera.pixelRay(0, 0).x(), -319.5 / camera.focalLength(), 1e-15);
  EXPECT_NEAR(camera.pixelRay(479, 639).y(), 239.5 / camera.focalLength(), 1e-15);
  EXPECT_EQ(camera.pixelRay(7, 9).z(), 1.0);
  // Quantized depths are disparities in steps of 1/8 pixel.
  for (double z : { 0.6, 1.0, 1.7, 3.0 })
  {
    const double q = camera.quantizeDepth(z);
    const double disparity = camera.focalLength() * camera.baseline / q;
    EXPECT_NEAR(disparity * 8.0, std::round(disparity * 8.0), 1e-9) << z;
    EXPECT_LE(std::abs(q - z), 0.5 * camera.depthStep(z) * 1.01) << z;
  }
  EXPECT_TRUE(std::isnan(camera.quantizeDepth(0.0)));
  EXPECT_TRUE(std::isnan(camera.quantizeDepth(-1.0)));
}

TEST(DepthCamera, SceneNameAndBadSpecs)
{
  Scene s = Scene::Line;
  ASSERT_TRUE(parseScene("depth-camera", s));
  EXPECT_EQ(s, Scene::DepthCamera);
  EXPECT_STREQ(sceneName(Scene::DepthCamera), "depth-camera");
  EXPECT_EQ(static_cast<int>(Scene::DepthCamera), SceneCount - 1);
  EXPECT_STREQ(depthSurfaceName(DepthSurface::Cylinder), "cylinder");

  CloudSpec spec = cameraSpec(8, 6);
  spec.size = -1.0; // ignored by this scene
  spec.dimension = 2;
  EXPECT_EQ(generateCloud(spec).size(), 48u);
  for (auto spoil : std::vector<void (*)(DepthCameraSpec&)>{ [](DepthCameraSpec& c) { c.width = 0; },
         [](DepthCameraSpec& c) { c.height = -3; }, [](DepthCameraSpec& c) { c.horizontalFov = 180.0; },
         [](DepthCameraSpec& c) { c.depthNoise = std::nan(""); }, [](DepthCameraSpec& c) { c.baseline = 0.0; },
         [](DepthCameraSpec& c) { c.disparityStep = -0.1; }, [](DepthCameraSpec& c) { c.maxRange = 0.0; },
         [](DepthCameraSpec& c) { c.width = c.height = 20000; } })
  {
    CloudSpec bad = cameraSpec(8, 6);
    spoil(bad.camera);
    EXPECT_THROW(generateCloud(bad), std::invalid_argument);
  }
  CloudSpec other;
  other.scene = Scene::Sphere;
  EXPECT_THROW(generateDepthFrame(other), std::invalid_argument);
}

// Truth independent of the ray intersections: on a 160 x 120 image of the same scene, sphere
// tracing with the exact distance functions finds, for every pixel, whether its ray hits the
// scene, at which depth and on which surface, and whether the segment from that point to the
// projector meets the scene first. The frame's NaN pixels are exactly those without a hit or in
// the projector's shadow.
TEST(DepthCamera, NaNPixelsAreNoHitOrProjectorShadow)
{
  const CloudSpec spec = cameraSpec(160, 120);
  const DepthFrame frame = generateDepthFrame(spec);
  const DepthCameraSpec& camera = spec.camera;
  ASSERT_EQ(frame.points.size(), 160u * 120u);
  std::size_t nan = 0, expectedNaN = 0, shadows = 0, mismatches = 0;
  for (std::size_t k = 0; k < frame.points.size(); ++k)
  {
    const DepthPixel& pixel = frame.pixels[k];
    const Vec3 ray = camera.pixelRay(pixel.row, pixel.column);
    const Vec3 u = ray.normalized();
    const double t = sphereTrace(Vec3::Zero(), u, 10.0, 0.0);
    bool expectValid = std::isfinite(t);
    if (expectValid)
    {
      const Vec3 hit = t * u;
      EXPECT_EQ(nearestSurface(hit), pixel.surface) << "pixel " << pixel.row << ", " << pixel.column;
      EXPECT_NEAR(hit.z(), std::sqrt(pixel.sigma / camera.depthNoise), 1e-6);
      const Vec3 toProjector = camera.projector() - hit;
      const double blocked = sphereTrace(hit, toProjector.normalized(), toProjector.norm(), 1e-5);
      if (std::isfinite(blocked))
      {
        expectValid = false;
        ++shadows;
      }
    }
    else
    {
      EXPECT_EQ(pixel.surface, DepthSurface::None);
      EXPECT_EQ(pixel.sigma, 0.0);
    }
    const bool valid = finite(frame.points[k]);
    nan += valid ? 0 : 1;
    expectedNaN += expectValid ? 0 : 1;
    mismatches += valid == expectValid ? 0 : 1;
    EXPECT_EQ(valid, pixel.state == PixelState::Valid);
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(nan, expectedNaN);
  EXPECT_GT(shadows, 100u) << "the projector casts shadows beside every object";
  EXPECT_GT(nan, shadows + 500) << "the rows above the table's far edge see nothing";
}

// Every object is seen by thousands of pixels of the default 640 x 480 frame, and each valid
// point is within its noise and quantization of the surface it came from, on its pixel's ray.
TEST(DepthCamera, PointsLieOnTheirSurfaces)
{
  const CloudSpec spec = cameraSpec();
  const DepthFrame frame = generateDepthFrame(spec);
  const DepthCameraSpec& camera = spec.camera;
  ASSERT_EQ(frame.width, 640);
  ASSERT_EQ(frame.height, 480);
  ASSERT_EQ(frame.points.size(), 640u * 480u);
  EXPECT_EQ(frame.viewpoint, Vec3::Zero());
  std::size_t valid[DepthSurfaceCount] = {};
  double worst = 0.0;
  for (std::size_t k = 0; k < frame.points.size(); ++k)
  {
    const DepthPixel& pixel = frame.pixels[k];
    ASSERT_EQ(static_cast<std::size_t>(pixel.row) * 640u + static_cast<std::size_t>(pixel.column), k);
    const Vec3& p = frame.points[k];
    if (!finite(p))
    {
      continue;
    }
    ++valid[static_cast<int>(pixel.surface)];
    ASSERT_NE(pixel.surface, DepthSurface::None);
    const Vec3 ray = camera.pixelRay(pixel.row, pixel.column);
    EXPECT_LT(p.cross(ray).norm(), 1e-12 * p.norm()) << "the noise moves a point along its ray";
    const double z = std::sqrt(pixel.sigma / camera.depthNoise); // the true depth
    const double bound = ray.norm() * (5.5 * pixel.sigma + camera.depthStep(1.05 * z));
    const double d = distanceToDepthSurface(pixel.surface, p);
    worst = std::max(worst, d / bound);
    EXPECT_LE(d, bound) << depthSurfaceName(pixel.surface) << " pixel " << pixel.row << ", " << pixel.column;
    EXPECT_LE(distanceToShape(spec, p), d);
  }
  for (int s = 1; s < DepthSurfaceCount; ++s)
  {
    EXPECT_GE(valid[s], 2000u) << depthSurfaceName(static_cast<DepthSurface>(s));
  }
  EXPECT_GT(worst, 0.2) << "the noise is there";
}

// A few pixels checked by hand on the full frame: the open table near the sensor is measured,
// a thin band just left of the box (the projector sits right of the camera) is in its shadow.
TEST(DepthCamera, ShadowLeftOfTheBoxAndOpenTable)
{
  const CloudSpec spec = cameraSpec();
  const DepthFrame frame = generateDepthFrame(spec);
  for (int row : { 470, 440, 400 })
  {
    for (int column = 5; column < 640; column += 25)
    {
      const std::size_t k = static_cast<std::size_t>(row) * 640 + static_cast<std::size_t>(column);
      EXPECT_EQ(frame.pixels[k].surface, DepthSurface::Table);
      EXPECT_TRUE(finite(frame.points[k])) << "open table at " << row << ", " << column;
    }
  }
  // Rows through the box: the table pixels touching the box's left silhouette are dark, and so
  // is no table pixel far left of it.
  std::size_t rowsChecked = 0;
  for (int row = 80; row <= 160; row += 10)
  {
    int left = -1;
    for (int column = 0; column < 640 && left < 0; ++column)
    {
      if (frame.pixels[static_cast<std::size_t>(row) * 640 + static_cast<std::size_t>(column)].surface == DepthSurface::Box)
      {
        left = column;
      }
    }
    if (left < 40)
    {
      continue; // the box is not in this row
    }
    ++rowsChecked;
    const DepthPixel& beside = frame.pixels[static_cast<std::size_t>(row) * 640 + static_cast<std::size_t>(left - 1)];
    EXPECT_EQ(beside.surface, DepthSurface::Table) << row;
    EXPECT_EQ(beside.state, PixelState::Shadow) << row;
    EXPECT_FALSE(finite(frame.points[static_cast<std::size_t>(row) * 640 + static_cast<std::size_t>(left - 1)]));
    const std::size_t far = static_cast<std::size_t>(row) * 640 + static_cast<std::size_t>(left - 30);
    if (frame.pixels[far].surface == DepthSurface::Table)
    {
      EXPECT_TRUE(finite(frame.points[far])) << row;
    }
  }
  EXPECT_EQ(rowsChecked, 9u);
}

// Along one image row on the table, the measured depths are a staircase: every depth is a
// disparity that is a whole number of 1/8 pixels, and neighbouring distinct depths differ by
// whole disparity steps, the smallest by about z^2 / (f b) / 8.
TEST(DepthCamera, DepthStepsAlongATableRow)
{
  const CloudSpec spec = cameraSpec();
  const DepthFrame frame = generateDepthFrame(spec);
  const DepthCameraSpec& camera = spec.camera;
  const double fb = camera.focalLength() * camera.baseline;
  for (int row : { 420, 300 })
  {
    std::set<double> depths;
    for (int column = 0; column < 640; ++column)
    {
      const std::size_t k = static_cast<std::size_t>(row) * 640 + static_cast<std::size_t>(column);
      if (frame.pixels[k].surface == DepthSurface::Table && finite(frame.points[k]))
      {
        const double z = frame.points[k].z();
        const double steps = fb / z / camera.disparityStep;
        EXPECT_NEAR(steps, std::round(steps), 1e-6) << "row " << row << " depth " << z;
        depths.insert(z);
      }
    }
    ASSERT_GE(depths.size(), 8u) << "row " << row << ": the rolled table's depth varies along it";
    double smallest = std::numeric_limits<double>::infinity();
    double predicted = 0.0;
    for (auto it = std::next(depths.begin()); it != depths.end(); ++it)
    {
      const double z1 = *std::prev(it), z2 = *it;
      // z2 - z1 = z1 z2 (d1 - d2) / (f b) exactly: a whole number of disparity steps.
      const double steps = (z2 - z1) * fb / (z1 * z2 * camera.disparityStep);
      EXPECT_NEAR(steps, std::round(steps), 1e-6);
      EXPECT_GE(std::round(steps), 1.0);
      if (z2 - z1 < smallest)
      {
        smallest = z2 - z1;
        predicted = camera.depthStep(0.5 * (z1 + z2));
      }
    }
    EXPECT_NEAR(smallest / predicted, 1.0, 0.02) << "row " << row;
  }
}

// Without quantization the depth error, in units of sigma0 z^2, is a standard normal; without
// noise it is the rounding of the disparity alone, at most half a step.
TEST(DepthCamera, NoiseAndQuantizationSeparately)
{
  CloudSpec spec = cameraSpec();
  spec.camera.disparityStep = 0.0;
  const std::vector<DepthPixelTruth> truth = traceDepthImage(spec.camera);
  const DepthFrame noisy = generateDepthFrame(spec);
  double sum = 0.0, sum2 = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < truth.size(); ++k)
  {
    if (finite(noisy.points[k]))
    {
      const double r = (noisy.points[k].z() - truth[k].depth) / noisy.pixels[k].sigma;
      sum += r;
      sum2 += r * r;
      ++n;
    }
  }
  ASSERT_GT(n, 200000u);
  const double mean = sum / static_cast<double>(n);
  EXPECT_NEAR(mean, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / static_cast<double>(n) - mean * mean), 1.0, 0.01);

  spec = cameraSpec();
  spec.camera.depthNoise = 0.0;
  const DepthFrame rounded = generateDepthFrame(spec);
  const double fb = spec.camera.focalLength() * spec.camera.baseline;
  for (std::size_t k = 0; k < truth.size(); ++k)
  {
    if (finite(rounded.points[k]))
    {
      const double z = truth[k].depth, q = rounded.points[k].z();
      ASSERT_LE(std::abs(q - z), 0.5 * spec.camera.disparityStep * z * q / fb * (1.0 + 1e-9));
      EXPECT_EQ(rounded.pixels[k].sigma, 0.0);
    }
  }
}

// Range and shadows as switches: beyond maxRange the hit pixels are NaN and say why; without
// projector shadows only the rays that hit nothing are NaN.
TEST(DepthCamera, RangeAndShadowSwitches)
{
  CloudSpec spec = cameraSpec(160, 120);
  const std::vector<DepthPixelTruth> truth = traceDepthImage(spec.camera);
  spec.camera.maxRange = 1.5;
  const DepthFrame near = generateDepthFrame(spec);
  spec.camera.maxRange = 4.0;
  spec.camera.projectorShadows = false;
  const DepthFrame lit = generateDepthFrame(spec);
  std::size_t beyond = 0;
  for (std::size_t k = 0; k < truth.size(); ++k)
  {
    const bool hit = truth[k].surface != DepthSurface::None;
    if (hit && truth[k].depth > 1.5)
    {
      ++beyond;
      EXPECT_EQ(near.pixels[k].state, PixelState::OutOfRange);
      EXPECT_FALSE(finite(near.points[k]));
    }
    EXPECT_EQ(finite(lit.points[k]), hit);
  }
  EXPECT_GT(beyond, 1000u);
}

TEST(DepthCamera, SameSeedSameBytes)
{
  CloudSpec spec = cameraSpec();
  const std::vector<Vec3> a = generateCloud(spec);
  const std::vector<Vec3> b = generateCloud(spec);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
  spec.seed = 2;
  const std::vector<Vec3> c = generateCloud(spec);
  std::size_t differ = 0, validA = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(finite(a[k]), finite(c[k])) << "which pixels are valid does not depend on the seed";
    if (finite(a[k]))
    {
      ++validA;
      differ += a[k] != c[k] ? 1 : 0;
    }
  }
  // Noise below half a step often rounds to the same disparity; most pixels still differ.
  EXPECT_GT(differ, validA / 4);
}

// The exact distances: zero on every true hit, and the scene's is the smallest surface's.
TEST(DepthCamera, DistancesAreExactOnTheHits)
{
  const DepthCameraSpec camera;
  const CloudSpec spec = cameraSpec();
  const std::vector<DepthPixelTruth> truth = traceDepthImage(camera);
  for (std::size_t k = 0; k < truth.size(); k += 37)
  {
    if (truth[k].surface == DepthSurface::None)
    {
      continue;
    }
    const int row = static_cast<int>(k / 640), column = static_cast<int>(k % 640);
    const Vec3 hit = truth[k].depth * camera.pixelRay(row, column);
    EXPECT_LT(distanceToDepthSurface(truth[k].surface, hit), 1e-12);
    EXPECT_LT(distanceToShape(spec, hit), 1e-12);
    // Back along the ray toward the sensor: at most the distance travelled (1-Lipschitz).
    const Vec3 back = hit * 0.99;
    EXPECT_LE(distanceToShape(spec, back), 0.01 * hit.norm() * (1.0 + 1e-12));
    double smallest = std::numeric_limits<double>::infinity();
    for (int s = 1; s < DepthSurfaceCount; ++s)
    {
      smallest = std::min(smallest, distanceToDepthSurface(static_cast<DepthSurface>(s), back));
    }
    EXPECT_EQ(distanceToShape(spec, back), smallest);
  }
  EXPECT_TRUE(std::isinf(distanceToDepthSurface(DepthSurface::None, Vec3::Zero())));
  // The sensor is 0.52 m above the table's plane, 0.2 m short of its near edge; nothing is nearer.
  EXPECT_NEAR(distanceToDepthSurface(DepthSurface::Table, Vec3::Zero()), std::hypot(0.52, 0.2), 1e-12);
  EXPECT_NEAR(distanceToShape(spec, Vec3::Zero()), std::hypot(0.52, 0.2), 1e-12);
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DepthCamera.h
 * @brief A simulated structured-light depth camera (Kinect v1 class) looking at a table with a
 *        box, a cylinder and a sphere on it: the geometry of the scene (exact ray intersections,
 *        exact distances to each surface) and of the sensor (rays, projector shadows, disparity
 *        quantization). The noisy frame itself is pss::generateDepthFrame (SyntheticClouds.h).
 *
 * Frame: the sensor's optical centre is the origin, x points right in the image, y down, z along
 * the optical axis (the frame of PCL's and OpenNI's organized clouds, viewpoint 0 0 0 1 0 0 0).
 * Lengths are metres. The scene, fixed, is described in a table frame (X across the table, Y away
 * from the sensor, Z up, the table top at Z = 0), the sensor 0.52 m above the table, pitched 30
 * degrees down and rolled 4 degrees about its optical axis:
 * - the table: the rectangle X in [-0.9, 0.9], Y in [0.2, 3.15] (seen from about 0.6 m at the
 *   image's bottom to 3 m; the top rows look past its far edge);
 * - a box 0.32 x 0.24 x 0.30 m centred at X = -0.28, Y = 1.05, turned 30 degrees about Z;
 * - a vertical cylinder of radius 0.08 m and height 0.28 m at X = 0.30, Y = 0.80;
 * - a sphere of radius 0.14 m resting on the table at X = 0.08, Y = 1.45.
 * In a 640 x 480 image each object covers over 10,000 pixels and none hides another; the
 * projector, right of the camera, casts shadows a few pixels wide left of each object.
 */
#pragma once

#include "pss/Types.h"

#include <vector>

namespace pss
{

/// The true surfaces of the depth-camera scene; the values are the `SurfaceId` array's.
enum class DepthSurface : int
{
  None = 0,     ///< the pixel's ray hits nothing
  Table = 1,    ///< the table top
  Box = 2,      ///< the box (its six faces)
  Cylinder = 3, ///< the cylinder (its side and both discs)
  Sphere = 4    ///< the sphere
};

constexpr int DepthSurfaceCount = 5;

/// "none", "table", "box", "cylinder", "sphere".
const char* depthSurfaceName(DepthSurface s);

/// Why a pixel has a point or not.
enum class PixelState : int
{
  Valid = 0,      ///< measured: the point is finite
  NoHit = 1,      ///< the ray hits nothing (NaN)
  OutOfRange = 2, ///< the hit is deeper than maxRange, or its noisy depth is not positive (NaN)
  Shadow = 3      ///< the projector cannot see the hit point, so no pattern is there to match (NaN)
};

/**
 * The sensor. Defaults: a Kinect v1-like camera, 640 x 480 pixels, 58 degrees across, projector
 * 7.5 cm to the right of the camera, disparity measured in steps of 1/8 pixel, depth noise
 * sigma(z) = depthNoise z^2 with depthNoise = 0.0012 / m (1.2 mm at 1 m, 11 mm at 3 m; about a
 * twentieth of a pixel of disparity, the order of the random error Kinect v1 studies report).
 */
struct DepthCameraSpec
{
  int width = 640;              ///< pixels per row
  int height = 480;             ///< rows
  double horizontalFov = 58.0;  ///< degrees across the image (square pixels)
  double depthNoise = 0.0012;   ///< sigma0 in 1/m: depth noise sigma(z) = sigma0 z^2 (0: none)
  double baseline = 0.075;      ///< metres from the camera to the projector, along +x
  double disparityStep = 0.125; ///< pixels: disparity is rounded to multiples of it (0: no rounding)
  double maxRange = 4.0;        ///< metres of depth z beyond which nothing is measured
  bool projectorShadows = true; ///< pixels the projector cannot see are NaN

  void validate() const; ///< throws std::invalid_argument

  /// Focal length in pixels: (width / 2) / tan(horizontalFov / 2); 577.3 for the defaults.
  double focalLength() const;

  /// The ray through the centre of pixel (@p row, @p column), scaled to z = 1: a point of depth z
  /// on it is z times this vector.
  Vec3 pixelRay(int row, int column) const;

  /// The projector's position, (baseline, 0, 0).
  Vec3 projector() const { return Vec3(baseline, 0.0, 0.0); }

  /// Depth between neighbouring disparity steps at depth @p z: z^2 disparityStep / (f b).
  double depthStep(double z) const;

  /// The depth the sensor reports for depth @p z: disparity f b / z rounded to a multiple of
  /// disparityStep, turned back into depth (NaN when it rounds to 0 or @p z is not positive).
  double quantizeDepth(double z) const;
};

/// The nearest intersection of a ray with the scene.
struct DepthHit
{
  DepthSurface surface = DepthSurface::None;
  double t = 0.0;         ///< ray parameter of the hit (in units of the direction's length)
  Vec3 point = Vec3::Zero();
};

/// Nearest exact intersection of origin + t direction, 0 < t < @p tMax, with the scene's surfaces.
DepthHit castDepthSceneRay(const Vec3& origin, const Vec3& direction, double tMax);

/// Exact distance from @p x (sensor frame) to the surface @p s (None: +infinity).
double distanceToDepthSurface(DepthSurface s, const Vec3& x);

/// Exact distance from @p x to the union of the scene's surfaces.
double distanceToDepthScene(const Vec3& x);

/// What the ray of one pixel hits, before any noise.
struct DepthPixelTruth
{
  DepthSurface surface = DepthSurface::None; ///< what the ray hits (also in shadow or out of range)
  PixelState state = PixelState::NoHit;      ///< before noise: Valid, NoHit, OutOfRange or Shadow
  double depth = 0.0;                        ///< true depth z of the hit (0 when nothing is hit)
};

/// Every pixel of @p camera's image in row-major order (row 0 at the top): the exact nearest hit,
/// its depth, and whether the sensor can measure it (range, projector shadow).
std::vector<DepthPixelTruth> traceDepthImage(const DepthCameraSpec& camera);

} // namespace pss

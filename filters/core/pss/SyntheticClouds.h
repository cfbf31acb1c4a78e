// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SyntheticClouds.h
 * @brief Test clouds with a known true shape: what the examples, the VTK source filter, the CLI
 *        and the benchmarks generate, and the exact distance to the shape they were drawn from.
 */
#pragma once

#include "pss/DepthCamera.h"
#include "pss/Types.h"

#include <string>
#include <vector>

namespace pss
{

enum class Scene : int
{
  Line = 0,       ///< segment of length size along x, centred at the origin
  Circle = 1,     ///< circle of radius size/2 in the xy-plane
  Corner = 2,     ///< two segments of length size/2 meeting at the origin at cornerAngle
  NoisyCurve = 3, ///< open sine arc over x in [0, size]; noise and spacing grow along it (Fig. 1)
  Plane = 4,      ///< square of side size in z = 0 (2D: its cross-section, a Line)
  Sphere = 5,     ///< sphere of radius size/2 (2D: the equator, a Circle)
  TwoSheets = 6,  ///< two squares of side size at z = +-gap/2 (2D: two parallel segments)
  DepthCamera = 7 ///< an organized depth frame of a table scene (3D only; DepthCamera.h)
};

constexpr int SceneCount = 8;

/// "line", "circle", "corner", "noisy-curve", "plane", "sphere", "two-sheets", "depth-camera".
const char* sceneName(Scene s);
bool parseScene(const std::string& text, Scene& out);

/**
 * What to generate. The DepthCamera scene reads only scene, seed and camera: its size is fixed
 * (metres, DepthCamera.h), its point count is camera.width x camera.height (one point per pixel,
 * NaN where the sensor measures nothing), its noise is camera.depthNoise (a different quantity:
 * sigma0 in 1/m, not a length), and it is always 3D; count, size, noise and dimension are ignored.
 */
struct CloudSpec
{
  Scene scene = Scene::NoisyCurve;
  std::size_t count = 1000; ///< number of points
  double size = 100.0;      ///< characteristic length (see Scene)
  double noise = 0.0;       ///< standard deviation of the Gaussian offset (NoisyCurve: at its noisy end)
  unsigned seed = 1;        ///< same seed, same cloud, on every platform
  int dimension = 2;        ///< 2 (points in the xy-plane) or 3
  double cornerAngle = 60.0; ///< degrees between the two Corner segments
  double gap = 10.0;        ///< distance between the TwoSheets sheets
  DepthCameraSpec camera;   ///< the DepthCamera scene's sensor

  void validate() const; ///< throws std::invalid_argument
};

/// The noise-free shape's points are drawn uniformly (NoisyCurve: with density falling along it),
/// then offset by isotropic Gaussian noise in the cloud's dimension. DepthCamera: the points of
/// generateDepthFrame, NaN included.
std::vector<Vec3> generateCloud(const CloudSpec& spec);

/// Distance from @p x to the noise-free shape of @p spec (in 2D, to its xy cross-section;
/// DepthCamera: to the union of the scene's surfaces, distanceToDepthScene).
double distanceToShape(const CloudSpec& spec, const Vec3& x);

/// What the sensor knows about one pixel of a depth frame.
struct DepthPixel
{
  int row = 0;    ///< 0 at the top
  int column = 0; ///< 0 at the left
  DepthSurface surface = DepthSurface::None; ///< the true surface the pixel's ray hits (None: nothing)
  PixelState state = PixelState::NoHit;      ///< Valid, or why the point is NaN
  double sigma = 0.0; ///< standard deviation of the depth noise at the true depth (0: no hit)
};

/// An organized depth frame: width x height points in row-major pixel order.
struct DepthFrame
{
  int width = 0;
  int height = 0;
  double focalLength = 0.0;       ///< pixels
  Vec3 viewpoint = Vec3::Zero();  ///< the sensor's position (it looks along +z, y down)
  std::vector<Vec3> points;       ///< NaN for every pixel whose state is not Valid
  std::vector<DepthPixel> pixels; ///< one per point
};

/**
 * The DepthCamera scene as the sensor sees it. For each pixel (row-major) the exact nearest hit
 * of its ray (traceDepthImage) at true depth z, then a structured-light measurement: the depth
 * plus Gaussian noise of sigma = camera.depthNoise z^2, whose disparity f b / z is rounded to a
 * multiple of camera.disparityStep and turned back into depth z'; the point is z' times the
 * pixel's ray (it moves along the ray). NaN where the ray hits nothing, beyond camera.maxRange,
 * where the noisy depth is not positive, or in the projector's shadow. One normal draw of the
 * portable generator per pixel, in pixel order, whatever the pixel's state: same seed, same frame.
 * Throws std::invalid_argument when @p spec is not the DepthCamera scene or its camera is invalid.
 */
DepthFrame generateDepthFrame(const CloudSpec& spec);

/// A point of the NoisyCurve's noise-free centre line, its unit normal (in the xy-plane, the
/// side of +y where the curve is horizontal) and the noise sigma of the points drawn there.
struct CurveFrame
{
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double sigma = 0.0;
};

/// The NoisyCurve at parameter @p u in [0, 1] (x = size u): what generateCloud draws around.
/// Throws std::invalid_argument for another scene or a u outside [0, 1].
CurveFrame noisyCurveFrame(const CloudSpec& spec, double u);

} // namespace pss

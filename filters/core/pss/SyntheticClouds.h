// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SyntheticClouds.h
 * @brief Test clouds with a known true shape: what the examples, the VTK source filter, the CLI
 *        and the benchmarks generate, and the exact distance to the shape they were drawn from.
 */
#pragma once

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
  TwoSheets = 6   ///< two squares of side size at z = +-gap/2 (2D: two parallel segments)
};

constexpr int SceneCount = 7;

/// "line", "circle", "corner", "noisy-curve", "plane", "sphere", "two-sheets".
const char* sceneName(Scene s);
bool parseScene(const std::string& text, Scene& out);

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

  void validate() const; ///< throws std::invalid_argument
};

/// The noise-free shape's points are drawn uniformly (NoisyCurve: with density falling along it),
/// then offset by isotropic Gaussian noise in the cloud's dimension.
std::vector<Vec3> generateCloud(const CloudSpec& spec);

/// Distance from @p x to the noise-free shape of @p spec (in 2D, to its xy cross-section).
double distanceToShape(const CloudSpec& spec, const Vec3& x);

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

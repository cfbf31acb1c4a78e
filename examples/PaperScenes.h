// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PaperScenes.h
 * @brief The scenes of Amenta & Kil, "The Domain of a Point Set Surface", and the numbers the
 *        paper claims about them, measured through the PointSetSurfaces VTK filters.
 *
 * Shared by the main demo (pss-paper-figures, which also writes the figures' data) and by the
 * acceptance tests (tests/paper), so both measure exactly the same thing. Nothing here computes
 * n, e, g or a projection: every such number comes from vtkPointSetSurfaceFieldSampler or
 * vtkPointSetSurfaceDomainClassifier; this file only builds scenes, start points and counts.
 *
 * Scenes (all 2D, deterministic):
 * - line: 401 evenly spaced points on a segment of length 40 h (h = 5), the input of Figure 5;
 * - noisy-curve: the core's noisy sine arc (600 points, density falling along it, noise sigma
 *   growing from 0.6 to 3, so the +-sigma band grows from 1.2 to 6, slightly wider than h = 5
 *   at the noisy end), the input of Figures 1, 2 and 7 with h = 5 and of Figures 9, 10 with h = 10;
 * - corner: the core's corner, two open arms of length 10 h meeting at 45 degrees, 200 points
 *   perturbed by 0.01 h (general position), the input of Figure 6.
 */
#ifndef PaperScenes_h
#define PaperScenes_h

#include "vtkPointSetSurface.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "pss/SyntheticClouds.h"

#include <limits>
#include <string>
#include <vector>

namespace pss_paper
{

/// @name Acceptance bounds (issue "Reproduce the paper"), in units of h where lengths.
///@{
constexpr double kFlipHeightLow = 0.68;       ///< n_MLS flip height above a line, lower bound
constexpr double kFlipHeightHigh = 0.74;      ///< ... upper bound (analytic: 1 / sqrt 2 = 0.7071)
constexpr double kNoFlipHeight = 5.0;         ///< COM and integral keep the normal up to here
constexpr double kOnCurveDistance = 0.5;      ///< "lands on the true curve": within 0.5 h of it
constexpr double kSpuriousDistance = 2.0;     ///< "spurious": converged, farther than 2 h from every point
constexpr double kNoisyCurveMinFraction = 0.97; ///< integral variant, Figure 2
constexpr double kCornerMaxSpuriousFraction = 0.01; ///< integral variant, Figure 6
constexpr int kCornerMinStarts = 2000;        ///< uniform random starts in the corner's box
constexpr double kStartMargin = 3.0;          ///< the start box is the cloud's box grown by 3 h
constexpr unsigned kCornerStartSeed = 7;      ///< seed of the corner's random starts
constexpr int kWideStarts = 2000;             ///< random starts of Figures 9 and 10
constexpr unsigned kWideStartSeed = 11;       ///< their seed
///@}

/// A point cloud with its true (noise-free) shape and the Gaussian scale h it is studied at.
struct Scene
{
  std::string name;                   ///< "line", "noisy-curve", "corner"
  pss::CloudSpec shape;               ///< the true shape, for pss::distanceToShape
  double h = 5.0;
  vtkSmartPointer<vtkPolyData> cloud; ///< one vertex per point, z = 0
};

Scene MakeLineScene();
/// The noisy curve studied at scale @p h (5 for Figures 1, 2 and 7, 10 for Figures 9 and 10).
Scene MakeNoisyCurveScene(double h = 5.0);
Scene MakeCornerScene();

/// vtkPointSetSurface::VariantType values of the four definitions of Figure 6 and the delta one.
const std::vector<int>& AllVariants();
/// "levin", "normalized", "com", "integral", "delta", "apss", "rimls".
std::string VariantName(int variant);
/// "Levin's MLS", "normalized MLS", "center of mass", "integral (e_I)", "delta", "APSS", "RIMLS".
std::string VariantTitle(int variant);

/// One vertex per point (double coordinates): sample or start points for the filters.
vtkSmartPointer<vtkPolyData> MakePointCloud(const std::vector<pss::Vec3>& points);

/// A surface description for @p scene: the given variant, h fixed to scene.h, 2D.
vtkSmartPointer<vtkPointSetSurface> MakeSurface(const Scene& scene, int variant);
/// The DeltaLatticeSpacing of every surface MakeSurface makes from now on (the program's
/// --delta-lattice; without a call, vtkPointSetSurface's default).
void SetDeltaLatticeSpacing(double spacing);

/// Axis-aligned bounds of the cloud grown by @p marginInH * h: {xmin, xmax, ymin, ymax}.
std::vector<double> GrownBounds(const Scene& scene, double marginInH);

/// @p count points uniformly distributed in GrownBounds(scene, marginInH) (portable generator).
vtkSmartPointer<vtkPolyData> UniformStarts(const Scene& scene, int count, double marginInH, unsigned seed);

/// What became of a set of projections (see Measure).
struct ProjectionStats
{
  std::string scene;
  int variant = 0;
  vtkIdType starts = 0;
  vtkIdType converged = 0;
  vtkIdType onCurve = 0;  ///< converged within kOnCurveDistance * h of the true shape
  vtkIdType spurious = 0; ///< converged farther than kSpuriousDistance * h from every cloud point
  double seconds = 0.0;   ///< wall time of the projection

  double OnCurveFraction() const { return starts ? double(onCurve) / double(starts) : 0.0; }
  double SpuriousFraction() const { return starts ? double(spurious) / double(starts) : 0.0; }
};

/// Category of a projected point (array `Outcome` added by Project).
enum Outcome
{
  ON_CURVE = 0,      ///< converged within 0.5 h of the true shape
  OFF_CURVE = 1,     ///< converged, farther than 0.5 h from the shape but within 2 h of the cloud
  SPURIOUS = 2,      ///< converged, farther than 2 h from every cloud point
  NOT_CONVERGED = 3  ///< iteration limit, no extremum along n, or n undefined
};

/// Output of Project: the classifier's end points (with `Outcome`) and, optionally, the lines.
struct Projection
{
  vtkSmartPointer<vtkPolyData> points; ///< vtkPointSetSurfaceDomainClassifier output 0 + `Outcome`
  vtkSmartPointer<vtkPolyData> lines;  ///< output 1 (start to end segments), + `Outcome` cell data
  ProjectionStats stats;
};

/**
 * Projects @p starts (the cloud itself when null) onto the surface of @p variant with
 * vtkPointSetSurfaceDomainClassifier (Definition 1: nearest minimum of e along n, repeated; with
 * @p seekMaxima the maxima of Figures 9 and 10), with the filter's default settings, and counts
 * the outcomes.
 */
Projection Project(const Scene& scene, int variant, vtkPolyData* starts, bool seekMaxima = false,
  bool projectionLines = false);

/// @name The line scene (Figure 5)
///@{
/// Columns x at which the line scene is probed: -10 h, -5 h, 0, 5 h, 10 h (the ends are 20 h away).
std::vector<double> LineColumns(const Scene& line);

/**
 * Height above the line (in units of h) at which n, sampled by vtkPointSetSurfaceFieldSampler up
 * the column x = @p x, first stops being closer to the normal (y) than to the tangent (x), or is
 * undefined: the flip of n_MLS from normal to tangent (analytically h / sqrt 2). Scanned in steps
 * of 0.01 h up to @p maxHeight h, then refined to 1e-4 h. Infinity when n never flips.
 */
double FlipHeight(const Scene& line, int variant, double x, double maxHeight);

/// Result of the domain scan on the line scene.
struct DomainScan
{
  double halfWidth = 0.0;  ///< in h: smallest, over the columns, height below which every start lands
  bool bounded = false;    ///< false when every start up to the top of the scan landed
  ProjectionStats stats;   ///< all the column starts together
};

/**
 * Domain half-width of @p variant on the line scene: starts every 0.05 h from 0.05 h to
 * @p maxHeight h on every column of LineColumns, projected with vtkPointSetSurfaceDomainClassifier;
 * per column the height of the last start below the first one that does not land on the line.
 */
DomainScan LineDomainHalfWidth(const Scene& line, int variant, double maxHeight = 10.0);
///@}

} // namespace pss_paper

#endif

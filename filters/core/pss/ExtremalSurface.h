// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ExtremalSurface.h
 * @brief What any SurfaceDefinition gives: the implicit function g of Eq. 2, the nearest
 *        extremum along a line, projection onto the extremal surface (Definition 1) or onto the
 *        maxima of Figures 9 and 10, and the centre-of-mass "plane" procedure.
 */
#pragma once

#include "pss/Parallel.h"
#include "pss/SurfaceDefinition.h"
#include "pss/Types.h"
#include "pss/Workspace.h"

#include <functional>
#include <vector>

namespace pss
{

/**
 * @brief How an unoriented n is turned into a vector (for g's sign and for stream tracers).
 *
 * AwayFromPoint: n . (x - reference) >= 0, i.e. n points away from a reference point (by default
 * the cloud's centroid). TowardPoint: n . (reference - x) >= 0, toward a sensor's viewpoint (every
 * surface one view sees faces it). AlongDirection: n . reference >= 0. Each is continuous wherever
 * n is, except on the set where n is orthogonal to (x - reference), respectively to reference.
 */
struct Orientation
{
  enum class Rule
  {
    AwayFromPoint,
    TowardPoint,
    AlongDirection
  };
  Rule rule = Rule::AwayFromPoint;
  Vec3 reference = Vec3::Zero();

  /// The rule used when nothing is said: away from the centroid of @p index.
  static Orientation awayFromCentroid(const PointIndex& index);
  /// Away from @p point (awayFromCentroid with a centroid known otherwise, e.g. reduced over MPI ranks).
  static Orientation awayFrom(const Vec3& point);
  /// Toward @p viewpoint (the sensor of a single view).
  static Orientation toward(const Vec3& viewpoint);
  /// n or -n, following the rule at x (n itself when the rule is undecided, i.e. exactly zero).
  Vec3 apply(const Vec3& n, const Vec3& x) const;
};

/// Everything the field-sampling and classification code wants to know at one point x.
struct ImplicitSample
{
  Direction direction;                 ///< n(x), oriented by the Orientation given
  double energy = 0.0;                 ///< e(x, n(x)) at true scale
  double g = 0.0;                      ///< Eq. 2: n(x) . grad_y e(y, n(x)) at y = x (true scale)
  double curvature = 0.0;              ///< d2/dt2 e(x + t n, n) at t = 0, same scale as energy
  ExtremumType type = ExtremumType::None; ///< Minimum if curvature > 0, Maximum if < 0
};

/**
 * g(x) and the sign of the second derivative along n(x). The second derivative is a central
 * difference (step 1e-4 h) of the analytic slope. When n(x) is undefined, g and curvature are 0
 * and type is None (the flag is direction.defined).
 */
ImplicitSample evaluateImplicit(const SurfaceDefinition& s, const Vec3& x, const Orientation& o, Workspace& ws);

/// Result of searching along a line for the nearest local extremum of e.
struct LineExtremum
{
  bool found = false;
  double t = 0.0;                        ///< signed offset along the line direction
  ExtremumType type = ExtremumType::None;
};

/**
 * Nearest local minimum (or maximum, with @p seekMaximum) of t -> e(x + t a, a) to t = 0.
 * Walks downhill (uphill for maxima) from t = 0 with growing steps, never longer than half the
 * distance to the cloud (the energy varies on that scale), until the slope changes sign, then
 * refines the root of the slope by bracketed secant/bisection to 1e-12 h. Gives up beyond
 * @p maxTravel (absolute distance).
 */
LineExtremum nearestExtremumOnLine(
  const SurfaceDefinition& s, const Vec3& x, const Vec3& a, bool seekMaximum, double maxTravel, Workspace& ws);

enum class Procedure : int
{
  Extremal = 0, ///< move to the nearest extremum of e along n(x), repeat (Definition 1)
  Plane = 1     ///< x <- x - <n(x), x - c(x)> n(x), repeat (the centre-of-mass fast path)
};

struct ProjectionOptions
{
  Procedure procedure = Procedure::Extremal;
  bool seekMaxima = false;   ///< converge to maxima of e along n (green curves, Figs. 9, 10)
  int maxIterations = 100;   ///< >= 1
  double tolerance = 1e-6;   ///< convergence when a step is below tolerance * h
  double maxTravel = 1000.0; ///< longest line search, in units of h

  void validate() const; ///< throws std::invalid_argument
};

/// What became of one start point (the start itself is the caller's: it is not repeated here).
struct ProjectionResult
{
  Vec3 point = Vec3::Zero();          ///< where the projection stopped (== start on InvalidInput)
  /// n at the final point. The plane procedure's converged result is the exception: its last
  /// step (below tolerance * h) lands on the plane last fitted without another fit, and n,
  /// energy and type are those of that fit.
  Direction direction;
  Direction startDirection;           ///< n at the start point
  double energy = 0.0;                ///< e(point, n(point)) at true scale
  int iterations = 0;
  bool converged = false;
  double lastStep = 0.0;              ///< length of the last step taken
  StopReason reason = StopReason::MaxIterations;
  ExtremumType type = ExtremumType::None; ///< kind of extremum at the final point
};

/// Projects one start point. Never throws for bad points: reports them in the result.
ProjectionResult project(const SurfaceDefinition& s, const Vec3& start, const ProjectionOptions& opt, Workspace& ws);

/**
 * Projects many start points on @p threads threads (0 = all cores), handing each result to
 * @p sink(i, result) from the worker that computed it (each i exactly once, in no particular
 * order), so callers keep only what they need. Each worker has its own Workspace, and the points
 * are visited in spatialOrder(), so consecutive projections share cached neighbours; results do
 * not depend on the order or the thread count: every point is computed independently and in the
 * same way.
 */
void projectEach(const SurfaceDefinition& s, const std::vector<Vec3>& starts, const ProjectionOptions& opt,
  int threads, const std::function<void(std::size_t, const ProjectionResult&)>& sink);

/**
 * What projectEach runs on: calls @p work(i, workspace) once for every start i through @p loop,
 * visiting the starts in spatialOrder() so that consecutive ones share cached neighbours. For
 * per-start work beyond a projection (domain classification) and for loops of the caller's own
 * (the VTK filters'). Returns false when the loop stopped early (then some i were not visited).
 */
bool forEachStart(const std::vector<Vec3>& starts, const ParallelLoop& loop,
  const std::function<void(std::size_t, Workspace&)>& work);

/**
 * forEachStart with the visiting order given: @p order holds every start index once (e.g.
 * spatialOrder(starts), or PointIndex::visitingOrder()'s ids when the starts are the indexed
 * cloud, which needs no copy of the points).
 */
bool forEachInOrder(const std::vector<std::uint32_t>& order, const ParallelLoop& loop,
  const std::function<void(std::size_t, Workspace&)>& work);

/// forEachInOrder by position: work(k, ws) for every k in [0, count), so that the caller can read
/// what it keeps in visiting order (forEachInOrder calls work(order[k], ws)).
bool forEachPosition(std::size_t count, const ParallelLoop& loop, const std::function<void(std::size_t, Workspace&)>& work);

/// projectEach, keeping every result (result i for start i).
std::vector<ProjectionResult> projectAll(const SurfaceDefinition& s, const std::vector<Vec3>& starts,
  const ProjectionOptions& opt, int threads = 0);

} // namespace pss

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesFieldEvaluation.h
 * @brief Private helper of the VTK module: the orientation rules for the unoriented direction n
 *        and the evaluation of every field quantity at one point. The single place where
 *        vtkPointSetSurfaceFieldSampler and vtkPointSetSurfaceImplicitFunction meet the core, so
 *        the two always agree to the last bit.
 *
 * The mathematics is the core's (pss::evaluateImplicit, pss::DistanceField, pss::Orientation);
 * this file only chooses the orientation, sanitises non-finite values and, for the sampler,
 * propagates a consistent orientation over a mesh.
 */
#ifndef PointSetSurfacesFieldEvaluation_h
#define PointSetSurfacesFieldEvaluation_h

#include "vtkType.h"

#include "pss/ExtremalSurface.h"
#include "pss/Kernel.h"
#include "pss/Types.h"

#include <string>

class vtkDataSet;

namespace pss
{
class PointIndex;
class SurfaceDefinition;
}

namespace pss_vtk
{

/// Point-wise orientation rules (the values of the OrientationMode enums of both classes).
enum OrientationRule : int
{
  ORIENT_AWAY_FROM_CENTROID = 0, ///< n . (x - centroid of the cloud) >= 0
  ORIENT_AWAY_FROM_POINT = 1,    ///< n . (x - reference point) >= 0
  ORIENT_ALONG_DIRECTION = 2     ///< n . reference direction >= 0
};

/**
 * The pss::Orientation meant by @p rule for a cloud whose finite points have the centroid
 * @p centroid (pss::PointIndex::centroid; in a run with ghost points, the one reduced over the
 * ranks). Returns false with a
 * message in @p error for an unknown rule, a non-finite reference point or a zero/non-finite
 * reference direction (which is normalised otherwise).
 */
bool MakeOrientation(int rule, const double referencePoint[3], const double referenceDirection[3],
  const pss::Vec3& centroid, pss::Orientation& out, std::string& error);

/// Everything sampled at one point. Never NaN or infinite: invalid values are written as 0.
struct FieldValues
{
  pss::Vec3 normal = pss::Vec3::Zero(); ///< oriented n(x); zero when n is undefined or x invalid
  double energy = 0.0;                  ///< e(x, n(x)) at true scale
  double delta = 0.0;                   ///< the approximate squared distance delta(x)
  double g = 0.0;                       ///< Eq. 2 with the same orientation as normal
  double stability = 0.0;               ///< stability of n(x), in [0, 1]
  int extremumType = 0;                 ///< pss::ExtremumType: 0 none, 1 minimum, 2 maximum
  bool valid = false;                   ///< x finite and every quantity finite
};

/// What EvaluateField computes (a point-wise evaluation may skip the expensive parts).
enum FieldParts : unsigned
{
  FIELD_DIRECTIONAL = 1u, ///< n, e, g, stability, extremum type (pss::evaluateImplicit)
  FIELD_DELTA = 2u,       ///< delta (pss::DistanceField)
  FIELD_ALL = 3u
};

/**
 * Evaluates the fields of one prepared definition at arbitrary points. Construct it after the
 * definition is prepared; it holds references to @p surface and its index, so it must not outlive
 * them. Evaluate() is const and thread-safe given a workspace per thread.
 */
class FieldEvaluator
{
public:
  FieldEvaluator(const pss::SurfaceDefinition& surface, const pss::Orientation& orientation);

  FieldValues Evaluate(const double x[3], pss::Workspace& ws, unsigned parts = FIELD_ALL) const;

  const pss::SurfaceDefinition& Surface() const { return this->Definition; }
  const pss::Orientation& Orientation() const { return this->Orient; }

private:
  const pss::SurfaceDefinition& Definition;
  pss::Orientation Orient;
  pss::DistanceField Distance;
};

/**
 * Makes the orientation of the field sampled at the points of @p mesh consistent between
 * neighbouring points: @p normals (3 per point), @p g (1 per point) and @p stability (1 per
 * point) are the sampled n, g and stability. A maximum spanning tree over the point graph of
 * @p mesh (two points are neighbours when they are adjacent along an axis of an image,
 * rectilinear or structured grid, or else consecutive in some cell) with weight |n_i . n_j|,
 * grown from the most stable point of each connected component, which keeps its point-wise
 * orientation; every other point takes the sign that agrees with its parent in the tree (Hoppe
 * et al. 1992). Flipping a point negates n and g together: e(y, -a) = e(y, a) for every
 * definition, so g(-n) = -g(n), while e, delta, the stability and the extremum type (the sign of
 * the second derivative along n) are even in n. Points without a direction (zero normal) are
 * left out and do not connect. Returns the number of points flipped.
 */
vtkIdType PropagateOrientation(vtkDataSet* mesh, double* normals, double* g, const double* stability);

}

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PaperFields.h
 * @brief The main demo's fields on grids: streamlines, iso-contours, near-singular points and
 *        extrema over the field sampler's and the projection's outputs (stock VTK filters), and
 *        Figure 7's measurements of delta.
 */
#ifndef PaperFields_h
#define PaperFields_h

#include "PaperOutput.h"
#include "PaperScenes.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <limits>
#include <vector>

class vtkImageData;
class vtkPolyData;

namespace pss_paper
{

/// Streamlines of the sampled n, seeded on a lattice of spacing @p seedSpacingInH, both ways.
vtkSmartPointer<vtkPolyData> Streamlines(vtkImageData* field, const Scene& scene, double seedSpacingInH,
  double lengthInH);

/// Iso-contours of @p array at @p values (vtkContourFilter; the contour value is kept as scalars).
vtkSmartPointer<vtkPolyData> Contours(vtkImageData* field, const char* array, const std::vector<double>& values);

/// @p count iso-values of `LogEnergy` evenly spaced between its 2nd and 98th percentiles.
vtkSmartPointer<vtkPolyData> EnergyContours(vtkImageData* field, int count);

/**
 * Near-singular points of n: grid samples whose `Stability` is a strict minimum of its 3 x 3
 * neighbourhood and below @p threshold (n is undefined where the stability is 0).
 */
vtkSmartPointer<vtkPolyData> NearSingularPoints(vtkImageData* field, double threshold);

/// Figure 7's claims about delta, checked on the sampled grid (distances by vtkStaticPointLocator).
struct DeltaStats
{
  vtkIdType samples = 0;
  vtkIdType aboveSquaredDistance = 0; ///< samples with delta >= d^2 (d: distance to the nearest point)
  double farRatioMin = std::numeric_limits<double>::infinity();  ///< delta / d^2 where d >= 2.5 h
  double farRatioMax = 0.0;
  vtkIdType minima = 0;              ///< strict local minima of delta over the 3 x 3 neighbours
  double minimaMaxDistance = 0.0;    ///< the largest d of those minima, in h
};

/// DeltaStats of the `Delta` array of @p field against the cloud of @p scene.
DeltaStats MeasureDelta(vtkImageData* field, const Scene& scene);

/// The converged end points of @p projection whose `ExtremumType` is @p type (1 min, 2 max).
vtkSmartPointer<vtkPolyData> Extrema(vtkPolyData* projection, int type);

/// The start points @p starts with the `DomainLabel` of their projections in @p projection (the
/// classifier's output 0, one point per start): the domain drawn where it is, at the starts.
vtkSmartPointer<vtkPolyData> DomainAtStarts(vtkPolyData* starts, vtkPolyData* projection);

} // namespace pss_paper

#endif

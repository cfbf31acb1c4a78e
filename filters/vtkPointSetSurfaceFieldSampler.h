// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceFieldSampler
 * @brief   sample the direction field n, the energy e, delta and the implicit function g of a
 *          point-set surface at the points of a dataset or on a regular grid (Figures 5-10)
 *
 * A probe-style filter in the manner of vtkPointInterpolator. Input 0 is any vtkDataSet whose
 * points are sampled (an image slice or volume, a plane, a line, a polydata); the source (input 1,
 * SetSourceConnection() / SetSourceData()) is the point cloud that defines the surface. Which
 * surface, at which scale, is GetSurface()'s business (a vtkPointSetSurface shared with the other
 * PointSetSurfaces filters). The output is a shallow copy of input 0 with these point arrays:
 * - `Normal` (3 doubles): n(x), oriented by OrientationMode (below); zero where n is undefined
 *   (no unique smallest eigenvalue) or x is invalid. Also the active vectors, so vtkStreamTracer
 *   and vtkGlyph3D use it without further settings.
 * - `Energy`: e(x, n(x)) at its true scale (LevinMLS underflows to 0 far away, never to NaN).
 * - `Delta`: the approximate squared distance delta(x) of Sec. 5 (pss::DistanceField).
 * - `ImplicitG`: g(x) = n(x) . grad_y e(y, n(x)) at y = x (Eq. 2), computed with the same
 *   oriented n as `Normal`. Its zero set holds the minima (the extremal surface) and the maxima
 *   of Figures 9 and 10. Also the active scalars, for vtkContourFilter at value 0.
 * - `Stability`: (lambda_1 - lambda_0) / (lambda_1 + lambda_0) of n(x) (or its e_I analogue).
 * - `ExtremumType`: 0 not an extremum / undetermined, 1 minimum, 2 maximum: the sign of the
 *   second derivative of e along n(x), i.e. on which side of g = 0 a sample is blue or green.
 * - `Valid` (0/1): 0 where the sample point has a NaN or infinite coordinate (or, never seen in
 *   practice, a quantity came out non-finite). Every other array is 0 there, never NaN.
 * - `DomainLabel` (ComputeDomainLabels on): pss::classifyStart of every sample, 0 in domain,
 *   1 spurious, 2 undefined, 3 not converged (see vtkPointSetSurfaceDomainClassifier). This
 *   projects every sample onto the surface (MaxIterations, Tolerance, MaxDistance,
 *   MaxNormalAngle, named and bounded as vtkPointSetSurfaceDomainClassifier's) and is
 *   expensive: on an 81 x 81 grid around a circle it multiplied the time by 3 (Delta), 6
 *   (CenterOfMass) and 45 (LevinMLS, whose far samples iterate long).
 *   Off by default.
 *
 * @par Orientation of n.
 * n is an unoriented direction (n and -n are the same), but a stream tracer integrates vectors
 * and the sign of g depends on the sign of n (g(-n) = -g(n), since e(y, -a) = e(y, a)). A line
 * field cannot in general be oriented continuously (its singularities, the end points and
 * junctions of Figures 9 and 10, have half-integer index), so every rule has seams where the
 * vector flips. Across a seam the interpolated velocity is small or reversed, so a streamline
 * that meets one stops (STAGNATION) or is turned away from n; and g changes sign there, which
 * vtkContourFilter reports as a spurious zero contour. The rules differ in where their seams lie:
 * - AWAY_FROM_CENTROID (default): n . (x - c) >= 0, c the centroid of the finite cloud points,
 *   i.e. pss::Orientation::awayFromCentroid, the orientation of vtkPointSetSurfaceProjection's
 *   `Normal` too. The seam is where n is orthogonal to x - c. Near a closed curve or surface
 *   around c, n normal to the cloud points outwards on both sides of it, so g changes sign
 *   through the surface (negative inside, positive outside): its zero contour is the surface.
 *   Where n is parallel to the cloud (LevinMLS beyond about h / sqrt(2), Fig. 5) n points away
 *   from the plane through c normal to n, so streamlines run away from c along the cloud instead
 *   of stopping. For a straight line through c the seams are the perpendicular through c (in
 *   Levin's tangent region) and the line itself (in the normal region), and streamlines run away
 *   from both. Not suitable for the sign of g when the cloud is an open sheet through c: n flips
 *   on the sheet itself, so g >= 0 on both sides of it.
 * - AWAY_FROM_POINT: the same with a user ReferencePoint (e.g. a point inside a closed shape
 *   whose centroid is not inside it, or a point off an open sheet).
 * - ALONG_DIRECTION: n . ReferenceDirection >= 0. For a sheet that is a graph over a plane, with
 *   the plane's normal as the direction, g changes sign through the sheet (a line cloud along x
 *   with direction +y: g < 0 below, > 0 above). The seam is where n is orthogonal to the
 *   direction, e.g. all of LevinMLS's tangent region above such a sheet.
 * - PROPAGATE: starts from AWAY_FROM_CENTROID and makes neighbouring samples agree: a maximum
 *   spanning tree over the points of the output (neighbours: axis neighbours of an image,
 *   rectilinear or structured grid, else points consecutive in a cell) with weight |n_i . n_j|,
 *   grown from the most stable sample, every sample taking the sign that agrees with its parent
 *   (the normal orientation of Hoppe et al. 1992). Seams then lie only where n itself turns
 *   sharply (its singularities, where the weights are small): what a stream tracer needs for
 *   clouds of any shape, e.g. Levin's tangent field along a curved cloud (Fig. 9), which no
 *   point-wise rule can orient (n . (x - c) = 0 there). It depends on the whole set of samples,
 *   so a single point (and vtkPointSetSurfaceImplicitFunction, which evaluates one point at a
 *   time) cannot reproduce it; samples not connected by cells keep AWAY_FROM_CENTROID.
 * Which rule the tests use, and why (tests/vtk/fields/FieldStreamlineTest.cxx): on a straight
 * line through its centroid both AWAY_FROM_CENTROID and PROPAGATE put no seam across the path of
 * a streamline, so every streamline follows n (|cos| > 0.99 away from Levin's singular height
 * h / sqrt(2)) until it leaves the grid, including Levin's tangent streamlines above the line.
 * Around a circle only PROPAGATE orients Levin's tangent field: a streamline 1.5 h outside goes
 * round for its whole length budget, where with AWAY_FROM_CENTROID it leaves the circle after
 * about 3 h.
 * Hence the default AWAY_FROM_CENTROID, which is point-wise (the sampler and the implicit
 * function agree to the last bit) and right for closed shapes around their centroid, and
 * PROPAGATE for streamlines of general clouds.
 *
 * @par Sampling grid.
 * With GenerateSamplingGrid on, input 0 is not needed (and ignored if connected): the output is
 * a vtkImageData of SampleDimensions points (default 101 x 101 x 1) spanning the cloud's bounds
 * enlarged by SamplingMargin * h on every side (default 3). A dimension of 1 samples the mid-plane
 * of that axis (for a planar cloud, the plane of the cloud: a 2D slice). The whole extent is
 * announced in RequestInformation; the origin and spacing depend on the cloud and on h, so they
 * are announced there from the cloud available at that time (exact for SetSourceData() or an
 * up-to-date pipeline; provisional, origin 0 and spacing 1, before an upstream filter has run)
 * and always set on the output, and on its information, from the cloud actually sampled in
 * RequestData (as vtkResampleToImage does with its input bounds). Only the update extent
 * requested downstream is sampled. Grids with a dimension below 1, more than 2^31
 * samples or more than 4 GiB of output arrays are rejected with an error.
 * The grid stays a mode of this filter rather than a source of its own: both modes evaluate the
 * same fields with the same surface, orientation and domain settings at the points of the
 * output, and differ only in where those points come from (SetUpSamplingGrid or a copy of input
 * 0). A second class would repeat every setting.
 *
 * @par Distributed runs.
 * Under MPI (pvbatch --symmetric, pvserver: a global vtkMultiProcessController with more than one
 * process) every rank asks for its own piece of the cloud, the pieces are gathered on every rank
 * (as vtkPointSetSurfaceProjection does), and each rank samples its own part: its piece of input 0,
 * or the part of the grid's extent the pipeline requests from it. Together the ranks' outputs are
 * the one-process output, bitwise; probe outputs carry `GlobalPointIds` (input 0's order, rank by
 * rank) unless input 0 has global ids. PROPAGATE needs the whole set of samples on one rank and is
 * refused with an error on every rank; use AWAY_FROM_CENTROID or ALONG_DIRECTION there.
 * With GhostMargin > 0 no rank holds the whole cloud: each holds its own cloud points plus the
 * other ranks' points inside the box of its samples grown by GhostMargin * h, and samples whose
 * evaluation reads beyond that box are evaluated again with a box grown by twice the margin (as
 * vtkPointSetSurfaceProjection does; the grid's geometry comes from the bounds and h reduced over
 * the ranks). Results are then bitwise the one-process output with the same GhostMargin (both
 * sum neighbourhoods in coordinate order).
 *
 * Errors (vtkErrorMacro, the update fails, no output): empty cloud or cloud without a finite
 * point, h <= 0 (AutomaticScale off and ScaleFactor <= 0), an invalid reference direction or
 * point, no input 0 without GenerateSamplingGrid, an absurd grid. Cloud points with NaN or
 * infinite coordinates are skipped with a warning.
 *
 * Runs threaded through vtkSMPTools (on the backend the application chose: see
 * vtkPointSetSurface::UseThreadedBackend), reports progress and honours AbortExecute.
 *
 * @sa vtkPointSetSurface vtkPointSetSurfaceImplicitFunction vtkPointSetSurfaceProjection
 *     vtkStreamTracer vtkContourFilter
 */
#ifndef vtkPointSetSurfaceFieldSampler_h
#define vtkPointSetSurfaceFieldSampler_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkDataSetAlgorithm.h"
#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <memory> // for std::unique_ptr

class vtkImageData;
class vtkPointSet;
class vtkPointSetSurface;
class vtkPolyData;

namespace pss_vtk
{
class UpstreamErrorWatch;
}

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceFieldSampler : public vtkDataSetAlgorithm
{
public:
  static vtkPointSetSurfaceFieldSampler* New();
  vtkTypeMacro(vtkPointSetSurfaceFieldSampler, vtkDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Orientation rules for n (see the class description).
  enum OrientationModeType
  {
    AWAY_FROM_CENTROID = 0,
    AWAY_FROM_POINT = 1,
    ALONG_DIRECTION = 2,
    PROPAGATE = 3
  };

  ///@{
  /// The surface definition and its parameters (never null; a default one is created).
  void SetSurface(vtkPointSetSurface* surface);
  vtkGetObjectMacro(Surface, vtkPointSetSurface);
  ///@}

  ///@{
  /// The point cloud (input 1).
  void SetSourceConnection(vtkAlgorithmOutput* output);
  void SetSourceData(vtkDataObject* data);
  vtkDataObject* GetSource();
  ///@}

  ///@{
  /// How n is oriented (see the class description). Default AWAY_FROM_CENTROID.
  vtkSetClampMacro(OrientationMode, int, AWAY_FROM_CENTROID, PROPAGATE);
  vtkGetMacro(OrientationMode, int);
  void SetOrientationModeToAwayFromCentroid() { this->SetOrientationMode(AWAY_FROM_CENTROID); }
  void SetOrientationModeToAwayFromPoint() { this->SetOrientationMode(AWAY_FROM_POINT); }
  void SetOrientationModeToAlongDirection() { this->SetOrientationMode(ALONG_DIRECTION); }
  void SetOrientationModeToPropagate() { this->SetOrientationMode(PROPAGATE); }
  ///@}

  ///@{
  /// Reference point of AWAY_FROM_POINT. Default (0, 0, 0).
  vtkSetVector3Macro(ReferencePoint, double);
  vtkGetVector3Macro(ReferencePoint, double);
  ///@}

  ///@{
  /// Reference direction of ALONG_DIRECTION (normalised; must not be zero). Default (0, 0, 1).
  vtkSetVector3Macro(ReferenceDirection, double);
  vtkGetVector3Macro(ReferenceDirection, double);
  ///@}

  ///@{
  /// Sample on a generated vtkImageData around the cloud instead of input 0. Default off.
  vtkSetMacro(GenerateSamplingGrid, bool);
  vtkGetMacro(GenerateSamplingGrid, bool);
  vtkBooleanMacro(GenerateSamplingGrid, bool);
  ///@}

  ///@{
  /// Points of the generated grid along x, y, z (each >= 1; 1 = the mid-plane). Default 101 101 1.
  vtkSetVector3Macro(SampleDimensions, int);
  vtkGetVector3Macro(SampleDimensions, int);
  ///@}

  ///@{
  /// Margin of the generated grid around the cloud's bounds, in units of h. Default 3.
  vtkSetClampMacro(SamplingMargin, double, 0.0, 1e6);
  vtkGetMacro(SamplingMargin, double);
  ///@}

  ///@{
  /// Add the `DomainLabel` array (projects every sample: expensive). Default off.
  vtkSetMacro(ComputeDomainLabels, bool);
  vtkGetMacro(ComputeDomainLabels, bool);
  vtkBooleanMacro(ComputeDomainLabels, bool);
  ///@}

  ///@{
  /// Domain threshold: a fixed point farther than this from the cloud is spurious (units of h),
  /// within [1e-6, 1e6]. Default 1.
  vtkSetClampMacro(MaxDistance, double, 1e-6, 1e6);
  vtkGetMacro(MaxDistance, double);
  ///@}

  ///@{
  /// Domain threshold: largest angle between n at the fixed point and the cloud's normal there
  /// (degrees). Default 30.
  vtkSetClampMacro(MaxNormalAngle, double, 0.0, 90.0);
  vtkGetMacro(MaxNormalAngle, double);
  ///@}

  ///@{
  /// Iteration limit of the projection behind `DomainLabel`. Default 100.
  vtkSetClampMacro(MaxIterations, int, 1, 100000);
  vtkGetMacro(MaxIterations, int);
  ///@}

  ///@{
  /// Convergence of the projection behind `DomainLabel`: a step below Tolerance * h. Default 1e-6.
  vtkSetClampMacro(Tolerance, double, 1e-14, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Distributed runs only (ignored in one process), as vtkPointSetSurfaceProjection's: 0 (default)
   * gathers the whole cloud on every rank (bitwise the one-process output); > 0 exchanges only
   * the cloud points within this many h of the box of a rank's samples. A grid sample far from
   * the cloud reads far (its neighbourhood reaches its nearest cloud point plus the kernel's
   * support), so the grid's corners may take a few rounds.
   */
  vtkSetClampMacro(GhostMargin, double, 0.0, 1e6);
  vtkGetMacro(GhostMargin, double);
  ///@}

  /// The rounds of ghost exchange the last distributed update with GhostMargin > 0 took (0
  /// otherwise); also the output's field data `GhostRounds`, beside `GhostPoints`.
  vtkGetMacro(GhostRounds, int);

  /// The h used by the last update (after automatic scaling).
  double GetEffectiveScale() const;

  vtkMTimeType GetMTime() override;

protected:
  vtkPointSetSurfaceFieldSampler();
  ~vtkPointSetSurfaceFieldSampler() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Always true: see "Distributed runs" above (also read by the plugin's XML test).
  bool SupportsDistributedRun() const { return true; }

  vtkPointSetSurface* Surface = nullptr;
  /// Every rank's cloud gathered by the last distributed update: the prepared surface refers to it.
  vtkSmartPointer<vtkPolyData> GatheredCloud;
  /// Armed in RequestUpdateExtent, checked in RequestData (vtkPointSetSurfaceAlgorithm's reason).
  std::unique_ptr<pss_vtk::UpstreamErrorWatch> UpstreamWatch;
  int OrientationMode = AWAY_FROM_CENTROID;
  double ReferencePoint[3] = { 0.0, 0.0, 0.0 };
  double ReferenceDirection[3] = { 0.0, 0.0, 1.0 };
  bool GenerateSamplingGrid = false;
  int SampleDimensions[3] = { 101, 101, 1 };
  double SamplingMargin = 3.0;
  bool ComputeDomainLabels = false;
  double MaxDistance = 1.0;
  double MaxNormalAngle = 30.0;
  int MaxIterations = 100;
  double Tolerance = 1e-6;
  double GhostMargin = 0.0;
  int GhostRounds = 0;

private:
  vtkPointSetSurfaceFieldSampler(const vtkPointSetSurfaceFieldSampler&) = delete;
  void operator=(const vtkPointSetSurfaceFieldSampler&) = delete;

  // Checks SampleDimensions (>= 1, at most 2^31 samples and 4 GiB of arrays); false after an error.
  bool CheckSampleDimensions();
  // Origin and spacing of the generated grid around the finite cloud points' bounds [lo, hi] at
  // scale h; false (after an error unless quiet) when the grid would be degenerate.
  bool ComputeGridGeometry(const double lo[3], const double hi[3], double h, double origin[3], double spacing[3],
    bool quiet);
  // The same for the prepared cloud.
  bool ComputeGridGeometry(vtkPointSet* cloud, double origin[3], double spacing[3], bool quiet);
  // GenerateSamplingGrid's path: gives @p image the grid's geometry (origin, spacing; the
  // requested part of its extent); false after an error. The probe's path is a shallow copy of
  // input 0.
  bool SetUpSamplingGrid(vtkImageData* image, const double origin[3], const double spacing[3], vtkInformation* outInfo);
};

#endif

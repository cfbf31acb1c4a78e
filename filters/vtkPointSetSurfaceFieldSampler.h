// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceFieldSampler
 * @brief   sample the direction field n, the energy e, delta and the implicit function g of a
 *          point-set surface at the points of a dataset or on a regular grid (Figures 5-10)
 *
 * A probe-style filter in the manner of vtkPointInterpolator. Input 0 is any vtkDataSet whose
 * points are sampled; the source (input 1, SetSourceConnection() / SetSourceData()) is the point
 * cloud that defines the surface. Which surface, at which scale, is GetSurface()'s business. The
 * output is a shallow copy of input 0 with these point arrays:
 * - `Normal` (3 doubles): n(x), oriented by OrientationMode; zero where n is undefined or x is
 *   invalid. The active vectors, for vtkStreamTracer and vtkGlyph3D.
 * - `Energy`: e(x, n(x)) at its true scale (LevinMLS underflows to 0 far away, never to NaN).
 * - `Delta`: the approximate squared distance delta(x) of Sec. 5.
 * - `ImplicitG`: g(x) = n(x) . grad_y e(y, n(x)) at y = x (Eq. 2), with the same oriented n. Its
 *   zero set holds the minima (the extremal surface) and the maxima of Figures 9 and 10. The
 *   active scalars, for vtkContourFilter at value 0.
 * - `Stability`: of n(x); `ExtremumType`: 0 undetermined, 1 minimum, 2 maximum (the sign of the
 *   second derivative of e along n(x)).
 * - `Valid` (0/1): 0 where the sample point has a NaN or infinite coordinate; every other array
 *   is 0 there, never NaN.
 * - `DomainLabel` (ComputeDomainLabels on; off by default, since it projects every sample):
 *   0 in domain, 1 spurious, 2 undefined, 3 not converged, as vtkPointSetSurfaceDomainClassifier.
 *
 * Orientation of n (OrientationMode): n is unoriented, so every rule has seams where the vector
 * flips. AWAY_FROM_CENTROID (default, n . (x - c) >= 0) is point-wise and right for closed shapes
 * around their centroid; AWAY_FROM_POINT uses ReferencePoint; ALONG_DIRECTION uses
 * ReferenceDirection (a sheet that is a graph over a plane); PROPAGATE makes neighbouring samples
 * agree (a maximum spanning tree of |n_i . n_j|), for streamlines of general clouds. Where each
 * rule puts its seams: docs/vtk-filters.md.
 *
 * With GenerateSamplingGrid on, input 0 is not needed: the output is a vtkImageData of
 * SampleDimensions points over the cloud's bounds enlarged by SamplingMargin * h (a dimension of 1
 * samples the mid-plane of that axis). Its origin and spacing are announced in
 * RequestInformation from the cloud available then and set again from the cloud actually
 * sampled; only the requested update extent is sampled. Grids with a dimension below 1, more than
 * 2^31 samples or more than 4 GiB of arrays are rejected with an error.
 *
 * Errors (the update fails, no output): an empty cloud, h <= 0, an invalid reference direction
 * or point, no input 0 without GenerateSamplingGrid, an absurd grid. Threads through vtkSMPTools,
 * reports progress and honours AbortExecute. Runs distributed under MPI, each rank sampling its
 * own part; PROPAGATE is refused there (docs/distributed.md).
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

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceAlgorithm
 * @brief   base of the filters that compute on a point-set surface and output polydata
 *
 * Owns what vtkPointSetSurfaceProjection (and so vtkPointSetSurfaceDomainClassifier),
 * vtkPointSetSurfaceEnergyGlyphs and vtkPointSetSurfaceMesher share: the vtkPointSetSurface that
 * says which surface and at which scale (a default one exists; several filters may share one),
 * the modification time that includes it, the h of the last update, and the input ports: port 0
 * is the cloud (any vtkPointSet), later ports are optional point sets (start or sample points).
 *
 * vtkPointSetSurfaceFieldSampler holds its surface the same way but derives from
 * vtkDataSetAlgorithm, since its output is an image or the probe dataset's type.
 *
 * @sa vtkPointSetSurface
 */
#ifndef vtkPointSetSurfaceAlgorithm_h
#define vtkPointSetSurfaceAlgorithm_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <memory> // for std::unique_ptr

class vtkMultiProcessController;
class vtkPointSet;
class vtkPointSetSurface;
class vtkPolyData;
namespace pss_vtk
{
class DistributedRun;
class UpstreamErrorWatch;
}

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceAlgorithm : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkPointSetSurfaceAlgorithm, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The surface definition and its parameters (shared with other filters). A default one exists.
  virtual void SetSurface(vtkPointSetSurface*);
  vtkGetObjectMacro(Surface, vtkPointSetSurface);
  ///@}

  /// The h used by the last update (after automatic scaling; 0 before).
  double GetEffectiveScale() const;

  /// Includes the surface's modification time, so changing its parameters re-executes the filter.
  vtkMTimeType GetMTime() override;

  /// Where n and the output normals point (see ViewpointMode).
  enum ViewpointModeType
  {
    VIEWPOINT_FROM_INPUT = 0, ///< toward the cloud's field data `Viewpoint` when it has one (PCD)
    VIEWPOINT_GIVEN = 1,      ///< toward the Viewpoint property
    VIEWPOINT_OFF = 2         ///< away from the cloud's centroid, as without a viewpoint
  };

  ///@{
  /**
   * Orienting n (the `Normal` arrays, the energy glyphs' segments, the mesh's normals) toward a
   * sensor: a single depth-camera view sees every surface from its front, so n . (viewpoint - x)
   * >= 0 is right everywhere, where the default rule, away from the cloud's centroid, is only
   * right on closed shapes. Default VIEWPOINT_FROM_INPUT: the first three values of the cloud's
   * field data `Viewpoint` (vtkPCDReader's, tx ty tz), and the centroid rule when it has none.
   * An update with a non-finite viewpoint fails with an error.
   */
  vtkSetClampMacro(ViewpointMode, int, VIEWPOINT_FROM_INPUT, VIEWPOINT_OFF);
  vtkGetMacro(ViewpointMode, int);
  void SetViewpointModeToFromInput() { this->SetViewpointMode(VIEWPOINT_FROM_INPUT); }
  void SetViewpointModeToGiven() { this->SetViewpointMode(VIEWPOINT_GIVEN); }
  void SetViewpointModeToOff() { this->SetViewpointMode(VIEWPOINT_OFF); }
  ///@}

  ///@{
  /// The sensor's position for VIEWPOINT_GIVEN. Default (0, 0, 0), where PCL's frames put it.
  vtkSetVector3Macro(Viewpoint, double);
  vtkGetVector3Macro(Viewpoint, double);
  ///@}

protected:
  vtkPointSetSurfaceAlgorithm();
  ~vtkPointSetSurfaceAlgorithm() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Arms UpstreamWatch: errors until RequestData come from the pipeline upstream.
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * What RequestData does first: the viewpoint n is oriented toward (OrientationViewpoint()),
   * then pss_vtk::DistributedRun::Prepare on @p cloud with this filter's upstream watch,
   * gathering the cloud into GatheredCloud in a distributed run. Collective in a distributed
   * update; false on every rank after the same error.
   */
  bool PrepareRun(pss_vtk::DistributedRun& run, vtkInformationVector** inputVector, vtkPointSet* cloud);

  /**
   * Whether this filter gives the one-process result in an MPI run of several processes, each
   * rank computing its own points on the gathered cloud. Default false: such a run is refused.
   */
  virtual bool SupportsDistributedRun() const { return false; }

  /// The global controller when this update runs distributed (SupportsDistributedRun() and more
  /// than one process), else nullptr.
  vtkMultiProcessController* DistributedController() const;

  /// The viewpoint the last PrepareRun found (ViewpointMode, the cloud's field data), or nullptr
  /// when n is oriented away from the centroid.
  const double* OrientationViewpoint() const;

  vtkPointSetSurface* Surface = nullptr;
  int ViewpointMode = VIEWPOINT_FROM_INPUT;
  double Viewpoint[3] = { 0.0, 0.0, 0.0 };

  /// Every rank's cloud gathered by the last distributed update: the prepared surface refers to it.
  vtkSmartPointer<vtkPolyData> GatheredCloud;

private:
  /// Sets ResolvedViewpoint from ViewpointMode and @p cloud; false (with an error) when not finite.
  bool ResolveViewpoint(vtkPointSet* cloud);

  std::unique_ptr<pss_vtk::UpstreamErrorWatch> UpstreamWatch;
  bool HasOrientationViewpoint = false;
  double ResolvedViewpoint[3] = { 0.0, 0.0, 0.0 };

  vtkPointSetSurfaceAlgorithm(const vtkPointSetSurfaceAlgorithm&) = delete;
  void operator=(const vtkPointSetSurfaceAlgorithm&) = delete;
};

#endif

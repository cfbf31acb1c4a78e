// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceDomainClassifier
 * @brief   is each start point inside the domain of the point-set surface? (Amenta & Kil, Secs. 3-6)
 *
 * A vtkPointSetSurfaceProjection that also labels every start point by what became of its
 * projection (pss::classifyStart). Ports, surface parameters, projection settings and the
 * projection's output arrays are those of the superclass; each point is projected once, and the
 * label is read off that projection.
 *
 * `DomainLabel` (the active scalars):
 * - 0 InDomain: the projection converged to a fixed point within MaxDistance * h of the cloud
 *   whose n agrees, within MaxNormalAngle degrees, with the cloud's own normal there;
 * - 1 Spurious: it converged, but too far from every cloud point or with n too far off the
 *   cloud's normal: a spurious component of the surface (Figures 6 and 9);
 * - 2 Undefined: n was not well defined along the way (StopReason 2), or the start point had a
 *   NaN or infinite coordinate (StopReason 4);
 * - 3 NotConverged: the iteration limit was reached (StopReason 1), or no extremum of e was found
 *   along the line of n (StopReason 3).
 * The cloud's normal at a fixed point is the centre-of-mass normal at the cloud point nearest to
 * it: it depends on the cloud only, whatever Variant is being classified.
 *
 * The evidence behind each label, so the thresholds can be checked or changed afterwards:
 * `DistanceToCloud` (from the fixed point to the nearest cloud point), `NormalAngle` (degrees,
 * n at the fixed point against the cloud's normal there), `StartAngle` (degrees, n at the start
 * against n at the fixed point), `StartStability`. The first three are NaN exactly where there is
 * no fixed point (DomainLabel 2 or 3).
 *
 * Runs distributed under MPI as the projection does. See docs/vtk-filters.md.
 *
 * @sa vtkPointSetSurfaceProjection vtkPointSetSurface
 */
#ifndef vtkPointSetSurfaceDomainClassifier_h
#define vtkPointSetSurfaceDomainClassifier_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPointSetSurfaceProjection.h"

#include <memory> // for std::unique_ptr

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceDomainClassifier : public vtkPointSetSurfaceProjection
{
public:
  static vtkPointSetSurfaceDomainClassifier* New();
  vtkTypeMacro(vtkPointSetSurfaceDomainClassifier, vtkPointSetSurfaceProjection);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The labels (values match pss::DomainLabel).
  enum DomainLabelType
  {
    IN_DOMAIN = 0,
    SPURIOUS = 1,
    UNDEFINED = 2,
    NOT_CONVERGED = 3
  };

  ///@{
  /**
   * A fixed point farther than MaxDistance * h from every cloud point is Spurious. In units of h,
   * within [1e-6, 1e6]. Default 1.
   */
  vtkSetClampMacro(MaxDistance, double, 1e-6, 1e6);
  vtkGetMacro(MaxDistance, double);
  ///@}

  ///@{
  /**
   * A fixed point whose n is more than MaxNormalAngle degrees off the cloud's normal there is
   * Spurious. Degrees within [0, 90]. Default 30.
   */
  vtkSetClampMacro(MaxNormalAngle, double, 0.0, 90.0);
  vtkGetMacro(MaxNormalAngle, double);
  ///@}

protected:
  vtkPointSetSurfaceDomainClassifier();
  ~vtkPointSetSurfaceDomainClassifier() override;

#ifndef __VTK_WRAP__
  bool BeginProjection(const pss::SurfaceDefinition& surface, vtkIdType numberOfStarts) override;
  pss::ProjectionResult ProjectPoint(vtkIdType i, const double start[3], const pss::SurfaceDefinition& surface,
    const pss::ProjectionOptions& options, pss::Workspace& ws) override;
  bool AddPointArrays(vtkPointSet* starts, vtkPointData* outPD) override;
#endif

  double MaxDistance = 1.0;
  double MaxNormalAngle = 30.0;

private:
  vtkPointSetSurfaceDomainClassifier(const vtkPointSetSurfaceDomainClassifier&) = delete;
  void operator=(const vtkPointSetSurfaceDomainClassifier&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif

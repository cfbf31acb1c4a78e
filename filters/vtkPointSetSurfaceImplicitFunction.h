// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceImplicitFunction
 * @brief   the implicit function g of a point-set surface (Eq. 2 of Amenta & Kil), or its energy
 *          or approximate squared distance, as a vtkImplicitFunction
 *
 * EvaluateFunction(x) returns, according to OutputQuantity,
 * - IMPLICIT_G (default): g(x) = n(x) . grad_y e(y, n(x)) at y = x (Eq. 2), whose zero set holds
 *   the extremal surface (minima of e along n) and the maxima of Figures 9 and 10;
 * - ENERGY: e(x, n(x)) at its true scale (LevinMLS underflows to 0 far from the cloud);
 * - DELTA: the approximate squared distance delta(x) of Sec. 5;
 * so that vtkSampleFunction, vtkContourFilter, vtkCutter, vtkClipPolyData, vtkExtractGeometry,
 * ... work on a point-set surface. The cloud is given by SetInputData() (or SetPoints()); the
 * definition and scale by GetSurface() (a vtkPointSetSurface, shareable with the filters).
 *
 * The values are those of vtkPointSetSurfaceFieldSampler's `ImplicitG`, `Energy` and `Delta`, to
 * the last bit. The sign of g follows the orientation of n, chosen by OrientationMode as in the
 * sampler (AWAY_FROM_CENTROID, AWAY_FROM_POINT, ALONG_DIRECTION; the sampler's PROPAGATE has no
 * point-wise equivalent). Where g is not defined the function returns 0: at NaN or infinite
 * points, where n(x) is undefined, and when the surface cannot be set up (reported once with
 * vtkErrorMacro). EvaluateGradient() is a central difference with step FiniteDifferenceStep * h.
 *
 * Thread safety: EvaluateFunction() and EvaluateGradient() may be called concurrently (as
 * vtkSampleFunction does). The surface is prepared once, under a mutex, on the first evaluation
 * after a change of this object, its surface or its cloud; do not modify them while evaluations
 * are running.
 *
 * @sa vtkPointSetSurfaceFieldSampler vtkPointSetSurface vtkSampleFunction vtkContourFilter
 */
#ifndef vtkPointSetSurfaceImplicitFunction_h
#define vtkPointSetSurfaceImplicitFunction_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkImplicitFunction.h"

#include <memory> // for std::unique_ptr

class vtkPoints;
class vtkPointSet;
class vtkPointSetSurface;

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceImplicitFunction : public vtkImplicitFunction
{
public:
  static vtkPointSetSurfaceImplicitFunction* New();
  vtkTypeMacro(vtkPointSetSurfaceImplicitFunction, vtkImplicitFunction);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// What EvaluateFunction() returns.
  enum OutputQuantityType
  {
    IMPLICIT_G = 0,
    ENERGY = 1,
    DELTA = 2
  };

  /// Point-wise orientation rules for n (values as in vtkPointSetSurfaceFieldSampler).
  enum OrientationModeType
  {
    AWAY_FROM_CENTROID = 0,
    AWAY_FROM_POINT = 1,
    ALONG_DIRECTION = 2
  };

  using Superclass::EvaluateFunction;
  /// g(x), e(x, n(x)) or delta(x) (see OutputQuantity); 0 where undefined.
  double EvaluateFunction(double x[3]) override;
  /// Central differences of EvaluateFunction() (see the class description).
  void EvaluateGradient(double x[3], double g[3]) override;

  ///@{
  /// The surface definition and its parameters (never null; a default one is created).
  void SetSurface(vtkPointSetSurface* surface);
  vtkGetObjectMacro(Surface, vtkPointSetSurface);
  ///@}

  ///@{
  /// The point cloud (a reference is held).
  void SetInputData(vtkPointSet* cloud);
  vtkPointSet* GetInput() { return this->Input; }
  ///@}

  /// Convenience: the cloud made of @p points (wrapped in a vtkPolyData; a reference is held).
  void SetPoints(vtkPoints* points);

  ///@{
  /// IMPLICIT_G (default), ENERGY or DELTA.
  vtkSetClampMacro(OutputQuantity, int, IMPLICIT_G, DELTA);
  vtkGetMacro(OutputQuantity, int);
  void SetOutputQuantityToImplicitG() { this->SetOutputQuantity(IMPLICIT_G); }
  void SetOutputQuantityToEnergy() { this->SetOutputQuantity(ENERGY); }
  void SetOutputQuantityToDelta() { this->SetOutputQuantity(DELTA); }
  ///@}

  ///@{
  /// How n is oriented, i.e. the sign of g. Default AWAY_FROM_CENTROID.
  vtkSetClampMacro(OrientationMode, int, AWAY_FROM_CENTROID, ALONG_DIRECTION);
  vtkGetMacro(OrientationMode, int);
  void SetOrientationModeToAwayFromCentroid() { this->SetOrientationMode(AWAY_FROM_CENTROID); }
  void SetOrientationModeToAwayFromPoint() { this->SetOrientationMode(AWAY_FROM_POINT); }
  void SetOrientationModeToAlongDirection() { this->SetOrientationMode(ALONG_DIRECTION); }
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
  /// Step of the central differences of EvaluateGradient(), in units of h. Default 1e-3.
  vtkSetClampMacro(FiniteDifferenceStep, double, 1e-8, 1.0);
  vtkGetMacro(FiniteDifferenceStep, double);
  ///@}

  /**
   * Prepares the surface for the current cloud and parameters now (otherwise the first
   * evaluation does). Returns false, after vtkErrorMacro, when it cannot be set up.
   */
  bool Initialize();

  /// The h in use after a successful preparation (0 before).
  double GetEffectiveScale();

  /// Includes the MTime of the surface, of the cloud and of its points.
  vtkMTimeType GetMTime() override;

protected:
  vtkPointSetSurfaceImplicitFunction();
  ~vtkPointSetSurfaceImplicitFunction() override;

  vtkPointSetSurface* Surface = nullptr;
  vtkPointSet* Input = nullptr;
  int OutputQuantity = IMPLICIT_G;
  int OrientationMode = AWAY_FROM_CENTROID;
  double ReferencePoint[3] = { 0.0, 0.0, 0.0 };
  double ReferenceDirection[3] = { 0.0, 0.0, 1.0 };
  double FiniteDifferenceStep = 1e-3;

private:
  vtkPointSetSurfaceImplicitFunction(const vtkPointSetSurfaceImplicitFunction&) = delete;
  void operator=(const vtkPointSetSurfaceImplicitFunction&) = delete;

  // True when the prepared state matches the current MTime and the surface's current definition.
  bool IsReady(bool acquire);

  struct Internals;
  std::unique_ptr<Internals> State;
};

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurface
 * @brief   which point-set surface to use, and at what scale: shared by every PointSetSurfaces filter
 *
 * vtkPointSetSurface describes one of the five surface definitions of Amenta & Kil, "The Domain
 * of a Point Set Surface" (LevinMLS, NormalizedMLS, CenterOfMass, Integral, Delta) or one of the
 * two that fit points with oriented normals (APSS, RIMLS; see NormalsArrayName), the Gaussian
 * scale h, the dimension of the cloud and the numerical settings of the kernel. The filters
 * (vtkPointSetSurfaceProjection, vtkPointSetSurfaceDomainClassifier,
 * vtkPointSetSurfaceFieldSampler, vtkPointSetSurfaceEnergyGlyphs, vtkPointSetSurfaceMesher) and
 * the implicit function vtkPointSetSurfaceImplicitFunction each hold one (GetSurface()), so a
 * pipeline can share a single description among them, the way vtkPointInterpolator shares an
 * interpolation kernel. The definitions and their equations: docs/paper.md.
 *
 * Prepare() builds the k-d tree and the surface definition for a cloud and caches them until the
 * cloud or a parameter changes. Points with NaN or infinite coordinates are left out of the index
 * and counted (GetNumberOfSkippedPoints()). The index and the automatic scale are computed on as
 * many threads as vtkSMPTools gives (one with its Sequential backend); they are the same, bit for
 * bit, for every thread count.
 *
 * Scale: with AutomaticScale on (the default), PointScales chooses between one h for the whole cloud,
 * ScaleMultiplier times the median distance from a point to its ScaleNeighbors-th nearest
 * neighbour (defaults 1 and 10: about five spacings along a curve, two on a surface), and a scale
 * per point h_i (weights exp(-|x - p_i|^2 / h_i^2): docs/paper.md, "A scale per point"), either
 * from the data (each point's ScaleNeighbors-th neighbour distance, median-smoothed over its
 * neighbours, times ScaleMultiplier and PointScaleMultiplier) or from a point array
 * (ScaleArrayName). The default,
 * POINT_SCALES_AUTOMATIC, takes a scale per point only where the data call for it: for a sensor
 * frame (field data `GridDimensions` of an organized image, or a `Viewpoint`: what vtkPCDReader
 * and the depth-camera scene write) or when the 90th percentile of the data's per-point scales
 * exceeds ScaleSpreadThreshold times their 10th; else one h, exactly as with POINT_SCALES_OFF. With AutomaticScale off, ScaleFactor is h and must be
 * > 0.
 *
 * @sa vtkPointSetSurfaceProjection vtkPointSetSurfaceImplicitFunction
 */
#ifndef vtkPointSetSurface_h
#define vtkPointSetSurface_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkPointSet;

#ifndef __VTK_WRAP__
namespace pss
{
class PointIndex;
class SurfaceDefinition;
struct SurfaceParameters;
}
#endif

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurface : public vtkObject
{
public:
  static vtkPointSetSurface* New();
  vtkTypeMacro(vtkPointSetSurface, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The surface definitions (values match pss::Variant).
  enum VariantType
  {
    LEVIN_MLS = 0,
    NORMALIZED_MLS = 1,
    CENTER_OF_MASS = 2,
    INTEGRAL = 3,
    DELTA = 4,
    APSS = 5,
    RIMLS = 6
  };

  /// How h is chosen when AutomaticScale is on (see the class description).
  enum PointScalesType
  {
    POINT_SCALES_AUTOMATIC = 0, ///< per point where the density varies (ScaleSpreadThreshold), else one h
    POINT_SCALES_OFF = 1,       ///< one h for the whole cloud
    POINT_SCALES_ESTIMATED = 2, ///< h_i from each point's neighbours
    POINT_SCALES_FROM_ARRAY = 3 ///< h_i from the point array ScaleArrayName
  };

  /// Dimension of the cloud: AUTO (2 when all z are equal, else 3), 2 (xy-plane) or 3.
  enum DimensionType
  {
    DIMENSION_AUTO = 0,
    DIMENSION_2D = 2,
    DIMENSION_3D = 3
  };

  ///@{
  /**
   * The surface definition. Default CENTER_OF_MASS: cheap, and with a wide domain on smooth
   * surfaces (Sec. 5 of the paper).
   */
  vtkSetClampMacro(Variant, int, LEVIN_MLS, RIMLS);
  vtkGetMacro(Variant, int);
  void SetVariantToLevinMLS() { this->SetVariant(LEVIN_MLS); }
  void SetVariantToNormalizedMLS() { this->SetVariant(NORMALIZED_MLS); }
  void SetVariantToCenterOfMass() { this->SetVariant(CENTER_OF_MASS); }
  void SetVariantToIntegral() { this->SetVariant(INTEGRAL); }
  void SetVariantToDelta() { this->SetVariant(DELTA); }
  void SetVariantToAPSS() { this->SetVariant(APSS); }
  void SetVariantToRIMLS() { this->SetVariant(RIMLS); }
  ///@}

  ///@{
  /**
   * Gaussian scale h (theta = exp(-d^2/h^2)), used when AutomaticScale is off. Not clamped: a value
   * <= 0 or non-finite makes Prepare() fail with an error, rather than silently becoming another h.
   * Default 1.
   */
  vtkSetMacro(ScaleFactor, double);
  vtkGetMacro(ScaleFactor, double);
  ///@}

  ///@{
  /// Derive h from the k-nearest-neighbour spacing (see the class description). Default on.
  vtkSetMacro(AutomaticScale, bool);
  vtkGetMacro(AutomaticScale, bool);
  vtkBooleanMacro(AutomaticScale, bool);
  ///@}

  ///@{
  /// k of the automatic scale rule. Default 10.
  vtkSetClampMacro(ScaleNeighbors, int, 1, 1000);
  vtkGetMacro(ScaleNeighbors, int);
  ///@}

  ///@{
  /// Multiplier of the automatic scale rule. Default 1.
  vtkSetClampMacro(ScaleMultiplier, double, 1e-3, 1e3);
  vtkGetMacro(ScaleMultiplier, double);
  ///@}

  ///@{
  /// POINT_SCALES_AUTOMATIC, POINT_SCALES_OFF, POINT_SCALES_ESTIMATED or POINT_SCALES_FROM_ARRAY. Default POINT_SCALES_AUTOMATIC.
  vtkSetClampMacro(PointScales, int, POINT_SCALES_AUTOMATIC, POINT_SCALES_FROM_ARRAY);
  vtkGetMacro(PointScales, int);
  void SetPointScalesToAutomatic() { this->SetPointScales(POINT_SCALES_AUTOMATIC); }
  void SetPointScalesToOff() { this->SetPointScales(POINT_SCALES_OFF); }
  void SetPointScalesToEstimated() { this->SetPointScales(POINT_SCALES_ESTIMATED); }
  void SetPointScalesToFromArray() { this->SetPointScales(POINT_SCALES_FROM_ARRAY); }
  ///@}

  ///@{
  /**
   * POINT_SCALES_AUTOMATIC takes a scale per point when the 90th percentile of the per-point scales is
   * more than this many times their 10th. Default 3 (measured: the bunny's merged scans 1.4, the
   * paper's scenes 1.4-2.7, the noisy curve of its Fig. 1 the highest; unorganized depth frames
   * 3.8 and a room scan 50).
   */
  vtkSetClampMacro(ScaleSpreadThreshold, double, 1.0, 1e6);
  vtkGetMacro(ScaleSpreadThreshold, double);
  ///@}

  ///@{
  /**
   * The extra factor of estimated per-point scales: h_i = ScaleMultiplier x PointScaleMultiplier x
   * the point's smoothed ScaleNeighbors-th neighbour distance. Default 3: in a depth frame the
   * nearest neighbours lie in one depth layer of the sensor's quantization, and the weights must
   * reach across layers (measured in docs/adaptive-scale.md: on three real frames, 1 gives hundreds
   * of pieces, 3 a few).
   */
  vtkSetClampMacro(PointScaleMultiplier, double, 1e-2, 1e2);
  vtkGetMacro(PointScaleMultiplier, double);
  ///@}

  ///@{
  /**
   * The point array of h_i for POINT_SCALES_FROM_ARRAY: one component, every value a positive finite
   * number (ScaleMultiplier is not applied). Default "Scale".
   */
  vtkSetStringMacro(ScaleArrayName);
  vtkGetStringMacro(ScaleArrayName);
  ///@}

  ///@{
  /// DIMENSION_AUTO, DIMENSION_2D or DIMENSION_3D (1 is rejected by Prepare()). Default AUTO.
  vtkSetClampMacro(Dimension, int, DIMENSION_AUTO, DIMENSION_3D);
  vtkGetMacro(Dimension, int);
  ///@}

  ///@{
  /**
   * Truncation of the Gaussian, in units of h beyond the nearest point: points farther than
   * sqrt(dmin^2 + (cutoff h)^2) are ignored, each weighing < exp(-cutoff^2) of the nearest.
   * Default 3 (1.2e-4).
   */
  vtkSetClampMacro(KernelCutoff, double, 0.5, 20.0);
  vtkGetMacro(KernelCutoff, double);
  ///@}

  ///@{
  /// Gauss-Hermite nodes per axis for the integral energy e_I. Default 6.
  vtkSetClampMacro(QuadratureOrder, int, 1, 32);
  vtkGetMacro(QuadratureOrder, int);
  ///@}

  ///@{
  /**
   * Spacing, in units of h, of the lattice from which the Integral and Delta definitions read delta
   * at e_I's quadrature nodes: delta, its gradient and Hessian are computed exactly at the
   * lattice's nodes and interpolated (tricubic Hermite) between them (pss/DeltaLattice.h). 0
   * evaluates delta exactly at every node and takes the stability's e_perp from the full rule
   * throughout: the reference, about 20 times slower on a cloud's own points (measured on the bunny
   * scans), but about 1.35 times faster for a few isolated start points, which the projection and
   * the classifier therefore send to the exact path themselves (pss::latticeServes: fewer than 1.5
   * start points per lattice brick of 8 x 8 x 8 nodes, counted over every rank). Default 0.5 (on the bunny
   * scans every end point within 6e-4 h of the exact path's; docs/paper.md, "Reading: the integral
   * energy's fast path", for the synthetic scenes). Within [0, 1]; values in (0, 0.05) are refused
   * by Prepare.
   */
  vtkSetClampMacro(DeltaLatticeSpacing, double, 0.0, 1.0);
  vtkGetMacro(DeltaLatticeSpacing, double);
  ///@}

  ///@{
  /**
   * APSS and RIMLS fit points with oriented normals. They are read from the point array of this
   * name when the cloud has one (3 components; default "Normals", what PLY nx ny nz, VTK and PCD
   * normal_x/y/z readers give); a zero, NaN or infinite normal fails Prepare, naming the point.
   * Without such an array they are estimated (the centre-of-mass normal at each point) and
   * oriented: toward the field data `Viewpoint` when the cloud has one, else by propagation over
   * the NormalNeighbors-nearest-neighbour graph (pss/NormalOrientation.h). Points without a
   * normal of their own (isolated) borrow their nearest neighbour's (GetBorrowedNormals()).
   */
  vtkSetStringMacro(NormalsArrayName);
  vtkGetStringMacro(NormalsArrayName);
  vtkSetClampMacro(NormalNeighbors, int, 1, 100);
  vtkGetMacro(NormalNeighbors, int);
  ///@}

  ///@{
  /**
   * Given normals are taken as they are by default. With ReorientNormals on, their signs are
   * chosen again by the rule estimated normals get (toward the Viewpoint, else propagated from
   * each piece's highest point facing up), which repairs a scan whose normals are flipped in
   * places. Default off.
   */
  vtkSetMacro(ReorientNormals, bool);
  vtkGetMacro(ReorientNormals, bool);
  vtkBooleanMacro(ReorientNormals, bool);
  ///@}

  ///@{
  /// APSS: how much of the fitted sphere's curvature is kept, in [0, 1] (1, the default: the
  /// algebraic sphere; 0: a plane fitted to the points and normals).
  vtkSetClampMacro(Sphericity, double, 0.0, 1.0);
  vtkGetMacro(Sphericity, double);
  ///@}

  ///@{
  /**
   * RIMLS's robust weights: sigma_n for the normals (unitless, default 0.75; smaller keeps sharp
   * edges sharper), sigma_r for the residuals in units of the local h (default 0.5; smaller
   * discounts outliers more), and the number of refits after the first fit (default 3, fixed so
   * that the surface is continuous in space).
   */
  vtkSetClampMacro(SigmaNormal, double, 0.01, 100.0);
  vtkGetMacro(SigmaNormal, double);
  vtkSetClampMacro(SigmaResidual, double, 0.01, 100.0);
  vtkGetMacro(SigmaResidual, double);
  vtkSetClampMacro(RobustRefits, int, 0, 100);
  vtkGetMacro(RobustRefits, int);
  ///@}

  ///@{
  /// Below this stability n(x) counts as undefined. Default 1e-5.
  vtkSetClampMacro(MinimumStability, double, 0.0, 0.999);
  vtkGetMacro(MinimumStability, double);
  ///@}

  /**
   * Builds (or reuses) the index and the surface definition for @p cloud. Returns false, with a
   * message in GetLastError(), for an empty cloud, a cloud of only non-finite points, h <= 0, an
   * automatic scale of zero (all points duplicates) or Dimension 1.
   */
  bool Prepare(vtkPointSet* cloud);

  /// Message of the last failed Prepare() (empty after a successful one).
  const char* GetLastError() const { return this->LastError.c_str(); }

  /// The h in use after a successful Prepare(); with a scale per point, the median h_i.
  double GetEffectiveScale() const { return this->EffectiveScale; }
  /// True after a Prepare() that gave every point its own scale.
  bool GetUsesPointScales() const { return this->UsesPointScales; }
  /// The spread (90th over 10th percentile) of the per-point scales POINT_SCALES_AUTOMATIC measured, or
  /// of the array's or the data's scales with a scale per point; 0 when not measured.
  double GetScaleSpread() const { return this->ScaleSpread; }
  ///@{
  /**
   * The rule Prepare() follows, for a caller that holds the cloud's index itself (a distributed
   * run's rank 0): the scales per point PointScales Estimated and Automatic estimate on @p index
   * (index order), and whether Automatic takes them, for a sensor frame (field data GridDimensions
   * or Viewpoint) or scales whose spread exceeds ScaleSpreadThreshold. EstimateScaleSpread is
   * the spread of EstimatePointScales' scales, measured on a sample above
   * pss::ScaleSpreadSampledAbove points (pss::estimateScaleSpread).
   */
  std::vector<double> EstimatePointScales(const pss::PointIndex& index, int threads) const;
  double EstimateScaleSpread(const pss::PointIndex& index, int threads) const;
  bool AutomaticTakesPointScales(bool sensorFrame, double spread) const;
  ///@}

  /// 2 or 3 after a successful Prepare().
  int GetEffectiveDimension() const { return this->EffectiveDimension; }
  /// Points of the last prepared cloud left out for NaN or infinite coordinates.
  vtkIdType GetNumberOfSkippedPoints() const { return this->SkippedPoints; }
  /// After a Prepare() for APSS or RIMLS: "array" (NormalsArrayName), "reoriented" (the array,
  /// ReorientNormals on) or "estimated"; else "".
  const char* GetNormalsSource() const { return this->NormalsSource.c_str(); }
  /// After a Prepare() that estimated normals: the points that borrowed a neighbour's.
  vtkIdType GetBorrowedNormals() const { return this->BorrowedNormals; }

  /**
   * Lets the filters use every core: switches vtkSMPTools from its Sequential backend (the
   * default of Debian's VTK and ParaView) to STDThread, unless a backend was chosen through the
   * environment variable VTK_SMP_BACKEND_IN_USE or is already threaded. Returns the backend in
   * use afterwards. The backend is a setting of the whole process, so no filter changes it: the
   * application chooses, once, where it starts. The pss tool, the ParaView plugin when it loads
   * and the Python module `pointsetsurfaces` when it is imported call this; a C++ application
   * calls it (or vtkSMPTools::SetBackend) at start, or the filters run on one thread.
   */
  static const char* UseThreadedBackend();

#ifndef __VTK_WRAP__
  /// The prepared definition (nullptr before a successful Prepare()).
  const pss::SurfaceDefinition* GetDefinition() const { return this->Definition.get(); }
  const pss::PointIndex* GetIndex() const { return this->Index.get(); }

  /**
   * Prepare() that, with @p coordinateOrder, sums every neighbourhood in the order of its points'
   * coordinates (pss::PointIndex::setCoordinateOrder): what the filters do when their GhostMargin
   * is above 0, in one process as on every rank, so that a run with ghost points equals the
   * one-process run bitwise. A surface prepared in one order is prepared again for the other.
   */
  bool Prepare(vtkPointSet* cloud, bool coordinateOrder);

  /**
   * Prepare() for one rank of a distributed run that holds only part of the cloud: @p points
   * (x, y, z of each) are its piece plus ghost points, every cloud point inside the box [@p lo,
   * @p hi] (sides at +-inf are open) and some outside; @p dimension and @p h are the whole
   * cloud's (the caller computes the automatic h over all ranks; ScaleFactor is not read).
   * Evaluations that read beyond the box are flagged (pss::Workspace::leftCompleteRegion).
   * Checks the parameters before the points, so that every rank fails alike whatever its piece
   * holds; with no point at all it then succeeds without a definition (GetDefinition() is
   * nullptr: every evaluation on this rank needs ghost points first). Never reuses an earlier
   * preparation.
   */
  bool PreparePiece(
    const std::vector<double>& points, int dimension, const double lo[3], const double hi[3], double h);
#endif

  /**
   * Checks the parameters for a cloud of @p dimension (2 or 3) at scale @p h, reading no point and
   * leaving the prepared surface alone: false with GetLastError() set. What PreparePiece refuses
   * before its points; a distributed run calls it on every rank, whatever each holds, so that all
   * fail alike.
   */
  bool CheckParameters(int dimension, double h);

protected:
  vtkPointSetSurface();
  ~vtkPointSetSurface() override;

  int Variant = CENTER_OF_MASS;
  double ScaleFactor = 1.0;
  bool AutomaticScale = true;
  int ScaleNeighbors = 10;
  double ScaleMultiplier = 1.0;
  double PointScaleMultiplier = 3.0;
  int PointScales = POINT_SCALES_AUTOMATIC;
  double ScaleSpreadThreshold = 3.0;
  char* ScaleArrayName = nullptr;
  int Dimension = DIMENSION_AUTO;
  double KernelCutoff = 3.0;
  int QuadratureOrder = 6;
  double DeltaLatticeSpacing = 0.5;
  double MinimumStability = 1e-5;
  char* NormalsArrayName = nullptr;
  int NormalNeighbors = 10;
  bool ReorientNormals = false;
  double Sphericity = 1.0;
  double SigmaNormal = 0.75;
  double SigmaResidual = 0.5;
  int RobustRefits = 3;

private:
  vtkPointSetSurface(const vtkPointSetSurface&) = delete;
  void operator=(const vtkPointSetSurface&) = delete;

  bool Fail(const std::string& message);
  /// The core's parameters at scale @p h.
  pss::SurfaceParameters Parameters(double h) const;
  /// Takes @p index and builds the definition at @p h (<= 0: the automatic scale over it, or
  /// @p arrayScales, the ScaleArrayName values in input order, with POINT_SCALES_FROM_ARRAY).
  /// @p cloud, when given, brings the normals APSS and RIMLS need (or the Viewpoint that orients
  /// estimated ones).
  bool Build(std::unique_ptr<pss::PointIndex> index, double h, const std::vector<double>& arrayScales = {},
    vtkPointSet* cloud = nullptr);
  /// Gives @p index the normals the variant needs, from @p cloud's array or estimated (see
  /// NormalsArrayName); false with the error set.
  bool SetCloudNormals(pss::PointIndex& index, const pss::SurfaceParameters& params, vtkPointSet* cloud);
  /// Sets the per-point scales PointScales asks for on @p index, or none; the h to use (0: failed).
  double ChooseScales(pss::PointIndex& index, const std::vector<double>& arrayScales);

  std::unique_ptr<pss::PointIndex> Index;
  std::unique_ptr<pss::SurfaceDefinition> Definition;
  vtkPointSet* PreparedCloud = nullptr; // identity only, never dereferenced after Prepare()
  vtkMTimeType PreparedTime = 0;
  bool PreparedCoordinateOrder = false;
  std::string LastError;
  std::string NormalsSource;
  vtkIdType BorrowedNormals = 0;
  double EffectiveScale = 0.0;
  bool UsesPointScales = false;
  double ScaleSpread = 0.0;
  bool SensorFrame = false; ///< the prepared cloud is an organized image or has a Viewpoint
  int EffectiveDimension = 3;
  vtkIdType SkippedPoints = 0;
};

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceCloudSource
 * @brief   synthetic point clouds with a known true shape, for trying out point-set surfaces
 *
 * vtkPointSetSurfaceCloudSource has no input. It draws NumberOfPoints points from one of the
 * scenes of the PointSetSurfaces core (pss::generateCloud), the same clouds the examples, the
 * command-line tool and the benchmarks use: same parameters and Seed, same cloud on every
 * platform.
 *
 * Scenes (Size is the characteristic length; in 2D every point has z = 0):
 * - LINE: a segment of length Size along x, centred at the origin;
 * - CIRCLE: a circle of radius Size/2 in the xy-plane;
 * - CORNER: two segments of length Size/2 meeting at the origin at CornerAngle degrees (the
 *   sharp corner of the paper's Figure 6);
 * - NOISY_CURVE: an open sine arc over x in [0, Size] whose density falls and whose noise grows
 *   along it, from Noise/5 to Noise (Figure 1);
 * - PLANE: a square of side Size in z = 0 (2D: its cross-section, a LINE);
 * - SPHERE: a sphere of radius Size/2 (2D: its equator, a CIRCLE);
 * - TWO_SHEETS: two squares of side Size at z = +-SheetGap/2 (2D: two parallel segments at
 *   y = +-SheetGap/2);
 * - DEPTH_CAMERA: one frame of a simulated structured-light depth camera (pss::generateDepthFrame,
 *   pss/DepthCamera.h) looking at a table with a box, a cylinder and a sphere on it, in metres.
 * The noise-free shape is sampled uniformly (NOISY_CURVE: with falling density), then every point
 * is offset by isotropic Gaussian noise of standard deviation Noise in the cloud's Dimension.
 *
 * Output: one vertex per point, and the point array `DistanceToShape` (pss::distanceToShape):
 * the exact distance from each point to the noise-free shape, i.e. how far the noise moved it
 * off the shape (in 2D, to the shape's xy cross-section). It is the active scalars.
 *
 * DEPTH_CAMERA reads only ImageWidth, ImageHeight, DepthNoise and Seed (NumberOfPoints, Size,
 * Noise and Dimension do not apply: the image fixes the count, the scene is in metres and 3D).
 * Its output is organized like vtkPCDReader's with SkipNaNPoints off: ImageWidth x ImageHeight
 * points in row-major pixel order, NaN where the sensor measures nothing (no hit, projector
 * shadow), the field data `GridDimensions` (width, height) and `Viewpoint` (0 0 0 1 0 0 0: the
 * sensor at the origin looking along +z, which the filters orient n toward), and the point arrays
 * `Pixel` (column, row), `SurfaceId` (the true surface the pixel's ray hits: 0 none, 1 table,
 * 2 box, 3 cylinder, 4 sphere; set also where the point is NaN) and `NoiseSigma` (the standard
 * deviation of the depth noise at the true depth, DepthNoise z^2; 0 where the ray hits nothing).
 * `DistanceToShape` is NaN at NaN points. vtkPCDWriter writes it as an organized PCD file.
 *
 * Invalid settings fail the update with an error message rather than being silently replaced:
 * Size <= 0, a NaN Size, Noise or SheetGap, more than 1e8 points (the core's limit), or values so
 * large that coordinates overflow. NumberOfPoints 0 gives an empty output. Only piece 0 of a piece request receives the cloud.
 *
 * @sa vtkPointSetSurfaceProjection vtkPointSetSurfaceDomainClassifier
 */
#ifndef vtkPointSetSurfaceCloudSource_h
#define vtkPointSetSurfaceCloudSource_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceCloudSource : public vtkPolyDataAlgorithm
{
public:
  static vtkPointSetSurfaceCloudSource* New();
  vtkTypeMacro(vtkPointSetSurfaceCloudSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The scenes (values match pss::Scene).
  enum SceneType
  {
    LINE = 0,
    CIRCLE = 1,
    CORNER = 2,
    NOISY_CURVE = 3,
    PLANE = 4,
    SPHERE = 5,
    TWO_SHEETS = 6,
    DEPTH_CAMERA = 7
  };

  ///@{
  /// The shape the points are drawn from (see the class description). Default NOISY_CURVE.
  vtkSetClampMacro(Scene, int, LINE, DEPTH_CAMERA);
  vtkGetMacro(Scene, int);
  void SetSceneToLine() { this->SetScene(LINE); }
  void SetSceneToCircle() { this->SetScene(CIRCLE); }
  void SetSceneToCorner() { this->SetScene(CORNER); }
  void SetSceneToNoisyCurve() { this->SetScene(NOISY_CURVE); }
  void SetSceneToPlane() { this->SetScene(PLANE); }
  void SetSceneToSphere() { this->SetScene(SPHERE); }
  void SetSceneToTwoSheets() { this->SetScene(TWO_SHEETS); }
  void SetSceneToDepthCamera() { this->SetScene(DEPTH_CAMERA); }
  /// Lower-case name of the current scene ("line", "circle", ..., "two-sheets", "depth-camera").
  const char* GetSceneAsString() const;
  ///@}

  ///@{
  /**
   * Number of points. Default 1000. Negative values become 0 (an empty cloud); more than 1e8
   * points fail the update with an error (the core's limit) instead of exhausting memory.
   */
  vtkSetClampMacro(NumberOfPoints, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(NumberOfPoints, vtkIdType);
  ///@}

  ///@{
  /**
   * Characteristic length of the scene (see the class description). Default 100. Not clamped: a
   * value <= 0 or non-finite fails the update with an error, rather than silently becoming
   * another size.
   */
  vtkSetMacro(Size, double);
  vtkGetMacro(Size, double);
  ///@}

  ///@{
  /// Standard deviation of the Gaussian noise added to every point (>= 0). Default 0.
  vtkSetClampMacro(Noise, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Noise, double);
  ///@}

  ///@{
  /// Seed of the portable random generator: same seed, same cloud. Default 1.
  vtkSetClampMacro(Seed, int, 0, VTK_INT_MAX);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// 2 (points in the xy-plane) or 3. Default 2.
  vtkSetClampMacro(Dimension, int, 2, 3);
  vtkGetMacro(Dimension, int);
  ///@}

  ///@{
  /// Angle between the two CORNER segments, in degrees, within [0.1, 179.9]. Default 60.
  vtkSetClampMacro(CornerAngle, double, 0.1, 179.9);
  vtkGetMacro(CornerAngle, double);
  ///@}

  ///@{
  /// Distance between the two TWO_SHEETS sheets (>= 0). Default 10.
  vtkSetClampMacro(SheetGap, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SheetGap, double);
  ///@}

  ///@{
  /**
   * DEPTH_CAMERA: pixels per row and rows of the image, within [1, 16384] each (at most 1e8
   * pixels in all). The field of view stays 58 degrees across. Default 640 x 480.
   */
  vtkSetClampMacro(ImageWidth, int, 1, 16384);
  vtkGetMacro(ImageWidth, int);
  vtkSetClampMacro(ImageHeight, int, 1, 16384);
  vtkGetMacro(ImageHeight, int);
  ///@}

  ///@{
  /**
   * DEPTH_CAMERA: sigma0 of the depth noise, in 1/m: its standard deviation at depth z is
   * sigma0 z^2 (>= 0; 0: quantization only). Default 0.0012, a Kinect v1-like 1.2 mm at 1 m.
   */
  vtkSetClampMacro(DepthNoise, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(DepthNoise, double);
  ///@}

protected:
  vtkPointSetSurfaceCloudSource();
  ~vtkPointSetSurfaceCloudSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData's DEPTH_CAMERA branch: the organized frame and its arrays.
  int RequestDepthCamera(vtkPolyData* output);

  int Scene = NOISY_CURVE;
  vtkIdType NumberOfPoints = 1000;
  double Size = 100.0;
  double Noise = 0.0;
  int Seed = 1;
  int Dimension = 2;
  double CornerAngle = 60.0;
  double SheetGap = 10.0;
  int ImageWidth = 640;
  int ImageHeight = 480;
  double DepthNoise = 0.0012;

private:
  vtkPointSetSurfaceCloudSource(const vtkPointSetSurfaceCloudSource&) = delete;
  void operator=(const vtkPointSetSurfaceCloudSource&) = delete;
};

#endif

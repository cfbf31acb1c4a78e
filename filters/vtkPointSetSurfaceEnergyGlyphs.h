// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSetSurfaceEnergyGlyphs
 * @brief   polar plots of the energy e(x, a) over all directions a, and the best-fitting line or
 *          plane at x (Amenta & Kil, Figures 4 and 5)
 *
 * Input 0 is the point cloud that defines the surface (any vtkPointSet); input 1, optional, holds
 * the sample points x (without it every cloud point is a sample: give sample points for large
 * clouds). Which surface definition, at which scale, is GetSurface()'s business.
 *
 * Output 0, the energy glyphs: for each sample x, the points x + c e(x, a) a over unit directions
 * a: in 2D Resolution directions on the circle, one closed polyline; in 3D a latitude-longitude
 * sphere of directions with Resolution longitude segments and max(2, Resolution/2) latitude bands,
 * triangulated with outward orientation. The narrowest direction of a glyph is n(x): a dumbbell
 * means a strong choice of n, an ellipse a weaker one, a circle or square an unstable one
 * (Figure 4).
 *
 * The constant c (ScaleMode): SCALE_GLOBAL (default) fixes c = GlyphSize * h / (largest e) within
 * the output, as in the paper, so glyph sizes compare energies (GetGlyphScale() is c);
 * SCALE_PER_GLYPH normalizes each glyph so that its widest direction reaches GlyphSize * h, so
 * shapes compare (exact even where the true energies underflow to 0).
 *
 * Output 1, the best fit at each sample: the line segment (2D) or square patch (3D) through x
 * normal to n(x), of half-length SegmentLength * h (Figure 5); none where n(x) is undefined.
 *
 * Arrays: `Energy` on glyph points (e(x, a) at its true scale; may underflow to 0, never NaN);
 * `SampleId` and `Stability` on the cells of both outputs; `Normal` (n(x), oriented away from the
 * cloud's centroid) on the cells of output 1. Sample points with NaN or infinite coordinates get
 * no glyph and no segment (a warning counts them); an empty cloud is an error. Runs distributed
 * under MPI, each rank plotting its own samples. See docs/vtk-filters.md.
 *
 * @sa vtkPointSetSurface vtkPointSetSurfaceProjection
 */
#ifndef vtkPointSetSurfaceEnergyGlyphs_h
#define vtkPointSetSurfaceEnergyGlyphs_h

#include "PointSetSurfacesFiltersModule.h" // for export macro
#include "vtkPointSetSurfaceAlgorithm.h"

class POINTSETSURFACESFILTERS_EXPORT vtkPointSetSurfaceEnergyGlyphs : public vtkPointSetSurfaceAlgorithm
{
public:
  static vtkPointSetSurfaceEnergyGlyphs* New();
  vtkTypeMacro(vtkPointSetSurfaceEnergyGlyphs, vtkPointSetSurfaceAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ScaleModeType
  {
    SCALE_GLOBAL = 0,
    SCALE_PER_GLYPH = 1
  };

  /// Sample points (input 1). Without them every cloud point is a sample.
  void SetSamplePointsConnection(vtkAlgorithmOutput* output);
  void SetSamplePointsData(vtkDataObject* data);

  ///@{
  /**
   * Directions per glyph: segments of the circle (2D) or longitude segments of the sphere (3D),
   * within [4, 1024]. Default 72 (every 5 degrees). Keep it even for centrally symmetric glyphs;
   * in 3D a glyph has about Resolution^2 / 2 directions, so 24 to 36 is usually plenty.
   */
  vtkSetClampMacro(Resolution, int, 4, 1024);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /// Size of the largest glyph (SCALE_GLOBAL) or of every glyph (SCALE_PER_GLYPH), in units of h.
  /// Within [0, 1e6]. Default 1.
  vtkSetClampMacro(GlyphSize, double, 0.0, 1e6);
  vtkGetMacro(GlyphSize, double);
  ///@}

  ///@{
  /// SCALE_GLOBAL (one c for the whole output, default) or SCALE_PER_GLYPH.
  vtkSetClampMacro(ScaleMode, int, SCALE_GLOBAL, SCALE_PER_GLYPH);
  vtkGetMacro(ScaleMode, int);
  void SetScaleModeToGlobal() { this->SetScaleMode(SCALE_GLOBAL); }
  void SetScaleModeToPerGlyph() { this->SetScaleMode(SCALE_PER_GLYPH); }
  ///@}

  ///@{
  /// Half-length of the best-fit segment (half side of the patch), in units of h, within
  /// [0, 1e6]. Default 1.
  vtkSetClampMacro(SegmentLength, double, 0.0, 1e6);
  vtkGetMacro(SegmentLength, double);
  ///@}

  /// The c of the last update in SCALE_GLOBAL mode (0 when every energy was 0); 0 in SCALE_PER_GLYPH.
  double GetGlyphScale() const { return this->GlyphScale; }

  ///@{
  /// Distributed runs only, as vtkPointSetSurfaceProjection's GhostMargin: 0 (default) gathers the
  /// whole cloud on every rank; > 0 exchanges only the cloud points within this many h of the box
  /// of a rank's samples, a glyph whose reads leave it being plotted again with a wider box.
  vtkSetClampMacro(GhostMargin, double, 0.0, 1e6);
  vtkGetMacro(GhostMargin, double);
  ///@}

  /// The rounds of ghost exchange of the last distributed update with GhostMargin > 0 (0 otherwise).
  vtkGetMacro(GhostRounds, int);

protected:
  vtkPointSetSurfaceEnergyGlyphs();
  ~vtkPointSetSurfaceEnergyGlyphs() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The glyphs give the one-process result in a distributed run (see the class description).
  bool SupportsDistributedRun() const override { return true; }

  int Resolution = 72;
  double GlyphSize = 1.0;
  int ScaleMode = SCALE_GLOBAL;
  double SegmentLength = 1.0;
  double GlyphScale = 0.0;
  double GhostMargin = 0.0;
  int GhostRounds = 0;

private:
  vtkPointSetSurfaceEnergyGlyphs(const vtkPointSetSurfaceEnergyGlyphs&) = delete;
  void operator=(const vtkPointSetSurfaceEnergyGlyphs&) = delete;
};

#endif

// SPDX-License-Identifier: BSD-3-Clause
/**
 * Energy glyphs (Figures 4 and 5): the polar plot x + c e(x, a) a over directions a.
 * - e(x, a) = e(x, -a) (a is unoriented), so with an even Resolution a glyph is centrally
 *   symmetric about x;
 * - n(x) = argmin_a e(x, a), so a glyph is narrowest along n(x), and the best-fit segment through
 *   x is perpendicular to it (Figure 4);
 * - above a line, Levin's glyph is narrowest across the line near it (height < h / sqrt(2)) and
 *   along the line farther up, while the integral energy's stays narrowest across it (Figure 5);
 * - c is fixed per output: the widest point of all glyphs is at GlyphSize * h from its sample.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceEnergyGlyphs.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkMath.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

using namespace pss_test;

namespace
{

// Unoriented angle between two vectors, in degrees within [0, 90].
double AngleDegrees(const Point& a, const Point& b)
{
  const double c = std::min(1.0, std::abs(Dot(a, b)) / (Norm(a) * Norm(b)));
  return std::acos(c) * 180.0 / M_PI;
}

struct GlyphCheck
{
  double symmetry = 0.0;        // max |(p_k - x) + (p_{k+R/2} - x)| / (GlyphSize h)
  double narrowestToNormal = 0.0; // degrees between the narrowest glyph direction and n(x)
  Point narrowest{};
  double widest = 0.0;          // largest |p_k - x|
};

// Examines the glyph of sample @p s (2D: one closed polyline of R + 1 ids, points s*R .. s*R+R-1).
GlyphCheck Examine2D(vtkPolyData* glyphs, vtkPolyData* fits, vtkIdType s, const Point& x, int resolution)
{
  GlyphCheck out;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  glyphs->GetLines()->GetCellAtId(s, npts, pts);
  EXPECT_EQ(npts, resolution + 1);
  EXPECT_EQ(pts[0], pts[resolution]) << "closed curve";
  double narrowestRadius = 1e300;
  for (int k = 0; k < resolution; ++k)
  {
    const Point a = Sub(Coordinates(glyphs, pts[k]), x);
    const Point b = Sub(Coordinates(glyphs, pts[(k + resolution / 2) % resolution]), x);
    out.symmetry = std::max(out.symmetry, Norm({ a[0] + b[0], a[1] + b[1], a[2] + b[2] }));
    const double r = Norm(a);
    out.widest = std::max(out.widest, r);
    if (r < narrowestRadius)
    {
      narrowestRadius = r;
      const double phi = 2.0 * M_PI * k / resolution; // the direction a_k, even where r is tiny
      out.narrowest = { std::cos(phi), std::sin(phi), 0.0 };
    }
  }
  const double* n = fits->GetCellData()->GetArray("Normal")->GetTuple3(s);
  out.narrowestToNormal = AngleDegrees(out.narrowest, { n[0], n[1], n[2] });
  return out;
}

vtkSmartPointer<vtkPointSetSurfaceCloudSource> DenseLine()
{
  auto source = vtkSmartPointer<vtkPointSetSurfaceCloudSource>::New();
  source->SetSceneToLine();
  source->SetDimension(2);
  source->SetNumberOfPoints(2000);
  source->SetSize(40.0); // 50 points per h with h = 1
  source->SetSeed(11);
  return source;
}

} // namespace

TEST(FilterEnergyGlyphs, CentrallySymmetricAndNarrowestAlongNormal2D)
{
  const double h = 1.0;
  const int resolution = 72;
  const std::vector<Point> samples = { { 0.3, 0.3 * h, 0.0 }, { -0.7, 2.0 * h, 0.0 } };
  auto source = DenseLine();
  auto sampleData = MakePoints(samples);

  for (int variant : { vtkPointSetSurface::LEVIN_MLS, vtkPointSetSurface::INTEGRAL })
  {
    vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
    vtkNew<ErrorObserver> observer;
    observer->Attach(glyphs);
    glyphs->SetInputConnection(0, source->GetOutputPort());
    glyphs->SetSamplePointsData(sampleData);
    glyphs->GetSurface()->SetVariant(variant);
    glyphs->GetSurface()->AutomaticScaleOff();
    glyphs->GetSurface()->SetScaleFactor(h);
    glyphs->SetResolution(resolution);
    glyphs->SetGlyphSize(0.8);
    glyphs->SetSegmentLength(1.5);
    glyphs->Update();
    ASSERT_TRUE(observer->Errors.empty());
    EXPECT_TRUE(observer->Warnings.empty());
    vtkPolyData* out = glyphs->GetOutput(0);
    vtkPolyData* fits = glyphs->GetOutput(1);
    ASSERT_EQ(out->GetNumberOfPoints(), 2 * resolution);
    ASSERT_EQ(out->GetNumberOfLines(), 2);
    ASSERT_EQ(fits->GetNumberOfLines(), 2);

    double widest = 0.0;
    double maxEnergy = 0.0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      maxEnergy = std::max(maxEnergy, Value(out, "Energy", i));
    }
    for (vtkIdType s = 0; s < 2; ++s)
    {
      const Point& x = samples[static_cast<std::size_t>(s)];
      const GlyphCheck g = Examine2D(out, fits, s, x, resolution);
      widest = std::max(widest, g.widest);
      std::printf("[measured] %s glyph at height %.1f h: symmetry defect %.2e h, narrowest direction "
                  "(%.3f, %.3f) at %.3f deg from n(x), stability %.4f\n",
        variant == vtkPointSetSurface::LEVIN_MLS ? "LevinMLS" : "Integral", x[1] / h, g.symmetry / h,
        g.narrowest[0], g.narrowest[1], g.narrowestToNormal, fits->GetCellData()->GetArray("Stability")->GetTuple1(s));
      // e(x, a) and e(x, -a) are the same sum (Levin: bit for bit; integral: the quadrature
      // nodes in the opposite order), times the same c: rounding only.
      EXPECT_LT(g.symmetry, 1e-9 * h);
      // The true minimum is n(x); the glyph samples a every 5 degrees: within half a step.
      EXPECT_LE(g.narrowestToNormal, 2.5 + 1e-9);
      // Figure 5: near the line (0.3 h) everything picks the line's normal (0, 1); at 2 h > h/sqrt(2)
      // Levin's n turns parallel to the line while the integral's stays normal to it. The
      // sampling of the line tilts n by well under a degree; 5 degrees is one glyph step.
      const bool across = !(variant == vtkPointSetSurface::LEVIN_MLS && s == 1);
      const Point expected = across ? Point{ 0.0, 1.0, 0.0 } : Point{ 1.0, 0.0, 0.0 };
      EXPECT_LE(AngleDegrees(g.narrowest, expected), 5.0) << "sample " << s;

      // The best-fit segment: through x, perpendicular to n(x), half-length SegmentLength h.
      vtkIdType npts = 0;
      const vtkIdType* pts = nullptr;
      fits->GetLines()->GetCellAtId(s, npts, pts);
      ASSERT_EQ(npts, 2);
      const Point a = Coordinates(fits, pts[0]);
      const Point b = Coordinates(fits, pts[1]);
      const double* n = fits->GetCellData()->GetArray("Normal")->GetTuple3(s);
      const Point ab = Sub(b, a);
      EXPECT_NEAR(Dot(ab, { n[0], n[1], n[2] }), 0.0, 1e-12 * h); // exactly perpendicular, rounding aside
      EXPECT_NEAR(Norm(ab), 2.0 * 1.5 * h, 1e-12 * h);
      EXPECT_NEAR((a[0] + b[0]) / 2, x[0], 1e-12 * h);
      EXPECT_NEAR((a[1] + b[1]) / 2, x[1], 1e-12 * h);
      EXPECT_EQ(fits->GetCellData()->GetArray("SampleId")->GetTuple1(s), s);
      EXPECT_EQ(out->GetCellData()->GetArray("SampleId")->GetTuple1(s), s);
    }
    // c is fixed per output: the widest point of all glyphs reaches GlyphSize h, and
    // c = GlyphSize h / max e (rounding of one multiplication and one division).
    EXPECT_NEAR(widest, 0.8 * h, 1e-12 * h);
    EXPECT_NEAR(glyphs->GetGlyphScale(), 0.8 * h / maxEnergy, 1e-12 * glyphs->GetGlyphScale());
  }
}

TEST(FilterEnergyGlyphs, LevinEnergyMatchesBruteForceSum)
{
  // e_MLS(x, a) = sum_i exp(-|p_i - x|^2 / h^2) <a, p_i - x>^2 over the whole cloud, summed here
  // without truncation. The core truncates at 3 h beyond the nearest point (each neglected term
  // weighs < exp(-9) = 1.2e-4 of the nearest), so the two agree to ~1e-4 relative.
  const double h = 1.0;
  auto source = DenseLine();
  source->Update();
  vtkPolyData* cloud = source->GetOutput();
  const Point x = { 0.3, 0.4 * h, 0.0 };
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  glyphs->SetInputData(0, cloud);
  glyphs->SetSamplePointsData(MakePoints({ x }));
  glyphs->GetSurface()->SetVariantToLevinMLS();
  glyphs->GetSurface()->AutomaticScaleOff();
  glyphs->GetSurface()->SetScaleFactor(h);
  glyphs->SetResolution(8);
  glyphs->Update();
  vtkPolyData* out = glyphs->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 8);
  double worst = 0.0;
  for (int k = 0; k < 8; ++k)
  {
    const Point a = { std::cos(2.0 * M_PI * k / 8), std::sin(2.0 * M_PI * k / 8), 0.0 };
    double sum = 0.0;
    for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
    {
      const Point d = Sub(Coordinates(cloud, i), x);
      sum += std::exp(-Dot(d, d) / (h * h)) * Dot(a, d) * Dot(a, d);
    }
    worst = std::max(worst, std::abs(Value(out, "Energy", k) - sum) / sum);
  }
  std::printf("[measured] Levin glyph energy vs brute-force sum: max relative difference %.2e\n", worst);
  EXPECT_LT(worst, 1e-3);
}

TEST(FilterEnergyGlyphs, PerGlyphScaleSurvivesUnderflow)
{
  // 40 h above the line Levin's true energy is ~exp(-1600): 0 in double. Global scaling collapses
  // the glyph (with a warning); per-glyph scaling still shows its shape, narrowest along the line.
  const double h = 1.0;
  auto source = DenseLine();
  const Point far = { 0.0, 40.0 * h, 0.0 };
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  vtkNew<ErrorObserver> observer;
  observer->Attach(glyphs);
  glyphs->SetInputConnection(0, source->GetOutputPort());
  glyphs->SetSamplePointsData(MakePoints({ { 0.2, 0.5 * h, 0.0 }, far }));
  glyphs->GetSurface()->SetVariantToLevinMLS();
  glyphs->GetSurface()->AutomaticScaleOff();
  glyphs->GetSurface()->SetScaleFactor(h);
  glyphs->SetResolution(36);
  glyphs->SetScaleModeToPerGlyph();
  glyphs->Update();
  ASSERT_TRUE(observer->Errors.empty());
  vtkPolyData* out = glyphs->GetOutput(0);
  ASSERT_EQ(out->GetNumberOfLines(), 2);
  for (vtkIdType s = 0; s < 2; ++s)
  {
    const Point x = s == 0 ? Point{ 0.2, 0.5 * h, 0.0 } : far;
    const GlyphCheck g = Examine2D(out, glyphs->GetOutput(1), s, x, 36);
    EXPECT_NEAR(g.widest, h, 1e-12 * h) << "each glyph normalized to GlyphSize h";
    EXPECT_LT(g.symmetry, 1e-9 * h);
    EXPECT_LE(g.narrowestToNormal, 5.0 + 1e-9); // half of the 10-degree step
  }
  for (vtkIdType k = 36; k < 72; ++k)
  {
    EXPECT_EQ(Value(out, "Energy", k), 0.0) << "true scale: underflows to 0, never NaN";
  }
  EXPECT_EQ(glyphs->GetGlyphScale(), 0.0);

  glyphs->SetScaleModeToGlobal();
  glyphs->SetSamplePointsData(MakePoints({ far }));
  glyphs->Update();
  EXPECT_TRUE(observer->HasWarning("every energy is 0"));
  for (vtkIdType k = 0; k < 36; ++k)
  {
    EXPECT_EQ(Coordinates(glyphs->GetOutput(), k), far); // collapsed onto the sample, not NaN
  }
}

TEST(FilterEnergyGlyphs, PlaneSmokeTest3D)
{
  const double h = 0.8;
  const int resolution = 16; // 8 latitude bands: 2 + 7 * 16 = 114 directions, 16 * 14 = 224 triangles
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToPlane();
  source->SetDimension(3);
  source->SetNumberOfPoints(1500);
  source->SetSize(10.0);
  const std::vector<Point> samples = { { 0.1, 0.2, 0.4 * h }, { -1.0, 0.5, -0.2 * h } };
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  vtkNew<ErrorObserver> observer;
  observer->Attach(glyphs);
  glyphs->SetInputConnection(0, source->GetOutputPort());
  glyphs->SetSamplePointsData(MakePoints(samples));
  glyphs->GetSurface()->SetVariantToCenterOfMass();
  glyphs->GetSurface()->SetDimension(3); // all z = 0: Auto would call it a 2D cloud
  glyphs->GetSurface()->AutomaticScaleOff();
  glyphs->GetSurface()->SetScaleFactor(h);
  glyphs->SetResolution(resolution);
  glyphs->Update();
  ASSERT_TRUE(observer->Errors.empty());
  vtkPolyData* out = glyphs->GetOutput(0);
  vtkPolyData* fits = glyphs->GetOutput(1);
  const vtkIdType perGlyph = 2 + 7 * resolution;
  ASSERT_EQ(out->GetNumberOfPoints(), 2 * perGlyph);
  ASSERT_EQ(out->GetNumberOfPolys(), 2 * 16 * 14);
  ASSERT_EQ(fits->GetNumberOfPolys(), 2);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    ASSERT_TRUE(std::isfinite(Value(out, "Energy", i)));
    ASSERT_GE(Value(out, "Energy", i), 0.0);
  }
  for (vtkIdType s = 0; s < 2; ++s)
  {
    const Point& x = samples[static_cast<std::size_t>(s)];
    // Central symmetry: direction (band i, longitude j) and (bands - i, j + R/2) are antipodal;
    // the poles are each other's antipodes.
    double symmetry = 0.0;
    double narrowest = 1e300;
    Point narrowestDir{};
    auto glyphPoint = [&](vtkIdType local) { return Sub(Coordinates(out, s * perGlyph + local), x); };
    for (vtkIdType k = 0; k < perGlyph; ++k)
    {
      vtkIdType opposite = 0;
      if (k == 0 || k == perGlyph - 1)
      {
        opposite = perGlyph - 1 - k;
      }
      else
      {
        const vtkIdType band = 1 + (k - 1) / resolution;
        const vtkIdType lon = (k - 1) % resolution;
        opposite = 1 + (8 - band - 1) * resolution + (lon + resolution / 2) % resolution;
      }
      const Point a = glyphPoint(k);
      const Point b = glyphPoint(opposite);
      symmetry = std::max(symmetry, Norm({ a[0] + b[0], a[1] + b[1], a[2] + b[2] }));
      if (Norm(a) < narrowest)
      {
        narrowest = Norm(a);
        narrowestDir = a;
      }
    }
    const double* n = fits->GetCellData()->GetArray("Normal")->GetTuple3(s);
    const double toNormal = AngleDegrees(narrowestDir, { n[0], n[1], n[2] });
    std::printf("[measured] 3D plane glyph %lld: symmetry defect %.2e h, narrowest at %.2f deg from n, "
                "n.z = %.6f\n",
      static_cast<long long>(s), symmetry / h, toNormal, n[2]);
    EXPECT_LT(symmetry, 1e-9 * h); // same sums, same c: rounding only
    // The directions are 22.5 degrees apart in latitude: the narrowest sampled one is within a step.
    EXPECT_LE(toNormal, 22.5);
    // A noise-free plane z = 0: n_COM is the plane's normal to rounding.
    EXPECT_NEAR(std::abs(n[2]), 1.0, 1e-12);

    // The patch: a square of side 2 SegmentLength h centred at x, in the plane normal to n.
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    fits->GetPolys()->GetCellAtId(s, npts, pts);
    ASSERT_EQ(npts, 4);
    Point centre{ 0.0, 0.0, 0.0 };
    for (int c = 0; c < 4; ++c)
    {
      const Point p = Coordinates(fits, pts[c]);
      const Point q = Coordinates(fits, pts[(c + 1) % 4]);
      const Point edge = Sub(q, p);
      EXPECT_NEAR(Norm(edge), 2.0 * h, 1e-12 * h);
      EXPECT_NEAR(Dot(edge, { n[0], n[1], n[2] }), 0.0, 1e-12 * h);
      for (int d = 0; d < 3; ++d)
      {
        centre[d] += p[d] / 4.0;
      }
    }
    EXPECT_LT(Norm(Sub(centre, x)), 1e-12 * h);
  }
  std::ostringstream print;
  glyphs->Print(print);
  for (const char* key : { "Resolution: 16", "GlyphSize", "ScaleMode: Global", "SegmentLength", "Surface" })
  {
    EXPECT_NE(print.str().find(key), std::string::npos) << key;
  }
}

TEST(FilterEnergyGlyphs, DefaultSamplesAreTheCloud)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToCircle();
  source->SetNumberOfPoints(60);
  source->SetSize(10.0);
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  glyphs->SetInputConnection(source->GetOutputPort());
  glyphs->SetResolution(12);
  glyphs->Update();
  EXPECT_EQ(glyphs->GetOutput(0)->GetNumberOfLines(), 60);
  EXPECT_EQ(glyphs->GetOutput(0)->GetNumberOfPoints(), 60 * 12);
  EXPECT_EQ(glyphs->GetOutput(1)->GetNumberOfLines(), 60);
}

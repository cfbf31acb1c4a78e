// SPDX-License-Identifier: BSD-3-Clause
// Figures 3, 4 and 8 of the main demo, and the mesher's polylines over Figures 6, 9 and 10. Every
// energy, every n and every polyline comes from the filters (through PaperMeasures.h, EnergyGlyphs
// and the field sampler); the code here places samples, draws the geometry of the figures (planes,
// residual segments, circles, the band, a chart) and reports.
#include "PaperFiguresExtra.h"

#include "pss/Types.h"

#include "vtkPointSetSurfaceFieldSampler.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

namespace pss_paper
{

namespace
{

// Polylines and segments with integer cell tags, built point by point.
class Drawing
{
public:
  Drawing()
  {
    Points->SetDataTypeToDouble();
  }
  /// A polyline through @p pts with the given tags (one value per tag array, in order).
  void Line(const std::vector<pss::Vec3>& pts, const std::vector<double>& tags)
  {
    std::vector<vtkIdType> ids;
    for (const pss::Vec3& p : pts)
    {
      ids.push_back(Points->InsertNextPoint(p.data()));
    }
    Cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    Tags.push_back(tags);
  }
  vtkSmartPointer<vtkPolyData> Build(const std::vector<std::string>& tagNames) const
  {
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(Points);
    poly->SetLines(Cells);
    for (std::size_t t = 0; t < tagNames.size(); ++t)
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(tagNames[t].c_str());
      for (const std::vector<double>& row : Tags)
      {
        a->InsertNextValue(t < row.size() ? row[t] : 0.0);
      }
      poly->GetCellData()->AddArray(a);
    }
    return poly;
  }

private:
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Cells;
  std::vector<std::vector<double>> Tags;
};

std::vector<pss::Vec3> Circle(const pss::Vec3& c, double r)
{
  std::vector<pss::Vec3> pts;
  for (int k = 0; k <= 96; ++k)
  {
    const double phi = 2.0 * M_PI * k / 96;
    pts.push_back(c + r * pss::Vec3(std::cos(phi), std::sin(phi), 0.0));
  }
  return pts;
}

const std::vector<double> Figure3DrawnHeights = { 0.25, 0.5, 1.0, 1.5, 2.0 }; // in h, at x = 0
// Figure 4's glyphs: heights above the line, each in its own column x (the line is uniform there).
const std::vector<double> Figure4Heights = { 0.1, 0.5, 0.7 }; // in h
const std::vector<double> Figure4Columns = { -1.2, 0.0, 1.2 }; // in h

// Where the panel of Figure 3's k-th drawn height and plane (0 parallel, 1 perpendicular) is
// drawn: columns 7 h apart, the perpendicular row 5.6 h below the parallel one (the renderer
// assumes this layout).
pss::Vec3 Figure3Offset(int k, int plane, double h)
{
  return pss::Vec3(7.0 * h * k, -5.6 * h * plane, 0.0);
}

// The window of Figure 8 around the noisy end of the curve, {xmin, xmax, ymin, ymax}.
const double Figure8Window[4] = { 128.0, 204.0, -40.0, 10.0 };
// The zoom of its glyph panel.
const double Figure8GlyphWindow[4] = { 163.0, 197.0, -32.0, 2.0 };

// n, e(x, n(x)) and the rest sampled on an image over Figure8Window, spacing @p spacingInH.
vtkSmartPointer<vtkImageData> SampleWindow(const Scene& scene, int variant, double spacingInH)
{
  const double spacing = spacingInH * scene.h;
  const int nx = static_cast<int>(std::lround((Figure8Window[1] - Figure8Window[0]) / spacing)) + 1;
  const int ny = static_cast<int>(std::lround((Figure8Window[3] - Figure8Window[2]) / spacing)) + 1;
  vtkNew<vtkImageData> probe;
  probe->SetOrigin(Figure8Window[0], Figure8Window[2], 0.0);
  probe->SetSpacing(spacing, spacing, 1.0);
  probe->SetDimensions(nx, ny, 1);
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  sampler->SetSurface(MakeSurface(scene, variant));
  sampler->SetInputData(probe);
  sampler->SetSourceData(scene.cloud);
  sampler->Update();
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->DeepCopy(vtkImageData::SafeDownCast(sampler->GetOutput()));
  if (field->GetNumberOfPoints() != static_cast<vtkIdType>(nx) * ny)
  {
    throw std::runtime_error("the field sampler failed on the noisy end of the curve");
  }
  AddLogEnergy(field);
  Label(field, VariantTitle(variant), scene.h);
  return field;
}

std::vector<pss::Vec3> Lattice(const double window[4], double step)
{
  std::vector<pss::Vec3> pts;
  for (double y = window[2] + 0.5 * step; y < window[3]; y += step)
  {
    for (double x = window[0] + 0.5 * step; x < window[1]; x += step)
    {
      pts.emplace_back(x, y, 0.0);
    }
  }
  return pts;
}

} // namespace

// ---- Figure 3 -----------------------------------------------------------------------------------

Figure3Result Figure3(const Scene& line, std::vector<Check>& checks)
{
  const int levin = vtkPointSetSurface::LEVIN_MLS;
  Figure3Result r;
  r.crossingLow = std::numeric_limits<double>::infinity();
  r.crossingHigh = -r.crossingLow;
  for (double x : LineColumns(line))
  {
    const double c = PerpendicularPlaneWinsHeight(line, levin, x, 2.0);
    r.crossingLow = std::min(r.crossingLow, c);
    r.crossingHigh = std::max(r.crossingHigh, c);
    ++r.columns;
  }
  std::vector<double> tableHeights;
  for (int k = 1; k <= 8; ++k)
  {
    tableHeights.push_back(0.25 * k);
  }
  r.table = LinePlaneEnergies(line, levin, 0.0, tableHeights);

  // The drawing, laid out as a grid of panels in one plane (one view renders them all, see
  // Figure3Offset): column k for the k-th drawn height, row 0 the plane parallel to the line, row 1
  // the perpendicular plane. Per panel: the plane (a segment of half-length 3 h through x), the circle
  // of radius h around x, x itself, the cloud points within 3 h of the column with their weight
  // theta(x, p), and each point's residual to the plane with the same weight. The weights are for
  // the drawing only: the energies come from the glyph filter.
  const double h = line.h;
  Drawing planes;
  Drawing circles;
  Drawing residuals;
  std::vector<pss::Vec3> near;
  for (vtkIdType i = 0; i < line.cloud->GetNumberOfPoints(); ++i)
  {
    double p[3];
    line.cloud->GetPoint(i, p);
    if (std::abs(p[0]) <= 3.0 * h)
    {
      near.emplace_back(p[0], p[1], 0.0);
    }
  }
  std::vector<pss::Vec3> drawnPoints;
  std::vector<double> drawnWeights;
  std::vector<pss::Vec3> centres;
  for (std::size_t k = 0; k < Figure3DrawnHeights.size(); ++k)
  {
    const pss::Vec3 x(0.0, Figure3DrawnHeights[k] * h, 0.0);
    for (int plane = 0; plane < 2; ++plane)
    {
      const pss::Vec3 o = Figure3Offset(static_cast<int>(k), plane, h);
      const pss::Vec3 along = plane == 0 ? pss::Vec3::UnitX() : pss::Vec3::UnitY();
      planes.Line({ o + x - 3.0 * h * along, o + x + 3.0 * h * along }, { static_cast<double>(plane) });
      circles.Line(Circle(o + x, h), { 0.0 });
      centres.push_back(o + x);
      for (const pss::Vec3& p : near)
      {
        const double theta = std::exp(-(p - x).squaredNorm() / (h * h));
        const pss::Vec3 foot = plane == 0 ? pss::Vec3(p.x(), x.y(), 0.0) : pss::Vec3(x.x(), p.y(), 0.0);
        residuals.Line({ o + p, o + foot }, { theta });
        drawnPoints.push_back(o + p);
        drawnWeights.push_back(theta);
      }
    }
  }
  vtkSmartPointer<vtkPolyData> weighted = MakePointCloud(drawnPoints);
  vtkNew<vtkDoubleArray> w;
  w->SetName("Weight");
  for (double v : drawnWeights)
  {
    w->InsertNextValue(v);
  }
  weighted->GetPointData()->AddArray(w);
  Label(weighted, "points on a line", h);
  Write(weighted, "fig03_points.vtp");
  Write(MakePointCloud(centres), "fig03_x.vtp");
  Write(planes.Build({ "Plane" }), "fig03_planes.vtp");
  Write(circles.Build({ "Circle" }), "fig03_circles.vtp");
  Write(residuals.Build({ "Weight" }), "fig03_residuals.vtp");

  // The chart: both energies against the height, 0 .. 2 h, in chart units (x: 10 per h, y: 10 at
  // the largest energy), and vertical marks at h / sqrt 2 (tag 2) and at the measured crossing (3).
  std::vector<double> heights;
  for (int k = 0; k <= 100; ++k)
  {
    heights.push_back(0.02 * k);
  }
  const PlaneEnergies curve = LinePlaneEnergies(line, levin, 0.0, heights);
  double top = 0.0;
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    top = std::max({ top, curve.parallel[k], curve.perpendicular[k] });
  }
  Drawing chart;
  std::vector<pss::Vec3> par;
  std::vector<pss::Vec3> perp;
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    par.emplace_back(10.0 * heights[k], 10.0 * curve.parallel[k] / top, 0.0);
    perp.emplace_back(10.0 * heights[k], 10.0 * curve.perpendicular[k] / top, 0.0);
  }
  chart.Line(par, { 0.0 });
  chart.Line(perp, { 1.0 });
  chart.Line({ pss::Vec3(10.0 * kPlaneCrossingTruth, 0, 0), pss::Vec3(10.0 * kPlaneCrossingTruth, 10.5, 0) }, { 2.0 });
  chart.Line({ pss::Vec3(0, 0, 0), pss::Vec3(20.5, 0, 0) }, { 4.0 });
  chart.Line({ pss::Vec3(0, 0, 0), pss::Vec3(0, 10.5, 0) }, { 4.0 });
  Write(chart.Build({ "Curve" }), "fig03_chart.vtp");

  const bool pass = std::abs(r.crossingLow - kPlaneCrossingTruth) <= kPlaneCrossingTolerance &&
    std::abs(r.crossingHigh - kPlaneCrossingTruth) <= kPlaneCrossingTolerance;
  checks.push_back({ "fig03.plane_crossing_over_h",
    "Fig. 3: e_MLS of the plane perpendicular to the line drops below the parallel plane's at h/sqrt(2) = " +
      Fixed(kPlaneCrossingTruth, 4) + " h (min over " + std::to_string(r.columns) + " columns, max " +
      Fixed(r.crossingHigh, 4) + ")",
    r.crossingLow, "within " + Fixed(kPlaneCrossingTolerance, 3) + " of 0.7071 at every column", pass });
  return r;
}

void PrintAndWriteFigure3(const Figure3Result& r)
{
  std::printf("\nFig. 3: Levin's e_MLS(x, a) at x = (0, t) above the line: a = (0, 1), the plane through x parallel\n"
              "to the line; a = (1, 0), the plane perpendicular to it (the lower one gives n_MLS)\n");
  std::printf("%8s %16s %16s %12s   %s\n", "t [h]", "e parallel", "e perpendicular", "perp / par", "lower");
  std::ofstream csv(OutDir / "fig03_plane_energies.csv");
  csv << "height_over_h,energy_parallel,energy_perpendicular\n";
  for (std::size_t k = 0; k < r.table.heights.size(); ++k)
  {
    const double par = r.table.parallel[k];
    const double perp = r.table.perpendicular[k];
    std::printf("%8.2f %16.6g %16.6g %12.4f   %s\n", r.table.heights[k], par, perp, perp / par,
      perp < par ? "perpendicular" : "parallel");
    csv << Fixed(r.table.heights[k], 2) << ',' << JsonNumber(par) << ',' << JsonNumber(perp) << '\n';
  }
  std::printf("the perpendicular plane's energy drops below the parallel one's at %.4f .. %.4f h over %d columns\n"
              "(analytically h / sqrt 2 = %.4f h)\n",
    r.crossingLow, r.crossingHigh, r.columns, kPlaneCrossingTruth);
  csv << "# crossing_over_h," << Fixed(r.crossingLow, 4) << ',' << Fixed(r.crossingHigh, 4) << '\n';
}

// ---- Figure 4 -----------------------------------------------------------------------------------

void Figure4(const Scene& line)
{
  std::vector<pss::Vec3> samples;
  for (std::size_t k = 0; k < Figure4Heights.size(); ++k)
  {
    samples.emplace_back(Figure4Columns[k] * line.h, Figure4Heights[k] * line.h, 0.0);
  }
  const Glyphs g = EnergyGlyphs(line, vtkPointSetSurface::LEVIN_MLS, samples, 0.4, 0.45);
  Write(g.glyphs, "fig04_glyphs.vtp");
  Write(g.fits, "fig04_fits.vtp");
  vtkDataArray* stability = g.fits->GetCellData()->GetArray("Stability");
  std::ofstream csv(OutDir / "fig04_legend.csv");
  csv << "x_over_h,height_over_h,stability\n";
  for (vtkIdType i = 0; i < g.fits->GetNumberOfCells(); ++i)
  {
    const std::size_t k = static_cast<std::size_t>(i);
    csv << Fixed(Figure4Columns[k], 2) << ',' << Fixed(Figure4Heights[k], 2) << ',' << Fixed(stability->GetTuple1(i), 4)
        << '\n';
  }
}

// ---- Figure 8 -----------------------------------------------------------------------------------

std::vector<BandMeasure> Figure8(const Scene& noisy, std::vector<Check>& checks)
{
  const int levin = vtkPointSetSurface::LEVIN_MLS;
  const int integral = vtkPointSetSurface::INTEGRAL;
  std::vector<BandMeasure> rows;
  for (int v : AllVariants())
  {
    rows.push_back(MeasureNoisyBand(noisy, v));
    Done("fig08: n across the noisy band, " + VariantName(v));
  }

  // The band (+-2 sigma(u) around the true curve) and the paths across it.
  Drawing band;
  std::vector<pss::Vec3> upper;
  std::vector<pss::Vec3> lower;
  for (int k = 0; k <= 200; ++k)
  {
    const pss::CurveFrame f = pss::noisyCurveFrame(noisy.shape, 0.6 + 0.4 * k / 200.0);
    upper.push_back(f.point + kBandSigmas * f.sigma * f.normal);
    lower.push_back(f.point - kBandSigmas * f.sigma * f.normal);
  }
  band.Line(upper, { 0.0 });
  band.Line(lower, { 0.0 });
  for (const BandPath& p : NoisyBandPaths(noisy))
  {
    band.Line({ p.foot, p.foot + kBandPathLength * noisy.h * p.normal }, { 1.0 });
  }
  Write(band.Build({ "Kind" }), "fig08_band.vtp");

  for (const BandMeasure& m : rows)
  {
    if (m.variant != levin && m.variant != integral)
    {
      continue;
    }
    const std::string stem = "fig08_" + VariantName(m.variant);
    // Where n first passes 45 degrees on each path.
    std::vector<pss::Vec3> turns;
    for (const PathProfile& p : m.paths)
    {
      if (std::isfinite(p.turn))
      {
        turns.push_back(p.path.foot + p.turn * noisy.h * p.path.normal);
      }
    }
    Write(MakePointCloud(turns), stem + "_turns.vtp");
    vtkSmartPointer<vtkImageData> field = SampleWindow(noisy, m.variant, 0.1);
    Write(field, stem + "_field.vti");
    const Glyphs g = EnergyGlyphs(noisy, m.variant, Lattice(Figure8GlyphWindow, 0.4 * noisy.h), 0.17, 0.17);
    Write(g.glyphs, stem + "_glyphs.vtp");
    Write(g.fits, stem + "_glyph_fits.vtp");
    const Glyphs f = EnergyGlyphs(noisy, m.variant, Lattice(Figure8Window, 0.5 * noisy.h), 0.2, 0.22);
    Write(f.fits, stem + "_fits.vtp");
    Done("fig08: energy image, glyphs, best-fitting lines, " + VariantName(m.variant));
  }

  const BandMeasure* lv = nullptr;
  const BandMeasure* in = nullptr;
  for (const BandMeasure& m : rows)
  {
    lv = m.variant == levin ? &m : lv;
    in = m.variant == integral ? &m : in;
  }
  const int paths = static_cast<int>(lv->paths.size());
  checks.push_back({ "fig08.levin_turn_over_sigma",
    "Fig. 8: n_MLS turns from the true normal past 45 deg in the band's outer part (median over " +
      std::to_string(paths) + " paths of the distance / local sigma; band: 2 sigma)",
    lv->medianTurnOverSigma, "in [" + Fixed(kLevinTurnLowSigmas, 1) + ", " + Fixed(kLevinTurnHighSigmas, 1) + "]",
    lv->medianTurnOverSigma >= kLevinTurnLowSigmas && lv->medianTurnOverSigma <= kLevinTurnHighSigmas });
  checks.push_back({ "fig08.integral_max_angle_deg",
    "Fig. 8: n_I stays close to the true normal across the band (median over the paths of the largest angle "
    "in the band, degrees; largest of all " + Fixed(in->maxAngleInBand, 1) + ", " +
      std::to_string(in->pathsPastTurnInBand) + " paths past 45)",
    in->medianMaxAngleInBand, "<= " + Fixed(kIntegralMedianMaxAngleInBand, 0),
    in->medianMaxAngleInBand <= kIntegralMedianMaxAngleInBand });
  const double factor = in->medianVariationInBand > 0.0 ? lv->medianVariationInBand / in->medianVariationInBand : 0.0;
  checks.push_back({ "fig08.smoothness_factor",
    "Fig. 8: n_I changes much more smoothly: median total variation of n_MLS in the band (" +
      Fixed(lv->medianVariationInBand, 1) + " deg) over n_I's (" + Fixed(in->medianVariationInBand, 1) + " deg)",
    factor, ">= " + Fixed(kSmoothnessFactor, 0), factor >= kSmoothnessFactor });
  // Beyond the paper: the definitions that fit normals see the curve's side in every neighbour's
  // normal, so their n should hold across the band at least as well as n_I.
  for (const BandMeasure& m : rows)
  {
    if (pss::needsNormals(static_cast<pss::Variant>(m.variant)))
    {
      checks.push_back({ "fig08." + VariantName(m.variant) + "_max_angle_deg",
        "beyond the paper: " + VariantTitle(m.variant) + "'s n stays as close to the true normal across the band as n_I "
          "(median over the paths of the largest angle in the band, degrees; " +
          std::to_string(m.pathsPastTurnInBand) + " paths past 45)",
        m.medianMaxAngleInBand, "<= " + Fixed(kIntegralMedianMaxAngleInBand, 0) + ", none past 45",
        m.medianMaxAngleInBand <= kIntegralMedianMaxAngleInBand && m.pathsPastTurnInBand == 0 });
    }
  }
  return rows;
}

MeshAgreement FigureMesh(const Scene& scene, int variant, vtkPolyData* ends, const std::string& stem,
  const std::string& checkPrefix, std::vector<Check>& checks)
{
  vtkSmartPointer<vtkPolyData> mesh = MeshScene(scene, variant);
  const MeshAgreement a = MeasureMeshAgreement(mesh, ends, scene.h);
  Label(mesh, VariantTitle(variant) + ": mesher polylines", scene.h);
  Write(mesh, stem + "_mesh.vtp");
  Done(stem + "_mesh: " + Describe(a));
  const std::string near = Fixed(kOnCurveDistance, 1) + " h";
  checks.push_back({ checkPrefix + "." + VariantName(variant) + "_mesh_agrees",
    VariantTitle(variant) + ": the mesher's polylines agree with the projections: every on-curve end point within " +
      near + " of a polyline (" + std::to_string(a.onCurveFar) + " of " + std::to_string(a.onCurve) +
      " farther, farthest " + Fixed(a.farthestOnCurve, 3) + " h), and no polyline piece without an end point within " +
      near + " (" + std::to_string(a.piecesWithoutEnds) + " of " + std::to_string(a.pieces) + ")",
    static_cast<double>(a.Disagreements()), "== 0", a.Disagreements() == 0 });
  return a;
}

void PrintAndWriteNoisyBand(const std::vector<BandMeasure>& rows)
{
  std::printf("\nnoisy band (Fig. 8, h = 5): n along %zu paths normal to the true curve (u = %.2f .. %.2f, both sides),\n"
              "angles to the true normal; band: within %.0f sigma(u) of the curve\n",
    rows.empty() ? std::size_t(0) : rows.front().paths.size(), kBandFirstU, kBandLastU, kBandSigmas);
  std::printf("%-11s %9s %12s %10s %11s %12s %11s %10s %11s %8s\n", "variant", "at curve", "turn 45 [s]", "turn [h]",
    "in outer", "max in band", "paths > 45", "max [deg]", "TV [deg]", "time [s]");
  std::ofstream csv(OutDir / "fig08_noisy_band.csv");
  csv << "variant,median_angle_at_curve_deg,median_turn_over_sigma,median_turn_over_h,turn_in_outer_part_fraction,"
         "median_max_angle_in_band_deg,paths_past_45_in_band,paths,max_angle_in_band_deg,"
         "median_total_variation_in_band_deg,seconds\n";
  for (const BandMeasure& m : rows)
  {
    const std::string paths = std::to_string(m.pathsPastTurnInBand) + "/" + std::to_string(m.paths.size());
    std::printf("%-11s %9.1f %12s %10s %11.2f %12.1f %11s %10.1f %11.1f %8.2f\n", VariantName(m.variant).c_str(),
      m.medianAngleAtCurve, Fixed(m.medianTurnOverSigma, 2).c_str(), Fixed(m.medianTurnOverH, 2).c_str(),
      m.turnInOuterPartFraction, m.medianMaxAngleInBand, paths.c_str(), m.maxAngleInBand, m.medianVariationInBand,
      m.seconds);
    csv << VariantName(m.variant) << ',' << Fixed(m.medianAngleAtCurve, 2) << ','
        << (std::isinf(m.medianTurnOverSigma) ? "inf" : Fixed(m.medianTurnOverSigma, 3)) << ','
        << (std::isinf(m.medianTurnOverH) ? "inf" : Fixed(m.medianTurnOverH, 3)) << ','
        << Fixed(m.turnInOuterPartFraction, 3) << ',' << Fixed(m.medianMaxAngleInBand, 2) << ','
        << m.pathsPastTurnInBand << ',' << m.paths.size() << ',' << Fixed(m.maxAngleInBand, 2) << ','
        << Fixed(m.medianVariationInBand, 2) << ',' << Fixed(m.seconds, 2) << '\n';
  }
  std::printf("at curve: median angle on the curve; turn 45: median distance where n first passes 45 degrees, in\n"
              "local sigma and in h ('none': most paths never); in outer: fraction of paths turning between 1 and 2\n"
              "sigma; max in band: median over the paths of the largest angle within 2 sigma; TV: median total\n"
              "variation of n along a path within 2 sigma (sum of the angles between consecutive samples 0.02 h apart).\n");
}

} // namespace pss_paper

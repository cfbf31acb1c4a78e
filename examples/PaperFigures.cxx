// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss-paper-figures: the main demo. Reproduces the figures of Amenta & Kil, "The Domain of a
 * Point Set Surface", as VTK data and PNG images, and checks the paper's claims as numbers.
 *
 *   pss-paper-figures [--out DIR] [--no-render] [--check] [--threads N] [--renderer SCRIPT]
 *                     [--delta-lattice S]
 *
 * Everything is computed with the PointSetSurfaces VTK filters (projection with projection lines
 * and domain labels, field sampling on grids, energy glyphs) and stock VTK (vtkStreamTracer on the
 * sampled n, vtkContourFilter on the sampled energy and delta). Written into DIR (default
 * ./paper-figures):
 * - fig01 / fig02: the noisy curve (h = 5) projected with Levin's MLS and with the integral
 *   variant: start-to-end projection lines and end points, with an `Outcome` array;
 * - fig05: energy glyphs and best-fitting lines at heights 0 .. 2 h above a line, MLS and e_I;
 * - fig06: the corner for Levin, normalized MLS, center of mass and integral: glyphs, sampled
 *   fields, streamlines of n, iso-contours of e(x, n(x)), surface points reached from 2000
 *   uniform random starts, and vtkPointSetSurfaceMesher's polylines (fig06_*_mesh.vtp, checked
 *   against those end points; PaperFiguresExtra.cxx);
 * - fig03 / fig04 (PaperFiguresExtra.cxx): two planes through a point above the line with the
 *   weighted points and a chart of their energies; the legend of the energy plots;
 * - fig07: delta on a grid (intensity) and its iso-contours;
 * - fig08 (PaperFiguresExtra.cxx): the noisy end of the curve (h = 5) for Levin and integral:
 *   energy glyphs, best-fitting lines, e(x, n(x)) as an image, the angle of n along paths across
 *   the noisy band (fig08_noisy_band.csv, all five definitions);
 * - fig09 / fig10: the noisy curve at h = 10 for Levin and integral: streamlines, iso-contours,
 *   minima (blue) and maxima (green) reached from random starts, near-singular points of n, and
 *   the mesher's polylines checked against the same starts' end points (fig09_levin_mesh.vtp,
 *   fig10_integral_mesh.vtp);
 * - domain_corner_*.vtp, domain_noisy10_*.vtp: for each of the seven definitions, the random
 *   starts of the corner and of the noisy curve at h = 10 with the DomainLabel of their
 *   projections (where each definition is defined);
 * - paper_table.csv (also printed): per scene and variant, the fraction of start points that land
 *   on the true curve, the number of spurious surface points, Levin's flip height and the domain
 *   half-width on the line scene;
 * - corner_breakdown.csv (also printed): where each definition's end points miss the corner (past
 *   the open ends, behind the apex, elsewhere) and where starts on the bisector end;
 * - paper_checks.json: the acceptance numbers with their bounds (--check: exit status 1 when one
 *   misses its bound).
 * Then, unless --no-render, examples/pvpython/render_paper_figures.py renders the PNG images with
 * pvbatch (under xvfb-run when there is no display); without pvbatch the images are skipped with
 * a message and the data files remain.
 */
#include "PaperFields.h"
#include "PaperFiguresExtra.h"
#include "PaperOutput.h"
#include "PaperScenes.h"

#include "pss/Types.h"

#include "vtkContourFilter.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkMath.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"
#include "vtkStreamTracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#ifndef PSS_PAPER_RENDER_SCRIPT
#define PSS_PAPER_RENDER_SCRIPT "render_paper_figures.py"
#endif

namespace
{

using namespace pss_paper;
namespace fs = std::filesystem;

struct Options
{
  std::string out = "paper-figures";
  bool render = true;
  bool check = false;
  int threads = 0;
  std::string renderer = PSS_PAPER_RENDER_SCRIPT;
};

const char* const Usage =
  "usage: pss-paper-figures [--out DIR] [--no-render] [--check] [--threads N] [--renderer SCRIPT]\n"
  "                         [--delta-lattice S]\n"
  "Reproduces the figures of Amenta & Kil, \"The Domain of a Point Set Surface\" (VTK files and\n"
  "PNG images in DIR, default ./paper-figures), prints the table of measured numbers and checks\n"
  "the paper's claims.\n"
  "  --out DIR         output folder (created)\n"
  "  --no-render       write the data and the table only, no PNG images\n"
  "  --check           exit with status 1 when a checked number misses its bound\n"
  "  --threads N       threads of the filters (default: all cores)\n"
  "  --delta-lattice S the integral and delta definitions' lattice spacing in h (default 0.5;\n"
  "                    0: delta exact at every quadrature node, the reference)\n"
  "  --renderer SCRIPT the pvbatch script (default: the source tree's render_paper_figures.py)\n";

Options Parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string flag = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        throw std::invalid_argument(flag + " needs a value");
      }
      return argv[++i];
    };
    if (flag == "--help" || flag == "-h")
    {
      std::cout << Usage;
      std::exit(0);
    }
    else if (flag == "--out")
      o.out = value();
    else if (flag == "--no-render")
      o.render = false;
    else if (flag == "--check")
      o.check = true;
    else if (flag == "--renderer")
      o.renderer = value();
    else if (flag == "--delta-lattice")
    {
      const std::string v = value();
      char* end = nullptr;
      const double s = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(s >= 0.0 && s <= 1.0))
      {
        throw std::invalid_argument("--delta-lattice expects a spacing in [0, 1] h, got '" + v + "'");
      }
      SetDeltaLatticeSpacing(s);
    }
    else if (flag == "--threads")
    {
      const std::string v = value();
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (end == v.c_str() || *end != '\0' || n < 0 || n > 4096)
      {
        throw std::invalid_argument("--threads expects a whole number >= 0, got '" + v + "'");
      }
      o.threads = static_cast<int>(n);
    }
    else
      throw std::invalid_argument("unknown option " + flag + " (see --help)");
  }
  return o;
}

// ---------------------------------------------------------------------------------------------
// Fields on grids, streamlines, contours: VTK filters over the sampler's output (the files, the
// sampler, the glyphs and the checks shared with Figures 3, 4 and 8 are in PaperOutput.h)

// Spacing of the sampling grids, in units of the scene's h.
constexpr double kCornerGridSpacing = 0.1;
constexpr double kDeltaGridSpacing = 0.1;
constexpr double kWideGridSpacing = 0.15;



// ---------------------------------------------------------------------------------------------
// The table and the checks

struct Row
{
  ProjectionStats stats;
  std::string scene;      // scene label in the table
  std::string starts;     // what the start points were
  double h = 0.0;
  double flip = std::numeric_limits<double>::quiet_NaN();      // line scene: flip height / h
  double halfWidth = std::numeric_limits<double>::quiet_NaN(); // line scene: domain half-width / h
  bool halfWidthBounded = true;
};


void PrintAndWriteTable(const std::vector<Row>& rows)
{
  std::printf("\n%-30s %-11s %-24s %6s %9s %9s %8s %10s %12s %8s\n", "scene", "variant", "start points", "starts",
    "converged", "on curve", "spurious", "flip [h]", "domain [h]", "time [s]");
  std::ofstream csv(OutDir / "paper_table.csv");
  csv << "scene,variant,h,start_points,starts,converged,on_curve,on_curve_fraction,spurious,"
         "flip_height_over_h,domain_half_width_over_h,seconds\n";
  std::string last;
  for (const Row& r : rows)
  {
    if (!last.empty() && last != r.scene)
    {
      std::printf("\n");
    }
    last = r.scene;
    std::string width = Fixed(r.halfWidth, 2);
    if (!std::isnan(r.halfWidth) && !r.halfWidthBounded)
    {
      width = ">= " + width;
    }
    std::printf("%-30s %-11s %-24s %6lld %9lld %9.4f %8lld %10s %12s %8.2f\n", r.scene.c_str(),
      VariantName(r.stats.variant).c_str(), r.starts.c_str(), static_cast<long long>(r.stats.starts),
      static_cast<long long>(r.stats.converged), r.stats.OnCurveFraction(), static_cast<long long>(r.stats.spurious),
      Fixed(r.flip, 3).c_str(), width.c_str(), r.stats.seconds);
    csv << '"' << r.scene << "\"," << VariantName(r.stats.variant) << ',' << r.h << ",\"" << r.starts << "\"," << r.stats.starts << ','
        << r.stats.converged << ',' << r.stats.onCurve << ',' << Fixed(r.stats.OnCurveFraction(), 4) << ','
        << r.stats.spurious << ',' << (std::isnan(r.flip) ? "" : std::isinf(r.flip) ? "inf" : Fixed(r.flip, 4)) << ','
        << (std::isnan(r.halfWidth) ? "" : (r.halfWidthBounded ? "" : ">=") + Fixed(r.halfWidth, 2)) << ','
        << Fixed(r.stats.seconds, 4) << '\n';
  }
  std::printf("\non curve: converged within %.1f h of the true curve; spurious: converged farther than %.0f h from\n"
              "every input point; flip: height where n first turns from the line's normal to its tangent (or is\n"
              "undefined), scanned to %.0f h; domain: height below which every start above the line lands on it.\n",
    kOnCurveDistance, kSpuriousDistance, kNoFlipHeight);
}


// ---------------------------------------------------------------------------------------------
// What each definition does at the corner

/// Where the converged end points that miss the corner (farther than 0.5 h from it) lie.
struct CornerBreakdown
{
  int variant = 0;
  vtkIdType pastOpenEnds = 0; ///< beyond the free end of an arm, along its direction
  vtkIdType behindApex = 0;   ///< on the convex side, below the apex (y < 0)
  vtkIdType elsewhere = 0;    ///< anywhere else (inside the wedge, beside the arms)
  std::vector<double> apexProbe; ///< end heights / h of starts on the bisector (NaN: not converged)
};

const std::vector<double> ApexProbeHeights = { -2.0, -1.0, -0.5, 0.5, 1.0, 2.0 }; // in h, on the bisector

CornerBreakdown BreakDownCorner(const Scene& corner, int variant, vtkPolyData* projected)
{
  CornerBreakdown out;
  out.variant = variant;
  const double half = 0.5 * corner.shape.cornerAngle * M_PI / 180.0;
  const double armLength = 0.5 * corner.shape.size;
  vtkDataArray* outcome = projected->GetPointData()->GetArray("Outcome");
  for (vtkIdType i = 0; i < projected->GetNumberOfPoints(); ++i)
  {
    const int o = static_cast<int>(outcome->GetTuple1(i));
    if (o != OFF_CURVE && o != SPURIOUS)
    {
      continue;
    }
    double p[3];
    projected->GetPoint(i, p);
    // Arm on p's side: direction (+-sin half, cos half) from the apex at the origin.
    const double along = std::abs(p[0]) * std::sin(half) + p[1] * std::cos(half);
    if (along > armLength)
    {
      ++out.pastOpenEnds;
    }
    else if (p[1] < 0.0)
    {
      ++out.behindApex;
    }
    else
    {
      ++out.elsewhere;
    }
  }
  std::vector<pss::Vec3> probes;
  for (double t : ApexProbeHeights)
  {
    probes.emplace_back(0.0, t * corner.h, 0.0);
  }
  const Projection probe = Project(corner, variant, MakePointCloud(probes));
  vtkDataArray* converged = probe.points->GetPointData()->GetArray("Converged");
  for (vtkIdType i = 0; i < probe.points->GetNumberOfPoints(); ++i)
  {
    out.apexProbe.push_back(
      converged->GetTuple1(i) != 0.0 ? probe.points->GetPoint(i)[1] / corner.h : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

void PrintAndWriteCornerBreakdown(const std::vector<CornerBreakdown>& rows)
{
  std::printf("\ncorner (Fig. 6): where the converged end points that miss the corner lie, and where starts on\n"
              "the bisector end (height / h; the apex is at 0, the wedge opens upwards)\n");
  std::printf("%-11s %10s %12s %10s   ", "variant", "past ends", "behind apex", "elsewhere");
  for (double t : ApexProbeHeights)
  {
    std::printf(" %6s", ("y0=" + Fixed(t, 1)).c_str());
  }
  std::printf("\n");
  std::ofstream csv(OutDir / "corner_breakdown.csv");
  csv << "variant,past_open_ends,behind_apex,elsewhere";
  for (double t : ApexProbeHeights)
  {
    csv << ",bisector_end_from_" << Fixed(t, 1) << "h";
  }
  csv << '\n';
  for (const CornerBreakdown& r : rows)
  {
    std::printf("%-11s %10lld %12lld %10lld   ", VariantName(r.variant).c_str(), static_cast<long long>(r.pastOpenEnds),
      static_cast<long long>(r.behindApex), static_cast<long long>(r.elsewhere));
    csv << VariantName(r.variant) << ',' << r.pastOpenEnds << ',' << r.behindApex << ',' << r.elsewhere;
    for (double y : r.apexProbe)
    {
      std::printf(" %6s", Fixed(y, 2).c_str());
      csv << ',' << (std::isnan(y) ? "" : Fixed(y, 4));
    }
    std::printf("\n");
    csv << '\n';
  }
}

// ---------------------------------------------------------------------------------------------
// Rendering

bool OnPath(const std::string& program)
{
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

void Render(const Options& opt)
{
  if (!OnPath("pvbatch"))
  {
    std::printf("\nrendering skipped: pvbatch is not on PATH (Debian: apt-get install paraview). The VTK files\n"
                "in %s open in ParaView as they are.\n",
      OutDir.string().c_str());
    return;
  }
  if (!fs::exists(opt.renderer))
  {
    std::printf("\nrendering skipped: the render script %s does not exist (--renderer SCRIPT).\n", opt.renderer.c_str());
    return;
  }
  std::string prefix;
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    if (!OnPath("xvfb-run"))
    {
      std::printf("\nrendering skipped: no display and no xvfb-run (Debian: apt-get install xvfb); ParaView 5.11\n"
                  "on Debian renders through X only.\n");
      return;
    }
    // -a takes the first free display from -n on; starting at a number drawn from the process id
    // keeps concurrent xvfb-run calls (tests, other users) from racing for the same display.
    prefix = "xvfb-run -a -n " + std::to_string(100 + getpid() % 800) + " -s \"-screen 0 1920x1080x24\" ";
  }
  const std::string command =
    prefix + "pvbatch \"" + opt.renderer + "\" \"" + OutDir.string() + "\" > \"" + (OutDir / "render.log").string() + "\" 2>&1";
  std::printf("\nrendering: %s\n", command.c_str());
  std::fflush(stdout);
  const auto t0 = Clock::now();
  int status = std::system(command.c_str());
  // xvfb-run -a can pick a display another xvfb-run is just taking: X then fails at once.
  for (int attempt = 1; status != 0 && !prefix.empty() && attempt < 3; ++attempt)
  {
    std::printf("rendering failed (status %d), retrying with a new virtual display\n", status);
    std::fflush(stdout);
    status = std::system(command.c_str());
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (status != 0)
  {
    std::printf("rendering FAILED (status %d, see %s)\n", status, (OutDir / "render.log").string().c_str());
    throw std::runtime_error("rendering failed");
  }
  std::printf("rendered the PNG images in %.1f s (log: %s)\n", seconds, (OutDir / "render.log").string().c_str());
}


} // namespace

int main(int argc, char** argv)
{
  try
  {
    const Options opt = Parse(argc, argv);
    // An application chooses the threading backend (the filters never change it).
    vtkPointSetSurface::UseThreadedBackend();
    if (opt.threads > 0)
    {
      vtkSMPTools::Initialize(opt.threads);
    }
    OutDir = fs::path(opt.out);
    fs::create_directories(OutDir);
    const auto start = ProgramStart;
    std::vector<Row> rows;
    std::vector<Check> checks;
    const int levin = vtkPointSetSurface::LEVIN_MLS;
    const int com = vtkPointSetSurface::CENTER_OF_MASS;
    const int integral = vtkPointSetSurface::INTEGRAL;
    const std::vector<int> figure6Variants = { levin, vtkPointSetSurface::NORMALIZED_MLS, com, integral };

    // ---- Figure 5: the line scene -------------------------------------------------------------
    std::printf("computing (each step: time since the start, time of the step)\n");
    const Scene line = MakeLineScene();
    Label(line.cloud, "points on a line", line.h);
    Write(line.cloud, "line_cloud.vtp");
    const std::vector<double> columns = LineColumns(line);
    for (int v : AllVariants())
    {
      Row r;
      r.scene = "line (Fig. 5)";
      r.h = line.h;
      r.starts = "columns, 0.05..10 h";
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (double x : columns)
      {
        const double f = FlipHeight(line, v, x, kNoFlipHeight);
        lo = std::min(lo, f);
        hi = std::max(hi, f);
      }
      r.flip = lo;
      const DomainScan scan = LineDomainHalfWidth(line, v);
      r.stats = scan.stats;
      r.halfWidth = scan.halfWidth;
      r.halfWidthBounded = scan.bounded;
      rows.push_back(r);
      Done("line: flip height and domain scan, " + VariantName(v));
      if (v == levin)
      {
        const double sqrtHalf = std::sqrt(0.5);
        checks.push_back({ "line.levin_flip_height_over_h",
          "n_MLS turns from normal to tangent at h/sqrt(2) = " + Fixed(sqrtHalf, 4) + " h above a line (Fig. 5); "
            "min over " + std::to_string(columns.size()) + " columns, max " + Fixed(hi, 4),
          lo, "[" + Fixed(kFlipHeightLow, 2) + ", " + Fixed(kFlipHeightHigh, 2) + "] at every column",
          lo >= kFlipHeightLow && hi <= kFlipHeightHigh });
      }
      const bool withNormals = pss::needsNormals(static_cast<pss::Variant>(v));
      if (v == com || v == integral || withNormals)
      {
        checks.push_back({ "line." + VariantName(v) + "_no_flip_up_to_5h",
          std::string(withNormals ? "beyond the paper: " : "") + VariantTitle(v) +
            ": n stays normal to the line up to 5 h (flip height, 'none' = never)", lo,
          "none up to " + Fixed(kNoFlipHeight, 0) + " h", std::isinf(lo) });
      }
    }
    {
      // Figure 5: glyphs at heights 0 .. 2 h (x = -0.6 h) and best-fitting lines (x = +0.6 h).
      std::vector<pss::Vec3> glyphSamples;
      std::vector<pss::Vec3> fitSamples;
      for (int k = 0; k <= 8; ++k)
      {
        glyphSamples.emplace_back(-0.6 * line.h, 0.25 * k * line.h, 0.0);
        fitSamples.emplace_back(0.6 * line.h, 0.25 * k * line.h, 0.0);
      }
      for (int v : { levin, integral })
      {
        const Glyphs g = EnergyGlyphs(line, v, glyphSamples, 0.11, 0.11);
        const Glyphs f = EnergyGlyphs(line, v, fitSamples, 0.11, 0.11);
        Write(g.glyphs, "fig05_" + VariantName(v) + "_glyphs.vtp");
        Write(f.fits, "fig05_" + VariantName(v) + "_fits.vtp");
      }
      Done("fig05: energy glyphs and best-fitting lines");
    }
    // Figures 3 and 4 (PaperFiguresExtra.cxx): two planes above the same line, and the legend of
    // the energy plots.
    const Figure3Result figure3 = Figure3(line, checks);
    Figure4(line);
    Done("fig03, fig04: plane energies above the line, legend glyphs");

    // ---- Figures 1 and 2: the noisy curve, h = 5 -----------------------------------------------
    const Scene noisy = MakeNoisyCurveScene(5.0);
    Label(noisy.cloud, "noisy curve", noisy.h);
    Write(noisy.cloud, "noisy_curve_cloud.vtp");
    double levinFraction = 0.0;
    double integralFraction = 0.0;
    for (int v : AllVariants())
    {
      const bool figure = v == levin || v == integral;
      const Projection p = Project(noisy, v, nullptr, false, figure);
      if (figure)
      {
        const std::string stem = v == levin ? "fig01_levin" : "fig02_integral";
        Label(p.lines, VariantTitle(v), noisy.h);
        Write(p.lines, stem + "_lines.vtp");
        Write(p.points, stem + "_projected.vtp");
      }
      Row r;
      r.scene = "noisy curve (Fig. 1, 2)";
      r.h = noisy.h;
      r.starts = "the 600 input points";
      r.stats = p.stats;
      rows.push_back(r);
      if (v == levin)
      {
        levinFraction = p.stats.OnCurveFraction();
      }
      if (v == integral)
      {
        integralFraction = p.stats.OnCurveFraction();
      }
      Done("noisy curve: project the input points, " + VariantName(v));
    }
    checks.push_back({ "noisy_curve.integral_on_curve_fraction",
      "Fig. 2: almost all input points project to the curve with the integral variant (h = 5)", integralFraction,
      ">= " + Fixed(kNoisyCurveMinFraction, 2), integralFraction >= kNoisyCurveMinFraction });
    checks.push_back({ "noisy_curve.levin_on_curve_fraction",
      "Fig. 1: with Levin's MLS some input points lie outside the domain", levinFraction,
      "< integral's " + Fixed(integralFraction, 4), levinFraction < integralFraction });

    // Figure 7: delta on the noisy curve (n is not needed: the cheap center-of-mass sampler).
    {
      vtkSmartPointer<vtkImageData> field = SampleField(noisy, com, kDeltaGridSpacing);
      Label(field, "delta", noisy.h);
      std::vector<double> levels;
      for (int k = -8; k <= 10; ++k)
      {
        levels.push_back(noisy.h * noisy.h * std::pow(2.0, 0.5 * k)); // h^2 / 16 .. 32 h^2, ratio sqrt 2
      }
      const DeltaStats ds = MeasureDelta(field, noisy);
      Write(field, "fig07_delta.vti");
      Write(Contours(field, "Delta", levels), "fig07_delta_contours.vtp");
      Done("fig07: delta on a grid, iso-contours");
      std::printf("             delta >= d^2 (d: distance to the nearest point) at %lld of %lld samples; delta / d^2 in\n"
                  "             [%.3f, %.3f] where d >= 2.5 h; %lld local minima of delta, all within %.2f h of a point\n",
        static_cast<long long>(ds.aboveSquaredDistance), static_cast<long long>(ds.samples), ds.farRatioMin,
        ds.farRatioMax, static_cast<long long>(ds.minima), ds.minimaMaxDistance);
    }
    // Figure 8 (PaperFiguresExtra.cxx): n across the noisy band.
    const std::vector<BandMeasure> band = Figure8(noisy, checks);

    // ---- Figure 6: the corner ------------------------------------------------------------------
    const Scene corner = MakeCornerScene();
    Label(corner.cloud, "corner", corner.h);
    Write(corner.cloud, "corner_cloud.vtp");
    vtkSmartPointer<vtkPolyData> cornerStarts = UniformStarts(corner, kCornerMinStarts, kStartMargin, kCornerStartSeed);
    Write(cornerStarts, "fig06_starts.vtp");
    vtkIdType integralSpurious = 0;
    std::vector<std::pair<int, vtkIdType>> spuriousByVariant;
    std::vector<CornerBreakdown> cornerBreakdown;
    for (int v : AllVariants())
    {
      const Projection p = Project(corner, v, cornerStarts);
      Row r;
      r.scene = "corner (Fig. 6)";
      r.h = corner.h;
      r.starts = std::to_string(kCornerMinStarts) + " uniform, box + 3 h";
      r.stats = p.stats;
      rows.push_back(r);
      spuriousByVariant.emplace_back(v, p.stats.spurious);
      if (v == integral)
      {
        integralSpurious = p.stats.spurious;
      }
      cornerBreakdown.push_back(BreakDownCorner(corner, v, p.points));
      Write(DomainAtStarts(cornerStarts, p.points), "domain_corner_" + VariantName(v) + ".vtp");
      const bool figure = std::find(figure6Variants.begin(), figure6Variants.end(), v) != figure6Variants.end();
      if (figure)
      {
        Label(p.points, VariantTitle(v), corner.h);
        Write(p.points, "fig06_" + VariantName(v) + "_surface_points.vtp");
      }
      Done("corner: project " + std::to_string(kCornerMinStarts) + " random starts, " + VariantName(v));
      if (figure)
      {
        // The mesher's polylines over the same end points (no second projection).
        FigureMesh(corner, v, p.points, "fig06_" + VariantName(v), "corner", checks);
      }
    }
    const vtkIdType cornerStartCount = cornerStarts->GetNumberOfPoints();
    checks.push_back({ "corner.start_points", "uniform random starts in the corner's bounding box grown by 3 h",
      static_cast<double>(cornerStartCount), ">= " + std::to_string(kCornerMinStarts),
      cornerStartCount >= kCornerMinStarts });
    const double integralSpuriousFraction = double(integralSpurious) / double(cornerStartCount);
    checks.push_back({ "corner.integral_spurious_fraction",
      "Fig. 6: the integral variant is reasonable even near sharp corners (spurious points / starts)",
      integralSpuriousFraction, "<= " + Fixed(kCornerMaxSpuriousFraction, 2),
      integralSpuriousFraction <= kCornerMaxSpuriousFraction });
    for (const auto& [v, count] : spuriousByVariant)
    {
      if (v == levin || v == com)
      {
        checks.push_back({ "corner." + VariantName(v) + "_spurious_points",
          "Fig. 6: " + VariantTitle(v) + " produces more spurious surface points than the integral variant",
          static_cast<double>(count), "> integral's " + std::to_string(integralSpurious), count > integralSpurious });
      }
      else if (pss::needsNormals(static_cast<pss::Variant>(v)))
      {
        // Beyond the paper: normals do not bound a fit to its data; APSS's and RIMLS's local fits
        // carry the arms on past their ends and past the apex, as the centre of mass's planes do.
        checks.push_back({ "corner." + VariantName(v) + "_spurious_points",
          "beyond the paper: " + VariantTitle(v) +
            ", though it fits normals, still has spurious surface points past the arms' ends and the apex",
          static_cast<double>(count), "> integral's " + std::to_string(integralSpurious), count > integralSpurious });
      }
    }
    for (int v : figure6Variants)
    {
      vtkSmartPointer<vtkImageData> field = SampleField(corner, v, kCornerGridSpacing);
      Write(field, "fig06_" + VariantName(v) + "_field.vti");
      vtkSmartPointer<vtkPolyData> lines = Streamlines(field, corner, 1.5, 2.5);
      Write(lines, "fig06_" + VariantName(v) + "_streamlines.vtp");
      Write(EnergyContours(field, 10), "fig06_" + VariantName(v) + "_contours.vtp");
      // Glyphs on a lattice of spacing 2 h over the start box.
      const std::vector<double> b = GrownBounds(corner, kStartMargin);
      std::vector<pss::Vec3> samples;
      for (double y = b[2] + corner.h; y < b[3]; y += 2.0 * corner.h)
      {
        for (double x = 0.0; x < b[1]; x += 2.0 * corner.h)
        {
          samples.emplace_back(x, y, 0.0);
          if (x > 0.0)
          {
            samples.emplace_back(-x, y, 0.0);
          }
        }
      }
      const Glyphs g = EnergyGlyphs(corner, v, samples, 0.8, 0.6);
      Write(g.glyphs, "fig06_" + VariantName(v) + "_glyphs.vtp");
      Write(g.fits, "fig06_" + VariantName(v) + "_fits.vtp");
      Done("fig06: field, streamlines, contours, glyphs, " + VariantName(v));
    }

    // ---- Figures 9 and 10: the noisy curve at h = 10 -------------------------------------------
    const Scene wide = MakeNoisyCurveScene(10.0);
    vtkSmartPointer<vtkPolyData> wideStarts = UniformStarts(wide, kWideStarts, kStartMargin, kWideStartSeed);
    for (int v : AllVariants())
    {
      const Projection minima = Project(wide, v, wideStarts);
      Row r;
      r.scene = "noisy curve h=10 (Fig. 9, 10)";
      r.h = wide.h;
      r.starts = std::to_string(kWideStarts) + " uniform, box + 3 h";
      r.stats = minima.stats;
      rows.push_back(r);
      Write(DomainAtStarts(wideStarts, minima.points), "domain_noisy10_" + VariantName(v) + ".vtp");
      Done("noisy curve h = 10: project " + std::to_string(kWideStarts) + " random starts, " + VariantName(v));
      if (v != levin && v != integral)
      {
        continue;
      }
      const std::string stem = v == levin ? "fig09_levin" : "fig10_integral";
      const Projection maxima = Project(wide, v, wideStarts, true);
      vtkSmartPointer<vtkPolyData> minimaPoints = Extrema(minima.points, 1);
      vtkSmartPointer<vtkPolyData> maximaPoints = Extrema(maxima.points, 2);
      Write(minimaPoints, stem + "_minima.vtp");
      Write(maximaPoints, stem + "_maxima.vtp");
      Done(stem.substr(0, 5) + ": seek maxima from the same starts (" + std::to_string(minimaPoints->GetNumberOfPoints()) +
        " minima, " + std::to_string(maximaPoints->GetNumberOfPoints()) + " maxima)");
      FigureMesh(wide, v, minima.points, stem, "noisy10", checks);
      vtkSmartPointer<vtkImageData> field = SampleField(wide, v, kWideGridSpacing);
      Write(field, stem + "_field.vti");
      Write(Streamlines(field, wide, 1.5, 3.0), stem + "_streamlines.vtp");
      Write(EnergyContours(field, 12), stem + "_contours.vtp");
      vtkSmartPointer<vtkPolyData> singular = NearSingularPoints(field, 0.05);
      Write(singular, stem + "_singular.vtp");
      Done(stem.substr(0, 5) + ": field, streamlines, contours, " + std::to_string(singular->GetNumberOfPoints()) +
        " near-singular points");
    }

    PrintAndWriteTable(rows);
    PrintAndWriteCornerBreakdown(cornerBreakdown);
    PrintAndWriteFigure3(figure3);
    PrintAndWriteNoisyBand(band);
    const bool allPass = PrintAndWriteChecks(checks);
    const double computeSeconds = Since(start);
    std::printf("\ncomputed in %.1f s; data in %s\n", computeSeconds, OutDir.string().c_str());
    if (opt.render)
    {
      Render(opt);
    }
    std::printf("total wall time %.1f s\n", Since(start));
    if (opt.check && !allPass)
    {
      std::fprintf(stderr, "pss-paper-figures: a checked number missed its bound (see above)\n");
      return 1;
    }
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "pss-paper-figures: error: " << e.what() << '\n';
    return 1;
  }
}

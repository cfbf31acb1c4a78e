// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PaperOutput.h
 * @brief What every figure of the main demo (pss-paper-figures) shares: writing its VTK files,
 *        labelling them for the renderer, sampling fields and energy glyphs through the filters,
 *        the checked claims (paper_checks.json) and the step timer.
 */
#ifndef PaperOutput_h
#define PaperOutput_h

#include "PaperScenes.h"

#include "vtkImageData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace pss_paper
{

/// The folder every file of the demo is written to (--out).
extern std::filesystem::path OutDir;

/// Writes @p data as VTK XML (appended, zlib) to OutDir / @p name, through a temporary name.
void Write(vtkPolyData* data, const std::string& name);
void Write(vtkImageData* data, const std::string& name);

/// A title and the h of a figure's data, as field data (the renderer reads them).
void Label(vtkDataObject* data, const std::string& title, double h);

/// The @p q quantile (0..1) of @p v (0 when empty).
double Percentile(std::vector<double> v, double q);

/// Adds `LogEnergy` = log10 of the `Energy` array, floored at its smallest positive value (Levin's
/// energy may underflow to 0 far away).
void AddLogEnergy(vtkDataSet* field);

/**
 * n, e, delta, g, stability on a grid over the cloud's bounds grown by 3 h, n oriented for stream
 * tracers (PROPAGATE), plus `LogEnergy`.
 */
vtkSmartPointer<vtkImageData> SampleField(const Scene& scene, int variant, double spacingInH);

struct Glyphs
{
  vtkSmartPointer<vtkPolyData> glyphs;
  vtkSmartPointer<vtkPolyData> fits;
};

/// Energy plots x + c e(x, a) a (each glyph scaled on its own) and best-fitting lines at @p samples.
Glyphs EnergyGlyphs(const Scene& scene, int variant, const std::vector<pss::Vec3>& samples, double glyphSizeInH,
  double segmentLengthInH);

/// A claim of the paper as a number and its bound (a row of paper_checks.json).
struct Check
{
  std::string name;
  std::string claim;
  double value = 0.0;
  std::string bound;
  bool pass = false;
};

/// @p v with @p digits decimals; "-" for NaN, "none" for infinity.
std::string Fixed(double v, int digits);
std::string JsonNumber(double v);
std::string JsonString(const std::string& s);

/// Prints the checks and writes OutDir/paper_checks.json; true when every check passes.
bool PrintAndWriteChecks(const std::vector<Check>& checks);

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0);
/// When the program started (the first step's reference).
extern Clock::time_point ProgramStart;
/// Prints one line per finished step: the time since the start and the step's own time.
void Done(const std::string& what);

} // namespace pss_paper

#endif

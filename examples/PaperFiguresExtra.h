// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PaperFiguresExtra.h
 * @brief Figures 3, 4 and 8 of the main demo (pss-paper-figures), and the mesher's polylines
 *        over Figures 6, 9 and 10: their VTK files, their tables and their checked claims. The
 *        measurements are PaperMeasures.h's, shared with tests/paper.
 */
#ifndef PaperFiguresExtra_h
#define PaperFiguresExtra_h

#include "PaperMeasures.h"
#include "PaperOutput.h"

#include <string>
#include <vector>

namespace pss_paper
{

/// Figure 3 as numbers: the two planes' energies above the line and where they cross.
struct Figure3Result
{
  PlaneEnergies table;          ///< at 0.25 h, 0.5 h, ... 2 h above the column x = 0
  double crossingLow = 0.0;     ///< smallest crossing height over LineColumns, in h
  double crossingHigh = 0.0;    ///< largest
  int columns = 0;
};

/**
 * Figure 3: for x at heights 0.25 h .. 2 h above the line (Levin's MLS, column x = 0), the plane
 * through x parallel to the line and the one perpendicular to it, the cloud points with their
 * weights theta(x, p) and their distances to each plane (fig03_*.vtp), and a chart of both
 * energies against the height (fig03_chart.vtp); the crossing height on every column of
 * LineColumns. Appends the check fig03.plane_crossing_over_h.
 */
Figure3Result Figure3(const Scene& line, std::vector<Check>& checks);

/// Figure 4: the legend of the circular plots, three glyphs of Levin's energy above the line (a
/// strong, a weak and an unstable minimum) with their stability (fig04_*.vtp, fig04_legend.csv).
void Figure4(const Scene& line);

/**
 * Figure 8: on the noisy curve (h = 5), for Levin's MLS and the integral variant, energy glyphs
 * on a lattice over the noisy end, best-fitting segments on a finer lattice, e(x, n(x)) sampled
 * as an image, the band and the paths across it with the points where n passes 45 degrees; the
 * band measures for all five definitions. Appends the three fig08 checks.
 */
std::vector<BandMeasure> Figure8(const Scene& noisy, std::vector<Check>& checks);

/**
 * The polylines of vtkPointSetSurfaceMesher for @p variant on @p scene (MeshScene), written as
 * @p stem + "_mesh.vtp", and their agreement with @p ends, the end points of the projections the
 * figure already made (Project's output with `Outcome`; MeasureMeshAgreement). Reports the counts
 * with Done and appends the check @p checkPrefix + "." + variant + "_mesh_agrees".
 */
MeshAgreement FigureMesh(const Scene& scene, int variant, vtkPolyData* ends, const std::string& stem,
  const std::string& checkPrefix, std::vector<Check>& checks);

/// Prints Figure 3's energies and writes fig03_plane_energies.csv.
void PrintAndWriteFigure3(const Figure3Result& r);
/// Prints the band table of Figure 8 and writes fig08_noisy_band.csv.
void PrintAndWriteNoisyBand(const std::vector<BandMeasure>& rows);

} // namespace pss_paper

#endif

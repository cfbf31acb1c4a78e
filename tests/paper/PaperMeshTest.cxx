// SPDX-License-Identifier: BSD-3-Clause
// The mesher's polylines on the paper's 2D scenes (Figures 6 and 10) against the demo's own
// projections: every end point the demo counts as on the curve lies near a polyline, and every
// polyline piece has end points of the demo near it (no invented piece). The meshing and the
// measurement are the demo's (examples/PaperMeasures.h).
#include "PaperMeasures.h"
#include "PaperScenes.h"

#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <iostream>

namespace
{

using namespace pss_paper;

void CheckAgainstProjections(const Scene& scene, vtkPolyData* starts)
{
  for (int variant : AllVariants())
  {
    SCOPED_TRACE(scene.name + " " + VariantName(variant));
    const Projection projection = Project(scene, variant, starts);
    ASSERT_NE(projection.points->GetPointData()->GetArray("Outcome"), nullptr);
    const MeshAgreement agreement = MeasureMeshAgreement(MeshScene(scene, variant), projection.points, scene.h);
    ASSERT_GT(agreement.segments, 0);
    std::cout << scene.name << " " << VariantName(variant) << ": " << Describe(agreement) << "\n";
    EXPECT_EQ(agreement.onCurveFar, 0) << "farthest " << agreement.farthestOnCurve << " h";
    EXPECT_EQ(agreement.piecesWithoutEnds, 0)
      << "a polyline piece with no projection ending within 0.5 h, at (" << agreement.pieceWithoutEnds[0] << ", "
      << agreement.pieceWithoutEnds[1] << ")";
  }
}

} // namespace

TEST(PaperMesh, CornerPolylinesAgreeWithTheProjections)
{
  const Scene corner = MakeCornerScene();
  CheckAgainstProjections(corner, UniformStarts(corner, kCornerMinStarts, kStartMargin, kCornerStartSeed));
}

TEST(PaperMesh, NoisyCurvePolylinesAgreeWithTheProjections)
{
  const Scene curve = MakeNoisyCurveScene(10.0);
  CheckAgainstProjections(curve, UniformStarts(curve, kWideStarts, kStartMargin, kWideStartSeed));
}

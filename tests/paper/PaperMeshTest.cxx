// SPDX-License-Identifier: BSD-3-Clause
// The mesher's polylines on the paper's 2D scenes (Figures 6 and 10) against the demo's own
// projections: every end point the demo counts as on the curve lies near a polyline, and every
// polyline piece has end points of the demo near it (no invented piece).
#include "PaperScenes.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceMesher.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <numeric>
#include <vector>

namespace
{

using namespace pss_paper;

struct Segment
{
  std::array<double, 2> a;
  std::array<double, 2> b;
  vtkIdType piece;
};

double DistanceToSegment(const double p[3], const Segment& s)
{
  const double dx = s.b[0] - s.a[0];
  const double dy = s.b[1] - s.a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p[0] - s.a[0]) * dx + (p[1] - s.a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (s.a[0] + t * dx), p[1] - (s.a[1] + t * dy));
}

// The polylines' segments, each with its connected piece.
std::vector<Segment> Segments(vtkPolyData* mesh, vtkIdType& pieces)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<vtkIdType> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](vtkIdType x) {
    while (parent[x] != x)
    {
      x = parent[x] = parent[parent[x]];
    }
    return x;
  };
  std::vector<std::array<vtkIdType, 2>> ids;
  vtkIdType count = 0;
  const vtkIdType* cell = nullptr;
  for (mesh->GetLines()->InitTraversal(); mesh->GetLines()->GetNextCell(count, cell);)
  {
    ids.push_back({ cell[0], cell[1] });
    parent[find(cell[0])] = find(cell[1]);
  }
  std::vector<Segment> out;
  std::vector<char> root(static_cast<std::size_t>(n), 0);
  for (const auto& e : ids)
  {
    double a[3];
    double b[3];
    mesh->GetPoint(e[0], a);
    mesh->GetPoint(e[1], b);
    out.push_back({ { a[0], a[1] }, { b[0], b[1] }, find(e[0]) });
    root[find(e[0])] = 1;
  }
  pieces = std::count(root.begin(), root.end(), 1);
  return out;
}

void CheckAgainstProjections(const Scene& scene, vtkPolyData* starts)
{
  for (int variant : AllVariants())
  {
    SCOPED_TRACE(scene.name + " " + VariantName(variant));
    const Projection projection = Project(scene, variant, starts);
    vtkNew<vtkPointSetSurfaceMesher> mesher;
    mesher->SetSurface(MakeSurface(scene, variant));
    // Levin's and the normalized MLS have a narrow domain (h / sqrt 2 about the curve): every corner
    // of a cell crossing the curve must lie in it.
    const bool narrow = variant == vtkPointSetSurface::LEVIN_MLS || variant == vtkPointSetSurface::NORMALIZED_MLS;
    mesher->SetCellSize(narrow ? 0.25 : 0.5);
    mesher->SetInputData(scene.cloud);
    mesher->Update();
    vtkIdType pieces = 0;
    const std::vector<Segment> segments = Segments(mesher->GetOutput(), pieces);
    ASSERT_FALSE(segments.empty());
    vtkPolyData* ends = projection.points;
    vtkDataArray* outcome = ends->GetPointData()->GetArray("Outcome");
    ASSERT_NE(outcome, nullptr);
    const double near = kOnCurveDistance * scene.h;
    std::vector<char> pieceSeen(static_cast<std::size_t>(mesher->GetOutput()->GetNumberOfPoints()), 0);
    vtkIdType onCurve = 0;
    vtkIdType onCurveFar = 0;
    double worst = 0.0;
    for (vtkIdType i = 0; i < ends->GetNumberOfPoints(); ++i)
    {
      const int o = static_cast<int>(outcome->GetComponent(i, 0));
      if (o == NOT_CONVERGED)
      {
        continue;
      }
      double p[3];
      ends->GetPoint(i, p);
      double best = 1e300;
      const Segment* nearest = nullptr;
      for (const Segment& s : segments)
      {
        const double d = DistanceToSegment(p, s);
        if (d < best)
        {
          best = d;
          nearest = &s;
        }
      }
      if (best <= near)
      {
        pieceSeen[static_cast<std::size_t>(nearest->piece)] = 1;
      }
      if (o == ON_CURVE)
      {
        ++onCurve;
        onCurveFar += best > near ? 1 : 0;
        worst = std::max(worst, best);
      }
    }
    std::cout << scene.name << " " << VariantName(variant) << ": " << segments.size() << " segments in " << pieces
              << " pieces; " << onCurve << " end points on the curve, " << onCurveFar
              << " of them farther than 0.5 h from a polyline (farthest " << worst / scene.h << " h)\n";
    EXPECT_EQ(onCurveFar, 0) << "farthest " << worst / scene.h << " h";
    for (const Segment& s : segments)
    {
      EXPECT_TRUE(pieceSeen[static_cast<std::size_t>(s.piece)])
        << "a polyline piece with no projection ending within 0.5 h, at (" << s.a[0] << ", " << s.a[1] << ")";
    }
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

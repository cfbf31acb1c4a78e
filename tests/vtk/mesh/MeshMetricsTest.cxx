// SPDX-License-Identifier: BSD-3-Clause
/**
 * The reference-free mesh metric (pss_metrics::MeasureWithoutReference) on meshes built by hand,
 * whose answers are known: a triangulated square grid whose cloud is its own vertices (spacing 1)
 * with a small hole cut where the scan has data (one small hole), a big hole (none), a small hole
 * where the scan has no data either (none), two separate squares (two pieces), a mesh lifted far
 * above its cloud (all of it far) and a mesh reaching past the edge of its cloud (the part beyond
 * three spacings far); the cloud points a big hole leaves farther than two spacings from the mesh
 * are uncovered; coincident cloud points (spacing 0) take the median spacing.
 */
#include "MeshMetrics.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace
{

// An n x n grid of unit cells at height z, from (x0, 0), two triangles per cell, without the
// cells for which @p cut(i, j) is true.
void AddGrid(vtkPoints* points, vtkCellArray* triangles, int n, double x0, double z,
  const std::function<bool(int, int)>& cut = [](int, int) { return false; })
{
  const vtkIdType base = points->GetNumberOfPoints();
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      points->InsertNextPoint(x0 + i, j, z);
    }
  }
  auto id = [&](int i, int j) { return base + static_cast<vtkIdType>(j) * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      if (cut(i, j))
      {
        continue;
      }
      const vtkIdType a[3] = { id(i, j), id(i + 1, j), id(i + 1, j + 1) };
      const vtkIdType b[3] = { id(i, j), id(i + 1, j + 1), id(i, j + 1) };
      triangles->InsertNextCell(3, a);
      triangles->InsertNextCell(3, b);
    }
  }
}

vtkSmartPointer<vtkPolyData> Mesh(vtkPoints* points, vtkCellArray* triangles)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

// The grid's vertices (n + 1)^2 at height 0 from x = 0, without those where @p drop(i, j).
vtkSmartPointer<vtkPoints> GridCloud(int n, const std::function<bool(int, int)>& drop = [](int, int) { return false; })
{
  auto cloud = vtkSmartPointer<vtkPoints>::New();
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      if (!drop(i, j))
      {
        cloud->InsertNextPoint(i, j, 0.0);
      }
    }
  }
  return cloud;
}

pss_metrics::ReferenceFreeQuality Measure(vtkPolyData* mesh, vtkPoints* cloud)
{
  pss_metrics::ReferenceFreeOptions options;
  options.samples = 20000;
  return pss_metrics::MeasureWithoutReference(mesh, cloud, options);
}

// The local spacing of a unit square grid: its 12th neighbour is 2 away, and 2 sqrt(pi / 12) is the
// side of the square each sample covers by that count.
const double kGridSpacing = 2.0 * std::sqrt(M_PI / 12.0);

// Cells (i, j) with lo <= i, j < hi.
std::function<bool(int, int)> Block(int lo, int hi)
{
  return [lo, hi](int i, int j) { return i >= lo && i < hi && j >= lo && j < hi; };
}

} // namespace

TEST(MeshMetricsWithoutReference, WholeGridIsClean)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 0.0);
  const auto q = Measure(Mesh(points, triangles), GridCloud(30));
  EXPECT_EQ(q.triangles, 2 * 30 * 30);
  EXPECT_NEAR(q.area, 900.0, 1e-9);
  EXPECT_EQ(q.components, 1u);
  EXPECT_DOUBLE_EQ(q.largestComponentShare, 1.0);
  EXPECT_EQ(q.boundaryEdges, 120u);
  EXPECT_EQ(q.cloudPoints, 31u * 31u);
  EXPECT_DOUBLE_EQ(q.medianSpacing, kGridSpacing);
  ASSERT_EQ(q.loops.size(), 1u) << "the square's border";
  EXPECT_NEAR(q.loops[0].length, 120.0, 1e-9);
  EXPECT_FALSE(q.loops[0].small) << "120 spacings around";
  EXPECT_EQ(q.smallHoles, 0u);
  EXPECT_EQ(q.farShare, 0.0);
  EXPECT_EQ(q.uncoveredShare, 0.0);
}

// Thirteen coincident cloud points half a cell above the grid: their own spacing is 0 (their 12
// nearest are each other), so they take the median spacing and count as covered (0.5 from the
// mesh, within two spacings), as the scan's other points do.
TEST(MeshMetricsWithoutReference, CoincidentPointsTakeTheMedianSpacing)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 0.0);
  auto cloud = GridCloud(30);
  for (int copy = 0; copy < 13; ++copy)
  {
    cloud->InsertNextPoint(15.5, 15.5, 0.5);
  }
  const auto q = Measure(Mesh(points, triangles), cloud);
  EXPECT_EQ(q.cloudPoints, 31u * 31u + 13u);
  EXPECT_DOUBLE_EQ(q.medianSpacing, kGridSpacing);
  EXPECT_EQ(q.uncoveredShare, 0.0);
  EXPECT_EQ(q.farShare, 0.0);
}

// A 2 x 2 cell hole (8 spacings around) where every cloud point is still there: one small hole.
TEST(MeshMetricsWithoutReference, SmallHoleWhereTheScanHasData)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 0.0, Block(14, 16));
  const auto q = Measure(Mesh(points, triangles), GridCloud(30));
  EXPECT_EQ(q.components, 1u);
  EXPECT_EQ(q.boundaryEdges, 120u + 8u);
  ASSERT_EQ(q.loops.size(), 2u);
  EXPECT_EQ(q.smallHoles, 1u);
  EXPECT_EQ(q.smallHoleEdges, 8u);
  const pss_metrics::HoleLoop& hole = q.loops[1];
  EXPECT_TRUE(hole.small);
  EXPECT_EQ(hole.edges, 8u);
  EXPECT_NEAR(hole.length, 8.0, 1e-12);
  EXPECT_DOUBLE_EQ(hole.spacing, kGridSpacing);
  EXPECT_NEAR(hole.centre[0], 15.0, 1e-12);
  EXPECT_NEAR(hole.centre[1], 15.0, 1e-12);
  EXPECT_NEAR(hole.cloudGap, 0.0, 1e-12) << "the grid point (15, 15) is in the cloud";
  EXPECT_EQ(q.farShare, 0.0) << "the hole removes area, it adds none";
  EXPECT_EQ(q.uncoveredShare, 0.0) << "the hole's middle point is one spacing from its border";
}

// A 12 x 12 cell hole is 48 spacings around: past the small-hole length, not counted.
TEST(MeshMetricsWithoutReference, BigHoleIsNotSmall)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 0.0, Block(9, 21));
  const auto q = Measure(Mesh(points, triangles), GridCloud(30));
  ASSERT_EQ(q.loops.size(), 2u);
  EXPECT_EQ(q.loops[1].edges, 48u);
  EXPECT_EQ(q.smallHoles, 0u);
  // The cloud points at least 3 from the hole's border (7 x 7 of them) are farther than 2
  // spacings (2.05) from the mesh; those 2 from it are not.
  EXPECT_DOUBLE_EQ(q.uncoveredShare, 49.0 / (31.0 * 31.0));
  // Just below the length limit it is small again: 9 x 9 cells, 36 spacings around.
  vtkNew<vtkPoints> points9;
  vtkNew<vtkCellArray> triangles9;
  AddGrid(points9, triangles9, 30, 0.0, 0.0, Block(10, 19));
  EXPECT_EQ(Measure(Mesh(points9, triangles9), GridCloud(30)).smallHoles, 1u);
}

// A 6 x 6 cell hole whose inside the scan did not see (no cloud point within 3 of its centre):
// the mesh is right to leave it open.
TEST(MeshMetricsWithoutReference, HoleWhereTheScanHasNoDataIsNotSmall)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 0.0, Block(12, 18));
  const auto inside = [](int i, int j) { return i > 12 && i < 18 && j > 12 && j < 18; };
  const auto q = Measure(Mesh(points, triangles), GridCloud(30, inside));
  ASSERT_EQ(q.loops.size(), 2u);
  EXPECT_NEAR(q.loops[1].cloudGap, 3.0, 1e-12);
  EXPECT_EQ(q.smallHoles, 0u);
  // The same hole over the full cloud is a small one.
  EXPECT_EQ(Measure(Mesh(points, triangles), GridCloud(30)).smallHoles, 1u);
}

TEST(MeshMetricsWithoutReference, TwoSeparateSquaresAreTwoPieces)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 12, 0.0, 0.0);
  AddGrid(points, triangles, 12, 20.0, 0.0);
  vtkNew<vtkPoints> cloud;
  for (double x0 : { 0.0, 20.0 })
  {
    for (int j = 0; j <= 12; ++j)
    {
      for (int i = 0; i <= 12; ++i)
      {
        cloud->InsertNextPoint(x0 + i, j, 0.0);
      }
    }
  }
  const auto q = Measure(Mesh(points, triangles), cloud);
  EXPECT_EQ(q.components, 2u);
  EXPECT_NEAR(q.largestComponentShare, 0.5, 1e-12);
  EXPECT_EQ(q.loops.size(), 2u);
  EXPECT_EQ(q.smallHoles, 0u) << "each border is 48 spacings around";
  EXPECT_EQ(q.farShare, 0.0);
}

TEST(MeshMetricsWithoutReference, MeshLiftedFarFromItsCloudIsAllFar)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 10.0);
  const auto q = Measure(Mesh(points, triangles), GridCloud(30));
  EXPECT_EQ(q.farShare, 1.0);
  // Over a cloud that reaches 5 beyond the mesh on every side (so that every point near it has a
  // whole grid around it): lifted by 2.9 spacings it is all within 3 of some point; by 3.1, none
  // of it is.
  auto wide = vtkSmartPointer<vtkPoints>::New();
  for (int j = -5; j <= 35; ++j)
  {
    for (int i = -5; i <= 35; ++i)
    {
      wide->InsertNextPoint(i, j, 0.0);
    }
  }
  vtkNew<vtkPoints> near;
  vtkNew<vtkCellArray> nearTriangles;
  AddGrid(near, nearTriangles, 30, 0.0, 2.9 * kGridSpacing);
  EXPECT_EQ(Measure(Mesh(near, nearTriangles), wide).farShare, 0.0);
  vtkNew<vtkPoints> beyond;
  vtkNew<vtkCellArray> beyondTriangles;
  AddGrid(beyond, beyondTriangles, 30, 0.0, 3.1 * kGridSpacing);
  EXPECT_EQ(Measure(Mesh(beyond, beyondTriangles), wide).farShare, 1.0);
}

// The cloud covers x <= 15 of a 30 x 30 mesh: the mesh beyond three spacings past the last column
// of points is far. Those points see fewer neighbours, so their spacing lies between the grid's
// and sqrt(5) sqrt(pi / 12) (their 12th neighbour is sqrt(5) away): the far share is between
// (15 - 3 x 1.144) / 30 and (15 - 3 x 1.023) / 30, up to the sampling.
TEST(MeshMetricsWithoutReference, MeshPastTheCloudsEdge)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  AddGrid(points, triangles, 30, 0.0, 0.0);
  vtkSmartPointer<vtkPoints> cloud = GridCloud(30, [](int i, int) { return i > 15; });
  const auto q = Measure(Mesh(points, triangles), cloud);
  const double edgeSpacing = std::sqrt(5.0) * std::sqrt(M_PI / 12.0);
  EXPECT_GE(q.farShare, (15.0 - 3.0 * edgeSpacing) / 30.0 - 0.005);
  EXPECT_LE(q.farShare, (15.0 - 3.0 * kGridSpacing) / 30.0 + 0.005);
  // Non-finite cloud points (a depth frame's invalid pixels) are left out, not counted.
  cloud->InsertNextPoint(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  const auto withNaN = Measure(Mesh(points, triangles), cloud);
  EXPECT_EQ(withNaN.cloudPoints, q.cloudPoints);
  EXPECT_EQ(withNaN.farShare, q.farShare);
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * The mesher on a simulated depth-camera frame, with every default (the automatic procedure, which
 * takes the plane procedure there) and with the extremal procedure (vtkPointSetSurfaceCloudSource's
 * DEPTH_CAMERA, seed 1: a table, a box, a cylinder and a sphere seen by a structured-light sensor
 * with depth noise sigma0 z^2 and disparity quantized to 1/8 pixel), measured against the exact
 * scene (pss::distanceToDepthScene, pss::traceDepthImage):
 * - every surface that at least 2,000 pixels see is meshed (a mesh vertex near nearly all its points);
 * - the vertices lie on the true surfaces: their median distance is at most half the sensor's
 *   noise sigma at their depth;
 * - no triangle bridges a depth discontinuity: a triangle from a foreground object to the
 *   background would cross the empty space between them, so every triangle's centre must lie
 *   within 3 local h (the scale of the cloud point nearest to it) of a true surface;
 * - boundary edges only where the frame ends or its data do: each lies, in the image, within 3 h
 *   of the frame border, of a pixel without a measurement (no hit, out of range, projector
 *   shadow) or of a depth discontinuity (4-neighbour pixels whose true depths differ by more than
 *   3%), or within 1 h of a step of the measured depths (4-neighbour pixels whose measured points
 *   lie more than 3 local point spacings apart, where a pixel's footprint is about one).
 * Both runs include the automatic trim (2.5 local spacings): it cuts the mesh back from its
 * border, and opens a hole where the mesh spans a gap of the data between the stripes of the
 * quantized depths wider than 3.1 spacings (the last category); a hole in surface whose pixels
 * hold evenly spaced points would be counted elsewhere, and fail.
 */
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceMesher.h"
#include "vtkPolyData.h"

#include "pss/DepthCamera.h"
#include "pss/PointIndex.h"
#include "vtkPointSetSurface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <vector>

namespace
{

using pss::Vec3;

double Median(std::vector<double> values)
{
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

Vec3 PointOf(vtkPolyData* pd, vtkIdType i)
{
  double x[3];
  pd->GetPoint(i, x);
  return Vec3(x[0], x[1], x[2]);
}

// Why a boundary edge may be there, read from the true image and the measured frame (one point
// per pixel, row-major) around a pixel.
struct ImageTruth
{
  pss::DepthCameraSpec camera;
  std::vector<pss::DepthPixelTruth> pixels;
  std::vector<Vec3> measured;

  std::size_t pixel(int row, int column) const
  {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(column);
  }
  const pss::DepthPixelTruth& at(int row, int column) const { return pixels[pixel(row, column)]; }

  // 0: the frame border, 1: an unmeasured pixel, 2: a depth discontinuity, within @p radius
  // pixels of (@p row, @p column); -1: none of them.
  int reason(double row, double column, int radius) const
  {
    const int r0 = static_cast<int>(std::floor(row)) - radius, r1 = static_cast<int>(std::floor(row)) + radius;
    const int c0 = static_cast<int>(std::floor(column)) - radius, c1 = static_cast<int>(std::floor(column)) + radius;
    if (r0 < 0 || c0 < 0 || r1 >= camera.height || c1 >= camera.width)
    {
      return 0;
    }
    int found = -1;
    for (int r = r0; r <= r1; ++r)
    {
      for (int c = c0; c <= c1; ++c)
      {
        const pss::DepthPixelTruth& p = at(r, c);
        if (p.state != pss::PixelState::Valid)
        {
          return 1;
        }
        for (const auto& [dr, dc] : { std::pair<int, int>{ 0, 1 }, std::pair<int, int>{ 1, 0 } })
        {
          if (r + dr <= r1 && c + dc <= c1)
          {
            const pss::DepthPixelTruth& q = at(r + dr, c + dc);
            if (q.state == pss::PixelState::Valid && std::abs(q.depth - p.depth) > 0.03 * std::min(p.depth, q.depth))
            {
              found = 2;
            }

          }
        }
      }
    }
    return found;
  }

  // True when two neighbouring pixels within @p radius of (@p row, @p column), both measured, hold
  // points farther apart than @p jump: a step of the quantized depths, which leaves a gap in the data.
  bool measuredJump(double row, double column, int radius, double jump) const
  {
    const int r0 = std::max(0, static_cast<int>(std::floor(row)) - radius);
    const int r1 = std::min(camera.height - 2, static_cast<int>(std::floor(row)) + radius);
    const int c0 = std::max(0, static_cast<int>(std::floor(column)) - radius);
    const int c1 = std::min(camera.width - 2, static_cast<int>(std::floor(column)) + radius);
    for (int r = r0; r <= r1; ++r)
    {
      for (int c = c0; c <= c1; ++c)
      {
        const Vec3& a = measured[pixel(r, c)];
        for (const Vec3& b : { measured[pixel(r, c + 1)], measured[pixel(r + 1, c)] })
        {
          if (a.allFinite() && b.allFinite() && (a - b).norm() > jump)
          {
            return true;
          }
        }
      }
    }
    return false;
  }
};

// Neighbouring pixels whose measured points lie farther apart than this many local point spacings
// (pss::estimateLocalSpacings: about one pixel's footprint) are a step of the measured depths.
constexpr double MeasuredStep = 3.0;

// Every check of the file comment on the frame meshed with @p procedure (every other default).
// Returns the mesher's UsedProcedure.
int CheckFrameMesh(int procedure)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToDepthCamera();
  source->SetSeed(1);
  vtkNew<vtkPointSetSurfaceMesher> mesher;
  mesher->SetProcedure(procedure);
  mesher->SetInputConnection(source->GetOutputPort());
  mesher->Update();
  vtkPolyData* frame = source->GetOutput();
  vtkPolyData* mesh = mesher->GetOutput();
  const double h = mesher->GetEffectiveScale();
  EXPECT_TRUE(mesher->GetSurface()->GetUsesPointScales()) << "a sensor frame takes a scale per point";
  EXPECT_EQ(mesher->GetUsedTrimDistance(), 2.5) << "the automatic trim runs on a sensor frame";
  vtkDataArray* trimmed = mesher->GetOutput()->GetFieldData()->GetArray("TrimmedTriangles");
  EXPECT_TRUE(trimmed && trimmed->GetTuple1(0) > 0) << "the trim cuts the mesh back somewhere on this frame";
  EXPECT_GT(mesh->GetNumberOfPolys(), 10000);
  if (mesh->GetNumberOfPolys() == 0)
  {
    return -1;
  }
  const double sigma0 = source->GetDepthNoise();
  std::cout << "frame " << frame->GetNumberOfPoints() << " pixels, median h " << h << ", mesh "
            << mesh->GetNumberOfPoints() << " vertices, " << mesh->GetNumberOfPolys() << " triangles\n";

  // On the surfaces: each vertex's distance to the scene in units of the noise at its depth.
  std::vector<double> ratios;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const Vec3 v = PointOf(mesh, i);
    ratios.push_back(pss::distanceToDepthScene(v) / (sigma0 * v.z() * v.z()));
  }
  const double medianRatio = Median(ratios);
  std::cout << "median vertex distance to the scene: " << medianRatio << " noise sigmas\n";
  EXPECT_LE(medianRatio, 0.5);

  // Every surface seen by 2,000 pixels or more is meshed: a mesh vertex within 1.5 h of at least
  // 90% of its points (the grid's cells are h wide; the mesh stops short of each surface's own
  // border by up to MaxDistance).
  pss::PointIndex meshIndex(
    [&] {
      std::vector<Vec3> v;
      for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
      {
        v.push_back(PointOf(mesh, i));
      }
      return v;
    }(),
    3);
  vtkDataArray* surfaceIds = frame->GetPointData()->GetArray("SurfaceId");
  if (surfaceIds == nullptr)
  {
    ADD_FAILURE() << "the frame has no SurfaceId array";
    return -1;
  }
  std::map<int, std::array<std::size_t, 2>> covered; // surface: {points, points near a vertex}
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i)
  {
    const Vec3 p = PointOf(frame, i);
    if (!std::isfinite(p.x()))
    {
      continue;
    }
    auto& c = covered[static_cast<int>(surfaceIds->GetComponent(i, 0))];
    ++c[0];
    c[1] += meshIndex.nearest(p).second <= 2.25 * h * h ? 1 : 0;
  }
  for (const auto& [surface, c] : covered)
  {
    const double share = static_cast<double>(c[1]) / static_cast<double>(c[0]);
    std::cout << pss::depthSurfaceName(static_cast<pss::DepthSurface>(surface)) << ": " << c[0]
              << " points, " << 100.0 * share << "% near the mesh\n";
    if (c[0] >= 2000)
    {
      EXPECT_GE(share, 0.9) << pss::depthSurfaceName(static_cast<pss::DepthSurface>(surface));
    }
  }

  // No bridge: every triangle's centre within 3 local h (the scale of the cloud point nearest to
  // it) of a true surface. Where a surface ends, the mesh may reach past its edge by up to
  // MaxDistance (1 local h); a bridge would cross the gap between two surfaces.
  const pss::PointIndex* cloudIndex = mesher->GetSurface()->GetIndex();
  if (cloudIndex == nullptr)
  {
    ADD_FAILURE() << "the surface kept no index";
    return -1;
  }
  double farthest = 0.0;
  const vtkIdType* ids = nullptr;
  vtkIdType count = 0;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
  {
    const Vec3 centre = (PointOf(mesh, ids[0]) + PointOf(mesh, ids[1]) + PointOf(mesh, ids[2])) / 3.0;
    const double local = cloudIndex->scale(cloudIndex->nearest(centre).first);
    farthest = std::max(farthest, pss::distanceToDepthScene(centre) / local);
  }
  std::cout << "farthest triangle centre from the scene: " << farthest << " local h\n";
  EXPECT_LE(farthest, 3.0);

  // Boundary edges, each sorted by the first reason found in the image within 3 local h of its
  // midpoint (the scale of the cloud point nearest to it: the cells, and so where the mesh's
  // border can fall, follow that scale).
  ImageTruth truth;
  truth.pixels = pss::traceDepthImage(truth.camera);
  std::map<std::pair<vtkIdType, vtkIdType>, int> uses;
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++uses[{ std::min(ids[k], ids[(k + 1) % 3]), std::max(ids[k], ids[(k + 1) % 3]) }];
    }
  }
  if (frame->GetNumberOfPoints() != static_cast<vtkIdType>(truth.pixels.size()))
  {
    ADD_FAILURE() << "the frame does not hold one point per pixel";
    return -1;
  }
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i)
  {
    truth.measured.push_back(PointOf(frame, i));
  }
  const std::vector<double> spacings = pss::estimateLocalSpacings(*cloudIndex);
  std::array<std::size_t, 5> reasons{}; // border, unmeasured, discontinuity, measured jump, none
  const double f = truth.camera.focalLength();
  for (const auto& [edge, n] : uses)
  {
    if (n != 1)
    {
      continue;
    }
    const Vec3 m = 0.5 * (PointOf(mesh, edge.first) + PointOf(mesh, edge.second));
    const double column = f * m.x() / m.z() + 0.5 * truth.camera.width;
    const double row = f * m.y() / m.z() + 0.5 * truth.camera.height;
    const std::size_t nearest = cloudIndex->nearest(m).first;
    const double local = cloudIndex->scale(nearest);
    const int radius = static_cast<int>(std::ceil(3.0 * local * f / m.z()));
    int why = truth.reason(row, column, radius);
    if (why < 0)
    {
      const double jump = MeasuredStep * spacings[nearest];
      why = truth.measuredJump(row, column, static_cast<int>(std::ceil(local * f / m.z())), jump) ? 3 : 4;
    }
    ++reasons[static_cast<std::size_t>(why)];
  }
  std::cout << "boundary edges: " << reasons[0] << " at the frame border, " << reasons[1]
            << " at unmeasured pixels, " << reasons[2] << " at depth discontinuities, " << reasons[3]
            << " at steps of the measured depths, " << reasons[4] << " elsewhere\n";
  EXPECT_EQ(reasons[4], 0u);
  return mesher->GetUsedProcedure();
}

} // namespace

// Every default: the procedure is automatic, which takes the plane procedure on a sensor frame.
TEST(DepthCameraMesh, MeshedWhereSeenOnTheSurfacesAndOpenOnlyAtTheFramesEdges)
{
  EXPECT_EQ(CheckFrameMesh(vtkPointSetSurfaceMesher::AUTOMATIC), vtkPointSetSurfaceMesher::PLANE);
}

// The extremal procedure (Definition 1) meets the same bounds.
TEST(DepthCameraMesh, ExtremalProcedureMeetsTheSameBounds)
{
  EXPECT_EQ(CheckFrameMesh(vtkPointSetSurfaceMesher::EXTREMAL), vtkPointSetSurfaceMesher::EXTREMAL);
}

// SPDX-License-Identifier: BSD-3-Clause
// A distributed run's index holds a piece of the cloud plus the points of a box around it
// (PointIndex::setCompleteRegion). A projection that reads only inside that box must give the
// whole cloud's result; one that reads beyond it must say so (Workspace::leftCompleteRegion).
// Checked for every definition on a noisy sphere cut by a plane.

#include "TestClouds.h"

#include "pss/Domain.h"
#include "pss/ExtremalSurface.h"
#include "pss/SurfaceDefinition.h"
#include "pss/Workspace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using namespace pss;
using namespace pss_test;

namespace
{

constexpr double inf = std::numeric_limits<double>::infinity();

std::vector<Vec3> noisySphere()
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  std::vector<Vec3> pts;
  for (int i = 0; i < 3000; ++i)
  {
    pts.push_back((1.0 + noise(rng)) * randomUnit(rng, 3));
  }
  return pts;
}

} // namespace

TEST(CompleteRegion, HoldsBallOnlyInsideTheClosedSides)
{
  PointIndex index(planeCloud(1.0, 0.1), 3);
  EXPECT_TRUE(index.holdsBall(Vec3(0, 0, 0), 1e300)); // the default region is everything
  index.setCompleteRegion(Vec3(-inf, -1.0, -inf), Vec3(0.5, inf, inf));
  EXPECT_TRUE(index.holdsBall(Vec3(-100.0, 0.0, 0.0), 0.5)); // open towards -x
  EXPECT_TRUE(index.holdsBall(Vec3(0.0, 0.0, 0.0), 0.5));    // touches x = 0.5
  EXPECT_FALSE(index.holdsBall(Vec3(0.0, 0.0, 0.0), 0.51));
  EXPECT_FALSE(index.holdsBall(Vec3(0.0, -0.9, 0.0), 0.2)); // crosses y = -1
  EXPECT_FALSE(index.holdsBall(Vec3(std::nan(""), 0.0, 0.0), 0.1));
  EXPECT_FALSE(index.holdsBall(Vec3(0.0, 0.0, 0.0), std::nan("")));
}

namespace
{

// Projects starts on one side of a piece (with its ghosts) and of the whole cloud: every start the
// piece does not flag must end bitwise where the whole cloud's does. With @p deltaLattice > 0
// the integral and delta definitions read delta from the lattice; with @p oneWorkspace the piece's
// projections share a workspace (its flag cleared before each), so lattice nodes computed for one
// start are read by later ones.
void checkPieceAgainstWhole(const std::vector<Variant>& variants, double deltaLattice, bool oneWorkspace)
{
  const std::vector<Vec3> cloud = noisySphere();
  const double h = 0.15;
  // This "rank" owns x < 0; its ghosts are the other points with x < margin. They come in
  // another order than in the whole cloud (a rank receives its ghosts after its own points).
  const double margin = 0.6;
  std::vector<Vec3> piece;
  for (const Vec3& p : cloud)
  {
    if (p.x() < margin)
    {
      piece.push_back(p);
    }
  }
  ASSERT_LT(piece.size(), cloud.size());
  std::shuffle(piece.begin(), piece.end(), std::mt19937(3));
  PointIndex whole(cloud, 3);
  PointIndex local(piece, 3);
  local.setCompleteRegion(Vec3::Constant(-inf), Vec3(margin, inf, inf));
  // Both sum every neighbourhood in the order of its points' coordinates, as a distributed run
  // and the one-process run it is compared with do. (In index order the same neighbourhoods are
  // summed in another order: measured on this piece, Levin's MLS then differs by up to 2e-5 h,
  // normalized MLS by 4e-13 h.)
  whole.setCoordinateOrder(true);
  local.setCoordinateOrder(true);

  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  for (Variant v : variants)
  {
    SCOPED_TRACE(variantName(v));
    SurfaceParameters sp = params(h);
    sp.deltaLattice = deltaLattice;
    const auto wholeSurface = makeSurface(v, whole, sp);
    const auto localSurface = makeSurface(v, local, sp);
    ProjectionOptions options;
    const int starts = v == Variant::Integral || v == Variant::Delta ? 25 : 150;
    int inside = 0;
    int flagged = 0;
    Workspace shared;
    for (int i = 0; i < starts; ++i)
    {
      const Vec3 start(-std::abs(u(rng)) * 0.9, u(rng), u(rng)); // starts on this rank's side
      Workspace wsWhole;
      Workspace fresh;
      Workspace& wsLocal = oneWorkspace ? shared : fresh;
      wsLocal.leftCompleteRegion = false;
      const ProjectionResult want = project(*wholeSurface, start, options, wsWhole);
      const ProjectionResult got = project(*localSurface, start, options, wsLocal);
      EXPECT_FALSE(wsWhole.leftCompleteRegion); // the whole cloud's index has no limit
      if (wsLocal.leftCompleteRegion)
      {
        ++flagged;
        continue;
      }
      ++inside;
      EXPECT_EQ(got.point, want.point) << start.transpose();
      EXPECT_EQ(got.direction.n, want.direction.n) << start.transpose();
      EXPECT_EQ(got.direction.stability, want.direction.stability) << start.transpose();
      EXPECT_EQ(got.energy, want.energy) << start.transpose();
      EXPECT_EQ(got.iterations, want.iterations) << start.transpose();
      EXPECT_EQ(got.reason, want.reason) << start.transpose();
      EXPECT_EQ(got.type, want.type) << start.transpose();
      // Unflagged means every read lay inside the box: the end point's support with it.
      EXPECT_LE(got.point.x() + 3.0 * h, margin + 1e-12) << start.transpose();
    }
    std::printf("%s: %d starts inside, %d flagged\n", variantName(v), inside, flagged);
    // Both kinds occur: starts near x = 0 reach past x = margin - 3h.
    EXPECT_GT(inside, 0);
    EXPECT_GT(flagged, 0);
  }
}

} // namespace

TEST(CompleteRegion, PieceWithGhostsGivesTheWholeCloudsProjectionsBitwiseOrSaysItCannot)
{
  checkPieceAgainstWhole(std::vector<Variant>(paperVariants().begin(), paperVariants().end()), 0.0, false);
}

// The delta lattice keeps a node's flag with its data (DeltaLattice.h): a projection that reads a
// node another projection computed from beyond the region is flagged too, so what is not flagged
// is still bitwise the whole cloud's.
TEST(CompleteRegion, LatticeNodesFromBeyondTheRegionFlagEveryRead)
{
  checkPieceAgainstWhole({ Variant::Integral, Variant::Delta }, 0.5, true);
}

TEST(CompleteRegion, CoordinateOrderRanksByCoordinatesThenIndex)
{
  // Equal points are ranked by index; -0 comes before +0.
  PointIndex index({ Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 1, 5), Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(-0.0, 0, 0) }, 3);
  index.setCoordinateOrder(true);
  ASSERT_TRUE(index.coordinateOrder());
  std::vector<Vec3> ordered(index.size());
  std::vector<bool> seen(index.size(), false);
  for (std::uint32_t i = 0; i < index.size(); ++i)
  {
    const std::uint32_t r = index.coordinateRank(i);
    ASSERT_LT(r, index.size());
    EXPECT_FALSE(seen[r]); // a permutation
    seen[r] = true;
    ordered[r] = index.point(i);
  }
  EXPECT_TRUE(std::signbit(ordered[0].x()));
  EXPECT_EQ(ordered[1], Vec3(0, 0, 0));
  EXPECT_FALSE(std::signbit(ordered[1].x()));
  EXPECT_EQ(ordered[2], Vec3(0, 1, 5));
  EXPECT_EQ(ordered[3], Vec3(0, 2, 0));
  EXPECT_EQ(ordered[4], Vec3(1, 0, 0));
  index.setCoordinateOrder(false);
  EXPECT_FALSE(index.coordinateOrder());
}

TEST(CompleteRegion, AnEvaluationBeyondTheRegionIsFlagged)
{
  PointIndex local(planeCloud(1.0, 0.1), 3);
  local.setCompleteRegion(Vec3(-inf, -inf, -inf), Vec3(0.2, inf, inf));
  const auto surface = makeSurface(Variant::CenterOfMass, local, params(0.2));
  Workspace ws;
  project(*surface, Vec3(-0.8, 0.0, 0.1), ProjectionOptions{}, ws);
  EXPECT_FALSE(ws.leftCompleteRegion);
  project(*surface, Vec3(0.1, 0.0, 0.1), ProjectionOptions{}, ws);
  EXPECT_TRUE(ws.leftCompleteRegion);
  // The flag is a report, not a cache: a cached neighbourhood read again is checked again.
  ws.leftCompleteRegion = false;
  project(*surface, Vec3(0.1, 0.0, 0.1), ProjectionOptions{}, ws);
  EXPECT_TRUE(ws.leftCompleteRegion);
}

TEST(CompleteRegion, ACachedCloudNormalFromBeyondTheRegionFlagsEveryUse)
{
  // A cloud point 0.1 inside the region's side at x = 0.2: its neighbourhood (3 h = 0.6) reaches
  // past it, so every evaluation that reads its normal, from the cache or not, is flagged.
  PointIndex local(planeCloud(1.0, 0.1), 3);
  local.setCompleteRegion(Vec3(-inf, -inf, -inf), Vec3(0.2, inf, inf));
  const auto surface = makeSurface(Variant::CenterOfMass, local, params(0.2));
  const CloudNormals normals(*surface);
  const std::size_t border = local.nearest(Vec3(0.1, 0.0, 0.0)).first;
  const std::size_t inside = local.nearest(Vec3(-0.8, 0.0, 0.0)).first;
  for (int use = 0; use < 2; ++use) // computed, then from the cache
  {
    Workspace ws;
    normals.at(border, ws);
    EXPECT_TRUE(ws.leftCompleteRegion) << "use " << use;
    Workspace clean;
    normals.at(inside, clean);
    EXPECT_FALSE(clean.leftCompleteRegion) << "use " << use;
  }
  // A flag already set stays set.
  Workspace flagged;
  flagged.leftCompleteRegion = true;
  normals.at(inside, flagged);
  EXPECT_TRUE(flagged.leftCompleteRegion);
}

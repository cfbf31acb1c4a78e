// SPDX-License-Identifier: BSD-3-Clause
// A Workspace only saves work (Workspace.h): a projection, a direction or an energy is the same,
// bit for bit, whatever the workspace served before (other clouds, other h, other definitions,
// other kinds of query), and the same as with a fresh workspace on a fresh thread.

#include "TestClouds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <thread>

using namespace pss;
using namespace pss_test;

namespace
{

bool sameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool sameBits(const Vec3& a, const Vec3& b)
{
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

bool sameBits(const Direction& a, const Direction& b)
{
  return sameBits(a.n, b.n) && sameBits(a.stability, b.stability) && a.defined == b.defined;
}

// Every field of the result.
void expectSameBits(const ProjectionResult& got, const ProjectionResult& fresh, const std::string& after)
{
  SCOPED_TRACE("after " + after);
  EXPECT_TRUE(sameBits(got.point, fresh.point)) << got.point.transpose() << " vs " << fresh.point.transpose();
  EXPECT_TRUE(sameBits(got.direction, fresh.direction));
  EXPECT_TRUE(sameBits(got.startDirection, fresh.startDirection));
  EXPECT_TRUE(sameBits(got.energy, fresh.energy)) << got.energy << " vs " << fresh.energy;
  EXPECT_TRUE(sameBits(got.lastStep, fresh.lastStep));
  EXPECT_EQ(got.iterations, fresh.iterations);
  EXPECT_EQ(got.converged, fresh.converged);
  EXPECT_EQ(got.reason, fresh.reason);
  EXPECT_EQ(got.type, fresh.type);
}

/// A noisy sphere of radius 3 h (h = 0.5): the cloud whose projections are checked.
std::vector<Vec3> noisySphere(unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  std::vector<Vec3> pts;
  for (int i = 0; i < 1500; ++i)
  {
    pts.push_back((1.5 + noise(rng)) * randomUnit(rng, 3));
  }
  return pts;
}

struct Case
{
  Variant variant;
  Procedure procedure;
  Vec3 start;
};

/// Every definition with both procedures, from starts near the sphere and well off it.
std::vector<Case> cases()
{
  std::vector<Case> out;
  for (Variant v : paperVariants())
  {
    for (Procedure p : { Procedure::Extremal, Procedure::Plane })
    {
      for (const Vec3& start : { Vec3(0.3, 1.2, 0.9), Vec3(-2.4, 0.5, 0.2) })
      {
        out.push_back({ v, p, start });
      }
    }
  }
  return out;
}

ProjectionOptions optionsFor(Procedure p)
{
  ProjectionOptions opt;
  opt.procedure = p;
  opt.maxIterations = 20;
  return opt;
}

} // namespace

// Truth: the workspace holds caches and scratch only, so every projection after any sequence of
// unrelated queries on the same thread and workspace equals the fresh-thread, fresh-workspace one.
TEST(Workspace, ProjectionIndependentOfEarlierCalls)
{
  const double h = 0.5;
  const PointIndex index(noisySphere(5u), 3);
  const std::vector<Case> all = cases();

  // The reference: each projection alone, on its own new thread with a new workspace.
  std::vector<ProjectionResult> fresh(all.size());
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    std::thread([&, i] {
      Workspace ws;
      const auto s = makeSurface(all[i].variant, index, params(h));
      fresh[i] = project(*s, all[i].start, optionsFor(all[i].procedure), ws);
    }).join();
  }

  // Unrelated work for the shared workspace: another cloud (2D and 3D), other scales and cut-offs
  // on the same cloud, every definition, every kind of query.
  const PointIndex other(randomBox(3000, 3, 6.0, 9u), 3);
  const PointIndex curve(lineCloud(4.0, 0.1), 2);
  struct Disturbance
  {
    std::string name;
    std::function<void(Workspace&)> run;
  };
  std::vector<Disturbance> disturbances;
  for (Variant v : paperVariants())
  {
    const std::string name = variantName(v);
    disturbances.push_back({ name + " on another cloud", [&, v](Workspace& ws) {
      const auto s = makeSurface(v, other, params(0.7));
      project(*s, Vec3(0.5, 1.2, -0.4), optionsFor(Procedure::Extremal), ws);
      evaluateImplicit(*s, Vec3(2.0, -1.0, 0.3), Orientation::awayFromCentroid(other), ws);
    } });
    disturbances.push_back({ name + " on a 2D curve", [&, v](Workspace& ws) {
      const auto s = makeSurface(v, curve, params(0.4));
      project(*s, Vec3(0.7, 0.3, 0.0), optionsFor(Procedure::Plane), ws);
    } });
    disturbances.push_back({ name + " with another h and cutoff on the same cloud", [&, v](Workspace& ws) {
      const auto s = makeSurface(v, index, params(0.8, 2.0));
      project(*s, Vec3(0.3, 1.2, 0.9), optionsFor(Procedure::Extremal), ws);
      s->lineSample(Vec3(0.1, 1.4, 0.2), Vec3(0, 1, 0), ws);
    } });
  }
  disturbances.push_back({ "domain classification with another h", [&](Workspace& ws) {
    const auto s = makeSurface(Variant::CenterOfMass, index, params(0.3));
    classifyStart(*s, Vec3(0.2, -1.1, 1.3), optionsFor(Procedure::Plane), DomainThresholds{}, ws);
    cloudNormalAt(*s, 17, ws);
  } });
  disturbances.push_back({ "distance field far away", [&](Workspace& ws) {
    DistanceField(index, params(h)).delta(Vec3(40.0, -3.0, 7.0), ws);
  } });

  Workspace ws;
  for (const Disturbance& d : disturbances)
  {
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      d.run(ws);
      const auto s = makeSurface(all[i].variant, index, params(h));
      const ProjectionResult got = project(*s, all[i].start, optionsFor(all[i].procedure), ws);
      expectSameBits(got, fresh[i], d.name + " (" + variantName(all[i].variant) + ")");
    }
  }

  // Value semantics: a copy and a moved-to workspace carry the caches along, and change nothing.
  Workspace copy = ws;
  Workspace moved = std::move(ws);
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    const auto s = makeSurface(all[i].variant, index, params(h));
    expectSameBits(project(*s, all[i].start, optionsFor(all[i].procedure), copy), fresh[i], "a copy");
    expectSameBits(project(*s, all[i].start, optionsFor(all[i].procedure), moved), fresh[i], "a move");
  }
}

// Truth: a plane fit hands on the neighbourhood its direction came from (DirectionFit), so the
// plane procedure's centroid is c(x) of x's own neighbourhood, whatever was gathered before.
TEST(Workspace, PlaneFitCentroidIsThatOfTheFitPoint)
{
  const double h = 0.5;
  const PointIndex index(noisySphere(6u), 3);
  const Vec3 x(0.2, 1.3, 0.7);
  for (Variant v : paperVariants())
  {
    SCOPED_TRACE(variantName(v));
    const auto s = makeSurface(v, index, params(h));
    Workspace fresh;
    gatherNeighbourhood(index, params(h), x, fresh.local, fresh);
    const Vec3 truth = centroidOffset(fresh.local);

    Workspace ws;
    s->direction(Vec3(-1.0, 0.4, 1.1), ws); // another point's neighbourhood in the workspace
    DirectionMemory memory;
    Vec3 offset;
    s->planeFit(x, offset, memory, ws);
    EXPECT_TRUE(sameBits(offset, truth)) << offset.transpose() << " vs " << truth.transpose();
  }
}

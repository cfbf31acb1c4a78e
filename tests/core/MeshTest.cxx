// SPDX-License-Identifier: BSD-3-Clause
// The domain-restricted mesh (SurfaceMesh.h) against shapes whose surface is known exactly:
// a sphere, a square patch, two parallel sheets, dihedral corners, and the paper's 2D scenes.
#include "TestClouds.h"

#include "pss/SurfaceMesh.h"
#include "pss/SyntheticClouds.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using pss::Vec3;

pss::PointIndex indexOf(const pss::CloudSpec& spec)
{
  return pss::PointIndex(pss::generateCloud(spec), spec.dimension);
}

pss::SurfaceMesh meshOf(const pss::PointIndex& index, pss::Variant variant, double h, pss::MeshOptions options = {},
  int threads = 0)
{
  auto surface = pss::makeSurface(variant, index, pss_test::params(h));
  return pss::extractSurfaceMesh(*surface, options, threads);
}

pss::CloudSpec sphereSpec()
{
  pss::CloudSpec spec;
  spec.scene = pss::Scene::Sphere;
  spec.dimension = 3;
  spec.size = 40.0; // radius 20 h with h = 1
  spec.count = 20000;
  spec.noise = 0.01;
  return spec;
}

} // namespace

TEST(Mesh, SphereIsOneClosedAccurateSurface)
{
  const pss::CloudSpec spec = sphereSpec();
  const pss::PointIndex index = indexOf(spec);
  const pss::SurfaceMesh mesh = meshOf(index, pss::Variant::CenterOfMass, 1.0);
  const pss::MeshStatistics& st = mesh.statistics;
  std::cout << "band cells " << st.bandCells << ", vertices " << mesh.points.size() << ", triangles "
            << mesh.triangles.size() << ", dropped " << st.droppedVertices << ", seams " << st.seamSimplices
            << ", components " << st.components << ", boundary " << st.boundaryEdges << ", euler "
            << st.eulerCharacteristic << ", area " << st.measure << "\n";
  EXPECT_EQ(st.components, 1u);
  EXPECT_EQ(st.boundaryEdges, 0u);
  EXPECT_EQ(st.nonManifoldEdges, 0u);
  EXPECT_EQ(st.eulerCharacteristic, 2);
  double worst = 0.0;
  for (const Vec3& p : mesh.points)
  {
    worst = std::max(worst, std::abs(p.norm() - 20.0));
  }
  EXPECT_LT(worst, 0.05);
  EXPECT_NEAR(st.measure, 4.0 * M_PI * 400.0, 0.01 * 4.0 * M_PI * 400.0);
}

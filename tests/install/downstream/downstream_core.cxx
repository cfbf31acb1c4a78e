// The installed core alone: a sphere of radius 10 sampled by 5,000 points, projected from points
// 1 off the sphere with the centre-of-mass definition (h = 1); each end point must be within 0.1 h
// of the sphere (the plane fit's bias is h^2 / 2R = 0.05 h here).
#include "pss/Core.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

int main()
{
  const double radius = 10.0;
  std::mt19937 random(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  auto onSphere = [&](double r) {
    pss::Vec3 v(gauss(random), gauss(random), gauss(random));
    return pss::Vec3(r * v.normalized());
  };
  std::vector<pss::Vec3> cloud;
  for (int i = 0; i < 5000; ++i)
  {
    cloud.push_back(onSphere(radius));
  }
  pss::PointIndex index(cloud, 3);
  pss::SurfaceParameters parameters;
  parameters.h = 1.0;
  auto surface = pss::makeSurface(pss::Variant::CenterOfMass, index, parameters);
  double worst = 0.0;
  pss::Workspace ws;
  for (int i = 0; i < 50; ++i)
  {
    const pss::ProjectionResult result =
      pss::project(*surface, onSphere(radius + (i % 2 ? 1.0 : -1.0)), pss::ProjectionOptions{}, ws);
    if (!result.converged)
    {
      std::printf("projection %d did not converge\n", i);
      return 1;
    }
    worst = std::max(worst, std::abs(result.point.norm() - radius));
  }
  std::printf("core: 50 projections, largest distance to the sphere %.4f h\n", worst / parameters.h);
  return worst < 0.1 * parameters.h ? 0 : 1;
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss-bench-core: projection throughput of the core, per surface definition, printed as a table.
 *
 *   pss-bench-core [--points 20000] [--queries 2000] [--threads 0]
 *
 * Cloud: a noisy sphere (3D) and a noisy circle (2D) of --points points; h = 2.5 mean spacings.
 * The Integral and Delta definitions (e_I needs a Gauss-Hermite plane quadrature per direction
 * trial) get a tenth of the queries in 3D. Numbers are wall-clock; quote medians of several runs.
 */
#include "pss/Core.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{

struct Options
{
  std::size_t points = 20000;
  std::size_t queries = 2000;
  int threads = 0;
};

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string flag = argv[i];
    const long value = std::strtol(argv[i + 1], nullptr, 10);
    if (flag == "--points")
      o.points = static_cast<std::size_t>(std::max(100L, value));
    else if (flag == "--queries")
      o.queries = static_cast<std::size_t>(std::max(10L, value));
    else if (flag == "--threads")
      o.threads = static_cast<int>(value);
  }
  return o;
}

void run(const Options& opt, int dimension)
{
  pss::CloudSpec spec;
  spec.scene = dimension == 3 ? pss::Scene::Sphere : pss::Scene::Circle;
  spec.dimension = dimension;
  spec.count = opt.points;
  spec.size = 100.0;
  // Mean spacing: sphere area / N (3D) or circumference / N (2D).
  const double spacing = dimension == 3 ? std::sqrt(M_PI * spec.size * spec.size / opt.points)
                                        : M_PI * spec.size / opt.points;
  spec.noise = 0.5 * spacing;
  const auto cloud = pss::generateCloud(spec);

  const auto t0 = std::chrono::steady_clock::now();
  const pss::PointIndex index(cloud, dimension);
  const double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  pss::SurfaceParameters params;
  params.h = 2.5 * spacing;
  pss::ProjectionOptions projection;
  std::printf("%dD: %zu points, h = %.4f, index built in %.4f s, threads %d\n", dimension, cloud.size(), params.h,
    buildSeconds, pss::resolveThreadCount(opt.threads));
  std::printf("  %-11s %8s %12s %14s %10s\n", "variant", "queries", "seconds", "points/second", "converged");
  for (int v = 0; v < pss::VariantCount; ++v)
  {
    const auto variant = static_cast<pss::Variant>(v);
    const bool expensive = dimension == 3 && (variant == pss::Variant::Integral || variant == pss::Variant::Delta);
    const std::size_t n = std::min(cloud.size(), expensive ? std::max<std::size_t>(10, opt.queries / 10) : opt.queries);
    const std::vector<pss::Vec3> starts(cloud.begin(), cloud.begin() + static_cast<std::ptrdiff_t>(n));
    const auto surface = pss::makeSurface(variant, index, params);
    const auto t1 = std::chrono::steady_clock::now();
    const auto results = pss::projectAll(*surface, starts, projection, opt.threads);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    std::size_t converged = 0;
    for (const auto& r : results)
    {
      converged += r.converged ? 1 : 0;
    }
    std::printf("  %-11s %8zu %12.4f %14.1f %10zu\n", pss::variantName(variant), n, seconds, n / seconds, converged);
  }
}

} // namespace

int main(int argc, char** argv)
{
  const Options opt = parse(argc, argv);
  run(opt, 2);
  run(opt, 3);
  return 0;
}

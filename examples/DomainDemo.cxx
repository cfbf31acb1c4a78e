// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss-domain-demo: the experiment of the paper's Figures 1 and 2 in numbers.
 *
 * A noisy open curve whose noise grows along it past the Gaussian scale h is projected onto the
 * surface of every definition. A point outside the domain moves away from (or along) the true
 * curve instead of towards it; the table counts those points, variant by variant.
 *
 *   pss-domain-demo [--h 5] [--noise 6] [--count 600] [--seed 1] [--threads 0] [--csv DIR]
 *
 * With --csv, DIR/<variant>.csv holds x0,y0,x,y,iterations,stop per point (start and end), ready
 * to draw the projection lines of Figure 1.
 */
#include "pss/Core.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

namespace
{

struct Options
{
  double h = 5.0;
  double noise = 6.0;
  std::size_t count = 600;
  unsigned seed = 1;
  int threads = 0;
  std::string csvDir;
};

double parseNumber(const std::string& flag, const char* text)
{
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0')
  {
    throw std::invalid_argument(flag + " expects a number, got '" + text + "'");
  }
  return v;
}

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h")
    {
      std::cout << "usage: pss-domain-demo [--h 5] [--noise 6] [--count 600] [--seed 1] [--threads 0] [--csv DIR]\n"
                   "Projects a noisy curve (noise growing to --noise) with all five surface definitions\n"
                   "and reports how many points move away from the true curve (outside the domain).\n";
      std::exit(0);
    }
    if (i + 1 >= argc)
    {
      throw std::invalid_argument(flag + " needs a value");
    }
    const char* value = argv[++i];
    if (flag == "--h")
      o.h = parseNumber(flag, value);
    else if (flag == "--noise")
      o.noise = parseNumber(flag, value);
    else if (flag == "--count")
      o.count = static_cast<std::size_t>(parseNumber(flag, value));
    else if (flag == "--seed")
      o.seed = static_cast<unsigned>(parseNumber(flag, value));
    else if (flag == "--threads")
      o.threads = static_cast<int>(parseNumber(flag, value));
    else if (flag == "--csv")
      o.csvDir = value;
    else
      throw std::invalid_argument("unknown option " + flag + " (see --help)");
  }
  return o;
}

double median(std::vector<double> v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

} // namespace

int main(int argc, char** argv)
{
  try
  {
    const Options opt = parse(argc, argv);
    pss::CloudSpec spec;
    spec.scene = pss::Scene::NoisyCurve;
    spec.count = opt.count;
    spec.size = 200.0;
    spec.noise = opt.noise;
    spec.seed = opt.seed;
    spec.dimension = 2;
    const std::vector<pss::Vec3> cloud = pss::generateCloud(spec);
    const pss::PointIndex index(cloud, 2);

    pss::SurfaceParameters params;
    params.h = opt.h;
    pss::ProjectionOptions projection;

    std::vector<double> before;
    for (const pss::Vec3& p : cloud)
    {
      before.push_back(pss::distanceToShape(spec, p));
    }
    std::printf("noisy curve: %zu points, noise sigma %.2f..%.2f, h = %.2f\n", cloud.size(), 0.2 * opt.noise,
      opt.noise, opt.h);
    std::printf("median distance of the raw points to the true curve: %.3f\n\n", median(before));
    std::printf("%-11s %10s %12s %12s %10s %10s\n", "variant", "converged", "median dist", "moved away",
      "> 2h off", "time [s]");
    for (int v = 0; v < pss::VariantCount; ++v)
    {
      const auto variant = static_cast<pss::Variant>(v);
      const auto surface = pss::makeSurface(variant, index, params);
      const auto t0 = std::chrono::steady_clock::now();
      const auto results = pss::projectAll(*surface, cloud, projection, opt.threads);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

      std::size_t converged = 0;
      std::size_t movedAway = 0;
      std::size_t farOff = 0;
      std::vector<double> after;
      for (std::size_t i = 0; i < results.size(); ++i)
      {
        const double d = pss::distanceToShape(spec, results[i].point);
        after.push_back(d);
        converged += results[i].converged ? 1 : 0;
        movedAway += d > before[i] + 0.25 * opt.h ? 1 : 0;
        farOff += d > 2.0 * opt.h ? 1 : 0;
      }
      std::printf("%-11s %10zu %12.3f %12zu %10zu %10.3f\n", pss::variantName(variant), converged, median(after),
        movedAway, farOff, seconds);

      if (!opt.csvDir.empty())
      {
        const std::string path = opt.csvDir + "/" + pss::variantName(variant) + ".csv";
        std::ofstream out(path);
        if (!out)
        {
          throw std::runtime_error("cannot write " + path);
        }
        out << "x0,y0,x,y,iterations,stop\n";
        for (const auto& r : results)
        {
          out << r.start.x() << ',' << r.start.y() << ',' << r.point.x() << ',' << r.point.y() << ','
              << r.iterations << ',' << pss::stopReasonName(r.reason) << '\n';
        }
      }
    }
    std::printf("\n'moved away': the projection ended more than h/4 farther from the true curve than it\n"
                "started; such start points lie outside the domain of that surface definition.\n");
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "pss-domain-demo: error: " << e.what() << '\n';
    return 1;
  }
}

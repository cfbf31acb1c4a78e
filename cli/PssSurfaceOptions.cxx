// SPDX-License-Identifier: BSD-3-Clause
// The surface definition's options, shared by every pss command (--variant, the scale, the kernel,
// and the normals of APSS and RIMLS).
#include "PssOptions.h"

#include "vtkPointSetSurface.h"

#include "pss/VariantCatalog.h"

#include <string>
#include <vector>

namespace pss_cli
{

namespace
{
// An integer flag within [lo, hi]: "2.5" is refused, not truncated.
int IntIn(const std::string& flag, const std::string& text, int lo, int hi)
{
  const int value = ToInt(flag, text);
  if (value < lo || value > hi)
  {
    throw UsageError{ "--" + flag + " expects an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
      "], got '" + text + "'" };
  }
  return value;
}
} // namespace

void AddSurfaceOptions(OptionTable& t, vtkPointSetSurface* s)
{
  // The choices are the core's variant table's names, in its order.
  std::vector<std::string> variants;
  std::string variantHelp;
  for (const pss::VariantInfo& row : pss::variantTable())
  {
    variants.emplace_back(row.name);
    variantHelp += (variantHelp.empty() ? "" : " | ") + variants.back();
  }
  variantHelp += std::string(" (default ") + pss::variantName(static_cast<pss::Variant>(s->GetVariant())) + ")";
  t.Value("variant", "NAME", variantHelp, [s, variants](const std::string& v) {
    s->SetVariant(static_cast<int>(pss::variantTable()[ToChoice("variant", v, variants)].variant));
  });
  t.Value("h", "H", "Gaussian scale h; turns the automatic scale off (default: automatic)", [s](const std::string& v) {
    s->SetScaleFactor(ToDouble("h", v));
    s->AutomaticScaleOff();
  });
  t.Value("point-scales", "automatic|off|estimated|array",
    "automatic h: one h (off), a scale per point h_i from each point's neighbours (estimated) or from the "
    "point array of --scale-array; automatic: per point for a sensor frame (organized or with a viewpoint) "
    "or where the density varies more than --scale-spread, else one h (default automatic)",
    [s](const std::string& v) {
      s->SetPointScales(ToChoice("point-scales", v, { "automatic", "off", "estimated", "array" }));
    });
  t.Value("scale-array", "NAME", "--point-scales array: the point array of h_i (default Scale)",
    [s](const std::string& v) { s->SetScaleArrayName(v.c_str()); });
  t.Value("scale-spread", "R",
    "--point-scales automatic: a scale per point when the 90th percentile of the points' scales exceeds R times "
    "their 10th (default 3)",
    [s](const std::string& v) {
      const double r = ToDouble("scale-spread", v);
      if (!(r >= 1.0) || !std::isfinite(r))
      {
        throw UsageError{ "--scale-spread expects a ratio >= 1, got '" + v + "'" };
      }
      s->SetScaleSpreadThreshold(r);
    });
  t.Value("point-scale-multiplier", "M",
    "estimated scales per point: h_i = --scale-multiplier x M x the point's smoothed k-NN distance (default 3)",
    [s](const std::string& v) {
      const double m = ToDouble("point-scale-multiplier", v);
      if (!(m >= 1e-2 && m <= 1e2))
      {
        throw UsageError{ "--point-scale-multiplier expects a number in [0.01, 100], got '" + v + "'" };
      }
      s->SetPointScaleMultiplier(m);
    });
  t.Value("scale-neighbors", "K", "automatic h: k of the k-th nearest neighbour distance (default 10)",
    [s](const std::string& v) { s->SetScaleNeighbors(ToInt("scale-neighbors", v)); });
  t.Value("scale-multiplier", "M", "automatic h: multiplier of the k-NN distances (default 1)",
    [s](const std::string& v) {
      const double m = ToDouble("scale-multiplier", v);
      if (!(m > 0.0) || !std::isfinite(m))
      {
        throw UsageError{ "--scale-multiplier expects a positive number, got '" + v + "'" };
      }
      s->SetScaleMultiplier(m);
    });
  t.Value("dimension", "D", "auto | 2 | 3 (default auto: 2 when all z are equal)", [s](const std::string& v) {
    const int d = ToChoice("dimension", v, { "auto", "1", "2", "3" });
    s->SetDimension(d == 0 ? vtkPointSetSurface::DIMENSION_AUTO : d);
  });
  t.Value("cutoff", "C", "kernel truncation in h beyond the nearest point (default 3)",
    [s](const std::string& v) { s->SetKernelCutoff(ToDouble("cutoff", v)); });
  t.Value("quadrature", "N", "Gauss-Hermite nodes per axis for e_I (default 6)",
    [s](const std::string& v) { s->SetQuadratureOrder(ToInt("quadrature", v)); });
  t.Value("delta-lattice", "S",
    "integral and delta: spacing in h of the lattice delta is interpolated from (default 0.5; 0: exact at "
    "every quadrature node)",
    [s](const std::string& v) {
      const double spacing = ToDouble("delta-lattice", v);
      if (!(spacing >= 0.0 && spacing <= 1.0))
      {
        // vtkPointSetSurface clamps; a command line says what it refuses.
        throw UsageError{ "--delta-lattice expects 0 or a lattice spacing in [0.05, 1] h, got '" + v + "'" };
      }
      s->SetDeltaLatticeSpacing(spacing);
    });
  t.Value("min-stability", "S", "n counts as undefined below this stability (default 1e-5)",
    [s](const std::string& v) { s->SetMinimumStability(ToDouble("min-stability", v)); });
  t.Value("normals-array", "NAME",
    "apss and rimls: the point array of oriented normals (default Normals); without it they are estimated and "
    "oriented toward the cloud's viewpoint, else by propagation",
    [s](const std::string& v) { s->SetNormalsArrayName(v.c_str()); });
  t.Value("cloud-normal-neighbors", "K",
    "apss and rimls: neighbours of the graph that orients estimated normals (default 10)",
    [s](const std::string& v) { s->SetNormalNeighbors(IntIn("cloud-normal-neighbors", v, 1, 100)); });
  t.Switch("reorient-normals",
    "apss and rimls: choose the signs of the --normals-array normals again, as estimated ones get them "
    "(repairs normals flipped in places)",
    [s]() { s->ReorientNormalsOn(); });
  t.Value("sphericity", "S", "apss: 1 fits spheres, 0 planes (default 1)",
    [s](const std::string& v) { s->SetSphericity(ToNumberIn("sphericity", v, 0.0, 1.0)); });
  t.Value("sigma-n", "S", "rimls: the normals' scale; smaller keeps edges sharper (default 0.75)",
    [s](const std::string& v) { s->SetSigmaNormal(ToNumberIn("sigma-n", v, 0.01, 100.0)); });
  t.Value("sigma-r", "S", "rimls: the residuals' scale in local h; smaller discounts outliers more (default 0.5)",
    [s](const std::string& v) { s->SetSigmaResidual(ToNumberIn("sigma-r", v, 0.01, 100.0)); });
  t.Value("robust-refits", "N", "rimls: refits of the robust weights after the first fit (default 3)",
    [s](const std::string& v) { s->SetRobustRefits(IntIn("robust-refits", v, 0, 100)); });
}

} // namespace pss_cli

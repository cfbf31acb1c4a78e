// SPDX-License-Identifier: BSD-3-Clause
#include "pss/VariantCatalog.h"

#include "pss/DirectionRulesAndEnergies.h"

#include <cctype>
#include <stdexcept>
#include <string>

namespace pss
{

namespace
{

template <CovarianceDirection::About about>
std::unique_ptr<DirectionRule> covariance(const PointIndex& index, const SurfaceParameters& params)
{
  return std::make_unique<CovarianceDirection>(index, params, about);
}

template <MLSEnergy::Weights weights>
std::unique_ptr<Energy> mlsEnergy(const PointIndex& index, const SurfaceParameters& params)
{
  return std::make_unique<MLSEnergy>(index, params, weights);
}

template <NormalFitKind kind>
std::unique_ptr<DirectionRule> normalFitDirection(const PointIndex& index, const SurfaceParameters& params)
{
  return std::make_unique<NormalFitDirection>(index, params, kind);
}

template <NormalFitKind kind>
std::unique_ptr<Energy> normalFitEnergy(const PointIndex& index, const SurfaceParameters& params)
{
  return std::make_unique<NormalFitEnergy>(index, params, kind);
}

template <class Part, class Base>
std::unique_ptr<Base> make(const PointIndex& index, const SurfaceParameters& params)
{
  return std::make_unique<Part>(index, params);
}

// The direction rules and energies of the paper's table, by the names the rows use.
constexpr auto aboutQuery = covariance<CovarianceDirection::About::Query>;
constexpr auto aboutCentroid = covariance<CovarianceDirection::About::Centroid>;
constexpr auto integralArgmin = make<IntegralDirection, DirectionRule>;
constexpr auto mls = mlsEnergy<MLSEnergy::Weights::Plain>;
constexpr auto normalizedMls = mlsEnergy<MLSEnergy::Weights::Normalized>;
constexpr auto integral = make<IntegralEnergy, Energy>;
constexpr auto delta = make<DeltaEnergy, Energy>;
constexpr auto sphereGradient = normalFitDirection<NormalFitKind::AlgebraicSphere>;
constexpr auto sphereValue = normalFitEnergy<NormalFitKind::AlgebraicSphere>;
constexpr auto robustGradient = normalFitDirection<NormalFitKind::RobustImplicit>;
constexpr auto robustValue = normalFitEnergy<NormalFitKind::RobustImplicit>;

} // namespace

const std::array<VariantInfo, VariantCount>& variantTable()
{
  // n(x) and e(y, a) of each definition: Levin = (eigenvector of C about x, Eq. 1), normalized =
  // (the same, Eq. 1 with theta_N), centre of mass = (eigenvector of the covariance about c(x),
  // normalized Eq. 1), integral = (argmin of e_I, e_I), delta = (argmin of e_I, delta); APSS and
  // RIMLS = (their fit's gradient, their fit's value squared).
  static const std::array<VariantInfo, VariantCount> table{ {
    { Variant::LevinMLS, "levin", "LevinMLS", "Levin MLS", aboutQuery, mls },
    { Variant::NormalizedMLS, "normalized", "NormalizedMLS", "Normalized MLS", aboutQuery, normalizedMls },
    { Variant::CenterOfMass, "com", "CenterOfMass", "Center of Mass", aboutCentroid, normalizedMls },
    { Variant::Integral, "integral", "Integral", "Integral Energy", integralArgmin, integral },
    { Variant::Delta, "delta", "Delta", "Delta Energy", integralArgmin, delta },
    { Variant::APSS, "apss", "APSS", "APSS (Algebraic Spheres)", sphereGradient, sphereValue },
    { Variant::RIMLS, "rimls", "RIMLS", "RIMLS (Robust Implicit MLS)", robustGradient, robustValue },
  } };
  return table;
}

namespace
{

// The row of v, or nullptr for a value outside the table (a cast from a bad int).
const VariantInfo* findRow(Variant v)
{
  const auto& table = variantTable();
  const auto row = static_cast<std::size_t>(v);
  return row < table.size() && table[row].variant == v ? &table[row] : nullptr;
}

} // namespace

const VariantInfo& variantInfo(Variant v)
{
  const VariantInfo* row = findRow(v);
  if (!row)
  {
    throw std::invalid_argument("unknown surface variant " + std::to_string(static_cast<int>(v)));
  }
  return *row;
}

std::unique_ptr<SurfaceDefinition> makeSurface(Variant v, const PointIndex& index, const SurfaceParameters& params)
{
  return std::make_unique<SurfaceDefinition>(variantInfo(v), index, params);
}

const char* variantName(Variant v)
{
  const VariantInfo* row = findRow(v);
  return row ? row->name : "unknown";
}

bool parseVariant(const std::string& text, Variant& out)
{
  // Case, '-', '_' and ' ' do not count, so "LevinMLS", "levin-mls" and "center of mass" parse.
  auto key = [](const std::string& s) {
    std::string k;
    for (char c : s)
    {
      if (c != '-' && c != '_' && c != ' ')
      {
        k.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
      }
    }
    return k;
  };
  const std::string wanted = key(text);
  for (const VariantInfo& row : variantTable())
  {
    if (wanted == key(row.name) || wanted == key(row.identifier))
    {
      out = row.variant;
      return true;
    }
  }
  // Levin's definition is "the" MLS surface in the literature.
  if (wanted == "mls")
  {
    out = Variant::LevinMLS;
    return true;
  }
  return false;
}

} // namespace pss

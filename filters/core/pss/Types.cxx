// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Types.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace pss
{

const char* variantName(Variant v)
{
  switch (v)
  {
    case Variant::LevinMLS:
      return "levin";
    case Variant::NormalizedMLS:
      return "normalized";
    case Variant::CenterOfMass:
      return "com";
    case Variant::Integral:
      return "integral";
    case Variant::Delta:
      return "delta";
  }
  return "unknown";
}

bool parseVariant(const std::string& text, Variant& out)
{
  std::string key;
  for (char c : text)
  {
    if (c != '-' && c != '_' && c != ' ')
    {
      key.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    }
  }
  struct Alias
  {
    const char* name;
    Variant value;
  };
  static const Alias aliases[] = { { "levin", Variant::LevinMLS }, { "levinmls", Variant::LevinMLS },
    { "mls", Variant::LevinMLS }, { "normalized", Variant::NormalizedMLS },
    { "normalizedmls", Variant::NormalizedMLS }, { "com", Variant::CenterOfMass },
    { "centerofmass", Variant::CenterOfMass }, { "integral", Variant::Integral },
    { "delta", Variant::Delta } };
  for (const Alias& a : aliases)
  {
    if (key == a.name)
    {
      out = a.value;
      return true;
    }
  }
  return false;
}

const char* stopReasonName(StopReason r)
{
  switch (r)
  {
    case StopReason::Converged:
      return "Converged";
    case StopReason::MaxIterations:
      return "MaxIterations";
    case StopReason::UndefinedDirection:
      return "UndefinedDirection";
    case StopReason::NoExtremum:
      return "NoExtremum";
    case StopReason::InvalidInput:
      return "InvalidInput";
  }
  return "Unknown";
}

double LineSample::trueValue() const
{
  return value * std::exp(logScale);
}

double LineSample::trueSlope() const
{
  return slope * std::exp(logScale);
}

} // namespace pss

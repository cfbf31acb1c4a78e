// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Types.h"

#include <cmath>

namespace pss
{

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

// SPDX-License-Identifier: BSD-3-Clause
// Which code runs (docs/development.md, "Portable binaries"): the loader takes the core's copy for
// x86-64-v3 where the CPU runs it, unless GLIBC_TUNABLES masks AVX2 (ctest Portable.Baseline.*
// runs every suite so); in the baseline copy, PSS_SIMD=baseline forces the kernels' SSE2 copy,
// otherwise their AVX2 copy runs where the CPU has it.
#include "pss/Kernel.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

namespace
{

bool environmentHas(const char* name, const char* text)
{
  const char* value = std::getenv(name);
  return value && std::strstr(value, text);
}

} // namespace

TEST(Dispatch, CopyAndKernelsFollowTheCpuAndTheEnvironment)
{
  const std::string chosen = pss::kernelInstructionSet();
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2");
  // What x86-64-v3 adds to AVX2 that a compiler's code uses (glibc checks these and a few more).
  const bool x86_64_v3 = avx2 && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
#else
  const bool avx2 = false;
  const bool x86_64_v3 = false;
#endif
#if defined(PSS_TEST_CORE_X86_64_V3)
  if (x86_64_v3 && !environmentHas("GLIBC_TUNABLES", "-AVX2"))
  {
    EXPECT_EQ(chosen, "x86-64-v3");
    return;
  }
#else
  (void)x86_64_v3;
#endif
  const char* forced = std::getenv("PSS_SIMD");
  if (forced && std::string(forced) == "baseline")
  {
    EXPECT_EQ(chosen, "baseline");
  }
  else
  {
    EXPECT_EQ(chosen, avx2 ? "avx2" : "baseline");
  }
}

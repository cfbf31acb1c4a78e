// SPDX-License-Identifier: BSD-3-Clause
// The vector kernels' run-time dispatch (pss/KernelDispatch.cxx): PSS_SIMD=baseline forces the SSE2 copy
// (ctest Portable.Baseline.* runs every suite so), otherwise the AVX2 copy runs where the CPU has it.
#include "pss/Kernel.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

TEST(Dispatch, InstructionSetFollowsTheEnvironment)
{
  const std::string chosen = pss::kernelInstructionSet();
  const char* forced = std::getenv("PSS_SIMD");
  if (forced && std::string(forced) == "baseline")
  {
    EXPECT_EQ(chosen, "baseline");
  }
  else
  {
    EXPECT_TRUE(chosen == "baseline" || chosen == "avx2") << chosen;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    EXPECT_EQ(chosen, __builtin_cpu_supports("avx2") ? "avx2" : "baseline");
#endif
  }
}

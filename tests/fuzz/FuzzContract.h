// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FuzzContract.h
 * @brief How the fuzz targets report a broken contract: a message naming the target and the line,
 *        then abort(), which libFuzzer records as a crash with the input that caused it.
 */
#pragma once

#include <cstdio>
#include <cstdlib>

/// The fuzz target's name in the messages (each target defines it once).
extern const char* const FuzzTargetName;

[[noreturn]] inline void FuzzFail(const char* what, int line)
{
  std::fprintf(stderr, "%s: contract broken at line %d: %s\n", FuzzTargetName, line, what);
  std::abort();
}

#define PSS_FUZZ_CHECK(cond)                                                                                       \
  do                                                                                                               \
  {                                                                                                                \
    if (!(cond))                                                                                                   \
    {                                                                                                              \
      FuzzFail(#cond, __LINE__);                                                                                   \
    }                                                                                                              \
  } while (false)

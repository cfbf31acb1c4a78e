// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FuzzContract.h
 * @brief How the fuzz targets report a broken contract: a message naming the target and the line,
 *        then abort(), which libFuzzer records as a crash with the input that caused it; and the
 *        scratch folder a target writes its inputs to.
 */
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>
#include <vector>

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

/// A new folder $TMPDIR/PREFIX-XXXXXX (TMPDIR default /tmp) for a target's scratch files; a
/// folder that cannot be made is a broken contract of the machine, reported as such.
inline std::string MakeScratchFolder(const char* prefix)
{
  const char* tmp = std::getenv("TMPDIR");
  const std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/" + prefix + "-XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (!mkdtemp(buffer.data()))
  {
    FuzzFail("mkdtemp failed", __LINE__);
  }
  return buffer.data();
}

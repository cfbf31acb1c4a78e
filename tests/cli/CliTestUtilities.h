// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CliTestUtilities.h
 * @brief Running the pss tool from a test: its exit code and everything it printed, and paths of
 *        scratch files under the build folder.
 */
#pragma once

#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <sys/wait.h>

namespace pss_cli_test
{

struct CommandResult
{
  int exitCode = -1;  // -1 when the command did not exit normally (a crash)
  std::string output; // stdout and stderr together
};

/// Runs a shell command line, capturing everything it prints.
inline CommandResult RunCommand(const std::string& commandLine)
{
  CommandResult r;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((commandLine + " 2>&1").c_str(), "r"), pclose);
  if (!pipe)
  {
    return r;
  }
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe.get()))
  {
    r.output += buffer.data();
  }
  const int status = pclose(pipe.release());
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// The pss executable under test.
inline const std::string& Pss()
{
  static const std::string path = PSS_CLI_PATH;
  return path;
}

/// A scratch file for @p name under the build folder's Testing/.
inline std::string TempPath(const std::string& name)
{
  return std::string(PSS_BINARY_DIR) + "/Testing/cli-" + name;
}

}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Text.h
 * @brief The few string helpers the readers share (tables, VTK XML attributes, extensions).
 */
#ifndef pss_cli_io_Text_h
#define pss_cli_io_Text_h

#include <string>
#include <vector>

namespace pss_cli
{
namespace io
{

std::string Lower(std::string s);

/// @p s without leading and trailing spaces, tabs and line ends.
std::string Trim(const std::string& s);

/// True when all of @p token (trimmed, not empty) is one number for strtod.
bool ParseDouble(const std::string& token, double& value);

/// The fields of @p line: comma-separated (trimmed) when @p commas, else whitespace-separated.
std::vector<std::string> Split(const std::string& line, bool commas);

}
}

#endif

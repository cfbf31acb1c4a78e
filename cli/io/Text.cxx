// SPDX-License-Identifier: BSD-3-Clause
#include "Text.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

namespace pss_cli
{
namespace io
{

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string Trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool ParseDouble(const std::string& token, double& value)
{
  const std::string t = Trim(token);
  if (t.empty())
  {
    return false;
  }
  char* end = nullptr;
  value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size();
}

std::vector<std::string> Split(const std::string& line, bool commas)
{
  std::vector<std::string> out;
  if (commas)
  {
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ','))
    {
      out.push_back(Trim(item));
    }
  }
  else
  {
    std::istringstream ss(line);
    std::string item;
    while (ss >> item)
    {
      out.push_back(item);
    }
  }
  return out;
}

}
}

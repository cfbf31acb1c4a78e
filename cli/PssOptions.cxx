// SPDX-License-Identifier: BSD-3-Clause
#include "PssOptions.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <sstream>

namespace pss_cli
{

void OptionTable::Value(const std::string& name, const std::string& hint, const std::string& help,
  std::function<void(const std::string&)> apply)
{
  this->Entries.push_back({ name, hint, help, std::move(apply) });
}

void OptionTable::Switch(const std::string& name, const std::string& help, std::function<void()> apply)
{
  this->Entries.push_back({ name, "", help, [apply](const std::string&) { apply(); } });
}

std::vector<std::string> OptionTable::Parse(const std::vector<std::string>& args) const
{
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (arg.size() < 2 || arg[0] != '-' || (arg.size() > 1 && std::isdigit(static_cast<unsigned char>(arg[1]))))
    {
      positional.push_back(arg);
      continue;
    }
    std::string name = arg.substr(arg.rfind("--", 0) == 0 ? 2 : 1);
    std::string value;
    bool hasValue = false;
    const auto eq = name.find('=');
    if (eq != std::string::npos)
    {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      hasValue = true;
    }
    const auto it = std::find_if(this->Entries.begin(), this->Entries.end(), [&](const Entry& e) { return e.name == name; });
    if (it == this->Entries.end())
    {
      throw UsageError{ "unknown option --" + name + " (see --help)" };
    }
    if (it->hint.empty())
    {
      if (hasValue)
      {
        throw UsageError{ "--" + name + " takes no value" };
      }
      it->apply("");
      continue;
    }
    if (!hasValue)
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ "--" + name + " needs a value (" + it->hint + ")" };
      }
      value = args[++i];
    }
    it->apply(value);
  }
  return positional;
}

std::string OptionTable::Help() const
{
  std::size_t width = 0;
  for (const Entry& e : this->Entries)
  {
    width = std::max(width, e.name.size() + (e.hint.empty() ? 0 : e.hint.size() + 1));
  }
  std::ostringstream out;
  for (const Entry& e : this->Entries)
  {
    std::string left = "--" + e.name + (e.hint.empty() ? "" : " " + e.hint);
    left.resize(width + 4, ' ');
    out << "  " << left << e.help << "\n";
  }
  return out.str();
}

double ToDouble(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
  {
    throw UsageError{ "--" + flag + " expects a number, got '" + text + "'" };
  }
  return v;
}

double ToNumberIn(const std::string& flag, const std::string& text, double lo, double hi, const std::string& unit)
{
  const double x = ToDouble(flag, text);
  if (!(x >= lo && x <= hi))
  {
    std::ostringstream msg;
    msg << "--" << flag << " must be within [" << lo << ", " << hi << "]" << unit << ", not " << text;
    throw std::runtime_error(msg.str());
  }
  return x;
}

int ToInt(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < INT_MIN || v > INT_MAX)
  {
    throw UsageError{ "--" + flag + " expects an integer, got '" + text + "'" };
  }
  return static_cast<int>(v);
}

void ToDimensions(const std::string& flag, const std::string& text, int dims[3])
{
  std::stringstream ss(text);
  std::string item;
  int count = 0;
  dims[2] = 1;
  while (std::getline(ss, item, ','))
  {
    if (count == 3)
    {
      throw UsageError{ "--" + flag + " expects NX,NY[,NZ], got '" + text + "'" };
    }
    dims[count++] = ToInt(flag, item);
  }
  if (count < 2)
  {
    throw UsageError{ "--" + flag + " expects NX,NY[,NZ], got '" + text + "'" };
  }
}

std::pair<int, int> ToImageSize(const std::string& flag, const std::string& text, int largest)
{
  const auto x = text.find('x');
  int width = 0, height = 0;
  try
  {
    width = x == std::string::npos ? 0 : ToInt(flag, text.substr(0, x));
    height = x == std::string::npos ? 0 : ToInt(flag, text.substr(x + 1));
  }
  catch (const UsageError&)
  {
    width = height = 0; // reported below with the expected form
  }
  if (width < 1 || height < 1 || width > largest || height > largest)
  {
    throw UsageError{ "--" + flag + " expects WIDTHxHEIGHT, each in [1, " + std::to_string(largest) + "], got '" +
      text + "'" };
  }
  return { width, height };
}

int ToChoice(const std::string& flag, const std::string& text, const std::vector<std::string>& names)
{
  auto canonical = [](std::string s) {
    for (char& c : s)
    {
      c = c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return s;
  };
  const std::string key = canonical(text);
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    if (canonical(names[i]) == key)
    {
      return static_cast<int>(i);
    }
  }
  std::string all;
  for (const std::string& n : names)
  {
    all += (all.empty() ? "" : ", ") + n;
  }
  throw UsageError{ "--" + flag + " must be one of " + all + ", got '" + text + "'" };
}

}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesWords.h
 * @brief The words of a line of a text header (PCD's, and PLY's in the pss tool): split at spaces,
 *        tabs and a Windows line end's carriage return.
 */
#ifndef PointSetSurfacesWords_h
#define PointSetSurfacesWords_h

#include <string_view>
#include <vector>

namespace pss_vtk
{

/// The words of @p line, as views into it.
inline std::vector<std::string_view> SplitWords(std::string_view line)
{
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && blank(line[i]))
    {
      ++i;
    }
    const std::size_t begin = i;
    while (i < line.size() && !blank(line[i]))
    {
      ++i;
    }
    if (i > begin)
    {
      words.push_back(line.substr(begin, i - begin));
    }
  }
  return words;
}

}

#endif

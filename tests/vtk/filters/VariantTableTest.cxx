// SPDX-License-Identifier: BSD-3-Clause
// The surface definitions are listed once, in the core's pss::variantTable(). Every other face
// that names them is checked against it here: the VTK enum, the plugin's drop-down, the pss
// tool's --variant choices and the pvpython examples' dictionary. Adding a row without updating
// a face (or renaming one) fails this test.
#include "vtkNew.h"
#include "vtkPointSetSurface.h"

#include "pss/VariantCatalog.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace
{

std::string ReadText(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Standard output of a command (empty if it cannot run).
std::string Output(const std::string& command)
{
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe)
  {
    return out;
  }
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe.get()))
  {
    out += buffer;
  }
  return out;
}

// "LevinMLS" -> "LEVIN_MLS": the VTK enum's spelling of a table identifier.
std::string EnumSpelling(const std::string& identifier)
{
  std::string out;
  for (std::size_t i = 0; i < identifier.size(); ++i)
  {
    const char c = identifier[i];
    const bool wordStart = i > 0 && std::isupper(static_cast<unsigned char>(c)) &&
      std::islower(static_cast<unsigned char>(identifier[i - 1]));
    if (wordStart)
    {
      out += '_';
    }
    out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

} // namespace

TEST(VariantTable, VtkEnumAgrees)
{
  // The header's enumerators, by name, with their values.
  const std::string header = ReadText(PSS_SOURCE_DIR "/filters/vtkPointSetSurface.h");
  const std::regex enumBlock(R"(enum VariantType\s*\{([^}]*)\})");
  std::smatch block;
  ASSERT_TRUE(std::regex_search(header, block, enumBlock)) << "no enum VariantType in vtkPointSetSurface.h";
  std::map<std::string, int> enumerators;
  const std::string body = block[1];
  const std::regex entry(R"((\w+)\s*=\s*(\d+))");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry); it != std::sregex_iterator(); ++it)
  {
    enumerators[(*it)[1]] = std::stoi((*it)[2]);
  }
  EXPECT_EQ(enumerators.size(), pss::variantTable().size()) << "the VTK enum and the table list different counts";
  vtkNew<vtkPointSetSurface> surface;
  for (const pss::VariantInfo& row : pss::variantTable())
  {
    const int value = static_cast<int>(row.variant);
    const std::string spelling = EnumSpelling(row.identifier);
    ASSERT_TRUE(enumerators.count(spelling)) << "vtkPointSetSurface has no enumerator " << spelling;
    EXPECT_EQ(enumerators[spelling], value) << spelling;
    EXPECT_NE(header.find("SetVariantTo" + std::string(row.identifier) + "()"), std::string::npos)
      << "vtkPointSetSurface has no SetVariantTo" << row.identifier;
    surface->SetVariant(value);
    EXPECT_EQ(surface->GetVariant(), value) << "SetVariant clamps " << row.name << " away";
  }
  // The clamp range ends at the table's last row.
  surface->SetVariant(static_cast<int>(pss::variantTable().size()));
  EXPECT_EQ(surface->GetVariant(), static_cast<int>(pss::variantTable().size()) - 1);
}

TEST(VariantTable, PluginDropDownAgrees)
{
  const std::string xml = ReadText(PSS_SOURCE_DIR "/paraview-plugin/PointSetSurfaces.xml.in");
  const std::regex property(
    R"re(<IntVectorProperty name="Variant"[\s\S]*?<EnumerationDomain[^>]*>([\s\S]*?)</EnumerationDomain>)re");
  std::smatch block;
  ASSERT_TRUE(std::regex_search(xml, block, property)) << "no Variant enumeration in the plugin XML";
  std::vector<std::pair<int, std::string>> entries;
  const std::string body = block[1];
  const std::regex entry(R"re(<Entry value="(\d+)" text="([^"]*)"/>)re");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry); it != std::sregex_iterator(); ++it)
  {
    entries.emplace_back(std::stoi((*it)[1]), (*it)[2]);
  }
  ASSERT_EQ(entries.size(), pss::variantTable().size());
  for (std::size_t i = 0; i < entries.size(); ++i)
  {
    const pss::VariantInfo& row = pss::variantTable()[i];
    EXPECT_EQ(entries[i].first, static_cast<int>(row.variant)) << row.name;
    EXPECT_EQ(entries[i].second, row.label) << row.name;
  }
}

TEST(VariantTable, CommandLineChoicesAgree)
{
  const std::string help = Output(std::string("\"") + PSS_CLI_PATH + "\" project --help");
  const std::regex line(R"(--variant NAME\s+([a-z|\s]+?)\s*\(default (\w+)\))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(help, m, line)) << "no --variant line in `pss project --help`:\n" << help;
  std::string expected;
  for (const pss::VariantInfo& row : pss::variantTable())
  {
    expected += (expected.empty() ? "" : " | ") + std::string(row.name);
  }
  EXPECT_EQ(std::regex_replace(std::string(m[1]), std::regex(R"(\s+)"), " "), expected);
}

TEST(VariantTable, PvpythonExamplesAgree)
{
  const std::string py = ReadText(PSS_SOURCE_DIR "/examples/pvpython/pss_example.py");
  const std::regex dict(R"(VARIANTS = \{([^}]*)\})");
  std::smatch block;
  ASSERT_TRUE(std::regex_search(py, block, dict)) << "no VARIANTS dictionary in pss_example.py";
  std::map<std::string, std::string> entries;
  const std::string body = block[1];
  const std::regex entry(R"re("([^"]+)": "([^"]+)")re");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry); it != std::sregex_iterator(); ++it)
  {
    entries[(*it)[1]] = (*it)[2];
  }
  ASSERT_EQ(entries.size(), pss::variantTable().size());
  for (const pss::VariantInfo& row : pss::variantTable())
  {
    ASSERT_TRUE(entries.count(row.name)) << "pss_example.VARIANTS has no " << row.name;
    EXPECT_EQ(entries[row.name], row.label) << row.name;
  }
}

// SPDX-License-Identifier: BSD-3-Clause
// The synthetic scenes are listed once, in the core (pss::Scene, pss::sceneName). Every face that
// names them is checked against it here: the cloud source's enum and SetSceneTo methods, the
// plugin's drop-down and the pss tool's --scene choices. A scene added to the core without a
// face (or renamed in one) fails this test.
#include "vtkNew.h"
#include "vtkPointSetSurfaceCloudSource.h"

#include "pss/SyntheticClouds.h"

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

// "two-sheets" -> "TWO_SHEETS", "TwoSheets" and "Two Sheets": the enum's, the setter's and the
// drop-down's spellings of a scene's name.
struct Spellings
{
  std::string enumerator, camel, label;
};

Spellings Spell(const std::string& name)
{
  Spellings s;
  bool wordStart = true;
  for (char c : name)
  {
    if (c == '-')
    {
      s.enumerator += '_';
      s.label += ' ';
      wordStart = true;
      continue;
    }
    const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    s.enumerator += upper;
    s.camel += wordStart ? upper : c;
    s.label += wordStart ? upper : c;
    wordStart = false;
  }
  return s;
}

} // namespace

TEST(SceneTable, CloudSourceAgrees)
{
  const std::string header = ReadText(PSS_SOURCE_DIR "/filters/vtkPointSetSurfaceCloudSource.h");
  std::smatch block;
  ASSERT_TRUE(std::regex_search(header, block, std::regex(R"(enum SceneType\s*\{([^}]*)\})")));
  std::map<std::string, int> enumerators;
  const std::string body = block[1];
  const std::regex entry(R"((\w+)\s*=\s*(\d+))");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry); it != std::sregex_iterator(); ++it)
  {
    enumerators[(*it)[1]] = std::stoi((*it)[2]);
  }
  EXPECT_EQ(enumerators.size(), static_cast<std::size_t>(pss::SceneCount));
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  for (int value = 0; value < pss::SceneCount; ++value)
  {
    const std::string name = pss::sceneName(static_cast<pss::Scene>(value));
    const Spellings s = Spell(name);
    ASSERT_TRUE(enumerators.count(s.enumerator)) << "no enumerator " << s.enumerator;
    EXPECT_EQ(enumerators[s.enumerator], value) << s.enumerator;
    EXPECT_NE(header.find("SetSceneTo" + s.camel + "()"), std::string::npos) << "no SetSceneTo" << s.camel;
    source->SetScene(value);
    EXPECT_EQ(source->GetScene(), value) << "SetScene clamps " << name << " away";
    EXPECT_EQ(source->GetSceneAsString(), name);
  }
  source->SetScene(pss::SceneCount);
  EXPECT_EQ(source->GetScene(), pss::SceneCount - 1);
}

TEST(SceneTable, PluginDropDownAgrees)
{
  const std::string xml = ReadText(PSS_SOURCE_DIR "/paraview-plugin/PointSetSurfaces.xml.in");
  std::smatch block;
  ASSERT_TRUE(std::regex_search(xml, block,
    std::regex(R"re(<IntVectorProperty name="Scene"[\s\S]*?<EnumerationDomain[^>]*>([\s\S]*?)</EnumerationDomain>)re")));
  std::vector<std::pair<int, std::string>> entries;
  const std::string body = block[1];
  const std::regex entry(R"re(<Entry value="(\d+)" text="([^"]*)"/>)re");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry); it != std::sregex_iterator(); ++it)
  {
    entries.emplace_back(std::stoi((*it)[1]), (*it)[2]);
  }
  ASSERT_EQ(entries.size(), static_cast<std::size_t>(pss::SceneCount));
  for (int value = 0; value < pss::SceneCount; ++value)
  {
    const std::string name = pss::sceneName(static_cast<pss::Scene>(value));
    EXPECT_EQ(entries[static_cast<std::size_t>(value)].first, value) << name;
    EXPECT_EQ(entries[static_cast<std::size_t>(value)].second, Spell(name).label) << name;
  }
}

TEST(SceneTable, CommandLineChoicesAgree)
{
  const std::string help = Output(std::string("\"") + PSS_CLI_PATH + "\" generate --help");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(help, m, std::regex(R"(--scene NAME\s+([a-z|\-\s]+?)\s*\(default)")))
    << "no --scene line in `pss generate --help`:\n"
    << help;
  std::string expected;
  for (int value = 0; value < pss::SceneCount; ++value)
  {
    expected += (expected.empty() ? "" : " | ") + std::string(pss::sceneName(static_cast<pss::Scene>(value)));
  }
  EXPECT_EQ(std::regex_replace(std::string(m[1]), std::regex(R"(\s+)"), " "), expected);
  // Every listed name is accepted.
  for (int value = 0; value < pss::SceneCount; ++value)
  {
    const std::string name = pss::sceneName(static_cast<pss::Scene>(value));
    const std::string out = Output(std::string("\"") + PSS_CLI_PATH + "\" generate --scene " + name +
      " --image 4x3 --count 5 -o \"" + PSS_BINARY_DIR + "/Testing/scene-table.csv\" 2>&1");
    EXPECT_EQ(out.find("--scene"), std::string::npos) << name << ": " << out;
  }
}

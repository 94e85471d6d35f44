// RobWork's workcell parser is a fixed grammar (reference §1.2): attributes in a fixed order,
// double quotes, a transform before any other child, <Q> last in a device, no unknown elements.
// The project's loader is more lenient, so these rules are checked here on the text of the
// project's hand files and of the workcell writer's output.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "built_scene.hpp"
#include "rw/loaders/workcell_writer.hpp"
#include "scene_test_helpers.hpp"

namespace {

namespace fs = std::filesystem;

// Attribute order of every element RobWork's grammar knows that these files use.
const std::map<std::string, std::vector<std::string>>& attributeOrder() {
  static const std::map<std::string, std::vector<std::string>> order{
      {"WorkCell", {"name"}},
      {"TreeDevice", {"name"}},
      {"SerialDevice", {"name"}},
      {"ParallelDevice", {"name"}},
      {"Junction", {}},
      {"Chains", {}},
      {"SerialChain", {"name"}},
      {"Frame", {"name", "refframe", "type", "daf"}},
      {"Joint", {"name", "refframe", "type", "state"}},
      {"Drawable", {"name", "refframe", "colmodel"}},
      {"CollisionModel", {"name", "refframe"}},
      {"RPY", {}},
      {"Pos", {}},
      {"RGB", {}},
      {"PosLimit", {"refjoint", "min", "max"}},
      {"VelLimit", {"refjoint", "max"}},
      {"AccLimit", {"refjoint", "max"}},
      {"Depend", {"on", "gain", "offset"}},
      {"Property", {"name", "type", "refframe", "desc"}},
      {"Q", {"name"}},
      {"Box", {"x", "y", "z"}},
      {"Sphere", {"radius"}},
      {"Cylinder", {"radius", "z"}},
      {"Tube", {"radius", "thickness", "z"}},
      {"Cone", {"radius", "z"}},
      {"Plane", {}},
      {"Custom", {"type", "param"}},
      {"Polytope", {"file"}},
      {"CollisionSetup", {"file"}},
      {"ProximitySetup", {"file"}},
  };
  return order;
}

bool takesTransform(const std::string& tag) {
  return tag == "Frame" || tag == "Joint" || tag == "Drawable" || tag == "CollisionModel";
}

bool isDevice(const std::string& tag) {
  return tag == "TreeDevice" || tag == "SerialDevice" || tag == "ParallelDevice";
}

struct OpenElement {
  std::string tag;
  int line = 0;
  std::vector<std::string> children;
};

// Checks the children of a closed element.
void checkChildren(const OpenElement& e, std::vector<std::string>& problems) {
  const auto where = " in <" + e.tag + "> at line " + std::to_string(e.line);
  if (takesTransform(e.tag)) {
    // RobWork needs the transform first, as a <RPY> <Pos> pair; the project writes RPY first.
    const bool hasTransform = !e.children.empty() && e.children[0] == "RPY";
    if (hasTransform && (e.children.size() < 2 || e.children[1] != "Pos")) {
      problems.push_back("<RPY> without a following <Pos>" + where);
    }
    for (std::size_t i = hasTransform ? 2 : 0; i < e.children.size(); ++i) {
      if (e.children[i] == "RPY" || e.children[i] == "Pos" || e.children[i] == "Transform") {
        problems.push_back("a transform that is not the first child" + where);
      }
    }
    if (!hasTransform && e.tag != "Frame" && e.tag != "Joint") {
      problems.push_back("no transform" + where + " (the project always writes one)");
    }
  }
  if (isDevice(e.tag)) {
    // The body, then (ParallelDevice) the Junctions, then the Qs.
    bool seenQ = false;
    bool seenJunction = false;
    for (const std::string& child : e.children) {
      if (seenQ && child != "Q") problems.push_back("<" + child + "> after a <Q>" + where);
      if (seenJunction && child != "Q" && child != "Junction") {
        problems.push_back("<" + child + "> after a <Junction>" + where);
      }
      seenQ = seenQ || child == "Q";
      seenJunction = seenJunction || child == "Junction";
    }
  }
}

// Reads the attribute names of a start tag's text (after the tag name), checking the quotes.
std::vector<std::string> attributeNames(const std::string& text, int line,
                                        std::vector<std::string>& problems) {
  std::vector<std::string> names;
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i >= text.size() || text[i] == '/') break;
    const std::size_t eq = text.find('=', i);
    if (eq == std::string::npos) break;
    names.push_back(text.substr(i, eq - i));
    if (eq + 1 >= text.size() || text[eq + 1] != '"') {
      problems.push_back("attribute " + names.back() + " not in double quotes at line " +
                         std::to_string(line));
      break;
    }
    i = text.find('"', eq + 2) + 1;
  }
  return names;
}

void checkAttributes(const std::string& tag, const std::vector<std::string>& names, int line,
                     std::vector<std::string>& problems) {
  const auto known = attributeOrder().find(tag);
  if (known == attributeOrder().end()) {
    problems.push_back("element <" + tag + "> at line " + std::to_string(line) +
                       " is not in RobWork's grammar");
    return;
  }
  std::size_t next = 0;
  for (const std::string& name : names) {
    const auto& allowed = known->second;
    std::size_t pos = next;
    while (pos < allowed.size() && allowed[pos] != name) ++pos;
    if (pos == allowed.size()) {
      problems.push_back("attribute \"" + name + "\" of <" + tag + "> at line " +
                         std::to_string(line) + " is unknown or out of RobWork's order");
    } else {
      next = pos + 1;
    }
  }
}

// Every breach of RobWork's grammar rules in a workcell document.
std::vector<std::string> grammarProblems(const std::string& xml) {
  std::vector<std::string> problems;
  std::vector<OpenElement> stack;
  std::size_t i = 0;
  while ((i = xml.find('<', i)) != std::string::npos) {
    const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + i, '\n'));
    if (xml.compare(i, 4, "<!--") == 0) {
      i = xml.find("-->", i) + 3;
      continue;
    }
    const std::size_t end = xml.find('>', i);
    std::string tagText = xml.substr(i + 1, end - i - 1);
    i = end + 1;
    if (tagText.starts_with("?")) continue;
    if (tagText.starts_with("/")) {
      if (!stack.empty()) {
        checkChildren(stack.back(), problems);
        stack.pop_back();
      }
      continue;
    }
    const bool selfClosing = tagText.ends_with("/");
    const std::size_t nameEnd = tagText.find_first_of(" \t\n/");
    const std::string tag = tagText.substr(0, nameEnd);
    checkAttributes(
        tag,
        attributeNames(nameEnd == std::string::npos ? "" : tagText.substr(nameEnd), line, problems),
        line, problems);
    if (!stack.empty()) stack.back().children.push_back(tag);
    if (!selfClosing) stack.push_back({tag, line, {}});
  }
  return problems;
}

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

TEST(RobWorkGrammar, TheCheckerSeesBreaches) {
  const auto problems = grammarProblems(
      "<TreeDevice name=\"D\">\n"
      "  <Joint type=\"Revolute\" name=\"J\"><PosLimit min=\"0\" max=\"1\"/>"
      "<RPY>0 0 0</RPY><Pos>0 0 0</Pos></Joint>\n"
      "  <Q name=\"Home\">0</Q>\n"
      "  <Frame name='F'><Sphere radius=\"1\"/></Frame>\n"
      "  <Unknown/>\n"
      "</TreeDevice>\n");
  EXPECT_EQ(problems.size(), 7u) << joined(problems);
}

TEST(RobWorkGrammar, TheCheckerSeesABodyElementAfterAJunction) {
  const auto problems = grammarProblems(
      "<ParallelDevice name=\"P\">\n"
      "  <Frame name=\"B\"/>\n"
      "  <Junction><Chains>A</Chains><Chains>B</Chains></Junction>\n"
      "  <Frame name=\"F\"/>\n"
      "  <Q name=\"Home\">0</Q>\n"
      "</ParallelDevice>\n");
  EXPECT_EQ(problems, std::vector<std::string>{"<Frame> after a <Junction> in <ParallelDevice> "
                                               "at line 1"});
}

TEST(RobWorkGrammar, ProjectHandsFollowRobWorksGrammar) {
  for (const fs::path& file :
       {visgrab::test::scenes::projectSdhFile(), visgrab::test::scenes::projectPg70File(),
        visgrab::test::sourceDir() / "scenes/hands/robotiq2f85/robotiq2f85.wc.xml",
        visgrab::test::sourceDir() / "scenes/hands/franka/franka.wc.xml"}) {
    EXPECT_EQ(joined(grammarProblems(readText(file))), "") << file;
  }
}

TEST(RobWorkGrammar, WriterOutputFollowsRobWorksGrammar) {
  visgrab::test::TempDir dir;
  const auto scene = visgrab::test::scenes::buildScene(dir.path());
  EXPECT_EQ(joined(grammarProblems(rw::loaders::writeWorkCell(*scene.wc, dir.path()))), "");
  const auto sdh = visgrab::test::scenes::load(visgrab::test::scenes::projectSdhFile());
  EXPECT_EQ(joined(grammarProblems(rw::loaders::writeWorkCell(*sdh, dir.path()))), "");
}

TEST(RobWorkGrammar, WriterOutputForRobWorksScenesFollowsRobWorksGrammar) {
  REQUIRE_COMPAT_DATA(data);
  visgrab::test::TempDir dir;
  for (const char* path : {"devices/SDH2/SchunkHand.wc.xml", "scene/grasping/pg70_box.wc.xml",
                           "devices/Robotiq-2-finger-85/robotiq.wc.xml"}) {
    const auto wc = visgrab::test::scenes::load(data / path);
    EXPECT_EQ(joined(grammarProblems(rw::loaders::writeWorkCell(*wc, dir.path()))), "") << path;
  }
}

}  // namespace

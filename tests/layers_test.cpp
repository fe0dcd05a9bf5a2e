// The layers of docs/architecture.md, a Y: the utilities and the effect
// registry at the foot; the simulator on one arm and the fitter (data →
// model → engines → fit) on the other, neither knowing the other; the
// studies join them; the command line on top. A source file includes headers
// of its own layer or of the layers below it, never of a layer above or of
// the other arm. Also checked: the libraries are linked the same way, and no
// source file is longer than 600 lines.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace gyrotherm {
namespace {

namespace fs = std::filesystem;

// Each layer and the layers it may use directly (the test closes them
// transitively).
const std::map<std::string, std::vector<std::string>>& graph() {
  static const std::map<std::string, std::vector<std::string>> g = {
      {"sim/util", {}},
      {"sim/effects", {"sim/util"}},
      {"sim", {"sim/effects", "sim/util"}},
      {"fit/data", {"sim/effects", "sim/util"}},
      {"fit/model", {"fit/data"}},
      {"fit/engines", {"fit/model"}},
      {"fit", {"fit/engines"}},
      {"studies", {"fit", "sim"}},
      {"app", {"studies"}},
      {"python", {"studies"}},  // the Python package's extension: beside app, not above it
  };
  return g;
}

// Every layer `layer` may include: itself and all below it.
std::set<std::string> reachable(const std::string& layer) {
  std::set<std::string> seen = {layer};
  std::vector<std::string> todo = {layer};
  while (!todo.empty()) {
    const std::string l = todo.back();
    todo.pop_back();
    for (const std::string& below : graph().at(l))
      if (seen.insert(below).second) todo.push_back(below);
  }
  return seen;
}

// The layer of a path relative to the source tree ("" outside the layers):
// the deepest folder of the graph that holds it.
std::string layer_of(const std::string& path) {
  std::string best;
  for (const auto& [layer, below] : graph()) {
    const std::string prefix = layer + "/";
    if (path.rfind(prefix, 0) == 0 && prefix.size() > best.size() + 1) best = layer;
  }
  return best;
}

std::vector<fs::path> sources() {
  std::vector<fs::path> out;
  const fs::path root(GYROTHERM_SOURCE_DIR);
  for (const char* top : {"sim", "fit", "studies", "app", "python"})
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const std::string ext = entry.path().extension().string();
      if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp" || ext == ".def"))
        out.push_back(entry.path());
    }
  return out;
}

TEST(Layers, KnowsWhereEachFolderSitsAndTheArmsOfTheY) {
  EXPECT_EQ(layer_of("sim/util/random.h"), "sim/util");
  EXPECT_EQ(layer_of("sim/simulator.h"), "sim");
  EXPECT_EQ(layer_of("fit/engines/ols.h"), "fit/engines");
  EXPECT_EQ(layer_of("fit/pipeline.h"), "fit");
  EXPECT_EQ(layer_of("studies/score/campaign.h"), "studies");
  EXPECT_EQ(layer_of("tests/cli_runner.h"), "");
  EXPECT_TRUE(reachable("fit/engines").contains("fit/model"));
  EXPECT_FALSE(reachable("fit/model").contains("fit/engines"));
  // The two arms: neither the simulator nor any part of the fitter reaches the other.
  for (const char* fitter : {"fit/data", "fit/model", "fit/engines", "fit"}) {
    EXPECT_FALSE(reachable(fitter).contains("sim")) << fitter;
    EXPECT_TRUE(reachable(fitter).contains("sim/effects")) << fitter;
    EXPECT_FALSE(reachable("sim").contains(fitter)) << fitter;
  }
  EXPECT_TRUE(reachable("studies").contains("sim"));
  EXPECT_TRUE(reachable("studies").contains("fit/data"));
}

TEST(Layers, NoFileIncludesALayerAboveItsOwn) {
  const fs::path root(GYROTHERM_SOURCE_DIR);
  const std::regex include(R"(^\s*#\s*include\s+\"([^\"]+)\")");
  std::vector<std::string> violations;
  std::size_t checked = 0;
  for (const fs::path& file : sources()) {
    const std::string rel = fs::relative(file, root).string();
    const std::string own = layer_of(rel);
    ASSERT_FALSE(own.empty()) << rel;
    const std::set<std::string> allowed = reachable(own);
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_search(line, m, include)) continue;
      const std::string target = layer_of(m[1].str());
      if (target.empty()) continue;  // a header beside it, or a system one
      ++checked;
      if (!allowed.contains(target)) violations.push_back(rel + " includes " + m[1].str());
    }
  }
  EXPECT_GT(checked, 100u) << "the scan found almost no includes: is the source tree there?";
  std::string list;
  for (const std::string& v : violations) list += "\n  " + v;
  EXPECT_TRUE(violations.empty()) << "includes that go up a layer or across the Y:" << list;
}

// The libraries' link lines (CMakeLists.txt of each folder) say the same: the
// simulator's and the fitter's libraries do not link each other.
TEST(Layers, TheLibrariesLinkAsTheLayers) {
  const fs::path root(GYROTHERM_SOURCE_DIR);
  const std::map<std::string, std::string> library = {
      {"sim/util", "gyrotherm_util"},    {"sim/effects", "gyrotherm_effects"}, {"sim", "gyrotherm_sim"},
      {"fit/data", "gyrotherm_data"},    {"fit/model", "gyrotherm_model"},     {"fit/engines", "gyrotherm_engines"},
      {"fit", "gyrotherm_fit"},          {"studies", "gyrotherm_studies"}};
  const std::regex link(R"(target_link_libraries\(\s*(\w+)([^)]*)\))");
  std::size_t seen = 0;
  for (const auto& [layer, name] : library) {
    std::ifstream in(root / layer / "CMakeLists.txt");
    ASSERT_TRUE(in) << layer;
    std::stringstream text;
    text << in.rdbuf();
    const std::string cmake = text.str();
    const std::set<std::string> allowed = reachable(layer);
    for (auto it = std::sregex_iterator(cmake.begin(), cmake.end(), link); it != std::sregex_iterator(); ++it) {
      if ((*it)[1].str() != name) continue;
      ++seen;
      const std::string targets = (*it)[2].str();
      for (const auto& [other_layer, other] : library) {
        const std::regex word("\\b" + other + "\\b");
        if (std::regex_search(targets, word)) {
          EXPECT_TRUE(allowed.contains(other_layer)) << name << " links " << other;
        }
      }
    }
  }
  EXPECT_EQ(seen, library.size()) << "each library's link line was found";
}

TEST(Layers, NoSourceFileIsLongerThan600Lines) {
  const fs::path root(GYROTHERM_SOURCE_DIR);
  std::vector<std::string> long_files;
  for (const fs::path& file : sources()) {
    std::ifstream in(file);
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    if (lines > 600)
      long_files.push_back(fs::relative(file, root).string() + " (" + std::to_string(lines) + ")");
  }
  std::string list;
  for (const std::string& f : long_files) list += "\n  " + f;
  EXPECT_TRUE(long_files.empty()) << "split these by job:" << list;
}

}  // namespace
}  // namespace gyrotherm

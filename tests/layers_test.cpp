// The layers of docs/architecture.md are one-way: a source file includes
// headers of its own layer or of layers below it, never above. The layers,
// bottom to top:
//
//   sim/util → sim/effects → sim → fit/data → fit/model → fit/engines → fit
//            → studies → app
//
// (a file belongs to the deepest folder of this list that holds it). Also
// checked: no source file is longer than 600 lines.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace gyrotherm {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kLayers = {"sim/util", "sim/effects", "sim",     "fit/data", "fit/model",
                                          "fit/engines", "fit",     "studies", "app"};

// The layer of a path relative to the source tree, or -1 outside the layers.
int layer_of(const std::string& path) {
  int best = -1;
  std::size_t best_length = 0;
  for (std::size_t i = 0; i < kLayers.size(); ++i) {
    const std::string prefix = kLayers[i] + "/";
    if (path.rfind(prefix, 0) == 0 && prefix.size() > best_length) {
      best = static_cast<int>(i);
      best_length = prefix.size();
    }
  }
  return best;
}

std::vector<fs::path> sources() {
  std::vector<fs::path> out;
  const fs::path root(GYROTHERM_SOURCE_DIR);
  for (const char* top : {"sim", "fit", "studies", "app"})
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const std::string ext = entry.path().extension().string();
      if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp" || ext == ".def"))
        out.push_back(entry.path());
    }
  return out;
}

TEST(Layers, KnowsWhereEachFolderSits) {
  EXPECT_EQ(layer_of("sim/util/random.h"), 0);
  EXPECT_EQ(layer_of("sim/simulator.h"), 2);
  EXPECT_EQ(layer_of("fit/engines/ols.h"), 5);
  EXPECT_EQ(layer_of("fit/pipeline.h"), 6);
  EXPECT_EQ(layer_of("studies/score/campaign.h"), 7);
  EXPECT_EQ(layer_of("tests/cli_runner.h"), -1);
  EXPECT_LT(layer_of("fit/model/terms.h"), layer_of("fit/engines/engine.h"));
}

TEST(Layers, NoFileIncludesALayerAboveItsOwn) {
  const fs::path root(GYROTHERM_SOURCE_DIR);
  const std::regex include(R"(^\s*#\s*include\s+\"([^\"]+)\")");
  std::vector<std::string> violations;
  std::size_t checked = 0;
  for (const fs::path& file : sources()) {
    const std::string rel = fs::relative(file, root).string();
    const int own = layer_of(rel);
    ASSERT_GE(own, 0) << rel;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_search(line, m, include)) continue;
      const int target = layer_of(m[1].str());
      if (target < 0) continue;  // a header beside it, or a system one
      ++checked;
      if (target > own) violations.push_back(rel + " includes " + m[1].str());
    }
  }
  EXPECT_GT(checked, 100u) << "the scan found almost no includes: is the source tree there?";
  std::string list;
  for (const std::string& v : violations) list += "\n  " + v;
  EXPECT_TRUE(violations.empty()) << "includes that go up a layer:" << list;
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

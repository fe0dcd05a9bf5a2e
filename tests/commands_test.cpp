// The subcommand registry (app/commands.def): every command listed there is
// on the command line, has its own help and its own file, and the CLI has no
// command that is not listed.

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "cli_runner.h"

namespace gyrotherm::testing {
namespace {

std::vector<std::string> listed_commands() {
  std::ifstream in(source_path("app/commands.def"));
  std::vector<std::string> out;
  const std::regex line(R"(^COMMAND\((\w+)\)\s*$)");
  for (std::string text; std::getline(in, text);) {
    std::smatch m;
    if (std::regex_match(text, m, line)) out.push_back(m[1].str());
  }
  return out;
}

TEST(Commands, EveryListedCommandIsOneFileAndAnswersHelp) {
  const std::vector<std::string> commands = listed_commands();
  ASSERT_GE(commands.size(), 10u) << "app/commands.def was read";
  ScratchDir dir;
  const CliResult help = run_cli(dir, "--help");
  ASSERT_EQ(help.exit_code, 0);
  for (const std::string& name : commands) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(std::filesystem::exists(source_path("app/" + name + "_command.cpp")));
    EXPECT_NE(help.out.find("  " + name + " "), std::string::npos) << help.out;
    const CliResult own = run_cli(dir, name + " --help");
    EXPECT_EQ(own.exit_code, 0) << own.err;
    EXPECT_NE(own.out.find("Usage:"), std::string::npos);
  }
  // No command on the line that the list does not hold.
  const std::regex shown(R"(^  (\w+)\s{2,})");
  std::istringstream lines(help.out.substr(help.out.find("Subcommands:")));
  std::set<std::string> on_line;
  for (std::string text; std::getline(lines, text);) {
    std::smatch m;
    if (std::regex_search(text, m, shown)) on_line.insert(m[1].str());
  }
  EXPECT_EQ(on_line, std::set<std::string>(commands.begin(), commands.end()));
}

}  // namespace
}  // namespace gyrotherm::testing

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

// A typo in a command or an option is answered with the name it was near
// (within two edits), exit 2; a word near nothing gets the list alone.
TEST(Commands, ATypoIsAnsweredWithTheNameItWasNear) {
  ScratchDir dir;
  expect_refused(dir, "fti data.csv", "'fti' is no command (did you mean 'fit'?); the commands: simulate, fit");
  expect_refused(dir, "fit data.csv --modle T", "--modle is no option of fit (did you mean '--model'?)");
  expect_refused(dir, "diagnose data.csv --candidate T^3", "did you mean '--candidates'?");
  expect_refused(dir, "xyzzy", "'xyzzy' is no command; the commands:");
  EXPECT_EQ(run_cli(dir, "xyzzy").err.find("did you mean"), std::string::npos);  // near nothing: the list alone
}

}  // namespace
}  // namespace gyrotherm::testing

#pragma once
// Every command's options, listed from its option table: what Python's
// options() returns, the contract test walks, and docs/options.md is
// generated from (options_markdown; tests/option_table_test.cpp fails when
// the file differs and rewrites it with GYROTHERM_UPDATE_DOCS=1).

#include <string>
#include <vector>

#include "sim/util/option_table.h"

namespace gyrotherm::studies {

struct CommandOptions {
  std::string command;
  std::vector<OptionInfo> rows;
};

// In the order the commands are documented.
const std::vector<CommandOptions>& every_command_options();
// The rows of `command`; nullptr for a command without a table.
const CommandOptions* command_options(const std::string& command);

// docs/options.md: per command, a table of each option's names, value,
// default and help.
std::string options_markdown();

}  // namespace gyrotherm::studies

#pragma once
// A command's option table (sim/util/option_table.h) on its CLI11
// subcommand: each row a positional, an option, a flag or a repeatable list,
// required or not, with its help; when the command is chosen its options are
// set from what was given (row.set, row by row) and handed to `work`. A value
// that does not parse is the row's InputError (exit 2, as every bad input).
// Every command's options are a table. Only option_binding.cpp includes CLI11.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "sim/util/option_table.h"

namespace CLI {
class Option;
}

namespace gyrotherm::app {

// (row, value) for every value given, rows in table order.
using GivenValues = std::vector<std::pair<std::size_t, std::string>>;
// Adds the rows to `command`; the function returned reads what was given.
std::function<GivenValues()> add_rows(CLI::App* command, const std::vector<OptionInfo>& rows);

template <class Options>
void bind_command(CLI::App* command, Run* run, const OptionTable<Options>& table,
                  std::function<int(const Options&)> work) {
  std::function<GivenValues()> given = add_rows(command, list_options(table));
  when_chosen(command, run, [&table, given = std::move(given), work = std::move(work)] {
    Options options;
    for (const auto& [row, value] : given()) table.rows[row].set(options, value);
    return work(options);
  });
}

// A subcommand `name` with its option table, in one call.
template <class Options>
void add_table_command(CLI::App& app, Run* run, const std::string& name, const std::string& description,
                       const OptionTable<Options>& table, std::function<int(const Options&)> work) {
  bind_command<Options>(add_subcommand(app, name, description), run, table, std::move(work));
}

}  // namespace gyrotherm::app

#include "app/option_binding.h"

#include <CLI/CLI.hpp>

#include <memory>

namespace gyrotherm::app {

std::function<GivenValues()> add_rows(CLI::App* command, const std::vector<studies::OptionInfo>& rows) {
  struct Slot {
    CLI::Option* option = nullptr;
    studies::OptionKind kind = studies::OptionKind::text;
    bool flag = false;
    std::string text;
    std::vector<std::string> list;
  };
  auto slots = std::make_shared<std::vector<Slot>>(rows.size());  // never resized: CLI11 keeps their addresses
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const studies::OptionInfo& row = rows[i];
    Slot& slot = (*slots)[i];
    slot.kind = row.kind;
    if (row.kind == studies::OptionKind::flag) {
      slot.option = command->add_flag(row.names, slot.flag, row.help);
    } else if (row.kind == studies::OptionKind::list) {
      slot.option = command->add_option(row.names, slot.list, row.help);
      slot.option->option_text(row.value_name + (row.required ? " REQUIRED" : ""));
    } else {
      slot.option = command->add_option(row.names, slot.text, row.help)->type_name(row.value_name);
    }
    if (row.required) slot.option->required();
  }
  return [slots] {
    GivenValues given;
    for (std::size_t i = 0; i < slots->size(); ++i) {
      const Slot& slot = (*slots)[i];
      if (slot.option->count() == 0) continue;
      if (slot.kind == studies::OptionKind::flag)
        given.emplace_back(i, slot.flag ? "true" : "false");
      else if (slot.kind == studies::OptionKind::list)
        for (const std::string& value : slot.list) given.emplace_back(i, value);
      else
        given.emplace_back(i, slot.text);
    }
    return given;
  };
}

}  // namespace gyrotherm::app

#pragma once
// "a,b,,c" → {"a", "b", "c"}: the comma-separated lists of the command line
// (--engines, --candidates, --axes).

#include <sstream>
#include <string>
#include <vector>

namespace gyrotherm {

inline std::vector<std::string> split_commas(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream s(list);
  std::string item;
  while (std::getline(s, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace gyrotherm

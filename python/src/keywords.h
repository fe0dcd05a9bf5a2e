#pragma once
// Keyword options from Python (keyword → value as text, a list as repeated
// pairs) read by each command's option table, the CLI's own
// (studies/options/): the same names, parsing, defaults, checks and messages.

#include <pybind11/pybind11.h>

#include <initializer_list>
#include <string>
#include <string_view>

#include "sim/util/option_table.h"

namespace gyrotherm::python {

using Keywords = KeywordValues;

// The command's options struct set from the keywords by its table; the rows
// named in `optional_here` are not required (simulate's output: a Python
// caller gets the record without a file).
template <class Options>
Options read_keywords(const OptionTable<Options>& table, const Keywords& keywords,
                      std::initializer_list<std::string_view> optional_here = {}) {
  Options options;
  if (optional_here.size() == 0) {
    apply_options(table, options, keywords);
    return options;
  }
  OptionTable<Options> relaxed = table;
  for (auto& row : relaxed.rows)
    for (std::string_view k : optional_here)
      if (row.keyword == k) row.required = false;
  apply_options(relaxed, options, keywords);
  return options;
}

// The keywords with data=NAME first, for a record given as arrays (the
// tables require the positional data a path would fill).
Keywords with_data(Keywords keywords, const std::string& name);

// gyrotherm.options(command): the table's rows as dicts.
pybind11::list option_rows(const std::string& command);

}  // namespace gyrotherm::python

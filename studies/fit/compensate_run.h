#pragma once
// `gyrotherm compensate`: every channel of a saved fit applied to a log, read
// with the fit's own columns and units (fit/compensation.h); a log too large
// to hold, with one channel, in one pass. All channels are computed before
// the output is written.

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fit/compensation.h"
#include "fit/data/table.h"

namespace gyrotherm::studies {

struct CompensateRequest {
  std::string data;
  std::string fit_file;
  // A fit given in memory (the Python package's), used in place of reading
  // fit_file, which then only names it.
  std::vector<fit::SavedFit> fits;
  std::string output;  // the compensated CSV, or ""
  bool causal = false;
  // Evaluate the model outside the temperature range it was fitted on,
  // rather than hold its temperature terms at the range's edge.
  bool extrapolate = false;
  // Columns and units of the log where they differ from the fit's (set
  // fields only; ColumnMap::unset()): --gyro-col lists one column per channel.
  fit::ColumnMap columns = fit::ColumnMap::unset();
};

struct CompensateRun {
  CompensateRequest request;
  std::vector<fit::SavedFit> fits;
  std::vector<fit::Compensation> channels;          // one per fit channel
  std::vector<nlohmann::ordered_json> channel_json;  // compensate --json per channel
};

CompensateRun run_compensate(const CompensateRequest& request);
// The same on a table of arrays held by the caller (fit/data/table.h), read
// into memory (fit::read_table) with the fit's columns, units and --rate (not
// its CSV's delimiter or decimal comma: fit::for_table) and request.columns;
// request.data is ignored (the run's copy and the JSON's data name the table).
CompensateRun run_compensate(const CompensateRequest& request, const fit::Table& table);
// compensate --json: one object, or {"channels": [...]}.
nlohmann::ordered_json compensate_json(const CompensateRun& run);
std::string compensate_text(const CompensateRun& run);

}  // namespace gyrotherm::studies

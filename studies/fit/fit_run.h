#pragma once
// `gyrotherm fit`: a model fitted to every gyro channel of a log, each read in
// memory or, for a log too large to hold, in one pass (fit/data/streaming.h);
// against the simulator's truth when the log is one `simulate` wrote
// (studies/simulated.h). Every channel is fitted before anything is written:
// a bad one leaves no file.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fit/data/table.h"
#include "fit/pipeline.h"
#include "studies/simulated.h"

namespace gyrotherm::studies {

struct FitRequest {
  std::string data;                       // the log
  std::vector<const fit::Term*> terms;    // the model
  std::string engine = "ols";
  fit::EngineSettings settings;
  fit::PipelineOptions pipeline;          // columns (gyro: the comma list of channels), units, rules
  std::string output;                     // -o FIT.json, or ""
  // The JSON records the data file's SHA-256 (data.sha256: check knows the
  // log fitted by it); the command's text report, which has no use for it,
  // spares the extra pass over a large log.
  bool hash_data = true;
};

struct ChannelFit {
  std::string channel;
  fit::PipelineOptions pipeline;
  fit::PreparedData data;
  fit::ModelFit result;
  std::optional<Truth> truth;
  bool streamed = false;  // prepared by its first kPrefixRows rows' rules: a large log, a long table
  nlohmann::ordered_json json;
};

struct FitRun {
  FitRequest request;
  const fit::EngineInfo* engine = nullptr;
  std::vector<ChannelFit> channels;
  // An accelerometer's three axes that make no gravity (accel_magnitude): a
  // fact of the three together, said once; each channel's JSON carries it.
  std::optional<fit::UnitCaution> gravity;
  std::string json;  // what -o saved and --json prints (one object, or {"channels": [...]})
};

// Fits every channel, then writes request.output (atomically) if named.
// Throws InputError (nothing written) on bad input.
FitRun run_fit(const FitRequest& request);
// The same on a table of arrays held by the caller (fit/data/table.h),
// prepared in one pass straight from its columns (fit::prepare_table);
// request.data is ignored (the run's copy, the JSON's data.file and the
// report name the table), and `truth`, when given, is set against a fit of
// one channel.
FitRun run_fit(const FitRequest& request, const fit::Table& table, std::optional<Truth> truth = {});

// The report for people: per channel the data, the coefficients with their
// intervals (and the truth), the instability and the engine's summary; with
// several channels, a summary table.
std::string fit_text(const FitRun& run);

}  // namespace gyrotherm::studies

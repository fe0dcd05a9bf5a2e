#pragma once
// `gyrotherm diagnose` over every gyro channel of a log (--gyro-col gx,gy,gz):
// each read in memory, where every other numeric column of the log may be a
// candidate, or, for a log too large to hold, in one pass without them
// (fit/data/streaming.h); diagnosed (studies/diagnose/report.h), with figures
// if asked; and the report for people.

#include <cstdint>
#include <string>
#include <vector>

#include <functional>

#include <nlohmann/json_fwd.hpp>

#include "fit/data/table.h"
#include "studies/diagnose/report.h"

namespace gyrotherm::studies {

// Logs over this size get progress: reading and diagnosing them take a second
// or more (the simulated 72 h record, 17 MB, 1.2 s; a 75 MB log, 12 s).
inline constexpr std::uintmax_t kDiagnoseProgressAboveBytes = 16ull << 20;

struct DiagnoseRequest {
  std::string data;
  std::vector<const fit::Term*> base_terms;  // --model
  std::vector<const fit::Term*> terms;       // --model and the --add terms
  std::vector<std::string> added;            // the --add texts, as given (for the report)
  std::string engine = "ols";
  fit::EngineSettings settings;
  fit::PipelineOptions pipeline;             // columns (gyro: the comma list of channels), units, rules
  DiagnosisOptions options;                  // --candidates (the channels are never candidates)
  std::string plots;                         // a folder for the figures, or ""
  // Progress (what, share done), called where the work is long: on a log
  // over progress_above_bytes, or streamed (fit/data/streaming.h): reading,
  // then each stage of the diagnosis of each channel. Empty: none.
  std::function<void(const std::string& step, double fraction)> progress;
  std::uintmax_t progress_above_bytes = kDiagnoseProgressAboveBytes;
};

struct ChannelDiagnosis {
  std::string channel;
  fit::PipelineOptions pipeline;
  fit::Measurement measurement;  // empty when streamed
  fit::PreparedData data;
  DiagnoseReport report;
  bool streamed = false;  // prepared in one pass: no samples held, no log columns as candidates
  std::string plots;      // this channel's figures' folder, or ""
};

struct DiagnoseRun {
  DiagnoseRequest request;
  std::vector<ChannelDiagnosis> channels;
};

// Diagnoses every channel, then draws the figures. Throws InputError on bad input.
DiagnoseRun run_diagnose(const DiagnoseRequest& request);
// The same on a table of arrays held by the caller (fit/data/table.h), read
// into memory (fit::read_table: its other numeric columns are candidates as
// a log's are); request.data is ignored (the run's copy and the report name
// the table).
DiagnoseRun run_diagnose(const DiagnoseRequest& request, const fit::Table& table);
// diagnose --json: one object (report.h's diagnosis_json), or {"channels": [...]}.
nlohmann::ordered_json diagnose_json(const DiagnoseRun& run);
// The five steps for people, a channel after another, and a summary table.
std::string diagnose_text(const DiagnoseRun& run);

}  // namespace gyrotherm::studies

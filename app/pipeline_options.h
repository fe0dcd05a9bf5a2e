#pragma once
// Command-line options shared by the commands that read measurements (fit,
// compensate, diagnose): column mapping, averaging window, derivative mode,
// outlier rule.

#include <optional>

#include <cstdint>
#include <string>
#include <vector>

#include "fit/model/formula.h"
#include <fmt/format.h>

#include "fit/pipeline.h"
#include "sim/util/input_error.h"

namespace CLI {
class App;
}

namespace gyrotherm::app {

struct DataOptions {
  fit::PipelineOptions pipeline;
  bool causal = false;
  bool keep_outliers = false;
  std::optional<double> outlier_threshold;
  // Applies the flags to pipeline (call after parsing).
  fit::PipelineOptions resolved() const;
  // The gyro channels of --gyro-col (a comma list), each a column name.
  std::vector<std::string> channels() const;
};

// `pipeline` reading one gyro channel.
fit::PipelineOptions for_channel(fit::PipelineOptions pipeline, const std::string& channel);

// work(channel, pipeline) for every channel in order, each with its own
// pipeline, all before the caller prints or writes anything; with several
// channels an error names its channel.
template <class Work>
auto for_each_channel(const std::vector<std::string>& channels, const fit::PipelineOptions& pipeline,
                      Work work) {
  std::vector<decltype(work(channels.front(), pipeline))> results;
  for (const std::string& channel : channels) {
    try {
      results.push_back(work(channel, for_channel(pipeline, channel)));
    } catch (const InputError& e) {
      if (channels.size() == 1) throw;
      throw InputError(fmt::format("channel {}: {}", channel, e.what()));
    }
  }
  return results;
}

void add_data_options(CLI::App* command, DataOptions& options, bool with_avg = true);

// The model and engine options shared by fit and diagnose.
struct ModelOptions {
  std::string model = std::string(fit::kDefaultModel);
  std::vector<std::string> add;  // terms appended with --add
  std::string engine = "ols";
  std::uint64_t seed = 1;
  // The terms of --model alone, and with the --add terms after them.
  std::vector<const fit::Term*> base_terms() const;
  std::vector<const fit::Term*> terms() const;
};

// `add_help` says what --add does for this command.
void add_model_options(CLI::App* command, ModelOptions& options, const std::string& add_help);

}  // namespace gyrotherm::app

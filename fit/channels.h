#pragma once
// Several gyro channels of one log (--gyro-col gx,gy,gz), each fitted,
// diagnosed, compensated or analysed on its own with the same options: the
// one loop every command runs over them. All channels are done before the
// caller prints or writes anything, so a bad one leaves no file; with several
// channels an error names its channel.

#include <fmt/format.h>

#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/fit_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

// The channels of --gyro-col: a comma list of column names (spaces around a
// name trimmed). Throws InputError for an empty or repeated name.
std::vector<std::string> parse_channels(const std::string& list);

// A file (or folder) name for each channel's output, in order: the channel's
// name with every character but a letter, a digit, '-', '_' and a '.' inside
// the name made '_' ("gyrox rad/s" → "gyrox_rad_s": a '/' would make a path),
// runs of '_' made one; where two channels would share a name, the later get
// _2, _3, ….
std::vector<std::string> channel_file_names(const std::vector<std::string>& channels);

// `pipeline` reading one gyro channel.
PipelineOptions for_channel(PipelineOptions pipeline, const std::string& channel);

// work(channel, pipeline) for every channel in order, each with its own pipeline.
template <class Work>
auto for_each_channel(const std::vector<std::string>& channels, const PipelineOptions& pipeline, Work work) {
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

// work(fit) for every channel a fit file holds (one for a single-channel file).
template <class Work>
auto for_each_saved_fit(const std::vector<SavedFit>& fits, Work work) {
  std::vector<decltype(work(fits.front()))> results;
  for (const SavedFit& fit : fits) {
    try {
      results.push_back(work(fit));
    } catch (const InputError& e) {
      if (fits.size() == 1) throw;
      throw InputError(fmt::format("channel {}: {}", fit.channel, e.what()));
    }
  }
  return results;
}

}  // namespace gyrotherm::fit

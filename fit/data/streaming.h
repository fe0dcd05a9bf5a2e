#pragma once
// Preparing a record too large to hold in memory (a 10-day log at 10 Hz is
// 8.6 million rows): the CSV is read twice and never stored.
//
//  Pass 1: the median time step (the sample interval) and the glitch filter's
//          noise floor s_floor = 1.4826·median|x_k − x_{k−1}|/√2 (or the
//          smallest non-zero step), each from a reservoir sample of all steps
//          (Vitter's algorithm R, 20 000 entries, fixed seed, so the result is
//          deterministic and exact for records of up to 20 001 samples).
//  Pass 2: a streaming Hampel filter with the rule of fit/data/outliers.h: a sample
//          is judged once every sample up to W/2 after it has arrived; its
//          window is the samples within ±W/2 of the same gap-free run; the
//          moving median comes from two balanced multisets (O(log w) per
//          sample), the local MAD is computed only where the floor alone
//          cannot clear the sample. Judged samples go straight into the
//          window averager (fit/data/averaging.h).
//
// Memory: the reservoirs, about W/Δ samples of window, and the averaged
// series; independent of the length of the record.

#include <filesystem>

#include "fit/data/prepare.h"

namespace gyrotherm::fit {

PreparedData prepare_data_streaming(const std::filesystem::path& csv, const PipelineOptions& options);

// The reader switches to streaming above this file size.
inline constexpr std::uintmax_t kStreamingThresholdBytes = 64ull << 20;

// prepare_data(), or prepare_data_streaming() for a file larger than
// kStreamingThresholdBytes; *streamed (if given) says which.
PreparedData prepare_csv(const std::filesystem::path& csv, const PipelineOptions& options,
                         bool* streamed = nullptr);

}  // namespace gyrotherm::fit

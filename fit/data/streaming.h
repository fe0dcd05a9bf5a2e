#pragma once
// Preparing a record of any length in one pass over its CSV, in bounded
// memory: the steps of prepare_data (fit/data/prepare.h), but every row is
// read and parsed once and only about a filter window of rows is held.
//
//  1. Prefix. The first kPrefixRows rows are held. They give what the later
//     steps need up front: the sample interval Δ (the median time step), the
//     glitch filter's floor s_floor and round-off level (fit/data/outliers.h),
//     and whether the record is bursty (fit/data/averaging.h). A record of up
//     to kPrefixRows rows (73 h at 1 Hz, 7.3 h at 10 Hz) is therefore prepared
//     exactly as in memory; a longer one gets the Δ, floor and burst decision
//     of its first kPrefixRows rows (the run lengths and spacing in the report
//     still cover the whole record).
//  2. Filter. The one glitch rule (fit/data/hampel.h, CentredHampel) with the
//     offline filter's window (the samples within ±W/2), median, MAD and
//     decisions. A sample is judged once a sample more than W/2 after it has
//     arrived; most are kept in O(1) by the window's running minimum and
//     maximum, and near glitches the window is kept in order (an
//     order-statistic tree: median O(log w), MAD O(log² w)). The report's scale is
//     taken over every max(1, n/10⁴)-th sample of a record that fits in the
//     prefix (as in memory), over every 1000th sample of a longer one.
//  3. Averaging. Judged samples go straight into the window averager.
//
// Reading and parsing run on other threads (for_each_batch,
// fit/data/measurement.h: a CSV's blocks parsed on one thread per core, in
// the file's order), which hand the rows over in batches (at most
// kBatchesInFlight), so parsing and filtering overlap.
//
// Memory: the prefix (kPrefixRows × 32 bytes, 8 MB), the filter's window, the
// batches (4 MB: large ones mean fewer hand-offs between the cores, each a
// wake-up; with 8192 rows a batch `fit` read 583 MB in 1.22 s, with 32768 in
// 1.0-1.1 s) and the averaged series; nothing grows with the record but the
// series, the gaps and the glitch times.

#include <cstddef>
#include <filesystem>
#include <functional>

#include "fit/data/prepare.h"

namespace gyrotherm::fit {

inline constexpr std::size_t kPrefixRows = std::size_t{1} << 18;  // 262 144
inline constexpr std::size_t kBatchRows = 32768;
inline constexpr std::size_t kBatchesInFlight = 4;

// Throws InputError (naming the file and line) on bad input, as prepare_data.
// Log columns as model terms (options.columns.extra, other_numeric) need the
// in-memory reader.
//
// observe (if given) sees every row, on the preparing thread, in order, a
// batch at a time: `count` rows of four doubles each (time s, temp °C, gyro
// °/h, temp2 °C, 0 without that column), after the units are applied.
using RowObserver = std::function<void(const double* rows, std::size_t count)>;
PreparedData prepare_data_streaming(const std::filesystem::path& csv, const PipelineOptions& options,
                                    const RowObserver& observe = {});

// The reader switches to streaming above this file size, or above
// GYROTHERM_STREAM_ABOVE_MB megabytes (2²⁰ bytes) when that is set (for tests,
// and for machines short of memory; 0 streams every file); throws InputError
// if it is not a whole number.
inline constexpr std::uintmax_t kStreamingThresholdBytes = 64ull << 20;
std::uintmax_t streaming_threshold_bytes();

// prepare_data(), or prepare_data_streaming() for a file larger than
// kStreamingThresholdBytes (without log columns as terms); *streamed (if
// given) says which.
PreparedData prepare_csv(const std::filesystem::path& csv, const PipelineOptions& options,
                         bool* streamed = nullptr);
// Whether prepare_csv streams this file with these options.
bool streams(const std::filesystem::path& csv, const PipelineOptions& options);

}  // namespace gyrotherm::fit

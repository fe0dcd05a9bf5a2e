#include "fit/data/streaming.h"

#include "fit/data/plausibility.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "fit/data/median.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

struct Row {
  double t, temp, gyro, temp2;
};

// What the prefix fixes for the rest of the record.
struct RecordRules {
  double interval_s = 0;  // Δ
  double floor_dph = 0;   // s_floor
  double zero_dph = 0;    // round-off level
  bool judge = false;     // at least 3 samples (fit/data/outliers.cpp judges none otherwise)
  bool bursts = false;
};

// The one-pass preparation: prefix, then filter and averager, one row at a time.
class OnePassPreparer {
 public:
  OnePassPreparer(const PipelineOptions& options, std::string file) : o_(options) { d_.file = std::move(file); }

  void set_header(const CsvHeader& header) {
    has_temp2_ = header.has_temp2;
    d_.units = header.units;
  }

  void add(const Row& r) {
    ++d_.raw_samples;
    probe_.add(r.t, r.temp, r.gyro);
    if (!averager_) {
      prefix_.push_back(r);
      if (prefix_.size() == kPrefixRows) begin_stream(false);
      return;
    }
    stream(r);
  }

  PreparedData finish() {
    if (!averager_) begin_stream(true);
    if (filter_) filter_->finish([this](const Row& r, bool kept) { judged(r, kept); });
    d_.series = averager_->finish();
    d_.averaging = averager_->report();
    d_.outliers.removed = d_.outliers.times_s.size();
    d_.outliers.scale_dph =
        !filter_ || filter_->scales().empty() ? d_.outliers.floor_dph : median_in_place(filter_->scales());
    check_windows_survive(d_.file, d_.series, *averager_, o_.averaging);
    d_.derived = derive(d_.series, o_.derivative, o_.derivative_span_s);
    d_.derivative_span_s = o_.derivative_span_s;
    d_.cautions = unit_cautions(d_.units, probe_.summary());
    return std::move(d_);
  }

 private:
  ReadProbe probe_;  // what the units' plausibility is judged on
  // The rules from the prefix (the whole record if `whole`), then the prefix
  // replayed through the filter.
  void begin_stream(bool whole) {
    const std::size_t n = prefix_.size();
    if (n < 2)
      throw InputError(located(d_.file, 0, fmt::format("{} sample{}: averaging needs at least 2", n,
                                                       n == 1 ? "" : "s")));
    std::vector<double> times(n), jumps(n - 1);
    double largest = std::abs(prefix_[0].gyro);
    times[0] = prefix_[0].t;
    for (std::size_t k = 1; k < n; ++k) {
      times[k] = prefix_[k].t;
      jumps[k - 1] = std::abs(prefix_[k].gyro - prefix_[k - 1].gyro);
      largest = std::max(largest, std::abs(prefix_[k].gyro));
    }
    rules_.interval_s = median_sample_interval_s(times);
    rules_.judge = o_.remove_outliers && n >= 3;
    if (rules_.judge) {
      rules_.zero_dph = kZeroRelative * largest;
      rules_.floor_dph = noise_floor_from_jumps(std::move(jumps), rules_.zero_dph);
    }
    rules_.bursts = in_bursts(times, rules_.interval_s, o_.averaging);
    if (rules_.judge)  // the report's scale: as in memory for a record within the prefix, every 1000th sample otherwise
      filter_.emplace(HampelRule{o_.outliers.threshold, rules_.floor_dph, rules_.zero_dph}, o_.outliers.window_s,
                      whole ? std::max<std::size_t>(1, n / 10000) : 1000);

    d_.outliers.floor_dph = rules_.floor_dph;
    try {
      averager_.emplace(o_.averaging, rules_.interval_s, has_temp2_, rules_.bursts);
    } catch (const InputError& e) {
      throw InputError(located(d_.file, 0, e.what()));
    }
    std::vector<Row> prefix;
    prefix.swap(prefix_);  // released when replayed
    for (const Row& r : prefix) stream(r);
  }

  void stream(const Row& r) {
    if (!rules_.judge) {
      averager_->add(r.t, r.temp, r.gyro, r.temp2, true);
      return;
    }
    filter_->add(r.t, r.gyro, r, [this](const Row& row, bool kept) { judged(row, kept); });
  }

  // A sample the glitch rule has judged goes to the averager.
  void judged(const Row& r, bool kept) {
    if (!kept) d_.outliers.times_s.push_back(r.t);
    averager_->add(r.t, r.temp, r.gyro, r.temp2, kept);
  }

  const PipelineOptions& o_;
  PreparedData d_;
  bool has_temp2_ = false;
  std::vector<Row> prefix_;
  RecordRules rules_;
  std::optional<WindowAverager> averager_;
  std::optional<CentredHampel<Row>> filter_;  // the glitch rule (fit/data/hampel.h)
};

// Batches of rows from the reading thread to the preparing one; emptied
// batches go back to be refilled, so no memory is allocated in the steady state.
class BatchQueue {
 public:
  struct Cancelled {};

  // Reader side.
  std::vector<Row> empty_batch() {
    std::unique_lock lock(mutex_);
    if (spare_.empty()) {
      std::vector<Row> batch;
      batch.reserve(kBatchRows);
      return batch;
    }
    std::vector<Row> batch = std::move(spare_.back());
    spare_.pop_back();
    return batch;
  }
  void set_header(const CsvHeader& header) {
    std::unique_lock lock(mutex_);
    header_ = header;
  }
  void push(std::vector<Row> batch) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return full_.size() < kBatchesInFlight || cancelled_; });
    if (cancelled_) throw Cancelled{};
    full_.push_back(std::move(batch));
    changed_.notify_all();
  }
  void close(std::exception_ptr error = nullptr) {
    std::unique_lock lock(mutex_);
    closed_ = true;
    error_ = std::move(error);
    changed_.notify_all();
  }

  // Preparer side: false at the end of the file; rethrows the reader's error.
  bool pop(std::vector<Row>& batch) {
    std::unique_lock lock(mutex_);
    if (batch.capacity() > 0) {
      batch.clear();
      spare_.push_back(std::move(batch));
    }
    changed_.wait(lock, [&] { return !full_.empty() || closed_; });
    if (!full_.empty()) {
      batch = std::move(full_.front());
      full_.pop_front();
      changed_.notify_all();
      return true;
    }
    if (error_) std::rethrow_exception(error_);
    return false;
  }
  std::optional<CsvHeader> header() {
    std::unique_lock lock(mutex_);
    return header_;
  }
  void cancel() {
    std::unique_lock lock(mutex_);
    cancelled_ = true;
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::vector<Row>> full_;
  std::vector<std::vector<Row>> spare_;
  std::optional<CsvHeader> header_;
  bool closed_ = false, cancelled_ = false;
  std::exception_ptr error_;
};

}  // namespace

PreparedData prepare_data_streaming(const std::filesystem::path& csv, const PipelineOptions& o,
                                    const RowObserver& observe) {
  static_assert(sizeof(Row) == 4 * sizeof(double));
  o.outliers.validate();
  o.averaging.validate();
  OnePassPreparer preparer(o, csv.string());
  BatchQueue queue;
  std::thread reader([&] {
    try {
      std::vector<Row> batch = queue.empty_batch();
      for_each_row(
          csv, o.columns,
          [&](double t, double temp, double gyro, double temp2) {
            batch.push_back({t, temp, gyro, temp2});
            if (batch.size() == kBatchRows) {
              queue.push(std::move(batch));
              batch = queue.empty_batch();
            }
          },
          [&](const CsvHeader& header) { queue.set_header(header); });
      if (!batch.empty()) queue.push(std::move(batch));
      queue.close();
    } catch (const BatchQueue::Cancelled&) {
      queue.close();
    } catch (...) {
      queue.close(std::current_exception());
    }
  });
  try {
    std::vector<Row> batch;
    bool started = false;
    while (queue.pop(batch)) {
      if (!started) preparer.set_header(*queue.header());
      started = true;
      if (observe) observe(reinterpret_cast<const double*>(batch.data()), batch.size());
      for (const Row& r : batch) preparer.add(r);
    }
    reader.join();
    return preparer.finish();
  } catch (...) {
    queue.cancel();
    if (reader.joinable()) reader.join();
    throw;
  }
}

std::uintmax_t streaming_threshold_bytes() {
  const char* text = std::getenv("GYROTHERM_STREAM_ABOVE_MB");
  if (text == nullptr || *text == '\0') return kStreamingThresholdBytes;
  std::uintmax_t mb = 0;
  const char* end = text + std::strlen(text);
  const auto [ptr, ec] = std::from_chars(text, end, mb);
  if (ec != std::errc() || ptr != end || mb > (std::uintmax_t{1} << 40))
    throw InputError(fmt::format("GYROTHERM_STREAM_ABOVE_MB={}: expected a whole number of MB (0 streams every file)", text));
  return mb << 20;
}

bool streams(const std::filesystem::path& csv, const PipelineOptions& options) {
  std::error_code size_error;
  const auto bytes = std::filesystem::file_size(csv, size_error);
  return !size_error && bytes > streaming_threshold_bytes() && options.columns.extra.empty() &&
         !options.columns.other_numeric;
}

PreparedData prepare_csv(const std::filesystem::path& csv, const PipelineOptions& options,
                         bool* streamed) {
  const bool stream = streams(csv, options);
  if (streamed != nullptr) *streamed = stream;
  return stream ? prepare_data_streaming(csv, options) : prepare_data(csv, options);
}

}  // namespace gyrotherm::fit

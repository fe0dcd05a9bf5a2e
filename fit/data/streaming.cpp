#include "fit/data/streaming.h"

#include "fit/data/one_pass.h"

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

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using one_pass::Row;

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
  one_pass::Preparer preparer(o, csv.string());
  BatchQueue queue;
  std::thread reader([&] {
    try {
      for_each_batch(
          csv, o.columns, kBatchRows,
          [&](std::vector<Row>& batch) { queue.push(std::exchange(batch, queue.empty_batch())); },
          [&](const CsvHeader& header) { queue.set_header(header); });
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

// The rest of a large CSV after its first row, read in blocks: one thread at
// a time reads the next block of about a megabyte (cut after its last LF),
// several threads parse blocks at once, and the reading thread takes the
// blocks in the file's order. A block's parse reads each row as parse_row
// would — the fast scan, or split_fields and parse_csv_number where the scan
// leaves it (quotes, blanks, 17-digit numbers) — and takes it only where
// parse_row would: values in range, time increasing within the block and from
// the block before. At the first row it does not take (an error, bar none),
// the rest of the block is read line by line by parse_row, on the reading
// thread, with its true line numbers: values, errors and messages are those
// of the line-by-line reader.

#include <sys/mman.h>

#include <algorithm>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <string_view>
#include <thread>
#include <vector>

#include "fit/data/csv_parser.h"

namespace gyrotherm::fit::csv_parsing {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// The line of `text` from `at` (without its LF, or a CR before it, as read()
// takes a line), `at` moved past it.
std::string_view next_line(std::string_view text, std::size_t& at) {
  const std::size_t lf = text.find('\n', at);
  const std::size_t end = lf == std::string_view::npos ? text.size() : lf;
  std::string_view line = text.substr(at, end - at);
  at = lf == std::string_view::npos ? text.size() : lf + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

}  // namespace

// A buffer in whole huge pages where the system gives them (2 MB aligned,
// MADV_HUGEPAGE): its first touch faults once rather than 512 times.
struct FreeBytes {
  void operator()(char* p) const { std::free(p); }
};

namespace {

std::unique_ptr<char[], FreeBytes> huge_buffer(std::size_t& bytes) {
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  bytes = (bytes + kHuge - 1) / kHuge * kHuge;
  auto* p = static_cast<char*>(std::aligned_alloc(kHuge, bytes));
  if (p == nullptr) throw std::bad_alloc();
  madvise(p, bytes, MADV_HUGEPAGE);  // a hint: without it, ordinary pages
  return std::unique_ptr<char[], FreeBytes>(p);
}

}  // namespace

struct CsvParser::Block {
  // The text, whole lines (a last line without LF only at the end of the
  // file); a buffer that is not zeroed as it grows.
  std::unique_ptr<char[], FreeBytes> text;
  std::size_t size = 0, capacity = 0;
  std::vector<RowValues> rows;   // the rows the parse took
  std::size_t lines = 0;         // the lines the parse went through (all, or those before left_at)
  std::size_t last_row_line = 0; // the line of the last row taken, from 1 in the block
  std::size_t left_at = kNone;   // the offset of the first line the parse left
  std::size_t index = 0;         // in the file
  bool ready = false;
  std::exception_ptr error;

  std::string_view view() const { return {text.get(), size}; }
  void reserve(std::size_t bytes) {
    if (bytes <= capacity) return;
    auto grown = huge_buffer(bytes);
    if (size > 0) std::memcpy(grown.get(), text.get(), size);  // (not from null: the first buffer)
    text = std::move(grown);
    capacity = bytes;
  }
};

bool CsvParser::blocks_possible() const {
  return block_threads_ > 0 && batch_sink_ && naming_ == RowNaming::line && extras_.empty() &&
         csv_.rate_hz <= 0.0 && !(csv_.decimal_comma && delimiter_ == ',');
}

bool CsvParser::converted(const double* values, RowValues& row) const {
  // take_values' conversion and checks, each role written out (the loop over
  // needed_ cost a tenth of the parsing threads' time)
  row.t = convert(kTime, values[column_of_[kTime]]);
  row.temp = convert(kTemp, values[column_of_[kTemp]]);
  row.gyro = convert(kGyro, values[column_of_[kGyro]]);
  row.temp2 = has_temp2_ ? convert(kTemp2, values[column_of_[kTemp2]]) : 0.0;
  return in_range(kTime, row.t) && in_range(kTemp, row.temp) && in_range(kGyro, row.gyro) &&
         (!has_temp2_ || in_range(kTemp2, row.temp2));
}

bool CsvParser::general_fields(std::string_view line, double* values, std::vector<std::string_view>& fields) const {
  // parse_row's general path after the first row, without extra columns
  // (blocks_possible): split_fields, then each needed value as read_row reads it
  if (!split_fields(line, delimiter_, fields).empty() || fields.size() != role_of_column_.size()) return false;
  for (const auto [column, role] : needed_) {
    const std::string_view field = fields[column];
    if (role == kTime && iso_time_) {
      Timestamp t;
      if (!parse_iso8601(unquote_field(field), t)) return false;
      values[column] = static_cast<double>(t.seconds - time_origin_.seconds) + (t.fraction - time_origin_.fraction);
    } else if (!parse_csv_number(field, csv_.decimal_comma, values[column]).empty()) {
      return false;
    }
  }
  return true;
}

void CsvParser::parse_block(Block& b, const std::vector<Take>& plan) const {
  b.rows.clear();
  b.lines = b.last_row_line = 0;
  b.left_at = kNone;
  std::vector<double> values(plan.size(), 0.0);
  std::vector<std::string_view> fields;
  const std::string_view text = b.view();
  for (std::size_t at = 0; at < text.size(); ++b.lines) {
    const std::size_t start = at;
    const std::string_view line = next_line(text, at);
    if (is_blank(line)) continue;
    RowValues row{};
    if (!(scan_fields(line, plan, values.data()) || general_fields(line, values.data(), fields)) ||
        !converted(values.data(), row) || (!b.rows.empty() && !(row.t > b.rows.back().t))) {
      b.left_at = start;
      return;
    }
    b.rows.push_back(row);
    b.last_row_line = b.lines + 1;
  }
}

std::size_t CsvParser::take_block(Block& b, std::size_t line, Measurement& m) {
  if (!b.rows.empty() && !(b.rows.front().t > last_time_)) {  // not after the block before: line by line
    b.rows.clear();
    b.left_at = 0;
    b.lines = 0;
  }
  if (!b.rows.empty()) {
    flush_batch();
    rows_ += b.rows.size();
    last_time_ = b.rows.back().t;
    previous_row_ = line + b.last_row_line;
    batch_sink_(b.rows);
  }
  line += b.lines;
  if (b.left_at == kNone) return line;
  const std::string_view text = b.view();
  for (std::size_t at = b.left_at; at < text.size();) {
    const std::string_view rest_line = next_line(text, at);
    ++line;
    if (!is_blank(rest_line)) parse_row(rest_line, line, m);
  }
  return line;
}

namespace {

// The blocks between the threads: the file's next bytes and the slots of the
// blocks in flight (by index modulo their number).
template <class Block>
class BlockSource {
 public:
  BlockSource(std::FILE* file, std::string_view buffered, bool at_end, std::size_t in_flight,
              std::size_t block_bytes)
      : file_(file), carry_(buffered), at_end_(at_end), slots_(in_flight, nullptr), block_bytes_(block_bytes) {}

  std::mutex mutex;
  std::condition_variable changed;

  // Under the lock: the next block's text into b (false at the end of the file).
  bool fill(Block& b) {
    b.size = 0;
    b.reserve(carry_.size() + 2 * block_bytes_);  // the carried part line and a block, unless a line is longer
    std::memcpy(b.text.get(), carry_.data(), carry_.size());
    b.size = carry_.size();
    carry_.clear();
    for (;;) {
      if (!at_end_) {
        b.reserve(b.size + block_bytes_);
        const std::size_t got = std::fread(b.text.get() + b.size, 1, block_bytes_, file_);
        b.size += got;
        if (got == 0) at_end_ = true;
      }
      if (at_end_) return b.size > 0;
      const void* lf = memrchr(b.text.get(), '\n', b.size);
      if (lf != nullptr) {
        const auto whole = static_cast<std::size_t>(static_cast<const char*>(lf) - b.text.get()) + 1;
        carry_.assign(b.text.get() + whole, b.size - whole);
        b.size = whole;
        return true;
      }
      // a line longer than the block: read on
    }
  }

  std::FILE* file_;
  std::string carry_;
  bool at_end_;
  std::vector<Block*> slots_;
  std::size_t block_bytes_;
  std::size_t next = 0, consumed = 0;
  bool exhausted = false, cancelled = false;

  Block*& slot(std::size_t index) { return slots_[index % slots_.size()]; }
};

}  // namespace

std::size_t CsvParser::read_blocks(LineReader& reader, std::FILE* file, std::size_t line_number, Measurement& m) {
  const std::vector<Take> plan = take_;  // the parsing threads' own: parse_row may plan again
  const std::size_t in_flight = 2 * block_threads_ + 2;
  BlockSource<Block> source(file, reader.rest(), reader.at_end(), in_flight, block_bytes_);
  std::vector<std::unique_ptr<Block>> blocks;
  for (std::size_t i = 0; i < in_flight; ++i) {
    blocks.push_back(std::make_unique<Block>());
    blocks.back()->rows.reserve(block_bytes_ / 24);  // here, in the program's heap, not the parsing threads'
  }
  std::vector<Block*> spare;
  for (auto& b : blocks) spare.push_back(b.get());

  const auto work = [&] {
    for (;;) {
      Block* b = nullptr;
      {
        std::unique_lock lock(source.mutex);
        source.changed.wait(lock, [&] {
          return source.cancelled || source.exhausted || source.next < source.consumed + in_flight;
        });
        if (source.cancelled || source.exhausted) return;
        b = spare.back();
        spare.pop_back();
        b->ready = false;
        b->error = nullptr;
        bool filled = false;
        try {
          filled = source.fill(*b);
        } catch (...) {
          b->error = std::current_exception();
          filled = true;
        }
        if (!filled) {
          spare.push_back(b);
          source.exhausted = true;
          source.changed.notify_all();
          return;
        }
        b->index = source.next++;
        source.slot(b->index) = b;
      }
      if (!b->error) try {
          parse_block(*b, plan);
        } catch (...) {
          b->error = std::current_exception();
        }
      std::unique_lock lock(source.mutex);
      b->ready = true;
      source.changed.notify_all();
    }
  };
  std::vector<std::jthread> threads;
  // Stops and joins the threads however this function ends.
  struct Stop {
    BlockSource<Block>& source;
    std::vector<std::jthread>& threads;
    ~Stop() {
      {
        std::unique_lock lock(source.mutex);
        source.cancelled = true;
        source.changed.notify_all();
      }
      threads.clear();
    }
  } stop{source, threads};
  for (unsigned i = 0; i < block_threads_; ++i) threads.emplace_back(work);

  for (;;) {
    Block* b = nullptr;
    {
      std::unique_lock lock(source.mutex);
      source.changed.wait(lock, [&] {
        const Block* s = source.slot(source.consumed);
        return (s != nullptr && s->index == source.consumed && s->ready) ||
               (source.exhausted && source.consumed == source.next);
      });
      b = source.slot(source.consumed);
      if (b == nullptr || b->index != source.consumed || !b->ready) break;  // the end of the file
    }
    if (b->error) std::rethrow_exception(b->error);
    line_number = take_block(*b, line_number, m);
    std::unique_lock lock(source.mutex);
    source.slot(b->index) = nullptr;
    spare.push_back(b);
    ++source.consumed;
    source.changed.notify_all();
  }
  return line_number;
}

}  // namespace gyrotherm::fit::csv_parsing

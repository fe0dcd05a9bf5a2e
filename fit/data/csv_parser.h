#pragma once
// The CSV reader's classes, for fit/data/measurement.cpp (line by line) and
// fit/data/csv_blocks.cpp (the rest of a large file in blocks on several
// threads) only.

#include <cstddef>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fit/data/autopilot_log.h"
#include "fit/data/column_reader.h"
#include "fit/data/csv_dialect.h"
#include "fit/data/measurement.h"

namespace gyrotherm::fit::csv_parsing {

namespace fs = std::filesystem;
using namespace column_rules;

// Reads a file in fixed blocks and hands out one line at a time (without its
// LF), so a file of any size costs one block of memory plus the longest line.
// std::getline into a std::string would also work, but a block scan with
// memchr is several times faster and lets us count the bytes consumed.
class LineReader {
 public:
  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

  explicit LineReader(std::FILE* file) : file_(file), buffer_(kBlockBytes) {}

  // False at the end of the file. The view is valid until the next call.
  bool next(std::string_view& line) {
    for (;;) {
      const char* first = buffer_.data() + begin_;
      const std::size_t available = end_ - begin_;
      if (const void* lf = std::memchr(first, '\n', available)) {
        const auto length = static_cast<std::size_t>(static_cast<const char*>(lf) - first);
        line = std::string_view(first, length);
        begin_ += length + 1;
        consumed_ += length + 1;
        return true;
      }
      if (at_end_) {
        if (available == 0) return false;
        line = std::string_view(first, available);  // a last line without LF
        begin_ = end_;
        consumed_ += available;
        return true;
      }
      refill();
    }
  }

  bool failed() const { return std::ferror(file_) != 0; }
  // The bytes read but not yet handed out, for a reader that goes on in blocks.
  std::string_view rest() const { return {buffer_.data() + begin_, end_ - begin_}; }
  bool at_end() const { return at_end_; }
  std::size_t consumed_bytes() const { return consumed_; }

 private:
  // Keeps the partial line at the front, grows the buffer only for a line
  // longer than a block, and reads what fits.
  void refill() {
    if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
    const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
    end_ += got;
    if (got == 0) at_end_ = true;
  }

  std::FILE* file_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0, consumed_ = 0;
  bool at_end_ = false;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

bool is_blank(std::string_view line);

// A CSV's lines (or an autopilot log's samples) read by the column rules.
class CsvParser : public ColumnReader {
 public:
  CsvParser(const fs::path& file, const ColumnMap& map) : ColumnReader(file.string(), map, RowNaming::line) {}

  Measurement read(const fs::path& file);
  // Whether read() goes on in blocks of about `block_bytes` (read_blocks)
  // after the first row, on `threads` threads: with a batch sink, for a CSV
  // whose rows can be read apart (no extra columns, no --rate, no decimal
  // commas between comma delimiters).
  void read_in_blocks(unsigned threads, std::size_t block_bytes) {
    block_threads_ = threads;
    if (block_bytes > 0) block_bytes_ = block_bytes;
  }

 private:
  void parse_header(std::string_view line, std::size_t line_number, Measurement& m);
  void parse_row(std::string_view line, std::size_t line_number, Measurement& m);
  // The row read field by field without copies (csv_dialect.h's scan_*): true
  // when taken; false, having taken nothing, for a row it leaves to the
  // general path (split_fields, parse_csv_number), which reads it to the same
  // values or says what is wrong. Not the first row (it fixes the time's form).
  bool parse_row_fast(std::string_view line, std::size_t line_number, Measurement& m);
  // What the fast path does with each column, from the roles, the extras still
  // read and the time's form (after each row the general path reads).
  enum class Take : unsigned char { skip, number, iso_time };
  void plan_fast_rows();
  // The fields of `line` read by `plan` into values (one per column): false,
  // having read part, for a line the fast path leaves to the general one.
  bool scan_fields(std::string_view line, const std::vector<Take>& plan, double* values) const;
  // The same by the general path (split_fields, parse_csv_number) for a line
  // the scan leaves: false where parse_row would fail.
  bool general_fields(std::string_view line, double* values, std::vector<std::string_view>& fields) const;
  // The needed values (values, one per column) converted and checked as
  // take_values does: false where take_values would fail.
  bool converted(const double* values, RowValues& row) const;

  // Reading in blocks (csv_blocks.cpp): the rest of the file after the first
  // row, from `reader`'s buffer on; returns the last line's number.
  bool blocks_possible() const;
  std::size_t read_blocks(LineReader& reader, std::FILE* file, std::size_t line_number, Measurement& m);
  struct Block;
  // The rows of a block's text its parse takes, up to the first line it
  // leaves (csv_blocks.cpp).
  void parse_block(Block& block, const std::vector<Take>& plan) const;
  // A block's rows handed on, and the lines it left read one by one; returns
  // the number of its last line.
  std::size_t take_block(Block& block, std::size_t line_number, Measurement& m);
  // An autopilot log (fit/data/autopilot_log.h) read as the table
  // time_s, temp_c, gyro_x, gyro_y, gyro_z (s, °C, rad/s) of one gyro.
  void read_log(const fs::path& file, const LogFormat& format, Measurement& m);
  // The time field of a row, in the file's unit or as an ISO 8601 timestamp
  // (seconds since the first row's): "" on success, else what is wrong.
  std::string read_time(std::string_view field, Measurement& m, double& value);
  void reserve_for_file(Measurement& m, std::size_t line_bytes) const;

  char delimiter_ = ',';
  std::vector<std::string_view> fields_;  // of the row being read
  Timestamp time_origin_;                 // the first row's, when the time is ISO 8601
  std::vector<Take> take_;                // plan_fast_rows
  std::uintmax_t file_bytes_ = 0, header_end_bytes_ = 0;
  unsigned block_threads_ = 0;               // read_in_blocks: 0 reads line by line
  std::size_t block_bytes_ = std::size_t{1} << 20;
};

}  // namespace gyrotherm::fit::csv_parsing

// Reading a CSV in blocks on several threads (for_each_batch) against reading
// it line by line (for_each_row): the same rows, bit for bit, and the same
// error, whatever the block size, the number of threads and where the
// awkward lines fall (quotes, CRLF, blank lines, a bad value, time going
// back across a block boundary, a line longer than a block, no final LF).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "fit/data/measurement.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

struct Read {
  std::vector<RowValues> rows;
  std::string error;  // the InputError's message, or ""
  std::size_t header_rows = 0;
  std::size_t largest_batch = 0;  // a block's rows come in one batch, however many
};

Read by_lines(const std::filesystem::path& csv) {
  Read r;
  try {
    r.header_rows = for_each_row(csv, ColumnMap{}, [&](double t, double temp, double gyro, double temp2) {
                      r.rows.push_back({t, temp, gyro, temp2});
                    }).rows;
  } catch (const InputError& e) {
    r.error = e.what();
  }
  return r;
}

Read by_blocks(const std::filesystem::path& csv, unsigned threads, std::size_t block_bytes) {
  Read r;
  try {
    r.header_rows = for_each_batch(
                        csv, ColumnMap{}, 7,
                        [&](std::vector<RowValues>& batch) {
                          r.largest_batch = std::max(r.largest_batch, batch.size());
                          r.rows.insert(r.rows.end(), batch.begin(), batch.end());
                          batch.clear();
                        },
                        {}, threads, block_bytes)
                        .rows;
  } catch (const InputError& e) {
    r.error = e.what();
  }
  return r;
}

// The same error, or every pair of rows the same to the last bit (before an
// error, rows still waiting in a batch are not handed on).
void expect_same(const Read& lines, const Read& blocks, const std::string& what) {
  EXPECT_EQ(lines.error, blocks.error) << what;
  if (!lines.error.empty()) return;
  EXPECT_EQ(lines.header_rows, blocks.header_rows) << what;
  ASSERT_EQ(lines.rows.size(), blocks.rows.size()) << what;
  for (std::size_t i = 0; i < lines.rows.size(); ++i)
    ASSERT_EQ(std::memcmp(&lines.rows[i], &blocks.rows[i], sizeof(RowValues)), 0) << what << ", row " << i;
}

// `rows` rows of time, temperature, gyro and a second temperature; `line(i)`
// may replace row i's text.
template <class Edit>
std::string table(std::size_t rows, Edit line) {
  std::string text = "time_s,temp_c,gyro_dph,temp2_c,other\n";
  for (std::size_t i = 0; i < rows; ++i) {
    std::string row = fmt::format("{},{:.3f},{:.6f},{:.2f},x{}", 0.1 * static_cast<double>(i),
                                  20.0 + 0.001 * static_cast<double>(i % 977), 0.5 - 1e-4 * static_cast<double>(i % 313),
                                  21.0 + 0.01 * static_cast<double>(i % 41), i);
    line(i, row);
    text += row + "\n";
  }
  return text;
}

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

void expect_same_every_way(const std::filesystem::path& csv, const std::string& what) {
  const Read lines = by_lines(csv);
  for (const unsigned threads : {1u, 2u, 3u})
    for (const std::size_t block : {std::size_t{40}, std::size_t{333}, std::size_t{4096}, std::size_t{0}})
      expect_same(lines, by_blocks(csv, threads, block), fmt::format("{}: {} threads, blocks of {}", what, threads, block));
}

TEST(CsvBlocks, PlainRowsAreReadAsLineByLine) {
  ScratchDir dir;
  write(dir / "plain.csv", table(5000, [](std::size_t, std::string&) {}));
  const Read lines = by_lines(dir / "plain.csv");
  ASSERT_EQ(lines.rows.size(), 5000u);
  EXPECT_TRUE(lines.error.empty());
  expect_same_every_way(dir / "plain.csv", "plain");
  // The rows did come in blocks: batches of a block's rows, not of 7.
  EXPECT_GT(by_blocks(dir / "plain.csv", 2, 4096).largest_batch, 50u);
}

TEST(CsvBlocks, AwkwardLinesAnywhereAreReadAsLineByLine) {
  ScratchDir dir;
  // Quoted and padded fields (the general path), CRLF endings, blank lines,
  // a comment-free file without its final LF.
  std::string text = table(3000, [](std::size_t i, std::string& row) {
    if (i % 97 == 5) row = fmt::format("\"{}\", {:.3f} ,\"{:.6f}\",{:.2f},\"a,b\"", 0.1 * static_cast<double>(i), 20.5, 0.25, 21.0);
    if (i % 89 == 7) row += "\r";
    if (i % 71 == 3) row += "\n   ";
  });
  text.pop_back();  // no final LF
  write(dir / "awkward.csv", text);
  const Read lines = by_lines(dir / "awkward.csv");
  ASSERT_TRUE(lines.error.empty()) << lines.error;
  ASSERT_EQ(lines.rows.size(), 3000u);
  expect_same_every_way(dir / "awkward.csv", "awkward");
  // The quoted rows were read in their blocks, not left to the reading thread.
  EXPECT_GT(by_blocks(dir / "awkward.csv", 2, 4096).largest_batch, 50u);
}

TEST(CsvBlocks, ErrorsNameTheSameLineAsLineByLine) {
  ScratchDir dir;
  const std::vector<std::pair<std::string, std::size_t>> cases = {
      {"not a number", 2345},      // a value the fast path leaves and the general path refuses
      {"time goes back", 1800},    // time not after the row before
      {"out of range", 2999},      // a temperature no instrument reads
      {"too few fields", 1201},
  };
  for (const auto& [what, at] : cases) {
    const std::string text = table(3000, [&](std::size_t i, std::string& row) {
      if (i != at) return;
      if (what == "not a number") row = "1e999x,20,0.5,21,x";
      if (what == "time goes back") row = fmt::format("{},20,0.5,21,x", 0.1 * static_cast<double>(i) - 1.0);
      if (what == "out of range") row = fmt::format("{},-400,0.5,21,x", 0.1 * static_cast<double>(i));
      if (what == "too few fields") row = "1,2";
    });
    write(dir / "bad.csv", text);
    const Read lines = by_lines(dir / "bad.csv");
    ASSERT_FALSE(lines.error.empty()) << what;
    EXPECT_NE(lines.error.find(fmt::format(":{}:", at + 2)), std::string::npos) << what << ": " << lines.error;
    expect_same_every_way(dir / "bad.csv", what);
  }
}

TEST(CsvBlocks, TimeGoingBackAtEveryBlockBoundaryIsCaught) {
  // Rows that go back in time only from one block to the next: each block on
  // its own increases, so only the check across the boundary can see it.
  ScratchDir dir;
  std::string text = "time_s,temp_c,gyro_dph\n0,20,0.5\n";
  for (int k = 0; k < 40; ++k) text += fmt::format("{},20,0.5\n", 10 - (k % 10));  // 10, 9, ... back in time
  write(dir / "back.csv", text);
  const Read lines = by_lines(dir / "back.csv");
  ASSERT_NE(lines.error.find("is not after"), std::string::npos) << lines.error;
  expect_same_every_way(dir / "back.csv", "back");
}

TEST(CsvBlocks, LineLongerThanABlockIsReadWhole) {
  ScratchDir dir;
  const std::string text = table(400, [](std::size_t i, std::string& row) {
    if (i == 200) row += std::string(5000, 'y');  // the last field: a long word, not read
  });
  write(dir / "long.csv", text);
  const Read lines = by_lines(dir / "long.csv");
  ASSERT_TRUE(lines.error.empty()) << lines.error;
  ASSERT_EQ(lines.rows.size(), 400u);
  expect_same_every_way(dir / "long.csv", "long");
}

}  // namespace
}  // namespace gyrotherm::fit

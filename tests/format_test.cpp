// sim/util/format.h: numbers and counts in messages for people.

#include <gtest/gtest.h>

#include <string_view>
#include <utility>

#include "sim/util/format.h"

namespace gyrotherm {
namespace {

TEST(Format, CountsTakeTheNounInTheRightNumber) {
  EXPECT_EQ(counted(1, "term"), "1 term");
  EXPECT_EQ(counted(0, "term"), "0 terms");
  EXPECT_EQ(counted(3, "window"), "3 windows");
  EXPECT_EQ(counted(1, "glitch", "glitches"), "1 glitch");
  EXPECT_EQ(counted(2, "glitch", "glitches"), "2 glitches");
}

TEST(Format, ARangeShowsEnoughDecimalsToTellItsEndsApart) {
  EXPECT_EQ(range_text(-40.0, 60.0, 0), "-40..60");
  EXPECT_EQ(range_text(13.02, 13.4, 0), "13.0..13.4");   // not 13..13
  EXPECT_EQ(range_text(13.3, 13.6, 0), "13.3..13.6");    // not 13..14
  EXPECT_EQ(range_text(13.3, 13.4, 0), "13.3..13.4");
  EXPECT_EQ(range_text(20.001, 20.004, 1, " to "), "20.001 to 20.004");
  EXPECT_EQ(range_text(5.0, 5.0, 1), "5.0..5.0");        // equal ends: the decimals asked for
  EXPECT_EQ(decimals_to_tell_apart(1.0, 1.0 + 1e-12, 0), 6);  // at most 6
}

// A word a POSIX shell reads back as it was: plain words bare, anything
// with a character the shell would act on in single quotes, a quote inside
// them closed, escaped and reopened.
TEST(Format, AShellWordIsQuotedOnlyWhenTheShellWouldChangeIt) {
  const std::pair<std::string_view, std::string_view> words[] = {
      {"t=0.05,lag=0.3", "t=0.05,lag=0.3"}, {"step@3600", "step@3600"}, {"logs/run_1.csv", "logs/run_1.csv"},
      {"T^3", "'T^3'"}, {"T*dT", "'T*dT'"}, {"my log.csv", "'my log.csv'"}, {"it's", "'it'\\''s'"}, {"", "''"}};
  for (const auto& [word, written] : words) EXPECT_EQ(shell_word(word), written) << word;
}

}  // namespace
}  // namespace gyrotherm

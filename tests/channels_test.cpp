// fit/channels.h: several gyro channels of one log; the file names of their
// outputs, made from channel names such as the PAN log's "gyrox rad/s".

#include "fit/channels.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "cli_runner.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

TEST(Channels, FileNamesAreSafeAndDistinct) {
  EXPECT_EQ(fit::channel_file_names({"gx_dph"}), std::vector<std::string>{"gx_dph"});
  EXPECT_EQ(fit::channel_file_names({"gyrox rad/s", "gyroy rad/s"}),
            (std::vector<std::string>{"gyrox_rad_s", "gyroy_rad_s"}));
  EXPECT_EQ(fit::channel_file_names({"a/b", "a b", "a_b"}), (std::vector<std::string>{"a_b", "a_b_2", "a_b_3"}));
  EXPECT_EQ(fit::channel_file_names({"..", "/", "temp (C)"}), (std::vector<std::string>{"_.", "channel", "temp_C"}));
}

// Two channels named like the PAN log's ("gyrox rad/s"): 3 h at 1 Hz over
// 10..30 °C, each with its own temperature slope and white noise.
void write_slashed_channels(const std::filesystem::path& csv) {
  write_ramp_log(csv, "gyrox rad/s,gyroy rad/s", {2.0, -1.0}, 3.0, 10.0, 30.0, 3);
}

// allan --plot and diagnose --plots write one figure (folder) per channel,
// named safely, and say which.
TEST(Channels, PlotsOfChannelsWithSlashesInTheirNamesAreWrittenWhereTheTextSays) {
  ScratchDir dir;
  write_slashed_channels(dir / "log.csv");
  const std::string channels = " --gyro-col 'gyrox rad/s,gyroy rad/s'";
  const auto allan = run_cli(dir, "allan log.csv" + channels + " --plot adev.png");
  ASSERT_EQ(allan.exit_code, 0) << allan.err;
  for (const char* png : {"adev_gyrox_rad_s.png", "adev_gyroy_rad_s.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / png)) << png;
    EXPECT_NE(allan.out.find(std::string("plot: ") + png + "\n"), std::string::npos) << allan.out;
  }
  EXPECT_EQ(allan.out.find("plot: adev.png"), std::string::npos) << "a file that was not written";

  const auto diagnose = run_cli(dir, "diagnose log.csv" + channels + " --model T --plots figs");
  ASSERT_EQ(diagnose.exit_code, 0) << diagnose.err;
  for (const char* folder : {"gyrox_rad_s", "gyroy_rad_s"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "figs" / folder / "bias_time.png")) << folder;
    EXPECT_NE(diagnose.out.find(std::string("plots in figs/") + folder + "/"), std::string::npos) << diagnose.out;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "figs" / "gyrox rad")) << "no folder nested by the '/'";
}

}  // namespace
}  // namespace gyrotherm

// The shipped scenario files load and describe the paper's tests; bad files
// are rejected with the file, line and key in the message.

#include "sim/config_loader.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "sim/effects/effect.h"
#include "sim/util/input_error.h"
#include "sim/profile.h"

namespace gyrotherm::sim {
namespace {

using namespace gyrotherm::testing;


TEST(ConfigLoader, ShippedCycleIsThePapersTrainingTest) {
  const Scenario s = load_scenario(source_path("scenarios/cycle.toml"));
  EXPECT_TRUE(s.chamber);
  const Profile p(s.start_c, s.segments);
  double lo = 1e9, hi = -1e9;
  int up = 0, down = 0;
  for (std::size_t i = 0; i < s.segments.size(); ++i) {
    const Segment& seg = s.segments[i];
    if (seg.kind == SegmentKind::ramp) {
      EXPECT_EQ(seg.rate_c_per_min, 5.0);
      (seg.temp_c > p.segment_start_c(i) ? up : down)++;
    } else {
      EXPECT_EQ(seg.kind, SegmentKind::hold);
      EXPECT_EQ(seg.duration_s, 7200.0);
    }
    lo = std::min(lo, seg.temp_c);
    hi = std::max(hi, seg.temp_c);
  }
  EXPECT_EQ(lo, -40.0);
  EXPECT_EQ(hi, 60.0);
  EXPECT_GE(up, 2);  // up, down, up
  EXPECT_GE(down, 1);
  const RigConfig rig = load_rig(s.rig_file);
  EXPECT_EQ(rig.chamber.min_c, -60.0);
  EXPECT_EQ(rig.chamber.max_c, 130.0);
  EXPECT_EQ(rig.power.electronics_w, 0.0);  // electronics outside the chamber
  const GyroConfig gyro = load_gyro(s.gyro_file);
  EXPECT_EQ(gyro.coefficient.at("T"), -3.05e-4);
  EXPECT_EQ(gyro.coefficient.at("dT"), 1.81);
}

TEST(ConfigLoader, ShippedRandomProfileIsTest1) {
  const Scenario s = load_scenario(source_path("scenarios/random.toml"));
  std::vector<double> holds;
  for (const Segment& seg : s.segments) {
    if (seg.kind == SegmentKind::ramp) {
      EXPECT_EQ(seg.rate_c_per_min, 1.0);
    }
    if (seg.kind == SegmentKind::hold) {
      holds.push_back(seg.temp_c);
      EXPECT_EQ(seg.duration_s, 8.0 * 3600.0);
    }
  }
  EXPECT_EQ(s.start_c, 15.0);
  EXPECT_EQ(holds, (std::vector<double>{-20, 30, 0, 10, 50, -5, 60, 25}));
  EXPECT_EQ(s.segments.back().kind, SegmentKind::free);
}

TEST(ConfigLoader, ShippedWarmUpHasNoChamber) {
  const Scenario s = load_scenario(source_path("scenarios/warmup.toml"));
  EXPECT_FALSE(s.chamber);
  EXPECT_EQ(s.room_c, 23.0);
  EXPECT_EQ(s.start_c, 23.0);
  const RigConfig rig = load_rig(s.rig_file);
  EXPECT_TRUE(rig.case_.natural_convection);
}

TEST(ConfigLoader, UnknownKeyNamesFileLineAndKey) {
  ScratchDir dir;
  write_text(dir / "rig.toml", "[chamber]\ncapacity_j_per_k = 1000.0\nheater_max = 5.0\n");
  expect_input_error([&] { load_rig(dir / "rig.toml"); },
               {"rig.toml:3", "unknown key 'chamber.heater_max'", "heater_max_w"});
}

TEST(ConfigLoader, NegativeCapacityIsRejected) {
  ScratchDir dir;
  write_text(dir / "rig.toml", "[case]\n\ncapacity_j_per_k = -5\n");
  expect_input_error([&] { load_rig(dir / "rig.toml"); },
               {"rig.toml:3", "case.capacity_j_per_k = -5", "must be > 0"});
}

TEST(ConfigLoader, WrongTypeIsRejected) {
  ScratchDir dir;
  write_text(dir / "gyro.toml", "[noise]\narw_deg_per_sqrt_h = \"low\"\n");
  expect_input_error([&] { load_gyro(dir / "gyro.toml"); },
               {"gyro.toml:2", "noise.arw_deg_per_sqrt_h", "expected a number"});
}

TEST(ConfigLoader, UnknownHiddenTermListsTheValidOnes) {
  ScratchDir dir;
  write_text(dir / "gyro.toml", "[hidden]\ngradient = 0.1\n");
  expect_input_error([&] { load_gyro(dir / "gyro.toml"); },
               {"gyro.toml:2", "hidden.gradient", effects::hidden_names()});
}

TEST(ConfigLoader, InvalidTomlReportsTheLine) {
  ScratchDir dir;
  write_text(dir / "s.toml", "name = \"x\"\nseed = = 3\n");
  expect_input_error([&] { load_scenario(dir / "s.toml"); }, {"s.toml:2", "not valid TOML"});
}

TEST(ConfigLoader, MissingFile) {
  expect_input_error([&] { load_scenario("/nonexistent/scenario.toml"); },
               {"/nonexistent/scenario.toml", "no such file"});
}

std::string scenario_with(const std::string& segment) {
  return "name = \"t\"\nstart_c = 20.0\n\n[[segment]]\n" + segment;
}

TEST(ConfigLoader, NegativeDuration) {
  ScratchDir dir;
  write_text(dir / "s.toml", scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = -1.0\n"));
  expect_input_error([&] { load_scenario(dir / "s.toml"); },
               {"s.toml:7", "segment 1.duration_h = -1", "must be > 0"});
}

TEST(ConfigLoader, ZeroOrNegativeRampRate) {
  ScratchDir dir;
  for (const std::string rate : {"0.0", "-5.0"}) {
    write_text(dir / "s.toml",
               scenario_with("kind = \"ramp\"\ntarget_c = 60.0\nrate_c_per_min = " + rate + "\n"));
    expect_input_error([&] { load_scenario(dir / "s.toml"); },
                 {"s.toml:7", "segment 1.rate_c_per_min", "must be > 0"});
  }
}

TEST(ConfigLoader, TwoDurationsAreAmbiguous) {
  ScratchDir dir;
  write_text(dir / "s.toml", scenario_with("kind = \"free\"\nduration_h = 1.0\nduration_s = 5.0\n"));
  expect_input_error([&] { load_scenario(dir / "s.toml"); },
               {"s.toml:4", "exactly one of duration_s, duration_min, duration_h"});
}

TEST(ConfigLoader, UnknownSegmentKind) {
  ScratchDir dir;
  write_text(dir / "s.toml", scenario_with("kind = \"soak\"\nduration_h = 1.0\n"));
  expect_input_error([&] { load_scenario(dir / "s.toml"); },
               {"s.toml:4", "kind = \"soak\"", "\"hold\", \"ramp\" or \"free\""});
}

TEST(ConfigLoader, KeyThatASegmentKindDoesNotUse) {
  ScratchDir dir;
  write_text(dir / "s.toml",
             scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = 1.0\nrate_c_per_min = 2\n"));
  expect_input_error([&] { load_scenario(dir / "s.toml"); },
               {"s.toml:8", "unknown key 'segment 1.rate_c_per_min'"});
}

TEST(ConfigLoader, SetPointOutsideTheChamberRange) {
  ScratchDir dir;
  write_text(dir / "s.toml", scenario_with("kind = \"ramp\"\ntarget_c = 150.0\nrate_c_per_min = 5\n"));
  const Scenario s = load_scenario(dir / "s.toml");
  expect_input_error([&] { check_scenario_against_rig(s, RigConfig{}, "rig.toml"); },
               {"s.toml:4", "target_c = 150", "outside the chamber's range, -60..130", "rig.toml"});
}

TEST(ConfigLoader, NoChamberAllowsOnlyFreeSegments) {
  ScratchDir dir;
  write_text(dir / "s.toml",
             "chamber = false\n[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_h = 1\n");
  expect_input_error([&] { load_scenario(dir / "s.toml"); }, {"s.toml:2", "chamber = false", "free"});
}

// [spread]: relative ranges of gyro parameters for `gyrotherm score`.
TEST(ConfigLoader, SpreadTableIsRead) {
  ScratchDir dir;
  write_text(dir / "s.toml", scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = 1.0\n") +
                                 "\n[spread]\nb1_dph_per_c = 0.1\narw_deg_per_sqrt_h = 0.2\nglitch_rate_per_h = 0\n");
  const Scenario s = load_scenario(dir / "s.toml");
  EXPECT_EQ(s.spread, (std::map<std::string, double>{
                          {"b1_dph_per_c", 0.1}, {"arw_deg_per_sqrt_h", 0.2}, {"glitch_rate_per_h", 0.0}}));
}

TEST(ConfigLoader, NoSpreadTableMeansNoSpread) {
  EXPECT_TRUE(load_scenario(source_path("scenarios/warmup.toml")).spread.empty());
}

TEST(ConfigLoader, UnknownSpreadKeyNamesFileLineAndKey) {
  ScratchDir dir;
  write_text(dir / "s.toml", scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = 1.0\n") +
                                 "[spread]\nb1 = 0.1\n");
  expect_input_error([&] { load_scenario(dir / "s.toml"); },
               {"s.toml:9", "unknown key 'spread.b1' in [spread]", "b1_dph_per_c", "arw_deg_per_sqrt_h"});
}

TEST(ConfigLoader, SpreadOutOfRangeOrWrongType) {
  ScratchDir dir;
  for (const std::string value : {"1.0", "-0.1", "2"}) {
    write_text(dir / "s.toml", scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = 1.0\n") +
                                   "[spread]\nb3_dph_per_c_per_s = " + value + "\n");
    expect_input_error([&] { load_scenario(dir / "s.toml"); },
                 {"s.toml:9", "spread.b3_dph_per_c_per_s = ", "must be >= 0 and < 1"});
  }
  write_text(dir / "s.toml", scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = 1.0\n") +
                                 "[spread]\nb0_dph = \"wide\"\n");
  expect_input_error([&] { load_scenario(dir / "s.toml"); }, {"s.toml:9", "spread.b0_dph", "expected a number"});
  write_text(dir / "s.toml", "spread = 0.1\n" + scenario_with("kind = \"hold\"\ntemp_c = 20.0\nduration_h = 1.0\n"));
  expect_input_error([&] { load_scenario(dir / "s.toml"); }, {"s.toml:1", "spread: expected a table [spread]"});
}

TEST(ConfigLoader, HiddenOption) {
  GyroConfig g;
  apply_hidden_option(g, "T*dT=2.5e-3");
  EXPECT_EQ(g.coefficient["T*dT"], 2.5e-3);
  expect_input_error([&] { apply_hidden_option(g, "gradient=1"); },
               {"unknown term 'gradient'", effects::hidden_names()});
  // Every effect of the registry is either hidden (settable here) or one of
  // the paper's, set in [truth] under its key.
  for (const effects::Effect* e : effects::registry()) {
    const std::string spec = std::string(e->name) + "=1e-3";
    if (e->hidden()) {
      apply_hidden_option(g, spec);
      EXPECT_EQ(g.coefficient_of(*e), 1e-3) << e->name;
    } else {
      expect_input_error([&] { apply_hidden_option(g, spec); }, {"[truth]", std::string(e->truth_key)});
    }
  }
  expect_input_error([&] { apply_hidden_option(g, "grad=abc"); }, {"'abc' is not a finite number"});
  expect_input_error([&] { apply_hidden_option(g, "grad"); }, {"expected TERM=COEF"});
}

}  // namespace
}  // namespace gyrotherm::sim

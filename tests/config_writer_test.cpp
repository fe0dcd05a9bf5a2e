// The files sim/config_writer.h writes read back (sim/config_loader.h) to
// exactly the values they were written from: the shipped gyro, rigs and
// scenarios, and values chosen to be awkward (no short decimal form, hidden
// effects, a quoted name, the largest seed).

#include "sim/config_writer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <type_traits>
#include <concepts>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "sim/config_loader.h"
#include "sim/effects/effect.h"

namespace gyrotherm::sim {
namespace {

using namespace gyrotherm::testing;

// A field added to one of these must be written by sim/config_writer.cpp and
// compared below: the sizes tell.
static_assert(sizeof(ChamberConfig) == 9 * sizeof(double));
static_assert(sizeof(CaseConfig) == 5 * sizeof(double));  // four numbers and a flag
static_assert(sizeof(BlockConfig) == 5 * sizeof(double));
static_assert(sizeof(SensorConfig) == 3 * sizeof(double));
static_assert(sizeof(PowerConfig) == 3 * sizeof(double));
static_assert(sizeof(NoiseConfig) == 11 * sizeof(double));  // ten numbers and an integer

// Every field, as a tuple of references (compared with ==: the same doubles,
// not close ones; or changed one by one).
template <class Noise>
  requires std::same_as<std::remove_const_t<Noise>, NoiseConfig>
auto fields(Noise& n) {
  return std::tie(n.arw_deg_per_sqrt_h, n.bias_instability_dph, n.flicker_tau_min_s, n.flicker_tau_max_s,
                  n.flicker_processes, n.rrw_dph_per_sqrt_h, n.quantization_arcsec, n.glitch_rate_per_h,
                  n.glitch_size_dph, n.arw_temp_ref_c, n.arw_temp_coeff_per_c2);
}
template <class Rig>
  requires std::same_as<std::remove_const_t<Rig>, RigConfig>
auto fields(Rig& r) {
  auto& c = r.chamber;
  auto& b = r.block;
  return std::tuple_cat(
      std::tie(c.capacity_j_per_k, c.insulation_w_per_k, c.heater_max_w, c.cooler_max_w, c.kp_w_per_k, c.ti_s,
               c.feedforward_j_per_k, c.min_c, c.max_c),
      std::tie(r.case_.capacity_j_per_k, r.case_.convection_w_per_k, r.case_.natural_convection, r.case_.emissivity,
               r.case_.area_m2),
      std::tie(b.anode_capacity_j_per_k, b.far_capacity_j_per_k, b.anode_far_w_per_k, b.anode_case_w_per_k,
               b.far_case_w_per_k),
      std::tie(r.sensor.time_constant_s, r.sensor.noise_c, r.sensor.resolution_c),
      std::tie(r.power.discharge_w, r.power.dither_w, r.power.electronics_w));
}

// Every field moved off its default, within the loader's rules: a number by
// 10 % and 0.01 (no short decimal), an integer by 1, a flag flipped. A field
// the writer left out would read back as its default.
template <class Config>
Config away_from_defaults() {
  Config config;
  std::apply(
      [](auto&... field) {
        const auto move = [](auto& f) {
          using T = std::remove_reference_t<decltype(f)>;
          if constexpr (std::is_same_v<T, bool>) f = !f;
          else if constexpr (std::is_same_v<T, int>) f += 1;
          else f = f * 1.1 + 0.01;
        };
        (move(field), ...);
      },
      fields(config));
  return config;
}

// A scenario's but `file` and the segments (compared on their own).
auto fields(const Scenario& s) {
  return std::make_tuple(s.name, s.description, s.rig_file.string(), s.gyro_file.string(), s.seed, s.sample_rate_hz,
                         s.room_c, s.chamber, s.start_c, s.initial, s.spread);
}
// A segment's but `source_line` (where it was read).
auto fields(const Segment& s) { return std::tie(s.kind, s.temp_c, s.rate_c_per_min, s.duration_s); }

// The same as values (gtest prints them without their addresses).
template <class Config>
auto values(const Config& config) {
  return std::apply([](const auto&... field) { return std::make_tuple(field...); }, fields(config));
}

// The values every effect gets (coefficient and parameter), and the maps
// themselves when `same_maps`.
void expect_same(const GyroConfig& a, const GyroConfig& b, bool same_maps) {
  EXPECT_EQ(a.b0_dph, b.b0_dph);
  for (const effects::Effect* e : effects::registry()) {
    EXPECT_EQ(a.coefficient_of(*e), b.coefficient_of(*e)) << e->name;
    EXPECT_EQ(a.parameter_of(*e), b.parameter_of(*e)) << e->name;
  }
  if (same_maps) {
    EXPECT_EQ(a.coefficient, b.coefficient);
    EXPECT_EQ(a.parameter, b.parameter);
  }
  EXPECT_EQ(values(a.noise), values(b.noise));
}

void expect_same(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(fields(a), fields(b));
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i)
    EXPECT_EQ(values(a.segments[i]), values(b.segments[i])) << "segment " << i + 1;
}

constexpr std::string_view kHeader = "written by config_writer_test\n(a round trip)";

// The scenario written beside the original with its rig and gyro by absolute
// path, read back.
Scenario round_trip(const ScratchDir& dir, const Scenario& s) {
  const auto file = dir / "written.toml";
  write_text(file, scenario_toml(s, s.rig_file.string(), s.gyro_file.string(), kHeader));
  return load_scenario(file);
}

TEST(ConfigWriter, ShippedGyroReadsBackTheSame) {
  const ScratchDir dir;
  const GyroConfig gyro = load_gyro(source_path("scenarios/gyro.toml"));
  const std::string text = gyro_toml(gyro, kHeader);
  EXPECT_EQ(text.rfind("# written by config_writer_test\n# (a round trip)\n", 0), 0u) << text;
  write_text(dir / "gyro.toml", text);
  const GyroConfig back = load_gyro(dir / "gyro.toml");
  expect_same(gyro, back, true);
  EXPECT_EQ(gyro_toml(back, kHeader), text);  // a fixed point
}

TEST(ConfigWriter, ShippedRigsReadBackTheSame) {
  const ScratchDir dir;
  for (const char* name : {"rig_shield.toml", "rig_room.toml", "rig_ins.toml"}) {
    SCOPED_TRACE(name);
    const RigConfig rig = load_rig(source_path(std::string("scenarios/") + name));
    write_text(dir / name, rig_toml(rig, kHeader));
    const RigConfig back = load_rig(dir / name);
    EXPECT_EQ(values(rig), values(back));
  }
}

TEST(ConfigWriter, EveryRigAndNoiseKeyIsWritten) {
  const ScratchDir dir;
  const RigConfig rig = away_from_defaults<RigConfig>();
  const RigConfig defaults;
  EXPECT_NE(values(rig), values(defaults));
  write_text(dir / "rig.toml", rig_toml(rig, kHeader));
  const RigConfig rig_back = load_rig(dir / "rig.toml");
  EXPECT_EQ(values(rig), values(rig_back));
  GyroConfig gyro;
  gyro.noise = away_from_defaults<NoiseConfig>();
  write_text(dir / "gyro.toml", gyro_toml(gyro, kHeader));
  const GyroConfig gyro_back = load_gyro(dir / "gyro.toml");
  EXPECT_EQ(values(gyro.noise), values(gyro_back.noise));
}

TEST(ConfigWriter, ShippedScenariosReadBackTheSame) {
  const ScratchDir dir;
  for (const char* name : {"cycle", "warmup", "random"}) {
    SCOPED_TRACE(name);
    const Scenario s = load_scenario(source_path(std::string("scenarios/") + name + ".toml"));
    expect_same(s, round_trip(dir, s));
  }
  // Hours became seconds: the cycle's 2 h soaks.
  const std::string text = scenario_toml(load_scenario(source_path("scenarios/cycle.toml")), "r.toml", "g.toml", "");
  EXPECT_NE(text.find("duration_s = 7200.0\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("duration_h"), std::string::npos);
  EXPECT_EQ(text.rfind("\nname = \"cycle\"", 0), 0u) << text;  // no header asked for: none
}

TEST(ConfigWriter, RelativeRigAndGyroAreResolvedFromTheWrittenFile) {
  const ScratchDir dir;
  const Scenario s = load_scenario(source_path("scenarios/cycle.toml"));
  write_text(dir / "plan.toml", scenario_toml(s, "rigs/rig.toml", "gyro \"7\".toml", kHeader));
  const Scenario back = load_scenario(dir / "plan.toml");
  EXPECT_EQ(back.rig_file, dir / "rigs/rig.toml");
  EXPECT_EQ(back.gyro_file, dir / "gyro \"7\".toml");
}

TEST(ConfigWriter, GyroWithHiddenEffectsAndAwkwardNumbersReadsBackTheSame) {
  const ScratchDir dir;
  GyroConfig gyro;
  gyro.b0_dph = 0.1 + 0.2;  // 0.30000000000000004: no short decimal
  gyro.coefficient["T"] = -1.0 / 3.0;
  gyro.coefficient.erase("T^2");  // absent: 0
  gyro.coefficient["grad"] = 0.0123;
  gyro.coefficient["lag"] = 3e-3;
  gyro.coefficient["T*dT"] = -2.5e-7;  // a quoted key
  gyro.parameter["lag"] = 1234.5678901234567;
  gyro.noise.arw_deg_per_sqrt_h = 2.7e-4;
  gyro.noise.bias_instability_dph = std::numeric_limits<double>::denorm_min();
  gyro.noise.flicker_tau_max_s = 1e300;
  gyro.noise.flicker_processes = 50;
  gyro.noise.quantization_arcsec = 0.0;
  gyro.noise.arw_temp_ref_c = -0.0;
  gyro.noise.glitch_size_dph = 12345678901234567890.0;  // a whole number beyond int64
  const std::string text = gyro_toml(gyro, kHeader);
  EXPECT_NE(text.find("\"T*dT\" = -2.5e-07"), std::string::npos) << text;
  EXPECT_NE(text.find("lag_time_constant_s = 1234.5678901234567"), std::string::npos) << text;
  write_text(dir / "gyro.toml", text);
  const GyroConfig back = load_gyro(dir / "gyro.toml");
  expect_same(gyro, back, false);  // the loader fills in every hidden term and parameter
  EXPECT_EQ(back.coefficient.at("T^2"), 0.0);
  EXPECT_EQ(back.parameter.at("warmup"), effects::find("warmup")->parameter->simulator_default);
  // Read back once, the maps are complete and the next round trip keeps them.
  write_text(dir / "again.toml", gyro_toml(back, kHeader));
  expect_same(back, load_gyro(dir / "again.toml"), true);
}

TEST(ConfigWriter, GyroWithoutHiddenEffectsHasNoHiddenTable) {
  const ScratchDir dir;
  const GyroConfig gyro;  // the defaults: the paper's terms only
  const std::string text = gyro_toml(gyro, kHeader);
  EXPECT_EQ(text.find("[hidden]"), std::string::npos) << text;
  write_text(dir / "gyro.toml", text);
  expect_same(gyro, load_gyro(dir / "gyro.toml"), true);
}

TEST(ConfigWriter, ScenarioWithoutChamberQuotedTextSpreadAndLargestSeedReadsBackTheSame) {
  const ScratchDir dir;
  Scenario s = load_scenario(source_path("scenarios/warmup.toml"));
  s.name = "plan \"β\"\\2";
  s.description = "line one\nline two\ttab \x01";
  s.seed = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  s.sample_rate_hz = 10.0 / 3.0;
  s.room_c = -0.1;
  s.start_c = s.room_c;  // as the loader leaves it without a chamber
  s.initial = InitialCondition::steady;
  s.segments.push_back({.kind = SegmentKind::free, .duration_s = 0.1});
  s.spread = {{"arw_deg_per_sqrt_h", 0.25}, {"b0_dph", 1.0 / 7.0}};
  expect_same(s, round_trip(dir, s));

  Scenario chamber = load_scenario(source_path("scenarios/cycle.toml"));
  chamber.start_c = 21.123456789;
  chamber.segments.front().duration_s = 1234.5;
  chamber.segments.push_back({.kind = SegmentKind::ramp, .temp_c = 20.0, .rate_c_per_min = 0.7});
  expect_same(chamber, round_trip(dir, chamber));
}

TEST(ConfigWriter, SeedBeyondATomlIntegerIsRefused) {
  Scenario s = load_scenario(source_path("scenarios/cycle.toml"));
  s.seed = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) + 1;
  expect_input_error([&] { (void)scenario_toml(s, "rig.toml", "gyro.toml", ""); },
                     {"seed 9223372036854775808", "up to 9223372036854775807"});
}

}  // namespace
}  // namespace gyrotherm::sim

// diagnose's candidates (studies/diagnose/candidates.h): another motion
// sensor's channels of the same log (fit/data/column_role.h) are no cause of the bias unless named,
// and the report says which of the log's columns were tried.

#include "studies/diagnose/candidates.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>

#include "cli_runner.h"

namespace gyrotherm::studies {
namespace {

using testing::run_cli;
using testing::run_shell;
using testing::ScratchDir;
using testing::simulate_shipped;

bool has_term(const nlohmann::json& j, const std::string& term) {
  const auto& m = j["missing_effects"];
  return std::any_of(m.begin(), m.end(), [&](const nlohmann::json& e) { return e["term"] == term; });
}

// A three-axis log whose other axis carries the same temperature-driven bias
// (a hidden gradient): by correlation it would "explain" gx's missing effect.
TEST(Candidates, AnotherGyroAxisIsNoCauseUnlessNamed) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "--hidden grad=0.0533 --seed 3", "cycle.csv");
  ASSERT_EQ(run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"; srand(1)} /^#/{next} "
                           "/^time/{print \"time_s,chamber_c,case_c,temp_c,temp2_c,gx_dph,gy_dph\"; next} "
                           "{print $1,$2,$3,$4,$5,$6,$7+0.002*(rand()-0.5)}' cycle.csv | tee three.csv")
                .exit_code,
            0);
  const auto plain = run_cli(dir, "diagnose three.csv --gyro-col gx_dph --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const nlohmann::json j = nlohmann::json::parse(plain.out);
  EXPECT_FALSE(has_term(j, "gy_dph"));
  EXPECT_FALSE(has_term(j, "d(gy_dph)"));
  EXPECT_EQ(j["columns_tried"], nlohmann::json({"case_c", "chamber_c"}));
  const std::string skipped = j["skipped"].dump();
  EXPECT_NE(skipped.find("gy_dph (another motion sensor's channel"), std::string::npos) << skipped;
  // Named, it is tried (and, sharing gx's bias, it explains it).
  const auto named = run_cli(dir, "diagnose three.csv --gyro-col gx_dph --candidates +gy_dph --json");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_TRUE(has_term(nlohmann::json::parse(named.out), "gy_dph"));
  // The text says which columns were tried.
  const auto text = run_cli(dir, "diagnose three.csv --gyro-col gx_dph");
  EXPECT_NE(text.out.find("the log's columns tried as causes (each with its rate): case_c, chamber_c"),
            std::string::npos)
      << text.out;
}

}  // namespace
}  // namespace gyrotherm::studies

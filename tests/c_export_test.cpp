// `gyrotherm export --format c` (studies/export/c_header): the generated header,
// compiled by the system's C compiler as strict C99 (and as C++17), run over
// a simulated record, gives compensate --causal's model sample by sample.

#include "studies/export/c_header.h"

#include <gtest/gtest.h>

#include <cctype>
#include <sstream>

#include "cli_runner.h"
#include "fit/compensation.h"
#include "fit/model/terms.h"
#include "fit/pipeline.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;

// Reads the simulator's CSV (time_s, chamber_c, case_c, temp_c, temp2_c,
// gyro_dph, …) and prints the header's bias for every sample.
constexpr const char* kDriver = R"C(
#include <stdio.h>
#include <string.h>
#include "comp.h"
int main(int argc, char **argv) {
  char line[4096];
  gt_comp_state s;
  FILE *f = fopen(argv[1], "r");
  const int gyro = argc > 2 && strcmp(argv[2], "gyro") == 0;
  if (!f) return 2;
  gt_comp_init(&s);
  while (fgets(line, sizeof line, f)) {
    double t, chamber, box, T, T2, g;
    if (line[0] == '#' || line[0] == 't') continue;
    if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf", &t, &chamber, &box, &T, &T2, &g) != 6) return 3;
    printf("%.17g\n", gyro ? gt_comp_update_gyro(&s, t, T, T2, g) : gt_comp_update(&s, t, T, T2));
  }
  fclose(f);
  return 0;
}
)C";

std::vector<double> numbers(const std::string& text) {
  std::vector<double> v;
  std::istringstream in(text);
  for (double x; in >> x;) v.push_back(x);
  return v;
}

// The header for `model` fitted to a simulated `scenario`, compiled as C99
// (and as C++17), run over the record: its bias equals compensate --causal's
// on every sample.
void expect_header_gives_causal(const std::string& scenario, const std::string& model,
                                const std::string& fit_options = "") {
  SCOPED_TRACE(scenario + ": " + model);
  ScratchDir dir;
  simulate_shipped(dir, scenario, "", "d.csv");
  const auto fitted = run_cli(dir, "fit d.csv --model '" + model + "' " + fit_options + " -o fit.json");
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
  const auto exported = run_cli(dir, "export fit.json --format c -o comp.h");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const std::string header = slurp(dir / "comp.h");
  EXPECT_NE(header.find("SHA-256"), std::string::npos);
  EXPECT_NE(header.find("Valid: "), std::string::npos);
  for (const char* forbidden : {"malloc", "printf", "FILE", "<stdio.h>", "<stdlib.h>"})
    EXPECT_EQ(header.find(forbidden), std::string::npos) << forbidden;
  write_text(dir / "drv.c", kDriver);
  const auto cc = run_shell(dir, "cc -std=c99 -Wall -Wextra -Werror -pedantic -O2 drv.c -o drv -lm");
  ASSERT_EQ(cc.exit_code, 0) << cc.err;
  write_text(dir / "drv.cpp", kDriver);
  const auto cxx = run_shell(dir, "c++ -std=c++17 -Wall -Wextra -Werror -pedantic -c drv.cpp -o drv.o");
  EXPECT_EQ(cxx.exit_code, 0) << cxx.err;

  const fit::SavedFit fit = fit::load_fit(dir / "fit.json");
  fit::PipelineOptions pipeline = fit::reading_columns_of(fit.pipeline, fit.terms);
  pipeline.derivative = fit::DerivativeMode::causal;
  const fit::Compensation expected = fit::compensate(fit::read_measurement_csv(dir / "d.csv", pipeline.columns), fit, pipeline);
  const auto run = run_shell(dir, std::string("./drv d.csv ") + (fit.pipeline.remove_outliers ? "gyro" : ""));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<double> got = numbers(run.out);
  ASSERT_EQ(got.size(), expected.model_dph.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < got.size(); ++k) worst = std::max(worst, std::abs(got[k] - expected.model_dph[k]));
  EXPECT_LE(worst, 1e-9) << "°/h";
}

// Every registry term, joined by +.
std::string every_registry_term() {
  std::string model;
  for (const fit::Term* t : fit::term_registry()) model += (model.empty() ? "" : " + ") + std::string(t->name);
  return model;
}

// Each effect of the registry in C, beside the paper's terms: a new effect is
// checked here without a line of this file changing.
class CExportEffect : public ::testing::TestWithParam<const fit::Term*> {};

TEST_P(CExportEffect, TheHeaderGivesCompensateCausalSampleBySample) {
  const std::string name(GetParam()->name);
  const std::string paper = "T + T^2 + dT";
  const bool in_paper = name == "T" || name == "T^2" || name == "dT";
  expect_header_gives_causal("cycle", in_paper ? paper : paper + " + " + name);
}

INSTANTIATE_TEST_SUITE_P(Registry, CExportEffect, ::testing::ValuesIn(fit::term_registry()),
                         [](const ::testing::TestParamInfo<const fit::Term*>& param_info) {
                           std::string name;
                           for (const char c : param_info.param->name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

// Every term at once, with their states side by side, and a step (on the
// random profile, whose range and rates separate them all); without the
// glitch rule; and the warm-up's timing.
TEST(CExport, EveryTermAtOnce) { expect_header_gives_causal("random", every_registry_term() + " + step@20000"); }

TEST(CExport, WithoutTheGlitchRuleAndOnAWarmUp) {
  expect_header_gives_causal("cycle", "T + T^2 + dT", "--keep-outliers");
  expect_header_gives_causal("warmup", "T + T^2 + dT + warmup + t");
}

TEST(CliExportC, BadInputIsRefused) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  write_columns(dir, "d.csv", "v.csv", {{"gyro_dph", "$6"}, {"supply_v", "28+0.001*$1%7"}});
  ASSERT_EQ(run_cli(dir, "fit v.csv --model 'T + dT + supply_v' -o col.json").exit_code, 0);
  expect_refused(dir, "export col.json --format c -o c.h", "the term 'supply_v' has no C form (a log column");
  ASSERT_EQ(run_cli(dir, "fit d.csv -o fit.json").exit_code, 0);
  expect_refused(dir, "export fit.json --format c --prefix 9lives -o c.h", "expected a C identifier");
  write_columns(dir, "d.csv", "two.csv", {{"gx", "$6"}, {"gy", "-$6"}});
  ASSERT_EQ(run_cli(dir, "fit two.csv --gyro-col gx,gy -o two.json").exit_code, 0);
  expect_refused(dir, "export two.json --format c -o c.h", "choose one with --channel");
  expect_refused(dir, "export two.json --format c --channel gz -o c.h", "--channel gz: not a channel of two.json (its channels: gx, gy)");
  EXPECT_FALSE(std::filesystem::exists(dir / "c.h"));
  EXPECT_EQ(run_cli(dir, "export two.json --format c --channel gy --prefix gyro_y -o c.h").exit_code, 0);
  EXPECT_NE(slurp(dir / "c.h").find("gyro_y_update_gyro"), std::string::npos);
}

}  // namespace
}  // namespace gyrotherm::studies

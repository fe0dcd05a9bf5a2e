// Coverage study of ols's 95 % intervals on the simulated −40..60 °C cycle:
// 100 seeds of the simulator's noise, the paper's model fitted by the
// pipeline, how often each interval contains the true coefficient. Writes a
// Markdown table (argument: output file, default results/ols_coverage.md).
// Variants separate the causes: the interval method (nw, ewc), the model (with
// and without d2T, the sensor lag's term), and the noise (with and without
// flicker).

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/util/atomic_file.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"

using namespace gyrotherm;

struct Row {
  std::string method, model;
  bool flicker;
  int covered[3] = {0, 0, 0};
  double bias[3] = {0, 0, 0}, sd[3] = {0, 0, 0}, half[3] = {0, 0, 0};
};

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "results/ols_coverage.md";
  const int seeds = argc > 2 ? std::atoi(argv[2]) : 100;
  const sim::Scenario base = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml");
  const sim::RigConfig rig = sim::load_rig(base.rig_file);
  const sim::GyroConfig gyro = sim::load_gyro(base.gyro_file);
  const double truth[3] = {gyro.coefficient.at("T"), gyro.coefficient.at("T^2"), gyro.coefficient.at("dT")};

  std::vector<Row> rows = {{"nw", "T + T^2 + dT", true},  {"ewc", "T + T^2 + dT", true},
                           {"nw", "T + T^2 + dT + d2T", true}, {"nw", "T + T^2 + dT", false},
                           {"nw", "T + T^2 + dT + d2T", false}, {"ewc", "T + T^2 + dT + d2T", false}};
  for (Row& row : rows) {
    sim::GyroConfig g = gyro;
    if (!row.flicker) g.noise.bias_instability_dph = 0.0;
    const auto terms = fit::parse_formula(row.model);
    fit::EngineSettings settings;
    settings.options["intervals"] = row.method;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int seed = 1; seed <= seeds; ++seed) {
      sim::Scenario sc = base;
      sc.seed = static_cast<std::uint64_t>(seed);
      const sim::SimulationResult r = sim::Simulator(sc, rig, g).run();
      fit::Measurement m;
      m.file = "cycle";
      m.time_s = r.time_s;
      m.temp_c = r.temp_c;
      m.gyro_dph = r.gyro_dph;
      const fit::PreparedData data = fit::prepare_data(m, {});
      const fit::ModelFit f = fit::fit_model(data, terms, fit::find_engine("ols"), settings);
      for (int j = 0; j < 3; ++j) {
        const fit::Interval& iv = f.engine.intervals[static_cast<std::size_t>(j)];
        row.covered[j] += iv.lower <= truth[j] && truth[j] <= iv.upper;
        const double err = f.coefficients.b[static_cast<std::size_t>(j)] / truth[j] - 1.0;
        sum[j] += err;
        sum2[j] += err * err;
        row.half[j] += 0.5 * (iv.upper - iv.lower) / std::abs(truth[j]) / seeds;
      }
    }
    for (int j = 0; j < 3; ++j) {
      row.bias[j] = sum[j] / seeds;
      row.sd[j] = std::sqrt(std::max(0.0, sum2[j] / seeds - row.bias[j] * row.bias[j]));
    }
    fmt::print(stderr, "{} {} flicker={}: {} {} {}\n", row.method, row.model, row.flicker,
               row.covered[0], row.covered[1], row.covered[2]);
  }

  std::string md = fmt::format(
      "# ols: coverage of the 95 % intervals on the simulated cycle\n\n"
      "Made by `scripts/ols_coverage.sh` (`build/bench/ols_coverage`): {} seeds of the shipped "
      "`scenarios/cycle.toml` with the default gyro and rig, fitted by the pipeline (glitches "
      "removed, 100 s windows, central differences), counting how often each 95 % interval "
      "holds the true coefficient (b1 of T, b2 of T^2, b3 of dT). Bias and sd are of the "
      "relative error over the seeds; half-width is the mean relative half-width of the "
      "interval. A correct 95 % interval has half-width ≈ 2 sd and covers about 95.\n\n"
      "| intervals | model | flicker | covered T | T^2 | dT | bias T / T^2 / dT | sd T / T^2 / dT | half-width T / T^2 / dT |\n"
      "|---|---|---|---|---|---|---|---|---|\n",
      seeds);
  for (const Row& r : rows)
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {:+.3f} / {:+.3f} / {:+.4f} | {:.3f} / {:.3f} / {:.4f} | {:.3f} / {:.3f} / {:.4f} |\n",
                      r.method, r.model, r.flicker ? "on" : "off", r.covered[0], r.covered[1],
                      r.covered[2], r.bias[0], r.bias[1], r.bias[2], r.sd[0], r.sd[1], r.sd[2],
                      r.half[0], r.half[1], r.half[2]);
  md +=
      "\nReading it:\n\n"
      "* With the default noise the intervals are too narrow (the half-width is about one sd, "
      "not two). The default flicker has correlation times up to hours, the time scale of the "
      "cycle itself: the regression absorbs that drift into T and T^2, the residuals look "
      "whiter than the noise was, and no residual-based long-run variance (kernel or cosine) "
      "can recover what was absorbed. The issue's target, 85 of 100, is **not met** here.\n"
      "* Without flicker, the rest of the gap is bias: the 20 s Pt800 lag makes the model in "
      "the measured temperature miss a d2T term (b3·τ ≈ 36 °/h per °C/s²); adding d2T removes "
      "the bias of b1.\n"
      "* On synthetic AR(1) residuals (ρ = 0.9) the pre-whitened Newey-West intervals do cover "
      "(tests/ols_test.cpp); the equal-weighted cosine (ewc) does not there, but does better "
      "than nw on the simulated flicker, which is why both are offered (`--option "
      "intervals=ewc`).\n";
  write_file_atomically(out, md);
  fmt::print("wrote {}\n", out);
  return 0;
}

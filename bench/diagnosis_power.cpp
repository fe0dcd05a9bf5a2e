// The power and false-alarm rate of diagnose (results/diagnosis_power.md,
// scripts/diagnosis_power.sh): how often it names a hidden step or effect,
// and how often it names anything on a record that hides nothing, under four
// kinds of gyro noise.
//
// Records: the shipped cycle (or another scenario) simulated on a few base
// seeds gives the temperatures as the sensors read them and the true bias of
// the paper's model; each trial replaces the gyro's noise at the 100 s
// windows by an exact draw from a noise model (fit/model/noise_model.h:
// white + flicker, white + Gauss–Markov 1000 s or 1 h, white + random walk)
// and adds what is hidden:
//   * a bias step of 2, 4, 6 or 10 × the noise floor (diagnose's own
//     estimate, averaged over the cell's clean records) at a random time in
//     30–70 % of the record, of random sign: found when diagnose reports a
//     significant step within an hour of it with the right sign;
//   * a registry effect at 3 or 6 × its detection threshold (1.96 standard
//     errors of its coefficient added to the paper's model, GLS under the
//     cell's noise), its regressor at its default parameter: found when it
//     (or a group holding it) is the first candidate and passed the test;
//   * nothing: a false alarm when anything passes the test.
// Usage: diagnosis_power OUT.md [SEEDS] [PART] [SCENARIO] [CELLS] — PART
// "steps", "effects", "clean" or "all" (default); each row's seeds are
// 1..SEEDS; CELLS a comma list of the noise cells to run (0-3, default all),
// so that cells run side by side (scripts/diagnosis_power.sh joins them).

#include <fmt/format.h>

#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>  // atoi
#include <algorithm>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "fit/model/formula.h"
#include "fit/model/noise_whitening.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"
#include "sim/util/gauss_markov.h"
#include "sim/util/random.h"
#include "studies/diagnose/diagnosis.h"

using namespace gyrotherm;

namespace {

constexpr int kBases = 4;  // base simulations (sensor noise) the trials cycle through

struct Cell {
  std::string name;
  fit::NoiseModel noise;
};

// The window-level noise models of the four cells: the default gyro's white
// noise (ARW 0.0003 °/√h) with flicker of floor 0.0005 °/h, a Gauss–Markov
// process of σ 0.0006 °/h at 1000 s or 1 h, or a rate random walk of
// 0.0005 °/h/√h.
std::vector<Cell> cells(const fit::WindowGrid& g) {
  const double qw = std::pow(0.0003 * 60.0, 2);
  std::vector<Cell> out;
  {
    Cell c{"white + flicker (B 0.0005 °/h)", {}};
    c.noise.amplitude[fit::kWhite] = qw;
    const double span = g.time_s.back() - g.time_s.front() + g.window_s;
    const int n = static_cast<int>(std::ceil(2.0 * std::log10(span / g.window_s))) + 1;
    for (int i = 0; i < n; ++i) c.noise.flicker_tau_s.push_back(g.window_s * std::pow(span / g.window_s, i / (n - 1.0)));
    c.noise.amplitude[fit::kFlicker] = std::pow(0.0005, 2) / bank_allan_peak(c.noise.flicker_tau_s, g.window_s, span, 200);
    out.push_back(c);
  }
  for (const double tau : {1000.0, 3600.0}) {
    Cell c{fmt::format("white + Gauss–Markov (σ 0.0006 °/h, {:g} s)", tau), {}};
    c.noise.amplitude[fit::kWhite] = qw;
    c.noise.amplitude[fit::kGaussMarkov] = 0.0006 * 0.0006;
    c.noise.gm_tau_s = tau;
    out.push_back(c);
  }
  Cell rw{"white + random walk (0.0005 °/h/√h)", {}};
  rw.noise.amplitude[fit::kWhite] = qw;
  rw.noise.amplitude[fit::kRandomWalk] = 0.0005 * 0.0005 / 3600.0;
  out.push_back(rw);
  return out;
}

struct Base {
  fit::PreparedData data;       // gyro = the true bias's window means
  std::vector<double> truth;    // the same
};

std::vector<Base> bases(const std::string& scenario) {
  sim::Scenario sc = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/" + scenario + ".toml");
  const sim::RigConfig rig = sim::load_rig(sc.rig_file);
  const sim::GyroConfig gyro = sim::load_gyro(sc.gyro_file);
  std::vector<Base> out;
  for (int b = 0; b < kBases; ++b) {
    sc.seed = 1000 + static_cast<std::uint64_t>(b);
    const sim::SimulationResult r = sim::Simulator(sc, rig, gyro).run();
    fit::Measurement m;
    m.file = scenario;
    m.time_s = r.time_s;
    m.temp_c = r.temp_c;
    m.temp2_c = r.temp2_c;
    m.gyro_dph = r.bias_true_dph;
    fit::PipelineOptions quiet;
    quiet.remove_outliers = false;
    Base base{fit::prepare_data(m, quiet), {}};
    base.truth = base.data.series.gyro_dph;
    out.push_back(std::move(base));
  }
  return out;
}

struct Outcome {
  bool anything = false;  // something passed the test
  std::vector<std::string> passed;  // what passed ("step" for any step)
  bool step_found = false;
  bool step_covered = false;  // the found step's 95 % interval holds its size
  bool effect_first = false;
  double floor = 0;
};

Outcome run(const fit::PreparedData& data, const std::vector<const fit::Term*>& model, double step_time_s,
            double step_dph, const std::string& effect) {
  const studies::Diagnosis d = studies::diagnose(data, model, fit::find_engine("ols"), {});
  Outcome o;
  o.floor = d.noise_floor_dph;
  for (const studies::CandidateReport& c : d.candidates)
    if (c.passed()) {
      o.anything = true;
      const std::string name(c.term->name);
      o.passed.push_back(name.rfind("step@", 0) == 0 ? "step" : name);
    }
  for (const studies::StepEvent& e : d.events)
    if (e.significant && std::abs(e.time_s - step_time_s) <= 3600.0 && e.size_dph * step_dph > 0.0) {
      o.step_found = true;
      o.step_covered = e.size_interval_dph.lower <= step_dph && step_dph <= e.size_interval_dph.upper;
    }
  if (!effect.empty() && !d.candidates.empty()) {
    const studies::CandidateReport& first = d.candidates.front();
    const bool named = first.term->name == effect ||
                       std::find(first.confounded_with.begin(), first.confounded_with.end(), effect) !=
                           first.confounded_with.end();
    o.effect_first = named && first.passed();
  }
  return o;
}

std::string share(int k, int n) { return fmt::format("{} of {} ({:.0f} %)", k, n, 100.0 * k / n); }

}  // namespace

int main(int argc, char** argv) {
  const std::string out_path = argc > 1 ? argv[1] : "results/diagnosis_power.md";
  const int seeds = argc > 2 ? std::atoi(argv[2]) : 100;
  const std::string part = argc > 3 ? argv[3] : "all";
  const std::string scenario = argc > 4 ? argv[4] : "cycle";
  const std::string only = argc > 5 ? fmt::format(",{},", argv[5]) : std::string();
  const auto started = std::chrono::steady_clock::now();
  const std::vector<Base> base = bases(scenario);
  const fit::WindowGrid grid = fit::window_grid(base.front().data);
  const std::vector<const fit::Term*> model = fit::parse_formula("T + T^2 + dT");
  const double span = base.front().data.series.time_s.back() - base.front().data.series.start_time_s;
  std::string md;
  int index = -1;
  for (const Cell& cell : cells(grid)) {
    if (++index; !only.empty() && only.find(fmt::format(",{},", index)) == std::string::npos) continue;
    // A trial: base k's record with a fresh draw of the cell's noise.
    const auto record = [&](int seed, std::uint64_t stream) {
      const Base& b = base[static_cast<std::size_t>(seed) % kBases];
      Rng rng = make_rng(static_cast<std::uint64_t>(seed), stream);
      boost::random::normal_distribution<double> normal;
      const fit::WindowGrid g = fit::window_grid(b.data);
      const Eigen::VectorXd noise = cell.noise.draw(g, [&] { return normal(rng); });
      fit::PreparedData d = b.data;
      for (std::size_t p = 0; p < d.series.size(); ++p) d.series.gyro_dph[p] = b.truth[p] + noise[static_cast<Eigen::Index>(p)];
      return d;
    };
    // Clean records: false alarms, and the floor that sizes the steps.
    int alarms = 0;
    double floor_sum = 0.0;
    std::map<std::string, int> alarm_terms;  // what passed on the clean records
    const int clean = part == "steps" || part == "effects" ? std::min(seeds, 20) : seeds;
    for (int s = 1; s <= clean; ++s) {
      const Outcome o = run(record(s, 1), model, -1e9, 0.0, "");
      alarms += o.anything;
      for (const std::string& name : o.passed) ++alarm_terms[name];
      floor_sum += o.floor;
    }
    const double floor = floor_sum / clean;
    md += fmt::format("\n## {}\n\nnoise floor (diagnose's estimate, mean of {} clean records): {:.3g} °/h\n\n", cell.name,
                      clean, floor);
    if (part == "all" || part == "clean") {
      std::string what;
      for (const auto& [name, n] : alarm_terms) what += fmt::format("{}{} {}", what.empty() ? "" : ", ", name, n);
      md += fmt::format("| clean records | anything significant | what passed (records) |\n|---|---|---|\n| {} | {} | {} |\n\n",
                        clean, share(alarms, clean), what.empty() ? "-" : what);
    }
    if (part == "all" || part == "steps") {
      md += "| step | found (significant, within 1 h, right sign) | its 95 % interval holds the size | anything significant |\n|---|---|---|---|\n";
      for (const double k : {2.0, 4.0, 6.0, 10.0}) {
        int found = 0, any = 0, covered = 0;
        for (int s = 1; s <= seeds; ++s) {
          fit::PreparedData d = record(s, 2);
          Rng rng = make_rng(static_cast<std::uint64_t>(s), 3);
          boost::random::uniform_real_distribution<double> u(0.0, 1.0);
          const double t = (0.3 + 0.4 * u(rng)) * span;
          const double size = (u(rng) < 0.5 ? -1.0 : 1.0) * k * floor;
          for (std::size_t p = 0; p < d.series.size(); ++p)
            if (d.series.time_s[p] - d.series.start_time_s >= t) d.series.gyro_dph[p] += size;
          const Outcome o = run(d, model, t, size, "");
          found += o.step_found;
          covered += o.step_covered;
          any += o.anything;
        }
        md += fmt::format("| {:g} × floor | {} | {} | {} |\n", k, share(found, seeds),
                          found > 0 ? share(covered, found) : std::string("-"), share(any, seeds));
        fmt::print(stderr, "{}: step {:g}x: {} found\n", cell.name, k, found);
      }
    }
    if (part == "all" || part == "effects") {
      md += "\n| effect | threshold (1.96 se) | 3 × threshold: named first | 6 × threshold: named first |\n|---|---|---|---|\n";
      const fit::NoiseWhitener whitener(cell.noise, grid);
      for (const fit::Term* term : fit::term_registry()) {
        if (std::find(model.begin(), model.end(), term) != model.end()) continue;
        const std::vector<double> param = fit::default_parameters({term});
        const Eigen::MatrixXd x = fit::design_matrix(base.front().data.derived, model, {NAN, NAN, NAN});
        const Eigen::MatrixXd c = fit::design_matrix(base.front().data.derived, {term}, param);
        Eigen::MatrixXd xc(x.rows(), x.cols() + 1);
        xc << x, c;
        const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(base.front().truth.data(), x.rows());
        const fit::GlsFit f = fit::gls(whitener, xc, y);
        const double threshold = 1.96 * std::sqrt(f.covariance(xc.cols(), xc.cols()));
        std::string row = fmt::format("| {} | {:.3g} {} |", term->name, threshold, term->coefficient_unit());
        for (const double k : {3.0, 6.0}) {
          int first = 0;
          for (int s = 1; s <= seeds; ++s) {
            fit::PreparedData d = record(s, 4);
            const Eigen::MatrixXd col = fit::design_matrix(d.derived, {term}, param);
            for (std::size_t p = 0; p < d.series.size(); ++p) d.series.gyro_dph[p] += k * threshold * col(static_cast<Eigen::Index>(p), 0);
            first += run(d, model, -1e9, 0.0, std::string(term->name)).effect_first;
          }
          row += fmt::format(" {} |", share(first, seeds));
        }
        md += row + "\n";
        fmt::print(stderr, "{}: {} done\n", cell.name, term->name);
      }
    }
  }
  const double minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() / 60.0;
  std::ofstream(out_path) << fmt::format(
      "# diagnose: power and false alarms\n\nMade by `scripts/diagnosis_power.sh` (`build/bench/diagnosis_power {} {} {} "
      "{}`, {:.0f} min): the `{}` scenario's temperatures and true bias on {} base seeds, the gyro's noise at the 100 s "
      "windows drawn exactly from each noise model below, the model `T + T^2 + dT`, diagnose's defaults. How it works: "
      "bench/diagnosis_power.cpp's header.\n{}",
      out_path, seeds, part, scenario, minutes, scenario, kBases, md);
  return 0;
}

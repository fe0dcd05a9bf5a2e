#include "studies/reproduce/report.h"

#include <fmt/core.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "fit/model/formula.h"
#include "sim/util/atomic_file.h"
#include "sim/util/format.h"
#include "sim/util/gnuplot.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {

using Json = nlohmann::ordered_json;

nlohmann::ordered_json table_json(const ReproduceResult& r, bool with_times) {
  const PaperFigures paper;
  Json j;
  Json cycle_engines;
  for (const auto& e : r.engines) {
    Json coefficients;
    coefficients["1"] = e.fit.coefficients.intercept;
    for (std::size_t k = 0; k < e.fit.terms.size(); ++k)
      coefficients[e.fit.terms[k]->name] = e.fit.coefficients.b[k];
    Json errors;
    for (const auto& [k, v] : e.coefficient_error) errors[k] = v;
    Json& engine = cycle_engines[e.engine];
    engine = {{"after_dph", e.fit.instability_after_dph},
              {"ratio", e.fit.ratio()},
              {"coefficients", coefficients},
              {"coefficient_error", errors},
              {"evaluations", e.fit.engine.evaluations}};
    if (with_times) engine["seconds"] = e.fit.engine.seconds;
    engine["termination"] = fit::to_string(e.fit.engine.termination);
    engine["gap_to_least_squares"] = e.fit.instability_after_dph / e.fit.optimum_dph - 1.0;
  }
  j["cycle"] = {{"raw_dph", r.cycle_raw_dph}, {"windows", r.cycle_data.series.size()},
                {"engines", cycle_engines}};
  for (const TestOutcome* t : {&r.test1, &r.test2}) {
    Json engines;
    for (const auto& [name, c] : t->by_engine)
      engines[name] = {{"after_dph", c.after_dph}, {"times", c.ratio()}};
    j[t->name] = {{"before_dph", t->before_dph}, {"windows", t->by_engine.empty() ? 0 : t->by_engine.begin()->second.data.series.size()},
                  {"compensation", "causal (backward differences, completed windows only)"},
                  {"engines", engines}};
  }
  j["paper"] = {{"cycle", {{"raw_dph", paper.cycle_raw}, {"stepwise_dph", paper.cycle_stepwise}, {"iafsa_dph", paper.cycle_iafsa}}},
                {"test1", {{"before_dph", paper.test1_before}, {"after_dph", paper.test1_after}, {"times", paper.test1_times}}},
                {"test2", {{"before_dph", paper.test2_before}, {"after_dph", paper.test2_after}, {"times", paper.test2_times}}}};
  j["seeds"] = {{"cycle", r.cycle_seed}, {"test1", r.test1.seed}, {"test2", r.test2.seed}};
  if (with_times) j["seconds"] = r.seconds;
  return j;
}

namespace {

std::string pct(double ours, double paper) { return fmt::format("{:+.0f} %", 100.0 * (ours / paper - 1.0)); }

}  // namespace

std::string table_markdown(const ReproduceResult& r) {
  const PaperFigures paper;
  auto find = [&](const std::string& name) -> const EngineOnCycle* {
    for (const auto& e : r.engines)
      if (e.engine == name) return &e;
    return nullptr;
  };
  std::string md = "# Table 1, side by side\n\n";
  md += fmt::format(
      "Made by `gyrotherm reproduce` (the README's main command); seeds: cycle {}, Test 1 {}, Test 2 {}. "
      "Instability = standard deviation of the 100 s means (°/h). The gyro is the default simulated one "
      "(`scenarios/gyro.toml`), calibrated as `results/calibration.md` describes. The same seeds give the "
      "same numbers on every run; run times go to the terminal (`reproduce --json` prints them).\n\n",
      r.cycle_seed, r.test1.seed, r.test2.seed);

  md += fmt::format("## Cycle (the training data: {})\n\n| | paper | ours | ours vs paper |\n|---|---|---|---|\n",
                    r.cycle_facts.text());
  md += fmt::format("| raw | {} | {:.5f} | {} |\n", paper.cycle_raw, r.cycle_raw_dph, pct(r.cycle_raw_dph, paper.cycle_raw));
  if (const auto* s = find("stepwise"))
    md += fmt::format("| stepwise | {} (4.35×) | {:.5f} ({:.2f}×) | {} |\n", paper.cycle_stepwise,
                      s->fit.instability_after_dph, s->fit.ratio(), pct(s->fit.instability_after_dph, paper.cycle_stepwise));
  if (const auto* s = find("iafsa"))
    md += fmt::format("| IAFSA | {} (5.15×) | {:.5f} ({:.2f}×) | {} |\n", paper.cycle_iafsa,
                      s->fit.instability_after_dph, s->fit.ratio(), pct(s->fit.instability_after_dph, paper.cycle_iafsa));
  // The model's terms, b1, b2, … as the paper numbers them.
  const std::vector<const fit::Term*>& terms = r.engines.front().fit.terms;
  std::string columns, bars, errors_head, truth;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    columns += fmt::format(" b{} ({}) |", k + 1, terms[k]->name);
    bars += "---|";
    errors_head += fmt::format("{}b{}", k ? " / " : "", k + 1);
    truth += fmt::format("{}b{} = {}", k ? ", " : "", k + 1, r.truth.coefficients.at(std::string(terms[k]->name)));
  }
  md += fmt::format("\nEvery engine on the cycle (the paper's model {}; errors against the simulator's truth):\n\n"
                    "| engine | after (°/h) | ratio | gap to least squares |{} error {} | evaluations |\n|---|---|---|---|{}---|---|\n",
                    fit::formula_text(terms), columns, errors_head, bars);
  for (const auto& e : r.engines) {
    std::string values, errors;
    for (std::size_t k = 0; k < terms.size(); ++k) {
      values += fmt::format(" {:.4g} |", e.fit.coefficients.b[k]);
      const auto it = e.coefficient_error.find(std::string(terms[k]->name));
      errors += (k ? " / " : "") +
                (it == e.coefficient_error.end() ? std::string("–") : fmt::format("{:+.1f} %", 100.0 * it->second));
    }
    md += fmt::format("| {} | {:.5f} | {:.2f} | {:.1e} |{} {} | {} |\n", e.engine, e.fit.instability_after_dph,
                      e.fit.ratio(), e.fit.instability_after_dph / e.fit.optimum_dph - 1.0, values, errors,
                      e.fit.engine.evaluations);
  }
  md += fmt::format("\nTruth: {} (the paper's IAFSA model).\n", truth);

  for (const TestOutcome* t : {&r.test1, &r.test2}) {
    const bool one = t->name == "test1";
    md += fmt::format("\n## {} ({}: {})\n\nEach engine's cycle fit applied with the causal, real-time compensator.\n\n"
                      "| | before (°/h) | after (°/h) | times |\n|---|---|---|---|\n",
                      one ? "Test 1" : "Test 2", one ? "the INS, random profile" : "the INS, natural warm-up",
                      t->facts.text());
    md += fmt::format("| paper (IAFSA) | {} | {} | {} |\n", one ? paper.test1_before : paper.test2_before,
                      one ? paper.test1_after : paper.test2_after, one ? paper.test1_times : paper.test2_times);
    for (const auto& e : r.engines) {
      const auto& c = t->by_engine.at(e.engine);
      md += fmt::format("| ours, {} | {:.5f} | {:.5f} | {:.2f} |\n", e.engine, c.before_dph, c.after_dph, c.ratio());
    }
    const std::string best = t->by_engine.count("iafsa") ? "iafsa" : r.engines.front().engine;
    const auto& c = t->by_engine.at(best);
    md += fmt::format("\nOurs ({}) against the paper: before {}, after {}{}.\n", best,
                      pct(c.before_dph, one ? paper.test1_before : paper.test2_before),
                      pct(c.after_dph, one ? paper.test1_after : paper.test2_after),
                      one ? "; the raw figure of Test 1 cannot be reached with the paper's coefficients "
                            "and profile (even a gyro following the chamber instantly gives about "
                            "0.0106 °/h), see results/calibration.md"
                          : "");
  }

  md += R"(
## What the engines can and cannot do

Every engine here minimises the same objective, the paper's σ of the residual
of the 100 s means, on the same data. On the training data nothing can beat the
exact least-squares optimum (`ols`): the objective is a convex quadratic in
the coefficients, so any engine that converges reaches the same σ and the same
coefficients, and the gap column above measures how close each came. The
paper's "IAFSA 15.5 % better than stepwise regression" cannot come from a
better optimiser of the same σ; an engine can differ from least squares only
when:

* **a term is dropped**: stepwise keeps a term only if its F-test passes, and a
  dropped term (here often T^2, whose effect over −40..60 °C is small next to
  the noise) leaves its part of the bias in the residual;
* **the search has not converged**: a swarm stopped by its iteration limit or
  budget sits above the optimum (see the gap column; basic AFSA is the usual
  case);
* **the terms differ**: a different model (another term, another derivative
  estimate, a different averaging) is a different problem with a different
  optimum;
* **the data differ**: outliers left in, or other preprocessing, change the
  optimum itself.

Out of sample (Tests 1 and 2) all converged engines give the same numbers
because they found the same coefficients; what differs from the cycle is the
data: the INS has other thermal paths than the gyro in its shield, and the
causal compensator sees dT/dt half a window late.
)";
  return md;
}

void plot_figures(const std::filesystem::path& dir, const ReproduceResult& r) {
  auto hours = [](const std::vector<double>& s) {
    std::vector<double> h(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) h[i] = s[i] / 3600.0;
    return h;
  };
  const auto& c = r.cycle_run;
  {
    GnuplotFigure fig(dir / "fig2_cycle_1s.png", 1400, 700);
    std::vector<double> t, g, temp;
    for (std::size_t k = 0; k < c.rows(); k += 2) {
      t.push_back(c.time_s[k] / 3600.0);
      g.push_back(c.gyro_dph[k]);
      temp.push_back(c.temp_c[k]);
    }
    fig.data("d", {"t_h", "gyro", "temp"}, {t, g, temp});
    // The gyro's temperature is what is plotted: it spans less than the chamber's set points.
    fig.commands(fmt::format(
        "set title 'Fig. 2: gyro output (1 s) and gyro temperature ({} °C); chamber set points {} °C'\n"
        "set xlabel 'time (h)'\nset ylabel 'gyro output (°/h)'\nset y2label 'gyro temperature (°C)'\n"
        "set y2tics\nset ytics nomirror\nset key outside right\n"
        "plot $d using 1:2 with dots lc rgb '#555555' title '1 s output', "
        "$d using 1:3 axes x1y2 with lines lw 2 lc rgb '#1f77b4' title 'gyro temperature'\n",
        range_text(r.cycle_facts.gyro_min_c, r.cycle_facts.gyro_max_c, 0),
        range_text(r.cycle_facts.set_min_c, r.cycle_facts.set_max_c, 0)));
    fig.render();
  }
  const fit::AveragedSeries& s = r.cycle_data.series;
  {
    GnuplotFigure fig(dir / "fig3_cycle_100s.png", 1400, 700);
    fig.data("d", {"t_h", "gyro", "temp"}, {hours(s.time_s), s.gyro_dph, s.temp_c});
    fig.commands(fmt::format("set title 'Fig. 3: 100 s means and temperature, cycle (instability {:.5f} °/h)'\n"
                             "set xlabel 'time (h)'\nset ylabel 'gyro, 100 s means (°/h)'\nset y2label 'gyro temperature (°C)'\n"
                             "set y2tics\nset ytics nomirror\nset key outside right\n"
                             "plot $d using 1:2 with linespoints pt 7 ps 0.4 lc rgb '#333333' title '100 s means', "
                             "$d using 1:3 axes x1y2 with lines lw 2 lc rgb '#1f77b4' title 'gyro temperature'\n",
                             r.cycle_raw_dph));
    fig.render();
  }
  {  // Figs. 4 and 5: compensated with stepwise and with IAFSA (or whatever ran).
    GnuplotFigure fig(dir / "fig4_5_cycle_compensated.png", 1400, 700);
    std::string plot = "plot ";
    int n = 0;
    for (const auto& e : r.engines) {
      if (e.engine != "stepwise" && e.engine != "iafsa" && e.engine != "ols") continue;
      const Eigen::MatrixXd x = fit::design_matrix(r.cycle_data.derived, e.fit.terms, e.fit.parameters);
      const std::vector<double> model = fit::model_values(x, e.fit.coefficients);
      std::vector<double> comp(s.size());
      for (std::size_t p = 0; p < s.size(); ++p) comp[p] = s.gyro_dph[p] - model[p];
      fig.data(fmt::format("e{}", n), {"t_h", "compensated"}, {hours(s.time_s), comp});
      plot += fmt::format("{}$e{} using 1:2 with linespoints pt 7 ps 0.4 title '{} ({:.5f} °/h)'", n ? ", " : "", n,
                          e.engine, e.fit.instability_after_dph);
      ++n;
    }
    fig.commands("set title 'Figs. 4-5: cycle after compensation (100 s means minus the model)'\n"
                 "set xlabel 'time (h)'\nset ylabel 'compensated bias (°/h)'\nset key outside right\n" + plot + "\n");
    if (n > 0) fig.render();
  }
  for (const TestOutcome* t : {&r.test1, &r.test2}) {
    if (t->by_engine.empty()) continue;
    const std::string best = t->by_engine.count("iafsa") ? "iafsa" : t->by_engine.begin()->first;
    const fit::Compensation& comp = t->by_engine.at(best);
    const fit::AveragedSeries& ts = comp.data.series;
    const bool one = t->name == "test1";
    GnuplotFigure fig(dir / (one ? "fig6_7_test1.png" : "fig8_9_test2.png"), 1400, 1000);
    fig.data("d", {"t_h", "gyro", "temp", "comp"}, {hours(ts.time_s), ts.gyro_dph, ts.temp_c, comp.window_compensated_dph});
    // Both panels share fixed left and right margins, so that their time axes
    // line up (gnuplot sizes each panel's margins to its own labels and key).
    fig.commands(fmt::format(
        "set multiplot layout 2,1 title '{}'\nset lmargin at screen 0.08\nset rmargin at screen 0.76\n"
        "set ylabel 'gyro, 100 s means (°/h)'\nset y2label 'gyro temperature (°C)'\nset y2tics\nset ytics nomirror\nset key outside right\n"
        "plot $d using 1:2 with lines lc rgb '#333333' title 'before ({:.5f} °/h)', $d using 1:3 axes x1y2 with lines lw 2 lc rgb '#1f77b4' title 'gyro temperature'\n"
        "unset y2tics\nunset y2label\nset xlabel 'time (h)'\nset ylabel 'compensated (°/h)'\n"
        "plot $d using 1:4 with lines lc rgb '#d62728' title 'after, {} causal ({:.5f} °/h)'\nunset multiplot\n",
        one ? "Figs. 6-7: Test 1, random profile, before and after real-time compensation"
            : "Figs. 8-9: Test 2, natural warm-up, before and after real-time compensation",
        comp.before_dph, best, comp.after_dph));
    fig.render();
  }
}

std::string shown_engine(const ReproduceResult& r) {
  if (r.engines.empty()) return "";
  for (const EngineOnCycle& e : r.engines)
    if (e.engine == "iafsa") return e.engine;
  return r.engines.front().engine;
}

nlohmann::ordered_json write_reproduce_report(const std::filesystem::path& dir,
                                              const ReproduceResult& r,
                                              std::chrono::steady_clock::time_point started,
                                              const std::function<void(const std::string&, double)>& progress) {
  const auto report = [&](const std::string& step, double f) {
    if (progress) progress(step, f);
  };
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create the folder ({})", dir.string(), ec.message()));
  report("drawing the figures", kReproduceComputedShare);
  plot_figures(dir, r);
  // The files hold what the seeds decide, so a run leaves them as they were;
  // the run times go to the terminal (the JSON returned).
  report("writing table1.json and table1.md", 0.5 * (1.0 + kReproduceComputedShare));
  write_file_atomically(dir / "table1.json", table_json(r, false).dump(2) + "\n");
  write_file_atomically(dir / "table1.md", table_markdown(r));
  report("done", 1.0);
  nlohmann::ordered_json j = table_json(r, true);
  j["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return j;
}

std::string reproduce_text(const ReproduceResult& r, const std::string& dir, double total_seconds) {
  const PaperFigures paper;
  std::string out = "Table 1, side by side (instability of 100 s means, °/h):\n";
  out += fmt::format("  cycle  raw      paper {:.5f}  ours {:.5f}\n", paper.cycle_raw, r.cycle_raw_dph);
  for (const auto& e : r.engines)
    out += fmt::format("  cycle  {:<8} {}  ours {:.5f} ({:.2f}x)\n", e.engine,
                       e.engine == "stepwise" ? fmt::format("paper {:.5f}", paper.cycle_stepwise)
                       : e.engine == "iafsa"  ? fmt::format("paper {:.5f}", paper.cycle_iafsa)
                                              : std::string(17, ' '),
                       e.fit.instability_after_dph, e.fit.ratio());
  const std::string best = shown_engine(r);
  out += fmt::format("  test 1 paper {:.5f} -> {:.5f} ({:.2f}x)  ours ({}) {:.5f} -> {:.5f} ({:.2f}x)\n",
                     paper.test1_before, paper.test1_after, paper.test1_times, best, r.test1.before_dph,
                     r.test1.by_engine.at(best).after_dph, r.test1.by_engine.at(best).ratio());
  out += fmt::format("  test 2 paper {:.5f} -> {:.5f} ({:.2f}x)  ours ({}) {:.5f} -> {:.5f} ({:.2f}x)\n",
                     paper.test2_before, paper.test2_after, paper.test2_times, best, r.test2.before_dph,
                     r.test2.by_engine.at(best).after_dph, r.test2.by_engine.at(best).ratio());
  out += fmt::format("wrote {0}/table1.md, {0}/table1.json and figures in {1:.1f} s\n", dir, total_seconds);
  return out;
}

}  // namespace gyrotherm::studies

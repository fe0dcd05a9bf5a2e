#include "studies/score/report.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sim/util/atomic_file.h"
#include "sim/util/gnuplot.h"
#include "sim/util/input_error.h"
#include "sim/util/format.h"

namespace gyrotherm::studies {

namespace {

using Json = nlohmann::ordered_json;

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json range_json(Range r) { return Json::array({number(r.low), number(r.high)}); }

void put_summary(Json& j, const std::string& name, const Summary& s, bool with_p10 = false) {
  j[name + "_median"] = number(s.median);
  if (with_p10) j[name + "_p10"] = number(s.p10);
  j[name + "_p90"] = number(s.p90);
}

// "seeds S..S+n−1", or "seed S" for one trial.
std::string seeds_text(const Scoreboard& b) {
  return b.trials == 1 ? fmt::format("seed {}", b.seed) : fmt::format("seeds {}..{}", b.seed, b.seed + (b.trials - 1));
}

}  // namespace

std::string scoreboard_json(const Scoreboard& b) {
  Json j;
  j["scenario"] = b.scenario;
  j["trials"] = b.trials;
  j["seed"] = b.seed;
  Json engines = Json::object();
  for (const EngineScore& e : b.engines) {
    Json x;
    // The fields of the contract (docs/contracts.md) first.
    x["success_rate"] = e.success_rate;
    x["evals_to_target_median"] = number(e.evaluations_to_target.median);
    x["seconds_median"] = number(e.seconds_to_target.median);
    x["gap_median"] = e.gap.median;
    Json errors = Json::object(), errors90 = Json::object(), errors_ci = Json::object();
    for (std::size_t k = 0; k < b.error_terms.size(); ++k) {
      errors[b.error_terms[k]] = e.coefficient_error[k].median;
      errors90[b.error_terms[k]] = e.coefficient_error[k].p90;
      errors_ci[b.error_terms[k]] = range_json(e.coefficient_error[k].median_ci);
    }
    x["coefficient_error_median"] = errors;
    x["ratio_median"] = e.ratio.median;
    // More.
    x["stochastic"] = e.stochastic;
    x["budget"] = e.budget;
    x["reached"] = e.reached;
    x["evals_to_target_p90"] = number(e.evaluations_to_target.p90);
    x["seconds_p90"] = number(e.seconds_to_target.p90);
    put_summary(x, "seconds_run", e.seconds);
    put_summary(x, "evaluations", e.evaluations);
    x["gap_p90"] = e.gap.p90;
    x["coefficient_error_p90"] = errors90;
    x["ratio_p10"] = e.ratio.p10;
    Json terminations = Json::object();
    for (const auto& [name, count] : e.terminations) terminations[name] = count;
    x["terminations"] = terminations;
    x["ci95"] = {{"success_rate", range_json(e.success_ci)},
                 {"evals_to_target_median", range_json(e.evaluations_to_target.median_ci)},
                 {"gap_median", range_json(e.gap.median_ci)},
                 {"ratio_median", range_json(e.ratio.median_ci)},
                 {"coefficient_error_median", errors_ci}};
    engines[e.engine] = x;
  }
  j["engines"] = engines;
  j["model"] = b.model;
  j["target"] = fmt::format("sigma <= optimum * (1 + {:g})", b.target_relative);
  j["target_relative"] = b.target_relative;
  j["seeds"] = {{"first", b.seed}, {"last", b.seed + (b.trials - 1)}};
  Json spread = Json::object();
  for (const auto& [key, r] : b.spread) spread[key] = r;
  j["spread"] = spread;
  j["error_terms"] = b.error_terms;
  j["instability_before_median_dph"] = b.before_median_dph;
  j["optimum_median_dph"] = b.optimum_median_dph;
  j["scenario_file"] = b.scenario_file;
  Json files = Json::object();
  for (const auto& [k, v] : b.file_sha256) files[k] = v;
  j["file_sha256"] = files;
  j["run"] = {{"threads", b.threads}, {"processes", b.processes}, {"seconds", b.seconds}};
  return j.dump(2) + "\n";
}

std::string scoreboard_markdown(const Scoreboard& b) {
  std::string md = fmt::format("# Scoreboard: {}, {}\n\n", b.scenario, counted(b.trials, "trial"));
  std::string spread;
  for (const auto& [key, r] : b.spread) spread += fmt::format("{}{} ±{:g} %", spread.empty() ? "" : ", ", key, 100.0 * r);
  md += fmt::format(
      "Scenario `{}`, {}, model `B = b0 + {}`; spread: {}. Target: σ ≤ σ*·(1 + {:g}), σ* the "
      "least-squares optimum of each trial (median σ* {:.6g} °/h, median raw instability {:.6g} °/h). "
      "Medians over the trials, evaluations with their 95 % interval; \"not reached\": the median "
      "trial did not reach the target. Coefficient errors are |fit − truth| / |truth|, median / 90th percentile. "
      "{} s on {} × {}.\n\n",
      b.scenario_file, seeds_text(b), b.model, spread.empty() ? "none" : spread,
      b.target_relative, b.optimum_median_dph, b.before_median_dph, fmt::format("{:.2f}", b.seconds),
      counted(b.threads, "thread"), counted(b.processes, "process", "processes"));
  md += "| engine | success | evaluations to target | seconds to target | final gap (median / p90) | ratio |";
  for (const std::string& t : b.error_terms) md += fmt::format(" error {} |", t == "1" ? "b0" : t);
  md += "\n|---|---|---|---|---|---|";
  for (std::size_t k = 0; k < b.error_terms.size(); ++k) md += "---|";
  md += "\n";
  for (const EngineScore& e : b.engines) {
    const Summary& ett = e.evaluations_to_target;
    const std::string evaluations =
        std::isfinite(ett.median) ? fmt::format("{:.0f} [{}, {}]", ett.median, format_value(ett.median_ci.low, "{:.0f}"),
                                                format_value(ett.median_ci.high, "{:.0f}"))
                                  : std::string("not reached");
    md += fmt::format("| {} | {:.0f} % ({}/{}) | {} | {} | {:.2g} / {:.2g} | {:.3f} |", e.engine,
                      100.0 * e.success_rate, e.reached, b.trials, evaluations,
                      format_value(e.seconds_to_target.median, "{:.2g}"), e.gap.median, e.gap.p90, e.ratio.median);
    for (const Summary& s : e.coefficient_error)
      md += fmt::format(" {:.2g} % / {:.2g} % |", 100.0 * s.median, 100.0 * s.p90);
    md += "\n";
  }
  md += "\nConvergence (median and quartiles of the gap of the best σ so far against evaluations): "
        "`convergence.csv`, `convergence.png`.\n";
  return md;
}

std::string convergence_csv(const Scoreboard& b) {
  std::string csv = "engine,evaluations,gap_q25,gap_median,gap_q75\n";
  auto cell = [](double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string(); };
  for (const EngineScore& e : b.engines)
    for (const CurvePoint& p : e.curve)
      csv += fmt::format("{},{},{},{},{}\n", e.engine, p.evaluations, cell(p.q25), cell(p.median), cell(p.q75));
  return csv;
}

void plot_convergence(const std::filesystem::path& png, const Scoreboard& b) {
  constexpr double kFloor = 1e-12;  // the log axis cannot show a gap of 0
  GnuplotFigure fig(png, 1400, 900);
  std::string plot = "plot ";
  const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                           "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  for (std::size_t e = 0; e < b.engines.size(); ++e) {
    const EngineScore& s = b.engines[e];
    std::vector<double> x, q25, median, q75;
    for (const CurvePoint& p : s.curve) {
      x.push_back(static_cast<double>(p.evaluations));
      auto floor = [&](double v) { return std::isfinite(v) ? std::max(v, kFloor) : NAN; };
      q25.push_back(floor(p.q25));
      median.push_back(floor(p.median));
      q75.push_back(floor(p.q75));
    }
    const std::string name = fmt::format("e{}", e);
    const char* colour = colours[e % std::size(colours)];
    fig.data(name, {"evaluations", "q25", "median", "q75"}, {x, q25, median, q75});
    plot += fmt::format("{}${} using 1:2:4 with filledcurves lc rgb '{}' notitle, "
                        "${} using 1:3 with linespoints pt 7 ps 0.5 lw 2 lc rgb '{}' title '{}'",
                        e ? ", " : "", name, colour, name, colour, s.engine);
  }
  fig.commands(fmt::format(
      "set title 'Convergence on {}: gap of the best sigma so far to the least-squares optimum, "
      "median and quartiles of {}'\n"
      "set xlabel 'objective evaluations'\nset ylabel 'sigma / optimum - 1 (gaps below {:g} drawn at {:g})'\n"
      "set logscale xy\nset format y '%.0e'\nset key outside right\n"
      "set style fill transparent solid 0.15 noborder\n"
      "set arrow from graph 0, first {:g} to graph 1, first {:g} nohead dt 2 lc rgb '#555555'\n"
      "set label 'target' at graph 0.01, first {:g} offset 0, 0.7 tc rgb '#555555'\n{}\n",
      b.scenario, counted(b.trials, "trial"), kFloor, kFloor, b.target_relative, b.target_relative, b.target_relative, plot));
  fig.render();
}

std::string scoreboard_text(const Scoreboard& b) {
  std::string t = fmt::format("{:<9} {:>8} {:>22} {:>11} {:>19} {:>7}", "engine", "success",
                              "evals to target [CI]", "s to target", "gap median / p90", "ratio");
  for (const std::string& term : b.error_terms) t += fmt::format(" {:>9}", "err " + (term == "1" ? "b0" : term));
  t += "\n";
  auto v = [](double x, const char* spec) {
    return std::isfinite(x) ? fmt::format(fmt::runtime(spec), x) : std::string("not reached");
  };
  for (const EngineScore& e : b.engines) {
    const auto& ett = e.evaluations_to_target;
    t += fmt::format("{:<9} {:>7.0f}% {:>22} {:>11} {:>19} {:>7.3f}", e.engine, 100.0 * e.success_rate,
                     std::isfinite(ett.median)
                         ? fmt::format("{:.0f} [{:.0f}, {}]", ett.median, ett.median_ci.low, v(ett.median_ci.high, "{:.0f}"))
                         : std::string("not reached"),
                     v(e.seconds_to_target.median, "{:.2g}"), fmt::format("{:.1e} / {:.1e}", e.gap.median, e.gap.p90),
                     e.ratio.median);
    for (const Summary& s : e.coefficient_error) t += fmt::format(" {:>8.3g}%", 100.0 * s.median);
    t += "\n";
  }
  return t;
}

std::vector<std::string> write_score_files(const std::filesystem::path& dir, const Scoreboard& board) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create the folder ({})", dir.string(), ec.message()));
  write_file_atomically(dir / "scoreboard.json", scoreboard_json(board));
  write_file_atomically(dir / "scoreboard.md", scoreboard_markdown(board));
  write_file_atomically(dir / "convergence.csv", convergence_csv(board));
  plot_convergence(dir / "convergence.png", board);
  std::vector<std::string> written;
  for (const char* f : {"scoreboard.json", "scoreboard.md", "convergence.csv", "convergence.png"})
    written.push_back((dir / f).string());
  return written;
}

std::string score_text(const Scoreboard& board) {
  std::string out = fmt::format(
      "score: {}, {} ({}), model B = b0 + {}, target sigma <= optimum*(1 + {:g})\n", board.scenario,
      counted(board.trials, "trial"), seeds_text(board), board.model, board.target_relative);
  out += fmt::format("median raw instability {:.6g} °/h, median least-squares optimum {:.6g} °/h; "
                     "medians over the trials, coefficient errors |fit - truth|/|truth|\n",
                     board.before_median_dph, board.optimum_median_dph);
  out += scoreboard_text(board);
  out += fmt::format("{:.2f} s on {} x {}\n", board.seconds, counted(board.threads, "thread"),
                     counted(board.processes, "process", "processes"));
  return out;
}

}  // namespace gyrotherm::studies

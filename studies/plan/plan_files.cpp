#include "studies/plan/plan_files.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <utility>

#include "sim/config_writer.h"
#include "sim/profile.h"
#include "sim/util/atomic_file.h"
#include "sim/util/gnuplot.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies::plan {

namespace {

std::string header_of(const PlanResult& r) {
  return fmt::format("Written by `gyrotherm plan` for B = b0 + {}: the shortest test found ({:.2f} h) at\n"
                     "{}..{} °C, at most {} °C/min; rig: {}.",
                     r.model, r.duration_s / 3600.0, r.limits.low_c, r.limits.high_c,
                     r.limits.max_rate_c_per_min, thermal_path_text(r.thermal_path));
}

void plot(const std::filesystem::path& png, const PlanResult& r, const PrecisionDetail& d) {
  GnuplotFigure fig(png, 1400, 1000);
  std::vector<double> t_h, w_h;
  for (double t : d.time_s) t_h.push_back(t / 3600.0);
  for (double t : d.window_time_s) w_h.push_back(t / 3600.0);
  fig.data("temps", {"t_h", "setpoint", "chamber", "sensor"}, {t_h, d.setpoint_c, d.chamber_c, d.sensor_c});
  std::vector<std::string> names = {"t_h"};
  std::vector<std::span<const double>> columns = {w_h};
  for (std::size_t j = 0; j < d.cumulative_share.size(); ++j) {
    names.push_back(r.terms[j].term);
    columns.emplace_back(d.cumulative_share[j]);
  }
  fig.data("share", names, columns);
  std::string cmd = fmt::format(
      "set multiplot layout 2,1 title 'Planned test: {:.2f} h for B = b0 + {}'\n"
      "set grid\nset lmargin 10\nset rmargin 20\nset xlabel 'time (h)'\nset ylabel 'temperature (°C)'\n"
      "set key outside right\n"
      "plot $temps using 1:2 with lines lw 2 dt 2 title 'set point', "
      "$temps using 1:3 with lines lw 1 title 'chamber air', "
      "$temps using 1:4 with lines lw 3 title 'gyro sensor'\n"
      "set ylabel 'share of the estimate (cumulative)'\nset yrange [0:1]\n"
      "set title \"Where each coefficient's information comes from: the running share of Σ w_i², "
      "w_i the weight of window i in the estimate\"\n",
      r.duration_s / 3600.0, r.model);
  std::string plots;
  for (std::size_t j = 0; j < d.cumulative_share.size(); ++j)
    plots += fmt::format("{}$share using 1:{} with lines lw 2 title '{}'", plots.empty() ? "plot " : ", ", j + 2,
                         r.terms[j].term);
  cmd += plots + "\nunset multiplot\n";
  fig.commands(cmd);
  fig.render();
}

}  // namespace

// The files, once the folder is there (below).
void write_into(PlanResult& r, const PlanSetup& setup, const PrecisionDetail& detail,
                const std::filesystem::path& dir);

std::string setpoint_csv(const ChamberProfile& profile, double step_s) {
  const sim::Profile p(profile.start_c, profile.segments);
  std::vector<double> times;
  for (double t = 0.0; t < p.duration_s(); t += step_s) times.push_back(t);
  for (std::size_t i = 0; i < profile.segments.size(); ++i) times.push_back(p.segment_end_s(i));
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), [](double a, double b) { return std::abs(a - b) < 1e-6; }),
              times.end());
  std::string out = "time_s,setpoint_c\n";
  for (double t : times) out += fmt::format("{:.6g},{:.6g}\n", t, p.at(t).temp_c);
  return out;
}

void write_plan_files(PlanResult& r, const PlanSetup& setup, const PrecisionDetail& detail) {
  const std::filesystem::path dir = r.request.out;
  std::error_code ec;
  const bool made = !std::filesystem::exists(dir, ec);
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot make the folder ({})", dir.string(), ec.message()));
  try {
    write_into(r, setup, detail, dir);
  } catch (...) {
    if (made) std::filesystem::remove_all(dir, ec);  // the folder this call made, with nothing in it
    throw;
  }
}

void write_into(PlanResult& r, const PlanSetup& setup, const PrecisionDetail& detail,
                const std::filesystem::path& dir) {
  const std::string header = header_of(r);
  sim::Scenario sc = setup.base;
  sc.name = "plan";
  sc.description = fmt::format("planned test for {} ({:.2f} h)", r.model, r.duration_s / 3600.0);
  sc.start_c = r.profile.start_c;
  sc.segments = r.profile.segments;
  const std::string scenario = sim::scenario_toml(sc, "rig.toml", "gyro.toml", header);
  const std::string rig = sim::rig_toml(setup.rig, header);
  const std::string gyro = sim::gyro_toml(setup.gyro, header);
  const std::string csv = setpoint_csv(r.profile);
  r.scenario_file = (dir / "plan.toml").string();
  r.rig_file = (dir / "rig.toml").string();
  r.gyro_file = (dir / "gyro.toml").string();
  r.setpoint_file = (dir / "plan_setpoint.csv").string();
  r.figure_file = (dir / "plan.png").string();
  // Every text in a temporary file first; the figure (the step most likely
  // to fail: gnuplot) next; then the renames, which do not fail on one file
  // system. A failure before them leaves no file.
  std::vector<std::unique_ptr<AtomicFile>> files;
  for (const auto& [path, text] : {std::pair{r.rig_file, &rig}, std::pair{r.gyro_file, &gyro},
                                   std::pair{r.setpoint_file, &csv}, std::pair{r.scenario_file, &scenario}}) {
    files.push_back(std::make_unique<AtomicFile>(path));
    files.back()->stream() << *text << std::flush;
    if (!files.back()->stream()) throw InputError(fmt::format("{}: writing failed (disk full?)", path));
  }
  // The figure to a name of its own, renamed with the rest.
  const std::filesystem::path figure_partial = r.figure_file + ".partial";
  TemporaryPath figure_guard(figure_partial);
  plot(figure_partial, r, detail);
  for (auto& f : files) f->commit();
  std::filesystem::rename(figure_partial, r.figure_file);
  figure_guard.release();
}

}  // namespace gyrotherm::studies::plan

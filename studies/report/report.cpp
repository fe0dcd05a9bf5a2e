#include "studies/report/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fit/channels.h"
#include "fit/fit_file.h"
#include "fit/model/formula.h"
#include "sim/util/atomic_file.h"
#include "sim/util/gnuplot.h"
#include "sim/util/input_error.h"
#include "sim/util/sha256.h"
#include "studies/allan/allan_study.h"
#include "studies/check/check_run.h"
#include "studies/diagnose/diagnose_run.h"
#include "studies/export/exporter.h"
#include "studies/fit/compensate_run.h"
#include "studies/fit/fit_run.h"
#include "studies/options/fit_options.h"
#include "studies/report/report_evidence.h"
#include "studies/report/report_page.h"

namespace gyrotherm::studies {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// A scratch folder for the figures, removed on every exit.
struct Scratch {
  fs::path dir;
  Scratch() {
    dir = fs::temp_directory_path() /
          fmt::format("gyrotherm-report-{}", std::chrono::steady_clock::now().time_since_epoch().count());
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string png_data(const fs::path& png) { return "data:image/png;base64," + base64(slurp(png)); }

// Heating (+1), cooling (−1) or holding (0) at each window, from its neighbours.
std::vector<double> legs(const std::vector<double>& time_s, const std::vector<double>& temp_c) {
  std::vector<double> out(temp_c.size(), 0.0);
  for (std::size_t i = 0; i < temp_c.size(); ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, temp_c.size() - 1);
    if (b == a) continue;
    const double rate = (temp_c[b] - temp_c[a]) / (time_s[b] - time_s[a]) * 60.0;  // °C/min
    out[i] = rate > 0.05 ? 1.0 : rate < -0.05 ? -1.0 : 0.0;
  }
  return out;
}

// The figures of one channel, from its compensation's windows.
// `stem`: the figures' path without the suffix, made safe for a file name.
ChannelFigures channel_figures(const fit::Compensation& c, const std::string& channel, const fs::path& stem,
                               const std::string& allan_png, const AxisCheck* firmware, const ChannelBand& band) {
  const fit::PreparedData& d = c.data;
  const std::vector<double>& t = d.series.time_s;
  std::vector<double> hours(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) hours[i] = t[i] / 3600.0;
  const std::vector<double> leg = legs(t, d.series.temp_c);
  ChannelFigures f;
  const fs::path bias_png = stem.string() + "_bias.png";
  {
    GnuplotFigure fig(bias_png, 1100, 700);
    const bool banded = band.band.half_width_dph.size() == c.window_model_dph.size();
    fig.data("w", {"temp", "gyro", "model", "leg", "half"},
             {d.series.temp_c, d.series.gyro_dph, c.window_model_dph, leg,
              banded ? band.band.half_width_dph : std::vector<double>(leg.size(), NAN)});
    std::string range;
    if (c.fit_range_c)
      range = fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead dt 2 lc rgb '#555555'\n"
                          "set arrow from {1},graph 0 to {1},graph 1 nohead dt 2 lc rgb '#555555'\n"
                          "set label 'fitted range' at {0},graph 0.97 offset 0.5,0 tc rgb '#555555'\n",
                          c.fit_range_c->first, c.fit_range_c->second);
    fig.commands(fmt::format(
        "set title 'Bias against temperature, {}: window means (heating red, cooling blue), the model (black){}'\n"
        "set xlabel 'gyro temperature (°C)'\nset ylabel 'gyro output, window mean (°/h)'\nset key bottom right\n{}"
        "plot {}$w using 1:($4>0?$2:NaN) with points pt 7 ps 0.6 lc rgb '#d62728' title 'heating', "
        "$w using 1:($4<0?$2:NaN) with points pt 7 ps 0.6 lc rgb '#1f77b4' title 'cooling', "
        "$w using 1:($4==0?$2:NaN) with points pt 7 ps 0.6 lc rgb '#999999' title 'holding', "
        "$w using 1:3 with points pt 1 ps 0.5 lc rgb '#000000' title 'model at each window'",
        channel, banded ? " with its 95 % band (grey)" : "", range,
        banded ? "$w using 1:3:($3-$5):($3+$5) with yerrorbars pt 0 lw 2 lc rgb '#cccccc' title '95 % band of the model', " : ""));
    fig.render();
  }
  const fs::path time_png = stem.string() + "_time.png";
  {
    GnuplotFigure fig(time_png, 1100, 700);
    // Each about its own mean, so that the two share one scale.
    const auto centred = [](std::vector<double> v) {
      double mean = 0.0;
      for (const double x : v) mean += x / static_cast<double>(v.size());
      for (double& x : v) x -= mean;
      return v;
    };
    const std::vector<double> raw = centred(d.series.gyro_dph), comp = centred(c.window_compensated_dph);
    fig.data("w", {"h", "raw", "comp", "temp"}, {hours, raw, comp, d.series.temp_c});
    // As the firmware applies the calibration checked (--params), on its own windows.
    std::string firmware_plot;
    if (firmware != nullptr && firmware->window_time_s.size() > 1) {
      std::vector<double> fh(firmware->window_time_s.size());
      for (std::size_t i = 0; i < fh.size(); ++i) fh[i] = firmware->window_time_s[i] / 3600.0;
      fig.data("fw", {"h", "comp"}, {fh, centred(firmware->window_compensated_dph)});
      firmware_plot = ", $fw using 1:2 with lines lw 1.5 lc rgb '#2ca02c' title 'as the firmware applies the checked calibration'";
    }
    fig.commands(fmt::format(
        "set title 'Uncompensated and compensated against time, {} (window means, each about its mean)'\n"
        "set xlabel 'time (h)'\nset ylabel 'gyro output − its mean (°/h)'\nset y2label 'gyro temperature (°C)'\n"
        "set ytics nomirror\nset y2tics\nset key top left\n"
        "plot $w using 1:2 with lines lw 1.5 lc rgb '#444444' title 'uncompensated', "
        "$w using 1:3 with lines lw 1.5 lc rgb '#d62728' title 'compensated (output − model)', "
        "$w using 1:4 axes x1y2 with lines dt 2 lc rgb '#ff7f0e' title 'temperature (right axis)'{}",
        channel, firmware_plot));
    fig.render();
  }
  f.bias = png_data(bias_png);
  f.time = png_data(time_png);
  if (!allan_png.empty() && fs::exists(allan_png)) f.allan = png_data(allan_png);
  return f;
}

std::string temperature_figure(const fit::Compensation& c, const fs::path& dir) {
  const std::vector<double>& t = c.data.series.time_s;
  std::vector<double> hours(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) hours[i] = t[i] / 3600.0;
  const std::vector<double> leg = legs(t, c.data.series.temp_c);
  const fs::path png = dir / "temperature.png";
  GnuplotFigure fig(png, 1100, 500);
  fig.data("w", {"h", "temp", "leg"}, {hours, c.data.series.temp_c, leg});
  fig.commands(
      "set title 'Gyro temperature against time (window means): heating red, cooling blue'\n"
      "set xlabel 'time (h)'\nset ylabel 'gyro temperature (°C)'\nset key top right\n"
      "plot $w using 1:2 with lines lw 1 lc rgb '#bbbbbb' notitle, "
      "$w using 1:($3>0?$2:NaN) with points pt 7 ps 0.5 lc rgb '#d62728' title 'heating', "
      "$w using 1:($3<0?$2:NaN) with points pt 7 ps 0.5 lc rgb '#1f77b4' title 'cooling'");
  fig.render();
  return png_data(png);
}

// The fits to report: the saved fit, or one made here (its fit-file JSON).
std::pair<std::vector<fit::SavedFit>, Json> fits_of(const ReportRequest& o) {
  if (!o.fit_file.empty()) return {fit::load_fits(o.fit_file), Json::parse(slurp(o.fit_file))};
  FitCommandOptions f;
  f.data = o.data;
  f.model = o.model;
  f.data_options = o.data_options;
  const FitRun run = run_fit(fit_request(f));
  const nlohmann::json parsed = nlohmann::json::parse(run.json);
  return {fit::load_fits_json(parsed, fit::kFitInMemory), Json::parse(run.json)};
}

// The fits' gyro columns as one comma list (diagnose's and check's channels).
std::string gyro_columns(const std::vector<fit::SavedFit>& fits) {
  std::string gyros;
  for (const fit::SavedFit& f : fits) gyros += (gyros.empty() ? "" : ",") + f.pipeline.columns.gyro;
  return gyros;
}

// diagnose on the log with the fit's model, columns and rules.
Json diagnosis_of(const ReportRequest& o, const std::vector<fit::SavedFit>& fits) {
  DiagnoseRequest d;
  d.data = o.data;
  d.base_terms = d.terms = fits.front().terms;
  d.pipeline = fits.front().pipeline;
  d.pipeline.columns.gyro = gyro_columns(fits);
  return diagnose_json(run_diagnose(d));
}

}  // namespace

std::string report_twin_file(const std::string& output) {
  return fs::path(output).replace_extension(".json").string();
}

ReportRun run_report(const ReportRequest& o) {
  const auto step = [&](const std::string& what, double share) {
    if (o.progress) o.progress(what, share);
  };
  step("fitting", 0.05);
  auto [fits, fit_json] = fits_of(o);
  step("compensating", 0.25);
  CompensateRequest cr;
  cr.data = o.data;
  cr.fit_file = o.fit_file.empty() ? std::string(fit::kFitInMemory) : o.fit_file;
  cr.fits = fits;
  const CompensateRun compensated = run_compensate(cr);
  std::vector<ChannelBand> bands;
  for (std::size_t k = 0; k < fits.size(); ++k) {
    std::error_code ec;  // the fit's own record: a band (its covariance belongs to it)
    // The same file by path, and the same windows by content (a path can
    // name another log than the one fitted): the instability before the fit.
    const double before = compensated.channels[k].before_dph;
    const bool same = o.fit_file.empty() ||
                      (fs::equivalent(fits[k].data_file, o.data, ec) && fits[k].instability_before_dph &&
                       std::abs(*fits[k].instability_before_dph - before) <= 1e-9 * std::abs(before));
    bands.push_back(channel_band(fits[k], compensated.channels[k], same));
  }
  step("Allan deviation", 0.4);
  Scratch scratch;
  AllanRequest ar;
  ar.data = o.data;
  ar.fit_file = cr.fit_file;
  ar.fits = fits;
  ar.plot = (scratch.dir / "allan.png").string();
  const std::vector<AllanStudy> allan = run_allan(ar);
  step("diagnosing", 0.55);
  const Json diagnosis = diagnosis_of(o, fits);
  std::optional<CheckResult> check;
  if (!o.params.empty()) {
    step("checking the calibration", 0.75);
    CheckRequest q;
    q.log = o.data;
    q.parameters = o.params;
    q.max_residual = o.max_residual_dph;
    // The log read as the fit read it: its columns, the channels as X, Y, Z.
    q.columns = fits.front().pipeline.columns;
    q.columns.gyro = gyro_columns(fits);
    check = run_check(q);
  }
  step("figures", 0.85);
  ReportContent content;
  content.twin = report_twin(o, fits, fit_json, compensated, allan, diagnosis, check, bands);
  content.temperature = temperature_figure(compensated.channels.front(), scratch.dir);
  for (std::size_t k = 0; k < fits.size(); ++k) {
    const std::string png = allan[k].plot;
    const std::string name = channel_name(fits[k]);
    const AxisCheck* firmware = check && k < check->axes.size() ? &check->axes[k] : nullptr;
    content.channels.push_back(channel_figures(compensated.channels[k], name,
                                               scratch.dir / fit::channel_file_names({name}).front(), png, firmware,
                                               bands[k]));
  }
  ReportRun run;
  run.html = report_html(content);
  run.twin = content.twin.dump(2) + "\n";
  run.html_file = o.output;
  run.twin_file = report_twin_file(o.output);
  step("writing", 0.95);
  write_file_atomically(run.twin_file, run.twin);
  try {
    write_file_atomically(run.html_file, run.html);
  } catch (...) {  // both or neither
    std::error_code ignored;
    fs::remove(run.twin_file, ignored);
    throw;
  }
  run.text = fmt::format("wrote {} ({} KB) and its JSON twin {}\n", run.html_file, run.html.size() / 1024, run.twin_file);
  return run;
}

}  // namespace gyrotherm::studies

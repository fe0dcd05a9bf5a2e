#include "studies/diagnose/diagnose_plots.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "sim/util/gnuplot.h"
#include "studies/allan/allan_study.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {
namespace {

const char* colour_of(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::heating: return "#f4c7c3";
    case SegmentKind::cooling: return "#c6dbef";
    case SegmentKind::turn_on: return "#fde9a8";
    default: return "#eeeeee";  // soak
  }
}

// Hours since the record's start (the segments' times are too).
std::vector<double> in_hours(const std::vector<double>& s, double start_s) {
  std::vector<double> h(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) h[i] = (s[i] - start_s) / 3600.0;
  return h;
}

}  // namespace

std::vector<std::size_t> windows_after_gaps(const fit::PreparedData& data) {
  const fit::AveragedSeries& s = data.series;
  const double spacing_s = data.averaging.bursts ? data.averaging.median_spacing_s : s.window_s;
  std::vector<std::size_t> out;
  for (std::size_t p = 1; p < s.size(); ++p)
    if (s.time_s[p] - s.time_s[p - 1] > 1.75 * spacing_s) out.push_back(p);
  return out;
}

void write_diagnosis_plots(const std::string& dir, const fit::Measurement& m,
                           const fit::PreparedData& data, const Diagnosis& d,
                           const Diagnosis* before) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--plots {}: cannot create the folder ({})", dir, ec.message()));
  const fit::AveragedSeries& s = data.series;
  const std::vector<double> t_h = in_hours(s.time_s, s.start_time_s);
  const std::vector<std::size_t> gaps = windows_after_gaps(data);  // the time plots' lines break there
  const std::string floor_text = fmt::format("{:.4g}", d.noise_floor_dph);
  const std::string_view unit = d.sensor->unit;  // °/h for a gyro
  // Gnuplot commands with the unit and the sensor's noun in place of {unit} and {noun}.
  const auto in_unit = [&](std::string text) {
    for (const auto& [key, value] : {std::pair{std::string_view("{unit}"), unit}, {"{noun}", d.sensor->noun}})
      for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
        text.replace(at, key.size(), value);
    return text;
  };

  {  // 1. Measured and modelled bias with the temperature.
    GnuplotFigure fig(dir + "/bias_time.png", 1400, 700);
    fig.data("d", {"t_h", "measured", "model", "temp"}, {t_h, s.gyro_dph, d.model_dph(), s.temp_c}, gaps);
    fig.commands(in_unit(
        "set title 'Measured and modelled bias (window means) with the {noun} temperature'\n"
        "set xlabel 'time since the start of the record (h)'\nset ylabel 'bias ({unit})'\nset y2label 'temperature (°C)'\n"
        "set y2tics\nset ytics nomirror\nset key outside right\n"
        "plot $d using 1:2 with points pt 7 ps 0.5 lc rgb '#444444' title 'measured', "
        "$d using 1:3 with lines lw 2 lc rgb '#d62728' title 'model', "
        "$d using 1:4 axes x1y2 with lines lw 1 lc rgb '#1f77b4' title 'temperature'\n"));
    fig.render();
  }
  {  // 2. Residual with the segments shaded and the worst marked.
    GnuplotFigure fig(dir + "/residual_segments.png", 1400, 700);
    std::vector<double> floor_hi(s.size(), d.noise_floor_dph), floor_lo(s.size(), -d.noise_floor_dph);
    fig.data("r", {"t_h", "residual", "floor", "minus_floor"}, {t_h, d.residual_dph(), floor_hi, floor_lo}, gaps);
    std::string cmds = in_unit(
        "set title 'Residual of the model; shading: turn-on (yellow), heating (red), cooling "
        "(blue), soak (grey); the three worst segments are labelled'\n"
        "set xlabel 'time since the start of the record (h)'\nset ylabel 'residual ({unit})'\nset key outside right\n");
    for (std::size_t i = 0; i < d.segments.size(); ++i) {
      const SegmentReport& seg = d.segments[i];
      cmds += fmt::format(
          "set object {} rect from {:.6f}, graph 0 to {:.6f}, graph 1 fc rgb '{}' fs solid 0.6 "
          "noborder behind\n",
          i + 1, (seg.start_s - 50.0) / 3600.0, (seg.end_s + 50.0) / 3600.0, colour_of(seg.kind));
    }
    const auto worst = d.worst_segments();
    for (std::size_t k = 0; k < worst.size() && k < 3; ++k) {
      const SegmentReport& seg = d.segments[worst[k]];
      cmds += fmt::format("set label {} '#{} {} {:.1f}x' at {:.6f}, graph 0.95 center front\n", k + 1,
                          k + 1, to_string(seg.kind), seg.ratio_to_floor, 0.5 * (seg.start_s + seg.end_s) / 3600.0);
    }
    cmds += "plot $r using 1:2 with linespoints pt 7 ps 0.4 lw 1 lc rgb '#222222' title 'residual', "
            "$r using 1:3 with lines dt 2 lc rgb '#2ca02c' title '± noise floor " + floor_text +
            "', $r using 1:4 with lines dt 2 lc rgb '#2ca02c' notitle\n";
    fig.commands(cmds);
    fig.render();
  }
  {  // 3. Residual against temperature and against dT/dt.
    GnuplotFigure fig(dir + "/residual_vs.png", 1400, 600);
    std::vector<double> rate_mk(s.size());
    for (std::size_t p = 0; p < s.size(); ++p) rate_mk[p] = data.derived.rate_c_per_s[p] * 60.0;
    fig.data("v", {"temp", "rate_c_per_min", "residual"}, {s.temp_c, rate_mk, d.residual_dph()});
    fig.commands(in_unit(
        "set multiplot layout 1,2 title 'Residual against temperature and temperature rate (a "
        "pattern here is a missing effect)'\n"
        "set xlabel 'temperature (°C)'\nset ylabel 'residual ({unit})'\nunset key\n"
        "plot $v using 1:3 with points pt 7 ps 0.5 lc rgb '#1f77b4'\n"
        "set xlabel 'dT/dt (°C/min)'\n"
        "plot $v using 2:3 with points pt 7 ps 0.5 lc rgb '#d62728'\nunset multiplot\n"));
    fig.render();
  }
  if (before != nullptr) {  // 4. Before and after the added effect.
    GnuplotFigure fig(dir + "/before_after.png", 1400, 700);
    fig.data("b", {"t_h", "before", "after"}, {t_h, before->residual_dph(), d.residual_dph()}, gaps);
    fig.commands(fmt::format(
        "set title 'Residual before ({0:.4g} {3}) and after ({1:.4g} {3}) adding the effect; noise "
        "floor {2}'\nset xlabel 'time since the start of the record (h)'\nset ylabel 'residual ({3})'\nset key outside right\n"
        "plot $b using 1:2 with lines lw 1.5 lc rgb '#aaaaaa' title 'before', "
        "$b using 1:3 with lines lw 2 lc rgb '#d62728' title 'after'\n",
        before->fit.instability_after_dph, d.fit.instability_after_dph, floor_text, unit));
    fig.render();
  }
  if (m.size() > 0) {  // 5. Allan deviation of the raw and the compensated output.
    std::vector<double> compensated(m.size());
    std::size_t p = 0;
    for (std::size_t k = 0; k < m.size(); ++k) {
      while (p + 1 < s.size() && s.time_s[p + 1] <= m.time_s[k]) ++p;
      double model = d.model_dph()[p];
      if (p + 1 < s.size() && m.time_s[k] >= s.time_s[p]) {
        const double f = (m.time_s[k] - s.time_s[p]) / (s.time_s[p + 1] - s.time_s[p]);
        model += f * (d.model_dph()[p + 1] - d.model_dph()[p]);
      }
      compensated[k] = m.gyro_dph[k] - model;
    }
    // The Allan deviation of studies/allan, with its intervals for the noise
    // type identified at each τ.
    const AllanCurve raw = allan_series(m.time_s, m.gyro_dph, {}, "raw").curve;
    const AllanCurve comp = allan_series(m.time_s, compensated, {}, "compensated").curve;
    std::vector<double> tr, r, rl, ru, tc, c, cl, cu;
    for (const AllanRow& a : raw.rows) {
      tr.push_back(a.tau_s); r.push_back(a.adev_dph); rl.push_back(a.lo_dph); ru.push_back(a.hi_dph);
    }
    for (const AllanRow& a : comp.rows) {
      tc.push_back(a.tau_s); c.push_back(a.adev_dph); cl.push_back(a.lo_dph); cu.push_back(a.hi_dph);
    }
    GnuplotFigure fig(dir + "/allan.png", 1000, 750);
    fig.data("raw", {"tau", "adev", "lo", "hi"}, {tr, r, rl, ru});
    fig.data("comp", {"tau", "adev", "lo", "hi"}, {tc, c, cl, cu});
    fig.commands(fmt::format(
        "set title 'Allan deviation of the raw and compensated output (68 % bands for the noise type at each τ)'\n"
        "set logscale xy\nset xlabel 'averaging time τ (s)'\nset ylabel 'Allan deviation ({3})'\n"
        "set key outside right\nset arrow from {0}, graph 0 to {0}, graph 1 nohead dt 3 lc rgb '#888888'\n"
        "set label 'floor {1}' at {0}, {2} point pt 9 ps 2 lc rgb '#2ca02c' offset 1,1\n"
        "plot $raw using 1:3:4 with filledcurves fc rgb '#cccccc' fs transparent solid 0.5 notitle, "
        "$raw using 1:2 with linespoints pt 7 ps 0.6 lc rgb '#444444' title 'raw', "
        "$comp using 1:3:4 with filledcurves fc rgb '#f4a582' fs transparent solid 0.5 notitle, "
        "$comp using 1:2 with linespoints pt 7 ps 0.6 lc rgb '#d62728' title 'compensated'\n",
        data.series.window_s, floor_text, d.noise_floor_dph, unit));  // a burst's length with bursts
    fig.render();
  }
}

}  // namespace gyrotherm::studies

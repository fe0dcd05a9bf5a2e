#include "studies/allan/allan_study.h"

#include "fit/data/plausibility.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "fit/channels.h"
#include "fit/compensation.h"
#include "fit/data/median.h"
#include "fit/fit_file.h"
#include "fit/pipeline.h"
#include "sim/util/gnuplot.h"
#include "sim/util/input_error.h"
#include "sim/util/format.h"
#include "studies/record_source.h"

namespace gyrotherm::studies {
namespace {

nlohmann::ordered_json coefficient_json(const NoiseCoefficient& read, const CoefficientLabel& label,
                                        const CoefficientLabels& labels) {
  const NoiseCoefficient k = reported(read, label);
  nlohmann::ordered_json j{{"shown", k.shown}, {"method", coefficient_method_name(k.method)}};
  if (k.shown) {
    j["value"] = k.value;
    j["lo"] = k.lo;
    j["hi"] = k.hi;
    j["tau_range_s"] = {k.tau_from_s, k.tau_to_s};
    j["tau_read_s"] = k.tau_read_s;
  }
  j["upper_bound"] = k.upper_bound > 0.0 ? nlohmann::ordered_json(k.upper_bound) : nlohmann::ordered_json();
  j["note"] = coefficient_note(read, labels);
  return j;
}

std::string coefficient_text(const NoiseCoefficient& k, const std::string& unit) {
  if (!k.shown) return k.upper_bound > 0.0 ? fmt::format("< {:.3g} {} (bound)", k.upper_bound, unit) : "—";
  return fmt::format("{:.4g} [{:.4g}, {:.4g}] {}", k.value, k.lo, k.hi, unit);
}

}  // namespace

AllanSeries allan_series(std::span<const double> time_s, std::span<const double> rate_dph, AllanOptions options,
                         std::string name, const fit::SensorKind* sensor) {
  AllanSeries s;
  std::vector<double> steps(time_s.size() > 1 ? time_s.size() - 1 : 0);
  for (std::size_t i = 0; i < steps.size(); ++i) steps[i] = time_s[i + 1] - time_s[i];
  if (!steps.empty()) s.noise = identify_series_noise(time_s, rate_dph, fit::median_of(steps));
  if (s.noise && sensor != nullptr && !sensor->is_gyro) s.noise->sensor = sensor;  // its names and units
  if (s.noise && !options.model_avar)
    options.model_avar = [model = *s.noise](double tau) { return model.allan_variance(tau); };
  s.curve = allan_curve(time_s, rate_dph, options, std::move(name));
  s.coefficients = read_noise_coefficients(s.curve);
  s.bias_support = settle_bias_instability(s.coefficients.bias_instability_dph, s.curve, s.noise);
  return s;
}

std::optional<double> AllanStudy::bias_instability_ratio() const {
  if (series.size() < 2) return std::nullopt;
  const auto& a = series.front().coefficients.bias_instability_dph;
  const auto& b = series.back().coefficients.bias_instability_dph;
  // The same reading on both sides (σ/0.664 holds white noise the model's floor does not).
  if (!a.shown || !b.shown || b.value <= 0.0 || a.method != b.method) return std::nullopt;
  return a.value / b.value;
}

AllanStudy allan_study(const fit::Measurement& m, const fit::SavedFit* fit, const AllanOptions& options) {
  AllanStudy s;
  s.data_file = m.file;
  s.units = m.units;
  s.cautions = fit::measurement_cautions(m);
  const fit::SensorKind* sensor = &m.units.kind();
  s.series.push_back(allan_series(m.time_s, m.gyro_dph, options, "raw", sensor));
  if (!m.temp_c.empty()) {
    const auto [lo, hi] = std::minmax_element(m.temp_c.begin(), m.temp_c.end());
    s.temp_span_c = *hi - *lo;
  }
  if (fit) {
    s.fit_file = fit->file.string();
    s.channel = fit->channel;
    fit::PipelineOptions pipeline = fit::reading_columns_of(fit->pipeline, fit->terms);
    pipeline.derivative = fit::DerivativeMode::causal;
    const fit::Compensation c = fit::compensate(m, *fit, pipeline);
    std::vector<double> compensated(c.gyro_dph.size());
    for (std::size_t i = 0; i < compensated.size(); ++i) {
      compensated[i] = c.gyro_dph[i] - c.model_dph[i];
      s.outliers += c.outlier[i];
    }
    s.series.push_back(allan_series(c.time_s, compensated, options, "compensated", sensor));
  }
  return s;
}

bool AllanStudy::raw_holds_thermal_drift() const { return temp_span_c >= kThermalDriftSpanC; }

nlohmann::ordered_json allan_json(const AllanStudy& study) {
  nlohmann::ordered_json j;
  const fit::SensorKind& kind = study.units.kind();
  const CoefficientLabels labels = coefficient_labels(kind);
  j["data"] = study.data_file;
  if (!kind.is_gyro) {
    // Another sensor's: the *_dph fields in its base unit, the coefficients by its names.
    j["sensor"] = kind.name;
    j["unit"] = kind.unit;
  }
  j["units"] = study.units.used();
  j["cautions"] = fit::caution_texts(study.cautions);
  j["fit"] = study.fit_file.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(study.fit_file);
  if (!study.channel.empty()) j["channel"] = study.channel;
  j["confidence"] = study.series.front().curve.confidence;
  j["temp_span_c"] = study.temp_span_c;
  j["raw_holds_thermal_drift"] = study.raw_holds_thermal_drift();
  j["series"] = nlohmann::ordered_json::array();
  for (const AllanSeries& s : study.series) {
    const AllanCurve& c = s.curve;
    nlohmann::ordered_json js{{"name", c.name},       {"tau0_s", c.tau0_s}, {"samples", c.samples},
                              {"runs", c.runs},       {"gaps", c.gaps},     {"span_s", c.span_s},
                              {"longest_run_s", c.longest_run_s}, {"limited_by_runs", c.limited_by_runs}};
    std::vector<double> tau, adev, lo, hi, edf;
    std::vector<std::string> type, from;
    std::vector<std::size_t> terms, gap_terms;
    for (const AllanRow& r : c.rows) {
      tau.push_back(r.tau_s);
      adev.push_back(r.adev_dph);
      lo.push_back(r.lo_dph);
      hi.push_back(r.hi_dph);
      edf.push_back(r.edf);
      type.push_back(noise_type_name(r.alpha));
      from.push_back(r.alpha_from_acf ? "acf" : r.alpha_from_model ? "model" : "slope");
      terms.push_back(r.terms);
      gap_terms.push_back(r.gap_terms);
    }
    js["taus_s"] = tau;
    js["adev_dph"] = adev;
    js["lo_dph"] = lo;
    js["hi_dph"] = hi;
    js["edf"] = edf;
    js["noise_type"] = type;
    js["noise_type_from"] = from;
    js["terms"] = terms;
    js["gap_terms"] = gap_terms;
    const NoiseCoefficients& k = s.coefficients;
    js["coefficients"] = {
        {labels.white.json_key, coefficient_json(k.arw_dpsh, labels.white, labels)},
        {labels.bias_instability.json_key,
         coefficient_json(k.bias_instability_dph, labels.bias_instability, labels)},
        {labels.random_walk.json_key, coefficient_json(k.rrw_dph_per_sqrt_h, labels.random_walk, labels)},
        {labels.quantization.json_key, coefficient_json(k.quantization_arcsec, labels.quantization, labels)}};
    js["coefficient_fit_chi2_per_dof"] = s.coefficients.fit_chi2_per_dof;
    js["bias_instability_support"] = bias_support_name(s.bias_support);
    if (s.noise) {
      js["noise_model"] = fit::noise_model_json(*s.noise);
      js["noise_model"]["method"] = "REML on the series (intercept only): white + flicker + rate random walk, a "
                                    "Gauss-Markov process where it pays";
    } else {
      js["noise_model"] = nullptr;
    }
    j["series"].push_back(std::move(js));
  }
  const auto ratio = study.bias_instability_ratio();
  j["bias_instability_ratio"] = ratio ? nlohmann::ordered_json(*ratio) : nlohmann::ordered_json();
  if (!study.fit_file.empty()) j["outliers_flagged"] = study.outliers;
  return j;
}

std::string allan_text(const AllanStudy& study) {
  const AllanCurve& first = study.series.front().curve;
  const fit::SensorKind& kind = study.units.kind();
  const CoefficientLabels labels = coefficient_labels(kind);
  const std::string& unit = labels.adev_unit;
  // The noise type by the sensor's words (a gyro's as the JSON's noise_type;
  // another's white noise and random walk by their names, "velocity_random_walk").
  const auto noise_type_text = [&](int alpha) {
    if (kind.is_gyro || (alpha != 0 && alpha != -2)) return noise_type_name(alpha);
    std::string name = alpha == 0 ? labels.white.name : labels.random_walk.name;
    for (char& c : name) c = c == ' ' ? '_' : c;
    return name;
  };
  std::string out = fmt::format(
      "allan {}{}: {} every {:.4g} s over {:.4g} h, {}; overlapping Allan deviation, "
      "{:.0f} % intervals (Greenhall's edf for the noise type at each τ)\n",
      study.data_file, study.channel.empty() ? "" : ", channel " + study.channel, counted(first.samples, "sample"),
      first.tau0_s, first.span_s / 3600.0, counted(first.runs, "gap-free run"), 100.0 * first.confidence);
  out += fit::units_text(study.units, study.cautions);
  if (first.gaps > 0)
    out += fmt::format("  {}: a τ whose clusters would span one uses only those that do not (the 'left out' "
                       "column); the longest gap-free run is {:.4g} s\n",
                       counted(first.gaps, "gap"), first.longest_run_s);
  if (first.limited_by_runs)
    out += fmt::format("  the longest τ is {:.4g} s: a τ needs one gap-free stretch of 2τ, and the runs are short "
                       "(bursts): the record cannot show longer τ, where bias instability and rate random walk sit\n",
                       first.rows.empty() ? 0.0 : first.rows.back().tau_s);
  if (!study.fit_file.empty())
    out += fmt::format("  compensated: {} applied as a real-time compensator (compensate --causal){}\n",
                       study.fit_file,
                       study.outliers ? fmt::format("; {} flagged, kept in both", counted(study.outliers, "glitch sample")) : "");
  for (const AllanSeries& s : study.series) {
    out += fmt::format("\n{}:\n  {:>10} {:>12} {:>25} {:>9}  {:<26} {:>9}\n", s.curve.name, "tau (s)",
                       fmt::format("adev ({})", unit), fmt::format("interval ({})", unit), "edf", "noise type",
                       "left out");
    for (const AllanRow& r : s.curve.rows)
      out += fmt::format("  {:>10.4g} {:>12.5g} [{:>11.5g}, {:>11.5g}] {:>9.4g}  {:<26} {:>9}\n", r.tau_s,
                         r.adev_dph, r.lo_dph, r.hi_dph, r.edf,
                         noise_type_text(r.alpha) + (r.alpha_from_acf ? "" : r.alpha_from_model ? " (model)" : " (slope)"), r.gap_terms);
  }
  out += "\nnoise coefficients (value [interval]):\n";
  std::string header = fmt::format("  {:<22}", "");
  for (const AllanSeries& s : study.series) header += fmt::format(" {:<42}", s.curve.name);
  out += header + "\n";
  const auto row = [&](const CoefficientLabel& label, auto member) {
    std::string line = fmt::format("  {:<22}", label.name);
    for (const AllanSeries& s : study.series)
      line += fmt::format(" {:<42}", coefficient_text(reported(s.coefficients.*member, label), label.unit));
    out += line + "\n";
  };
  row(labels.white, &NoiseCoefficients::arw_dpsh);
  row(labels.bias_instability, &NoiseCoefficients::bias_instability_dph);
  row(labels.random_walk, &NoiseCoefficients::rrw_dph_per_sqrt_h);
  row(labels.quantization, &NoiseCoefficients::quantization_arcsec);
  out += "how each was read:\n";
  for (const AllanSeries& s : study.series) {
    const NoiseCoefficients& k = s.coefficients;
    out += fmt::format("  {}: {}: {}\n  {}: bias instability: {}\n  {}: {}: {}\n", s.curve.name,
                       labels.white.short_name, coefficient_note(k.arw_dpsh, labels), s.curve.name,
                       coefficient_note(k.bias_instability_dph, labels), s.curve.name, labels.random_walk.short_name,
                       coefficient_note(k.rrw_dph_per_sqrt_h, labels));
    if (k.quantization_arcsec.shown)
      out += fmt::format("  {}: quantisation: {}\n", s.curve.name, coefficient_note(k.quantization_arcsec, labels));
  }
  out += fmt::format("  ({} is {}the −½ line's value at τ = 1 h; {} the +½ line's value at τ = 3 h; B = flat σ / 0.664, "
                     "or the noise model's flicker floor)\n",
                     labels.white.short_name,
                     labels.white.scale == 1.0 ? std::string() : fmt::format("{:g} × ", labels.white.scale),
                     labels.random_walk.short_name);
  // Bias instability is in the table above, once. Beside a compensated
  // series, the raw one still holds the thermal drift the fit removes: its
  // model reads that drift as slow noise, so it is no model of the gyro's noise;
  // without a fit, so is a raw series whose temperature moved.
  const bool compensated = study.series.size() > 1;
  const auto raw_caveat = [&] {
    if (compensated)
      return fmt::format(" (the raw series holds the thermal drift the fit removes, read here as slow noise: "
                         "the compensated series' model is the {}'s)",
                         kind.noun);
    if (study.raw_holds_thermal_drift())
      return fmt::format(" (the temperature moved {:.1f} °C on this record: the raw series holds the {}'s thermal "
                         "drift, read here as slow noise, and the white part may be understated; --fit FILE gives the "
                         "noise a compensation leaves)",
                         study.temp_span_c, kind.noun);
    return std::string();
  };
  for (const AllanSeries& s : study.series)
    if (s.noise)
      out += fmt::format("noise model of {} (REML): {}; bias instability in the table above{}\n", s.curve.name,
                         s.noise->description("bias_instability"),
                         &s == &study.series.front() ? raw_caveat() : std::string());
  if (const auto ratio = study.bias_instability_ratio())
    out += fmt::format("bias instability raw / compensated: {:.3g}\n", *ratio);
  return out;
}

void write_allan_plot(const std::filesystem::path& png, const AllanStudy& study) {
  GnuplotFigure fig(png, 1200, 850);
  const CoefficientLabels labels_of_kind = coefficient_labels(study.units.kind());
  const auto value_text = [](const std::string& name, const NoiseCoefficient& c, const CoefficientLabel& label) {
    const NoiseCoefficient k = reported(c, label);
    return fmt::format("{} {:.3g} {} [{:.3g}, {:.3g}]", name, k.value, label.unit, k.lo, k.hi);
  };
  static const char* kColours[] = {"#444444", "#d62728"};
  static const char* kBands[] = {"#cccccc", "#f4a582"};
  std::string plot = "plot ";
  std::string labels;
  double label_y = 0.95;
  for (std::size_t i = 0; i < study.series.size(); ++i) {
    const AllanSeries& s = study.series[i];
    std::vector<double> tau, adev, lo, hi;
    for (const AllanRow& r : s.curve.rows) {
      tau.push_back(r.tau_s);
      adev.push_back(r.adev_dph);
      lo.push_back(r.lo_dph);
      hi.push_back(r.hi_dph);
    }
    const std::string name = fmt::format("s{}", i);
    fig.data(name, {"tau", "adev", "lo", "hi"}, {tau, adev, lo, hi});
    const char* colour = kColours[i % 2];
    plot += fmt::format(
        "${0} using 1:3:4 with filledcurves fc rgb '{1}' fs transparent solid 0.45 notitle, "
        "${0} using 1:2 with linespoints pt 7 ps 0.7 lw 1.5 lc rgb '{2}' title '{3}', ",
        name, kBands[i % 2], colour, s.curve.name);
    // The slope lines of the coefficients read, over their regions (a little wider).
    const NoiseCoefficients& k = s.coefficients;
    const auto line = [&](const NoiseCoefficient& c, const std::string& expr, const std::string& text) {
      if (!c.shown) return;
      plot += fmt::format("[{}:{}] {} with lines dt 2 lw 1.2 lc rgb '{}' notitle, ", c.tau_from_s / 2.0,
                          c.tau_to_s * 2.0, expr, colour);
      labels += fmt::format("set label '{}: {}' at graph 0.02, graph {:.3f} tc rgb '{}'\n", s.curve.name, text,
                            label_y, colour);
      label_y -= 0.04;
    };
    const CoefficientLabels& l = labels_of_kind;
    line(k.arw_dpsh, fmt::format("{:.8g}/sqrt(x/3600.0)", k.arw_dpsh.value),
         value_text(l.white.short_name, k.arw_dpsh, l.white));
    line(k.bias_instability_dph, fmt::format("{:.8g}+0*x", kFlickerFloor * k.bias_instability_dph.value),
         fmt::format("{} ({})", value_text("bias instability", k.bias_instability_dph, l.bias_instability),
                     k.bias_instability_dph.method == CoefficientMethod::noise_model ? "the noise model floor"
                                                                                    : "the flat part"));
    line(k.rrw_dph_per_sqrt_h, fmt::format("{:.8g}*sqrt(x/3600.0/3.0)", k.rrw_dph_per_sqrt_h.value),
         value_text(l.random_walk.short_name, k.rrw_dph_per_sqrt_h, l.random_walk));
    if (!k.bias_instability_dph.shown && k.bias_instability_dph.upper_bound > 0.0) {
      labels += fmt::format("set label '{}: bias instability < {:.3g} {} (a bound)' at graph "
                            "0.02, graph {:.3f} tc rgb '{}'\n",
                            s.curve.name, k.bias_instability_dph.upper_bound, l.adev_unit, label_y, colour);
      label_y -= 0.04;
    }
    line(k.quantization_arcsec, fmt::format("{:.8g}*sqrt(3.0)/x", k.quantization_arcsec.value),
         fmt::format("quantisation {:.3g}{}{}", k.quantization_arcsec.value, l.quantization.unit == "″" ? "" : " ",
                     l.quantization.unit));
  }
  plot.resize(plot.size() - 2);
  fig.commands(fmt::format(
      "set title 'Overlapping Allan deviation, {:.0f} % intervals; dashed: the noise coefficients read'\n"
      "set logscale xy\nset xlabel 'averaging time τ (s)'\n"
      "set ylabel 'Allan deviation ({})'\nset grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
      "set key top right\n{}{}\n",
      100.0 * study.series.front().curve.confidence, labels_of_kind.adev_unit, labels, plot));
  fig.render();
}

namespace {

std::vector<AllanStudy> allan_record(const AllanRequest& r, const RecordSource& source) {
  std::vector<AllanStudy> studies;
  if (!r.fit_file.empty()) {
    // Every channel the fit holds, read with the fit's own columns and units.
    const std::vector<fit::SavedFit> fits = r.fits.empty() ? fit::load_fits(r.fit_file, fit::FitKinds::any) : r.fits;
    const std::vector<std::string> gyros = gyro_per_channel(r.fit_columns.gyro, fits.size(), r.fit_file);
    for (std::size_t k = 0; k < fits.size(); ++k) {
      const fit::SavedFit& fit = fits[k];
      fit::PipelineOptions pipeline = fit::reading_columns_of(fit.pipeline, fit.terms);
      fit::ColumnMap given = r.fit_columns;
      given.gyro = gyros[k];
      fit::check_given_sensor(fit, given.units.sensor);
      pipeline.columns = source.fit_columns(pipeline.columns).with(given);
      try {
        pipeline.columns.units.validate();
        studies.push_back(allan_study(source.read(pipeline.columns), &fit, r.options));
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}{} with the fit {}: {}", source.name(),
                                     fit.channel.empty() ? "" : ", channel " + fit.channel, r.fit_file, e.what()));
      }
    }
  } else {
    fit::PipelineOptions pipeline = r.pipeline;
    pipeline.columns = source.user_columns(pipeline.columns);
    const std::vector<std::string> channels = fit::parse_channels(pipeline.columns.gyro);
    studies = fit::for_each_channel(channels, pipeline, [&](const std::string& channel, const fit::PipelineOptions& p) {
      AllanStudy s = allan_study(source.read(p.columns), nullptr, r.options);
      if (channels.size() > 1) s.channel = channel;
      return s;
    });
  }
  // One figure per channel beside --plot, named after it (made safe for a file name).
  std::vector<std::string> channels;
  for (const AllanStudy& s : studies) channels.push_back(s.channel);
  const std::vector<std::string> names = fit::channel_file_names(channels);
  for (std::size_t i = 0; i < studies.size() && !r.plot.empty(); ++i) {
    std::filesystem::path png = r.plot;
    if (studies.size() > 1) png.replace_filename(png.stem().string() + "_" + names[i] + png.extension().string());
    write_allan_plot(png, studies[i]);
    studies[i].plot = png.string();
  }
  return studies;
}

}  // namespace

std::vector<AllanStudy> run_allan(const AllanRequest& request) { return allan_record(request, RecordSource(request.data)); }

std::vector<AllanStudy> run_allan(const AllanRequest& request, const fit::Table& table) {
  return allan_record(request, RecordSource(table));
}

nlohmann::ordered_json allan_json(const std::vector<AllanStudy>& studies) {
  if (studies.size() == 1) return allan_json(studies.front());
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const AllanStudy& s : studies) all.push_back(allan_json(s));
  return {{"channels", all}};
}

std::string allan_text(const std::vector<AllanStudy>& studies) {
  std::string out;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    if (i > 0) out += "\n";
    out += allan_text(studies[i]);
  }
  for (const AllanStudy& s : studies)
    if (!s.plot.empty()) out += fmt::format("plot: {}\n", s.plot);
  return out;
}

}  // namespace gyrotherm::studies

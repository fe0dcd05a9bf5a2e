#include "fit/compensation.h"

#include "fit/causal_compensator.h"
#include "fit/data/header_units.h"
#include "fit/data/plausibility.h"
#include "fit/data/streaming.h"
#include "fit/model/formula.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unistd.h>
#include <optional>
#include <nlohmann/json.hpp>

#include "sim/util/atomic_file.h"
#include "sim/util/input_error.h"
#include "sim/util/fast_number.h"

namespace gyrotherm::fit {

double instability_of(const std::vector<double>& v) {
  double mean = 0.0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

namespace {

// B of every window, the compensated windows, the instability before and after.
void window_models(Compensation& c, const SavedFit& fit, OutsideRange outside) {
  const AveragedSeries& s = c.data.series;
  c.fit_range_c = fit.temp_range_c;
  c.outside = outside;
  const bool hold = outside == OutsideRange::hold && fit.temp_range_c;
  if (fit.temp_range_c)
    for (double t : c.data.derived.temp_c) c.windows_outside += t < fit.temp_range_c->first || t > fit.temp_range_c->second;
  c.window_model_dph = model_values(hold ? design_matrix_held(c.data.derived, fit.terms, fit.parameters,
                                                              fit.temp_range_c->first, fit.temp_range_c->second)
                                         : design_matrix(c.data.derived, fit.terms, fit.parameters),
                                    fit.coefficients);
  for (std::size_t p = 0; p < s.size(); ++p)
    c.window_compensated_dph.push_back(s.gyro_dph[p] - c.window_model_dph[p]);
  if (s.size() >= 2) {
    c.before_dph = instability_of(s.gyro_dph);
    c.after_dph = instability_of(c.window_compensated_dph);
  }
}

// The real-time compensator's record constants: the fit's (this record's for
// fit files that lack them).
CausalSettings causal_settings(const SavedFit& fit, const PreparedData& data, OutsideRange outside) {
  CausalSettings settings;
  if (outside == OutsideRange::hold) settings.hold_c = fit.temp_range_c;
  settings.sample_interval_s = fit.sample_interval_s.value_or(data.averaging.sample_interval_s);
  settings.bursts = fit.bursts.value_or(data.averaging.bursts);
  settings.outlier_floor_dph = fit.outlier_floor_dph.value_or(data.outliers.floor_dph);
  return settings;
}

// Central mode: B at time t, interpolated between window centres of the same
// run; p is the window at or before t, advanced as t grows.
double model_at(const AveragedSeries& s, const std::vector<double>& model, double t, std::size_t& p) {
  while (p + 1 < s.size() && s.time_s[p + 1] <= t) ++p;
  const bool can_interpolate = p + 1 < s.size() && s.run[p + 1] == s.run[p] && t >= s.time_s[p];
  if (!can_interpolate) return model[p];
  const double f = (t - s.time_s[p]) / (s.time_s[p + 1] - s.time_s[p]);
  return model[p] + f * (model[p + 1] - model[p]);
}

// The unit part of a kind's default column ("dph", "mps2", "pa", "gauss"):
// the suffix of the output's model and compensated columns.
std::string_view column_suffix(const SensorKind& kind) { return kind.column.substr(kind.column.find('_') + 1); }

std::string csv_head(const Compensation& c) {
  // The figure is the prepared windows', which leave the glitches out; a
  // user averaging the compensated column would keep them unless told.
  const std::size_t removed = c.data.outliers.removed;
  const SensorKind& kind = c.data.units.kind();
  const std::string_view suffix = column_suffix(kind);
  return fmt::format(
      "# gyrotherm compensate: compensated_{1} = {0} - model_{1}; instability "
      "{2:.6g} -> {3:.6g} {4}{5}\ntime_s,temp_c,{0},model_{1},compensated_{1},outlier\n",
      kind.column, suffix, c.before_dph, c.after_dph, kind.noise[1].unit,
      removed == 0 ? std::string()
                   : fmt::format(" (window averages without {} glitch{}; the outlier column marks the samples flagged)",
                                 removed, removed == 1 ? "" : "es"));
}

// One output row, the digits of "{:.10g},{:.6f},{:.6f},{:.9f},{:.9f},{}",
// formatted by hand (sim/util/fast_number.h); needs kRowRoom bytes.
constexpr std::size_t kRowRoom = 6 * 350;
char* write_row(char* p, double t, double temp, double gyro, double model, bool outlier) {
  p = write_general(p, t, 10);
  *p++ = ',';
  p = write_fixed(p, temp, 6);
  *p++ = ',';
  p = write_fixed(p, gyro, 6);
  *p++ = ',';
  p = write_fixed(p, model, 9);
  *p++ = ',';
  p = write_fixed(p, gyro - model, 9);
  *p++ = ',';
  *p++ = outlier ? '1' : '0';
  *p++ = '\n';
  return p;
}

// The rows of a record kept on disk between the pass that reads the CSV and
// the one that writes the output: four doubles a row, in a temporary file
// beside the output (removed on every exit, interrupts included).
class RowSpill {
 public:
  explicit RowSpill(const std::filesystem::path& output)
      : path_(output.string() + ".rows.tmp." + std::to_string(::getpid())),
        file_(std::fopen(path_.path().c_str(), "w+b")) {
    if (file_ == nullptr) throw InputError(path_.path().string() + ": cannot create the temporary file of rows");
  }
  ~RowSpill() {
    if (file_ != nullptr) std::fclose(file_);
  }
  RowSpill(const RowSpill&) = delete;
  RowSpill& operator=(const RowSpill&) = delete;

  void write(const double* rows, std::size_t count) {
    if (std::fwrite(rows, 4 * sizeof(double), count, file_) != count)
      throw InputError(path_.path().string() + ": writing the temporary file of rows failed (disk full?)");
  }
  // Every row, in order: f(t, temp, gyro, temp2).
  template <typename F>
  void replay(F&& f) {
    if (std::fflush(file_) != 0 || std::fseek(file_, 0, SEEK_SET) != 0)
      throw InputError(path_.path().string() + ": cannot read back the temporary file of rows");
    std::vector<double> block(4 * 8192);
    for (std::size_t got; (got = std::fread(block.data(), 4 * sizeof(double), 8192, file_)) > 0;)
      for (std::size_t k = 0; k < got; ++k) f(block[4 * k], block[4 * k + 1], block[4 * k + 2], block[4 * k + 3]);
    if (std::ferror(file_) != 0) throw InputError(path_.path().string() + ": reading back the temporary file of rows failed");
  }

 private:
  TemporaryPath path_;
  std::FILE* file_;
};

}  // namespace

Compensation compensate_streaming(const std::filesystem::path& csv, const SavedFit& fit,
                                  const PipelineOptions& pipeline, const std::filesystem::path& output,
                                  OutsideRange outside) {
  Compensation c;
  std::optional<RowSpill> spill;
  if (!output.empty()) spill.emplace(output);
  c.data = prepare_data_streaming(csv, pipeline, [&](const double* rows, std::size_t count) {
    if (spill) spill->write(rows, count);
  });
  check_columns(fit.terms, c.data, pipeline.columns);
  window_models(c, fit, outside);
  if (!spill) return c;

  AtomicFile out(output);
  const std::string head = csv_head(c);
  out.stream().write(head.data(), static_cast<std::streamsize>(head.size()));
  std::string buffer(std::size_t{1} << 20, '\0');
  std::size_t used = 0;
  std::optional<CausalCompensator> causal;
  if (pipeline.derivative == DerivativeMode::causal) causal.emplace(fit, causal_settings(fit, c.data, outside));
  const AveragedSeries& s = c.data.series;
  const std::vector<double>& glitches = c.data.outliers.times_s;  // increasing
  std::size_t p = 0, g = 0;
  spill->replay([&](double t, double temp, double gyro, double temp2) {
    double model = 0.0;
    bool outlier = false;
    if (causal) {
      model = causal->update(t, temp, temp2, gyro, {}, &outlier);
    } else {
      model = model_at(s, c.window_model_dph, t, p);
      while (g < glitches.size() && glitches[g] < t) ++g;
      outlier = g < glitches.size() && glitches[g] == t;
    }
    used = static_cast<std::size_t>(write_row(buffer.data() + used, t, temp, gyro, model, outlier) - buffer.data());
    if (buffer.size() - used < kRowRoom) {
      out.stream().write(buffer.data(), static_cast<std::streamsize>(used));
      used = 0;
    }
  });
  out.stream().write(buffer.data(), static_cast<std::streamsize>(used));
  out.commit();
  return c;
}

Compensation compensate(const Measurement& m, const SavedFit& fit, const PipelineOptions& pipeline,
                        OutsideRange outside) {
  Compensation c;
  std::vector<unsigned char> valid(m.size(), 1);
  c.data.file = m.file;
  c.data.raw_samples = m.size();
  // The same checks of the units as fit's (a log in K under temp_c, rad/s read as °/h).
  c.data.units = m.units;
  c.data.cautions = measurement_cautions(m);
  if (pipeline.remove_outliers) c.data.outliers = flag_outliers(m, pipeline.outliers, valid);
  c.data.series = average_windows(m, valid, pipeline.averaging, &c.data.averaging);
  fit::derive_into(c.data, pipeline);
  check_columns(fit.terms, c.data, pipeline.columns);

  window_models(c, fit, outside);
  const AveragedSeries& s = c.data.series;

  c.time_s = m.time_s;
  c.temp_c = m.temp_c;
  c.gyro_dph = m.gyro_dph;
  c.outlier.resize(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) c.outlier[k] = valid[k] ? 0 : 1;
  c.model_dph.resize(m.size());
  if (pipeline.derivative == DerivativeMode::causal) {
    // The real-time compensator, sample by sample, with the fit's record
    // constants (this record's for fit files that lack them).
    const CausalSettings settings = causal_settings(fit, c.data, outside);
    std::vector<std::string> names;
    std::vector<const std::vector<double>*> columns;
    for (const auto& [name, values] : m.extra) {
      names.push_back(name);
      columns.push_back(&values);
    }
    CausalCompensator compensator(fit, settings, names);
    std::vector<double> extra(columns.size());
    for (std::size_t k = 0; k < m.size(); ++k) {
      for (std::size_t i = 0; i < extra.size(); ++i) extra[i] = (*columns[i])[k];
      bool glitch = false;
      c.model_dph[k] = compensator.update(m.time_s[k], m.temp_c[k], m.has_temp2() ? m.temp2_c[k] : 0.0,
                                          m.gyro_dph[k], extra, &glitch);
      c.outlier[k] = glitch ? 1 : 0;
    }
    return c;
  }
  std::size_t p = 0;  // windows are in time order
  for (std::size_t k = 0; k < m.size(); ++k) c.model_dph[k] = model_at(s, c.window_model_dph, m.time_s[k], p);
  return c;
}

void write_compensated_csv(const std::filesystem::path& file, const Compensation& c) {
  const std::string out = csv_head(c);
  std::string text(out.data(), out.size());
  std::size_t used = text.size();
  text.resize(used + c.time_s.size() * 80 + kRowRoom);
  for (std::size_t k = 0; k < c.time_s.size(); ++k) {
    if (text.size() - used < kRowRoom) text.resize(text.size() + (c.time_s.size() - k) * 80 + kRowRoom);
    char* p = write_row(text.data() + used, c.time_s[k], c.temp_c[k], c.gyro_dph[k], c.model_dph[k], c.outlier[k] != 0);
    used = static_cast<std::size_t>(p - text.data());
  }
  text.resize(used);
  write_file_atomically(file, text);
}

namespace {

// The columns' name for a channel: the channel's own, but without a unit it
// states that is not the base unit ("gyrox rad/s" -> "gyrox_dph"): the file
// holds °/h (another sensor's base unit), and a name saying rad/s would be
// read back as rad/s.
std::pair<std::string, std::string> channel_columns(const std::string& name, const SensorKind& kind) {
  const HeaderUnit stated = unit_in_header(kind.quantity, name);
  if (stated.said.empty() || (stated.unit != nullptr && stated.unit->name == base_unit(kind.quantity)))
    return {name, name};
  // The unit as the name writes it: "rad/s", or "rad_s" where the name joins with underscores.
  std::string written = stated.said;
  std::size_t at = name.rfind(written);
  if (at == std::string::npos) {
    std::replace(written.begin(), written.end(), '/', '_');
    at = name.rfind(written);
  }
  std::string base = name.substr(0, at);
  while (!base.empty() && std::string_view(" _([").find(base.back()) != std::string_view::npos) base.pop_back();
  if (base.empty()) base = std::string(kind.name);
  return {fmt::format("{}_{}", base, column_suffix(kind)), base};
}

}  // namespace

void write_compensated_csv(const std::filesystem::path& file,
                           const std::vector<std::pair<std::string, Compensation>>& channels) {
  fmt::memory_buffer out;
  const SensorKind& kind = channels.front().second.data.units.kind();
  const std::string_view suffix = column_suffix(kind);
  fmt::format_to(std::back_inserter(out),
                 "# gyrotherm compensate: NAME_compensated_{0} = NAME - NAME_model_{0}, per channel, all in {1} "
                 "(a channel named with another unit is written as its name without it, _{0})\n",
                 suffix, kind.noise[1].unit);
  fmt::format_to(std::back_inserter(out), "time_s,temp_c");
  for (const auto& [name, c] : channels) {
    const auto [raw, stem] = channel_columns(name, kind);
    fmt::format_to(std::back_inserter(out), ",{0},{1}_model_{2},{1}_compensated_{2},{1}_outlier", raw, stem, suffix);
  }
  fmt::format_to(std::back_inserter(out), "\n");
  const Compensation& first = channels.front().second;
  for (std::size_t k = 0; k < first.time_s.size(); ++k) {
    fmt::format_to(std::back_inserter(out), "{:.10g},{:.6f}", first.time_s[k], first.temp_c[k]);
    for (const auto& [name, c] : channels)
      fmt::format_to(std::back_inserter(out), ",{:.6f},{:.9f},{:.9f},{}", c.gyro_dph[k], c.model_dph[k],
                     c.gyro_dph[k] - c.model_dph[k], static_cast<int>(c.outlier[k]));
    fmt::format_to(std::back_inserter(out), "\n");
  }
  write_file_atomically(file, std::string_view(out.data(), out.size()));
}

nlohmann::ordered_json compensation_json(const Compensation& c, const SavedFit& fit,
                                         const PipelineOptions& pipeline, const std::string& data_file,
                                         const std::string& fit_file, const std::string& output) {
  nlohmann::ordered_json j;
  j["data"] = data_file;
  j["fit"] = fit_file;
  j["model"] = formula_text(fit.terms);
  j["engine"] = fit.engine;
  j["derivative"] = to_string(pipeline.derivative);
  if (const SensorKind& kind = c.data.units.kind(); !kind.is_gyro) {
    // Another sensor's: the *_dph fields in its base unit (as its fit's).
    j["sensor"] = kind.name;
    j["unit"] = kind.unit;
  }
  j["instability_before_dph"] = c.before_dph;
  j["instability_after_dph"] = c.after_dph;
  j["ratio"] = c.ratio();
  j["windows"] = c.data.series.size();
  j["outliers_removed"] = c.data.outliers.removed;
  j["cautions"] = caution_texts(c.data.cautions);  // numbers that look like another unit (as fit's data.cautions)
  if (c.fit_range_c) {
    // Where the record leaves the range the fit was made on, and what the model did there.
    j["fit_temp_range_c"] = {c.fit_range_c->first, c.fit_range_c->second};
    j["windows_outside_range"] = c.windows_outside;
    j["share_outside_range"] =
        c.data.series.size() > 0 ? static_cast<double>(c.windows_outside) / static_cast<double>(c.data.series.size()) : 0.0;
    j["outside_range"] = c.outside == OutsideRange::hold ? "held" : "extrapolated";
  }
  if (!output.empty()) j["output"] = output;
  return j;
}

}  // namespace gyrotherm::fit

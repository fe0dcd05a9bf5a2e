#include "fit/data/prepare.h"

#include "fit/data/plausibility.h"

#include <fmt/format.h>

#include "sim/util/format.h"

namespace gyrotherm::fit {

void derive_into(PreparedData& d, const PipelineOptions& options) {
  d.derived = derive(d.series, options.derivative, options.derivative_span_s, options.sensor_tau_s);
  d.derivative = options.derivative;
  d.derivative_span_s = options.derivative_span_s;
  d.sensor_tau_s = options.sensor_tau_s;
}

PreparedData prepare_data(const Measurement& m, const PipelineOptions& options) {
  PreparedData d;
  d.file = m.file;
  d.units = m.units;
  d.cautions = measurement_cautions(m);
  d.raw_samples = m.size();
  std::vector<unsigned char> valid(m.size(), 1);
  if (options.remove_outliers) d.outliers = flag_outliers(m, options.outliers, valid);
  // A window refused for numbers read in the wrong unit (a time in ms read
  // as s: samples 1000 s apart) says what looks wrong.
  d.series = with_cautions(d.cautions, [&] { return average_windows(m, valid, options.averaging, &d.averaging); });
  derive_into(d, options);
  return d;
}

PreparedData prepare_data(const std::filesystem::path& csv, const PipelineOptions& options) {
  return prepare_data(read_measurement_csv(csv, options.columns), options);
}

std::string describe_windows(const PreparedData& d, const PipelineOptions& o) {
  const std::size_t n = d.series.size();
  if (!d.averaging.bursts) return fmt::format("{} of {} s", counted(n, "window"), human(o.averaging.window_s));
  return fmt::format("{} of {} s every {} s, each averaged as one window (shorter than the {} s "
                     "window)",
                     counted(n, "burst"), human(d.averaging.median_run_s), human(d.averaging.median_spacing_s),
                     human(o.averaging.window_s));
}

std::string averages_name(const PreparedData& d, const PipelineOptions& o) {
  if (d.averaging.bursts) return "the burst means";
  return fmt::format("{} s averages", human(o.averaging.window_s));
}

}  // namespace gyrotherm::fit

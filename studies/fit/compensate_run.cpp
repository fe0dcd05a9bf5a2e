#include "studies/fit/compensate_run.h"

#include <algorithm>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "fit/channels.h"
#include "fit/model/formula.h"
#include "sim/util/input_error.h"
#include "studies/record_source.h"

namespace gyrotherm::studies {

namespace {

CompensateRun compensate_record(const CompensateRequest& o, const RecordSource& source) {
  CompensateRun run;
  run.request = o;
  run.request.data = source.name();
  run.fits = o.fits.empty() ? fit::load_fits(o.fit_file, fit::FitKinds::any) : o.fits;
  const std::vector<std::string> gyros = gyro_per_channel(o.columns.gyro, run.fits.size(), o.fit_file);
  bool streamed = false;
  std::size_t channel = 0;
  run.channels = fit::for_each_saved_fit(run.fits, [&](const fit::SavedFit& fit) {
    fit::PipelineOptions pipeline = fit::reading_columns_of(fit.pipeline, fit.terms);
    fit::ColumnMap given = o.columns;
    given.gyro = gyros[channel++];
    fit::check_given_sensor(fit, given.units.sensor);
    pipeline.columns = source.fit_columns(pipeline.columns).with(given);
    pipeline.columns.units.validate();
    if (o.causal) pipeline.derivative = fit::DerivativeMode::causal;
    // A log too large to hold, one channel: never held, the output written as
    // it is computed (fit/compensation.h).
    streamed = run.fits.size() == 1 && source.streams(pipeline);
    const fit::OutsideRange outside = o.extrapolate ? fit::OutsideRange::extrapolate : fit::OutsideRange::hold;
    fit::Compensation c = streamed ? fit::compensate_streaming(source.name(), fit, pipeline, o.output, outside)
                                   : fit::compensate(source.read(pipeline.columns), fit, pipeline, outside);
    run.channel_json.push_back(fit::compensation_json(c, fit, pipeline, source.name(), o.fit_file, o.output));
    return c;
  });
  if (!o.output.empty() && !streamed) {
    if (run.channels.size() == 1) {
      fit::write_compensated_csv(o.output, run.channels.front());
    } else {
      std::vector<std::pair<std::string, fit::Compensation>> named;
      for (std::size_t i = 0; i < run.fits.size(); ++i) named.emplace_back(run.fits[i].channel, run.channels[i]);
      fit::write_compensated_csv(o.output, named);
    }
  }
  return run;
}

}  // namespace

CompensateRun run_compensate(const CompensateRequest& request) {
  return compensate_record(request, RecordSource(request.data));
}

CompensateRun run_compensate(const CompensateRequest& request, const fit::Table& table) {
  return compensate_record(request, RecordSource(table));
}

nlohmann::ordered_json compensate_json(const CompensateRun& run) {
  if (run.fits.size() == 1) return run.channel_json.front();
  std::vector<std::pair<std::string, nlohmann::ordered_json>> all;
  for (std::size_t i = 0; i < run.fits.size(); ++i) all.emplace_back(run.fits[i].channel, run.channel_json[i]);
  return fit::channels_json(all);
}

std::string compensate_text(const CompensateRun& run) {
  std::string out;
  for (std::size_t i = 0; i < run.fits.size(); ++i) {
    const fit::SavedFit& fit = run.fits[i];
    const fit::Compensation& c = run.channels[i];
    out += fmt::format("compensate {}{} with {} ({}: B = b0 + {}, {} derivatives)\n", run.request.data,
                       run.fits.size() > 1 ? ", channel " + fit.channel : "", run.request.fit_file, fit.engine,
                       fit::formula_text(fit.terms), run.channel_json[i]["derivative"].get<std::string>());
    out += fmt::format("instability (std of {}): {:.6g} -> {:.6g} {} ({:.2f}x)\n",
                       fit::averages_name(c.data, fit.pipeline), c.before_dph, c.after_dph,
                       fit.pipeline.columns.units.kind().unit, c.ratio());
    for (const fit::UnitCaution& caution : c.data.cautions) out += "caution: " + fit::caution_text(caution) + "\n";
    if (c.windows_outside > 0 && c.fit_range_c) {
      const auto [lo, hi] = std::minmax_element(c.data.derived.temp_c.begin(), c.data.derived.temp_c.end());
      out += fmt::format(
          "caution: {} of {} windows ({:.0f} %) lie outside the temperature range the fit was made on, {:.1f}..{:.1f} "
          "°C (this record: {:.1f}..{:.1f} °C); {}\n",
          c.windows_outside, c.data.series.size(), 100.0 * static_cast<double>(c.windows_outside) / static_cast<double>(c.data.series.size()),
          c.fit_range_c->first, c.fit_range_c->second, *lo, *hi,
          c.outside == fit::OutsideRange::hold
              ? "there the model is held at the range's edge, as PX4 and ArduPilot hold it (--extrapolate evaluates it anyway)"
              : "there the model is extrapolated (--extrapolate): nothing measured supports it");
    }
  }
  if (!run.request.output.empty()) out += fmt::format("wrote {}\n", run.request.output);
  return out;
}

}  // namespace gyrotherm::studies

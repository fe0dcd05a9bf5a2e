// gyrotherm export FIT.json --format c|px4|ardupilot [--channel NAME] [--prefix P]
//                           [--axes A,B,C] [--instance N] [--device-id ID]
//                           [--drop-unsupported [--data CSV]] -o FILE
// A saved fit as an autopilot's gyro thermal compensation parameters
// (fit/firmware_export.h).

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <array>
#include <cmath>
#include <ctime>

#include "app/comma_list.h"
#include "app/commands.h"
#include "fit/c_export.h"
#include "fit/firmware_export.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/util/atomic_file.h"
#include "sim/util/input_error.h"
#include "sim/util/sha256.h"

namespace gyrotherm::app {
namespace {

struct ExportOptions {
  std::string fit_file;
  std::string format;
  std::string axes;
  std::string channel;
  std::string prefix = "gt_comp";
  int instance = -1;  // PX4 0, ArduPilot 1 unless set
  long device_id = 0;
  bool drop_unsupported = false;
  std::string data;
  std::string output;
};

std::string fit_name(const fit::SavedFit& f) { return f.channel.empty() ? f.pipeline.columns.gyro : f.channel; }

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

// With terms dropped: the instability of the fitted data with the whole
// model and with the cubic alone (the same coefficients, not refitted).
void report_dropped(const fit::SavedFit& f, const fit::CubicModel& cubic, const std::string& data_option) {
  std::filesystem::path data = data_option;
  if (data.empty()) {
    const std::filesystem::path named = f.data_file;
    if (!named.empty() && std::filesystem::exists(named)) data = named;
    else if (!named.empty() && std::filesystem::exists(f.file.parent_path() / named)) data = f.file.parent_path() / named;
    else
      throw InputError(fmt::format("--drop-unsupported: the data {} was fitted on ('{}') is not here; give it with "
                                   "--data so that export can say how much dropping {} costs",
                                   f.file.string(), f.data_file, cubic.dropped.front()));
  }
  const fit::PipelineOptions pipeline = fit::reading_columns_of(f.pipeline, f.terms);
  const fit::DroppedCost cost = fit::dropped_cost(f, cubic, fit::read_measurement_csv(data, pipeline.columns));
  std::string names;
  for (const std::string& n : cubic.dropped) names += (names.empty() ? "" : ", ") + n;
  fmt::print("{}: dropped {}: the instability on {} rises from {:.6g} to {:.6g} °/h ({:.2f}x); a polynomial refitted "
             "alone (fit --model 'T + T^2') would do better than these coefficients\n",
             fit_name(f), names, data.string(), cost.with_dph, cost.without_dph, cost.without_dph / cost.with_dph);
}

// --format c: one channel's model as a C99 real-time compensator.
int export_c(const ExportOptions& o) {
  const std::vector<fit::SavedFit> fits = fit::load_fits(o.fit_file);
  const fit::SavedFit* chosen = nullptr;
  std::string known;
  for (const fit::SavedFit& f : fits) {
    known += (known.empty() ? "" : ", ") + fit_name(f);
    if (o.channel.empty() ? fits.size() == 1 : fit_name(f) == o.channel) chosen = &f;
  }
  if (!chosen)
    throw InputError(o.channel.empty()
                         ? fmt::format("{} holds {} channels ({}); choose one with --channel", o.fit_file, fits.size(),
                                       known)
                         : fmt::format("--channel {}: not a channel of {} (its channels: {})", o.channel, o.fit_file,
                                       known));
  const fit::SavedFit& f = *chosen;
  if (!f.sample_interval_s || !f.bursts || (f.pipeline.remove_outliers && !f.outlier_floor_dph))
    throw InputError(fmt::format("{}: the fit lacks data.sample_interval_s, data.bursts or data.outlier_floor_dph "
                                 "(written by an earlier gyrotherm); fit again to export it in C",
                                 o.fit_file));
  fit::CausalSettings settings;
  settings.sample_interval_s = *f.sample_interval_s;
  settings.bursts = *f.bursts;
  settings.outlier_floor_dph = f.outlier_floor_dph.value_or(0.0);
  const fit::ExportHeader header{o.fit_file, sha256_file_hex(o.fit_file), f.engine, fit::formula_text(f.terms),
                                 utc_now()};
  write_file_atomically(o.output, fit::c_header(f, settings, o.prefix, header));
  fmt::print("wrote {}: {}_update() gives B = b0 + {} (°/h) sample by sample, as compensate --causal{}\n", o.output,
             o.prefix, fit::formula_text(f.terms),
             f.pipeline.remove_outliers ? fmt::format("; {}_update_gyro() also applies the glitch rule", o.prefix) : "");
  return 0;
}

int run_export(const ExportOptions& o) {
  if (o.format == "c") return export_c(o);
  if (o.format != "px4" && o.format != "ardupilot")
    throw InputError(fmt::format("--format {}: expected c, px4 or ardupilot", o.format));
  const std::vector<fit::SavedFit> fits = fit::load_fits(o.fit_file);

  // Which fit serves which axis.
  std::array<const fit::SavedFit*, 3> chosen{};
  if (o.axes.empty()) {
    if (fits.size() > 3)
      throw InputError(fmt::format("{} holds {} channels; choose three with --axes X,Y,Z", o.fit_file, fits.size()));
    for (std::size_t i = 0; i < fits.size(); ++i) chosen[i] = &fits[i];
  } else {
    const std::vector<std::string> names = split_commas(o.axes);
    if (names.size() != 3)
      throw InputError(fmt::format("--axes {}: expected three entries, for X, Y and Z (a channel of the fit, or - "
                                   "for an axis without compensation)",
                                   o.axes));
    for (std::size_t i = 0; i < 3; ++i) {
      if (names[i] == "-") continue;
      std::string known;
      for (const fit::SavedFit& f : fits) {
        if (fit_name(f) == names[i]) chosen[i] = &f;
        known += (known.empty() ? "" : ", ") + fit_name(f);
      }
      if (!chosen[i])
        throw InputError(fmt::format("--axes: '{}' is not a channel of {} (its channels: {})", names[i], o.fit_file,
                                     known));
    }
  }

  std::array<fit::AxisModel, 3> axes;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!chosen[i]) continue;
    const fit::SavedFit& f = *chosen[i];
    if (!f.temp_range_c)
      throw InputError(fmt::format("{}: no data.temp_range_c, the temperature range the model was fitted on (the "
                                   "file was written by an earlier gyrotherm); fit again to export it",
                                   o.fit_file));
    axes[i].present = true;
    axes[i].channel = fit_name(f);
    axes[i].model = fit::cubic_of(f, o.drop_unsupported, o.format == "px4" ? "PX4" : "ArduPilot");
    axes[i].temp_min_c = f.temp_range_c->first;
    axes[i].temp_max_c = f.temp_range_c->second;
    if (!axes[i].model.dropped.empty()) report_dropped(f, axes[i].model, o.data);
  }

  const fit::SavedFit* first = nullptr;
  for (const fit::SavedFit* f : chosen)
    if (f && !first) first = f;
  if (!first) throw InputError("--axes: every axis is '-': nothing to export");
  const fit::ExportHeader header{o.fit_file, sha256_file_hex(o.fit_file), first->engine,
                                 fit::formula_text(first->terms), utc_now()};
  const fit::ExportRange range = fit::export_range(axes);
  const std::string text = o.format == "px4"
                               ? fit::px4_parameters(axes, o.instance < 0 ? 0 : o.instance, o.device_id, header)
                               : fit::ardupilot_parameters(axes, o.instance < 0 ? 1 : o.instance, header);
  write_file_atomically(o.output, text);
  std::string used;
  for (std::size_t i = 0; i < 3; ++i)
    used += fmt::format("{}{}: {}", i ? ", " : "", "XYZ"[i], axes[i].present ? axes[i].channel : "-");
  fmt::print("wrote {}: {} gyro thermal compensation ({}); valid {:.2f} to {:.2f} °C{}\n", o.output,
             o.format == "px4" ? "PX4" : "ArduPilot", used, range.tmin_c, range.tmax_c,
             o.format == "px4" ? fmt::format(", TREF {:.2f} °C", static_cast<float>(range.tref_c)) : "");
  if (o.format == "px4" && o.device_id == 0)
    fmt::print("set TC_G{}_ID to your gyro's device id (CAL_GYRO{}_ID), or pass --device-id\n",
               o.instance < 0 ? 0 : o.instance, o.instance < 0 ? 0 : o.instance);
  return 0;
}

}  // namespace

void add_export_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand("export", "Export a saved fit as autopilot parameters (PX4, ArduPilot)");
  cmd->add_option("fit", o->fit_file, "Fit saved by 'gyrotherm fit -o'")->required();
  cmd->add_option("--format", o->format, "px4 (QGroundControl .params), ardupilot (.param), or c (a C99 header: the whole model)")
      ->required();
  cmd->add_option("--axes", o->axes,
                  "The fit's channels for the X, Y and Z axes, '-' for none (default: the channels in order)");
  cmd->add_option("--channel", o->channel, "The channel to export in C (--format c)");
  cmd->add_option("--prefix", o->prefix, "Prefix of the C names (--format c; default gt_comp)");
  cmd->add_option("--instance", o->instance, "Gyro instance: PX4's TC_G{n} (default 0), ArduPilot's INS_TCAL{n} (default 1)");
  cmd->add_option("--device-id", o->device_id, "PX4: the gyro's device id for TC_G{n}_ID (CAL_GYRO{n}_ID)");
  cmd->add_flag("--drop-unsupported", o->drop_unsupported,
                "Leave out terms the firmware cannot express, and say how much the instability rises");
  cmd->add_option("--data", o->data, "The data the fit was made on, for --drop-unsupported (default: the fit's own)");
  cmd->add_option("-o,--output", o->output, "The parameter file to write")->required();
  cmd->callback([o, run] { *run = [o] { return run_export(*o); }; });
}

}  // namespace gyrotherm::app

#include "studies/export/exporter.h"

#include <fmt/format.h>

#include <ctime>
#include <nlohmann/json.hpp>

#include "fit/model/formula.h"
#include "sim/util/atomic_file.h"
#include "sim/util/input_error.h"
#include "sim/util/sha256.h"

#include <filesystem>

namespace gyrotherm::studies {
namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

const std::vector<ExporterInfo>& exporter_registry() {
  static const std::vector<ExporterInfo> all = {
#define EXPORTER(name) name##_exporter(),
#include "studies/export/exporters.def"
#undef EXPORTER
  };
  return all;
}

std::string exporter_names(std::string_view last) {
  std::string out;
  const auto& all = exporter_registry();
  for (std::size_t k = 0; k < all.size(); ++k)
    out += std::string(k == 0 ? "" : k + 1 == all.size() ? last : ", ") + all[k].name;
  return out;
}

const ExporterInfo& find_exporter(std::string_view name) {
  for (const ExporterInfo& e : exporter_registry())
    if (e.name == name) return e;
  throw InputError(fmt::format("--format {}: expected {}", name, exporter_names()));
}

std::string channel_name(const fit::SavedFit& f) { return f.channel.empty() ? f.pipeline.columns.gyro : f.channel; }

ExportHeader export_header(const ExportRequest& r, const fit::SavedFit& f) {
  const fit::SensorKind& kind = f.pipeline.columns.units.kind();
  return {r.fit_file,  sha256_file_hex(r.fit_file), f.engine, fit::formula_text(f.terms), utc_now(), f.data_file,
          f.data_sha256, std::string(kind.noun), std::string(kind.unit)};
}

const fit::SavedFit& chosen_channel(const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
  const fit::SavedFit* chosen = nullptr;
  std::string known;
  for (const fit::SavedFit& f : fits) {
    known += (known.empty() ? "" : ", ") + channel_name(f);
    if (r.channel.empty() ? fits.size() == 1 : channel_name(f) == r.channel) chosen = &f;
  }
  if (!chosen)
    throw InputError(r.channel.empty()
                         ? fmt::format("{} holds {} channels ({}); choose one with --channel", r.fit_file, fits.size(),
                                       known)
                         : fmt::format("--channel {}: not a channel of {} (its channels: {})", r.channel, r.fit_file,
                                       known));
  return *chosen;
}

void warn_if_little_compensation(const fit::SavedFit& f, double after_dph, ExportOutput* out) {
  if (!f.instability_before_dph || !(*f.instability_before_dph > 0.0)) return;
  const double before = *f.instability_before_dph;
  if (after_dph <= kLittleCompensation * before) return;
  const fit::SensorKind& kind = f.pipeline.columns.units.kind();
  out->warnings.push_back(fmt::format(
      "{}: the exported model takes the instability of the data it was fitted on ({}) only from {:.3g} to {:.3g} "
      "{} ({:.0f} % off): it compensates little{}",
      channel_name(f), f.data_file.empty() ? std::string("unnamed") : f.data_file, before, after_dph, kind.unit,
      100.0 * (1.0 - after_dph / before),
      kind.is_gyro ? "; 'gyrotherm diagnose' on that data shows what the bias follows" : ""));
}

std::string exporter_descriptions() {
  std::string out;
  for (const ExporterInfo& e : exporter_registry()) out += fmt::format("{}{} ({})", out.empty() ? "" : ", ", e.name, e.description);
  return out;
}

std::string export_text(const ExportOutput& out) {
  std::string text;
  for (const std::string& line : out.lines) text += line + "\n";
  return text;
}

nlohmann::ordered_json export_json(const ExportRequest& request, const ExportOutput& out) {
  nlohmann::ordered_json j{{"format", request.format}, {"output", request.output}, {"lines", out.lines},
                           {"warnings", out.warnings}};
  for (const auto& [key, value] : out.json_fields) j[key] = nlohmann::ordered_json::parse(value);
  return j;
}

namespace {

// Refuses the export (InputError) when `cautions` hold any and the user did
// not --accept-caution: why, each caution, and what to do instead.
void refuse_unless_accepted(const ExportRequest& request, const std::vector<std::string>& cautions,
                            std::string_view why, std::string_view instead) {
  if (cautions.empty() || request.accept_caution) return;
  std::string list;
  for (const std::string& c : cautions) list += "\n  " + c;
  throw InputError(fmt::format("{}: {}:{}\n{}, or export anyway with --accept-caution (the cautions then go into the "
                               "file)",
                               request.fit_file, why, list, instead));
}

}  // namespace

ExportOutput run_export(const ExportRequest& request) {
  const ExporterInfo& exporter = find_exporter(request.format);
  // A file of every axis is checked and written for every axis: --channel
  // would narrow what is checked, not what is written.
  if (!request.channel.empty() && !exporter.one_channel)
    throw InputError(fmt::format("--channel {}: a {} file holds every axis (choose and order them with --axes "
                                 "X,Y,Z, '-' for none); --channel picks the one channel of a C export",
                                 request.channel, request.format));
  // Every sensor's fit: each format refuses the kinds its firmware has no
  // compensation for.
  const std::vector<fit::SavedFit> fits = fit::load_fits(request.fit_file, fit::FitKinds::any);
  // --data is the log the fit was made on (the outcome compares the two): where
  // the fit knows its data's bytes, another log is refused, not mixed in.
  if (!request.data.empty() && !fits.empty() && !fits.front().data_sha256.empty() &&
      std::filesystem::is_regular_file(request.data) && sha256_file_hex(request.data) != fits.front().data_sha256)
    throw InputError(fmt::format(
        "--data {}: not the log {} was fitted on (its SHA-256 differs from the fit's data.sha256, the bytes of {}): "
        "what the firmware achieves would mix two logs; give that log, or leave --data out to use the fit's own "
        "(to try the calibration on another log, use 'gyrotherm check')",
        request.data, request.fit_file, fits.front().data_file));
  // A fit made on de-lagged temperatures (--sensor-tau) holds for them: a
  // firmware, and the C compensator, read the sensor as it is.
  for (const fit::SavedFit& f : fits)
    if (f.pipeline.sensor_tau_s > 0.0)
      throw InputError(fmt::format(
          "{}: the fit reads its temperatures de-lagged by --sensor-tau {:g} s, which no exported form applies "
          "(firmwares and the C compensator read the sensor as it is): fit again without --sensor-tau to export",
          request.fit_file, f.pipeline.sensor_tau_s));
  // What the record could not support travels with the parameters, or stops them:
  // of the channels exported (--channel: that one).
  std::vector<fit::SavedFit> exported;
  for (const fit::SavedFit& f : fits)
    if (request.channel.empty() || channel_name(f) == request.channel) exported.push_back(f);
  std::vector<std::string> cautions;
  for (const fit::SavedFit& f : exported)
    for (const auto& [term, why] : f.support_flags)
      cautions.push_back(fmt::format("{}: {}: {}", channel_name(f), term, why));
  refuse_unless_accepted(request, cautions,
                         "the record it was fitted on cannot support these terms, so the exported parameters would "
                         "claim more than the fit showed",
                         "measure where the record has no data (a test over the whole range: 'gyrotherm plan')");
  // Numbers that looked like another unit when fitted (a temperature in K, a
  // rate in °/s read as °/h): the parameters would be wrong in the firmware.
  std::vector<std::string> units;
  for (const fit::SavedFit& f : exported)
    for (const std::string& c : f.data_cautions) units.push_back(fmt::format("{}: {}", channel_name(f), c));
  refuse_unless_accepted(request, units,
                         "the data it was fitted on look read in another unit, or moving, so the exported parameters "
                         "would be wrong in the firmware",
                         "fit again with the unit options the cautions name");
  ExportOutput out = exporter.write(request, fits);
  // Cautions of meaning (temperature locked to time) travel too, without stopping the export.
  std::vector<std::string> meaning;
  for (const fit::SavedFit& f : exported)
    for (const auto& [term, why] : f.meaning_flags) meaning.push_back(fmt::format("{}: {}: {}", channel_name(f), term, why));
  std::string top;
  if (!cautions.empty())
    top += fmt::format("{} CAUTION (exported with --accept-caution): the record the fit was made on cannot support:\n",
                       exporter.comment);
  for (const std::string& c : cautions) top += fmt::format("{}   {}\n", exporter.comment, c);
  if (!units.empty())
    top += fmt::format("{} CAUTION (exported with --accept-caution): the data the fit was made on look read in "
                       "another unit, or moving:\n",
                       exporter.comment);
  for (const std::string& c : units) top += fmt::format("{}   {}\n", exporter.comment, c);
  if (!meaning.empty())
    top += fmt::format("{} CAUTION: on the record the fit was made on, what these numbers mean is uncertain:\n",
                       exporter.comment);
  for (const std::string& c : meaning) top += fmt::format("{}   {}\n", exporter.comment, c);
  for (const auto* list : {&cautions, &units, &meaning})
    for (const std::string& c : *list) out.warnings.push_back("caution: " + c);
  out.text = top + out.text;
  write_file_atomically(request.output, out.text);
  return out;
}

}  // namespace gyrotherm::studies

#pragma once
// `gyrotherm export`: a saved fit as something a gyro's firmware loads. One
// registry entry per format, shaped like the engines' (fit/engines/engine.h):
// a name, a description and the function that writes it; each format is one
// file (defining `ExporterInfo NAME_exporter()`), one test and one line
// EXPORTER(NAME) in studies/export/exporters.def.
//
//   c          a C99 header: the whole model as the real-time compensator
//              (studies/export/c_header.h)
//   px4        PX4's TC_G* parameters, a QGroundControl .params file
//   ardupilot  ArduPilot's INS_TCAL* parameters, a .param file
//              (both: studies/export/firmware.h)
//
// run_export() loads the fit, lets the format write its text, and writes the
// file atomically only once all of it is known: a refusal leaves no file. A
// model that takes little off the instability of the data it was fitted on
// is exported with a warning (for stderr, not in the file) giving the numbers.

#include <functional>
#include <optional>

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fit/data/table.h"
#include "fit/fit_file.h"

namespace gyrotherm::studies {

// What `export` was asked (the command line's options).
struct ExportRequest {
  std::string fit_file;
  std::string format;
  std::string axes;     // firmware: the fit's channels for X, Y, Z, '-' for none
  std::string channel;  // C: the channel to export
  std::string prefix = "gt_comp";
  std::optional<int> instance;  // the firmware's gyro instance (default: its first)
  long long device_id = 0;      // PX4's TC_G{n}_ID
  std::optional<double> boot_temp_c;  // ArduPilot: the gyro offsets' boot temperature (default: the record's first)
  bool drop_unsupported = false;
  // Export even where the fit's record cannot support a term (too few
  // temperature levels, a gap, a narrow range): the cautions go into the
  // file's header, stderr and --json.
  bool accept_caution = false;
  std::string data;     // the fitted data, for the cost of dropping terms
  const fit::Table* data_table = nullptr;  // or that data as arrays (the Python package's), in place of `data`
  std::string output;
  bool json = false;    // --json: export_json on stdout instead of export_text
};

// What a format writes, and what export prints about it.
struct ExportOutput {
  std::string text;                   // the file
  std::vector<std::string> lines;     // for the terminal, in order
  std::vector<std::string> warnings;  // for stderr: the file does not hold them
  // The format's own fields for --json, (key, its value as JSON text): a
  // member of type ordered_json would need <nlohmann/json.hpp> in every file
  // that includes this one.
  std::vector<std::pair<std::string, std::string>> json_fields;
};

// An exported model that leaves more than this share of the instability of
// the data it was fitted on compensates little (under 20 % off): say so.
inline constexpr double kLittleCompensation = 0.8;
// A warning on *out when `fit`'s model, as exported (instability after_dph
// on its data: the fit's own, or with terms dropped what remains), takes
// less than 20 % off the instability before; nothing when that is unknown.
void warn_if_little_compensation(const fit::SavedFit& fit, double after_dph, ExportOutput* out);

// Where the exported file came from (the file's opening comment).
struct ExportHeader {
  std::string fit_file, fit_sha256, engine, model_text, date_utc;
  // The log the fit was made on and its bytes' SHA-256 (empty where the fit
  // does not record it): check finds that log given again by it.
  std::string data_file, data_sha256;
  // The sensor whose fit it is, and the base unit of its model: "gyro", "°/h".
  std::string sensor = "gyro", unit = "°/h";
};

struct ExporterInfo {
  std::string name;
  std::string description;  // for --help
  std::function<ExportOutput(const ExportRequest&, const std::vector<fit::SavedFit>&)> write;
  std::string comment = "#";  // how the format starts a comment line
  // One channel (--channel picks it), or every axis (--axes orders them).
  bool one_channel = false;
};

const std::vector<ExporterInfo>& exporter_registry();
// Throws InputError listing the known formats.
const ExporterInfo& find_exporter(std::string_view name);
// "c, px4 or ardupilot"
std::string exporter_names(std::string_view last = " or ");
// "c (a C99 header …), px4 (…), ardupilot (…)", for --help.
std::string exporter_descriptions();

// Loads the fit, writes request.output with the chosen format, returns what
// to print (lines, warnings). Throws InputError (no file written) on bad input,
// and where the fit's record cannot support a term of it (SavedFit::
// support_flags) unless request.accept_caution: then each caution is a
// comment line at the file's top and a warning.
ExportOutput run_export(const ExportRequest& request);
// What export prints: its lines, one a line.
std::string export_text(const ExportOutput& out);
// export --json: format, output, lines, warnings and the format's own fields.
nlohmann::ordered_json export_json(const ExportRequest& request, const ExportOutput& out);

// Shared by the formats: a fit's channel name, the header of the file
// exported from `fit` (its SHA-256 and the time now), and the fit a
// single-channel format exports (--channel, or the only one).
std::string channel_name(const fit::SavedFit& fit);
ExportHeader export_header(const ExportRequest& request, const fit::SavedFit& fit);
const fit::SavedFit& chosen_channel(const ExportRequest& request, const std::vector<fit::SavedFit>& fits);

// The registry entries, one function per format file.
#define EXPORTER(name) ExporterInfo name##_exporter();
#include "studies/export/exporters.def"
#undef EXPORTER

}  // namespace gyrotherm::studies

// The reading options' arithmetic (fit/data/measurement.h): Units — how the
// numbers of the needed columns become s, °C and °/h, and how that is said —
// and ColumnMap's merging of option sets.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "fit/data/autopilot_log.h"
#include "fit/data/column_role.h"
#include "fit/data/csv_dialect.h"
#include "fit/data/header_units.h"
#include "fit/data/sensor_kind.h"
#include "fit/data/measurement.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

namespace {

void check_scale(const char* option, double value, bool zero_allowed) {
  if (!std::isfinite(value) || (!zero_allowed && value == 0.0))
    throw InputError(fmt::format("{} {}: must be a finite number{}", option, value,
                                 zero_allowed ? "" : " other than 0"));
}

}  // namespace

namespace {
const Unit& unit_or_base(Quantity q, const std::string& name, std::string_view option) {
  return find_unit(q, name.empty() ? base_unit(q) : std::string_view(name), option);
}
}  // namespace

const Unit& Units::time_unit() const { return unit_or_base(Quantity::time, time, "--time-unit"); }
const SensorKind& Units::kind() const { return sensor_kind(sensor); }
const Unit& Units::gyro_unit() const { return unit_or_base(kind().quantity, gyro, "--gyro-unit"); }
const Unit& Units::temp_unit() const { return unit_or_base(Quantity::temperature, temp, "--temp-unit"); }

namespace {

// The names in a CSV's header line (after its '#' comments and blank
// lines), or none when the file cannot be read so far: the reader then says
// why.
std::vector<std::string> csv_column_names(const std::filesystem::path& file, const CsvDialect& csv) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  for (int lines = 0; lines < 1000 && std::getline(in, line); ++lines) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty() || line.front() == '#') continue;
    try {
      std::vector<std::string_view> fields;
      if (!split_fields(line, csv.delimiter_for(line), fields).empty()) return {};
      std::vector<std::string> names;
      for (const std::string_view f : fields) names.push_back(std::string(trim(unquote_field(f))));
      return names;
    } catch (const InputError&) {
      return {};
    }
  }
  return {};
}

// The axis a column's name states: one of its words is x, y or z.
char axis_of(std::string_view name) {
  char axis = 0;
  for (const std::string& w : column_words(name))
    if (w == "x" || w == "y" || w == "z") axis = axis == 0 ? w[0] : '?';
  return axis;
}

// The kind's measured column(s) in `names`, by role: the columns whose words
// name the kind or whose name states one of its units, less the other roles'
// and a model's, truth's or compensation's (model_mps2, accel_x_true_mps2):
// the one such column, or three with the axes x, y and z ("x,y,z" in that
// order); "" when they are none or ambiguous.
std::string by_role(const std::vector<std::string>& names, const ColumnMap& columns, const SensorKind& kind) {
  std::vector<std::string> found;
  for (const std::string& n : names) {
    if (n == columns.time || n == columns.temp || n == columns.temp2) continue;
    if (role_by_name(n) == ColumnRole::derived) continue;
    if (names_sensor(n, kind) || unit_in_header(kind.quantity, n).unit != nullptr) found.push_back(n);
  }
  if (found.size() == 1) return found.front();
  if (found.size() != 3) return {};
  std::string axes[3];
  for (const std::string& n : found)
    if (const char a = axis_of(n); a >= 'x' && a <= 'z' && axes[a - 'x'].empty()) axes[a - 'x'] = n;
  if (axes[0].empty() || axes[1].empty() || axes[2].empty()) return {};
  return axes[0] + "," + axes[1] + "," + axes[2];
}

}  // namespace

ColumnMap columns_for(const std::filesystem::path& file, ColumnMap columns) {
  const bool log = log_format_of(file) != nullptr;
  if (columns.gyro != ColumnMap{}.gyro) return columns;
  const SensorKind& kind = columns.units.kind();
  columns.gyro = std::string(log ? kind.log_columns : kind.column);
  if (log) return columns;
  const std::vector<std::string> names = csv_column_names(file, columns.csv);
  if (names.empty() || std::find(names.begin(), names.end(), columns.gyro) != names.end()) return columns;
  // The default written otherwise (GYRO_DPH, Gyro-DPH): the reader's "did you mean" says which.
  for (const std::string& n : names)
    if (folded_name(n) == folded_name(columns.gyro)) return columns;
  if (std::string chosen = by_role(names, columns, kind); !chosen.empty()) columns.gyro = std::move(chosen);
  return columns;
}

ColumnMap ColumnMap::unset() {
  ColumnMap c;
  c.time = c.temp = c.gyro = c.temp2 = "";
  c.units.gyro_scale = c.units.temp_scale = c.units.temp_offset = c.csv.rate_hz = std::nan("");
  return c;
}

ColumnMap ColumnMap::with(const ColumnMap& given) const {
  ColumnMap c = *this;
  for (auto [mine, theirs] : {std::pair{&c.time, &given.time}, {&c.temp, &given.temp}, {&c.gyro, &given.gyro},
                              {&c.temp2, &given.temp2}, {&c.units.time, &given.units.time},
                              {&c.units.gyro, &given.units.gyro}, {&c.units.temp, &given.units.temp},
                              {&c.units.sensor, &given.units.sensor}})
    if (!theirs->empty()) *mine = *theirs;
  // A unit given anew comes from the option, not from where this map had it.
  if (!given.units.time.empty()) c.units.time_from.clear(), c.units.time_weak = false;
  if (!given.units.gyro.empty()) c.units.gyro_from.clear(), c.units.gyro_weak = false;
  if (!given.units.temp.empty()) c.units.temp_from.clear(), c.units.temp_weak = false;
  for (auto [mine, theirs] : {std::pair{&c.units.gyro_scale, given.units.gyro_scale},
                              {&c.units.temp_scale, given.units.temp_scale},
                              {&c.units.temp_offset, given.units.temp_offset}, {&c.csv.rate_hz, given.csv.rate_hz}})
    if (!std::isnan(theirs)) *mine = theirs;
  if (!given.csv.delimiter.empty()) c.csv.delimiter = given.csv.delimiter;
  if (given.imu) c.imu = given.imu;
  c.csv.decimal_comma = c.csv.decimal_comma || given.csv.decimal_comma;
  return c;
}

std::string Units::used() const {
  auto one = [](std::string_view what, const Unit& u, const std::string& from) {
    return fmt::format("{} {}{}", what, u.name, from.empty() ? std::string() : " (" + from + ")");
  };
  return one("time", time_unit(), time_from) + ", " + one(kind().name, gyro_unit(), gyro_from) + ", " +
         one("temperature", temp_unit(), temp_from) + (layout.empty() ? "" : "; " + layout);
}

namespace {
constexpr std::string_view kFromFitFile = "the fit file ", kFromFitInMemory = "the fit given in memory";
}

void Units::set_from_fit(const std::string& file) {
  const std::string fit = file == kFitInMemory ? std::string(kFromFitInMemory) : std::string(kFromFitFile) + file;
  for (std::string* from : {&time_from, &gyro_from, &temp_from}) *from = fit + *from;
}

bool Units::from_fit() const { return gyro_from.starts_with(kFromFitFile) || gyro_from.starts_with(kFromFitInMemory); }

void Units::validate() const {
  // A unit of another sensor kind (--gyro-unit mps2 for a gyro): said so.
  if (!gyro.empty())
    for (const SensorKind& other : sensor_kinds())
      for (const Unit& u : unit_table())
        if (&other != &kind() && u.quantity == other.quantity && u.name == gyro)
          throw InputError(fmt::format("--gyro-unit {}: {}, a unit of the {}, but the column is read as the {}'s "
                                       "(--sensor {}); give --sensor {}, or one of {}",
                                       gyro, u.meaning, other.noun, kind().noun, kind().name, other.name,
                                       unit_names(kind().quantity, " or ")));
  time_unit();
  gyro_unit();
  temp_unit();
  check_scale("--gyro-scale", gyro_scale, false);
  check_scale("--temp-scale", temp_scale, false);
  check_scale("--temp-offset", temp_offset, true);
}

bool Units::identity() const {
  return time_unit().is_base() && gyro_unit().is_base() && temp_unit().is_base() && gyro_scale == 1.0 &&
         temp_scale == 1.0 && temp_offset == 0.0;
}

double Units::time_s(double t) const { return time_unit().to_base(t); }

double Units::gyro_dph(double g) const { return gyro_scale * g * gyro_unit().factor; }

double Units::temp_c(double x) const {
  // Untouched unless asked (so that −0.0 stays −0.0, as written).
  const double v = temp_scale == 1.0 && temp_offset == 0.0 ? x : temp_scale * x + temp_offset;
  const Unit& unit = temp_unit();
  return unit.is_base() ? v : unit.to_base(v);
}

std::string Units::description() const {
  if (identity()) return "none";
  std::vector<std::string> parts;
  if (!time_unit().is_base()) parts.push_back(fmt::format("time {} → s (× {:g})", time_unit().name, time_unit().factor));
  if (!gyro_unit().is_base() || gyro_scale != 1.0)
    parts.push_back(fmt::format("{} {}{} → {} (× {:.9g})", kind().name,
                                gyro_scale != 1.0 ? fmt::format("{:g} × ", gyro_scale) : "", gyro_unit().name,
                                kind().unit, gyro_scale * gyro_unit().factor));
  if (!temp_unit().is_base() || temp_scale != 1.0 || temp_offset != 0.0) {
    std::string raw = temp_scale != 1.0 ? fmt::format("{:g} × column", temp_scale) : "column";
    if (temp_offset != 0.0) raw += fmt::format(" {} {:g}", temp_offset < 0 ? "−" : "+", std::abs(temp_offset));
    parts.push_back(fmt::format("temp {}{} → °C", raw, !temp_unit().is_base() ? " in " + std::string(temp_unit().name) : std::string()));
  }
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

}  // namespace gyrotherm::fit

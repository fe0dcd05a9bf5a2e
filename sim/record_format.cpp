#include "sim/record_format.h"

#include <fmt/format.h>

#include <cctype>

#include "sim/output.h"
#include "sim/simulator.h"
#include "sim/util/input_error.h"

namespace gyrotherm::sim {
namespace {

void no_check(const GyroConfig&, const std::filesystem::path&) {}

// clang-format off
const RecordFormat kFormats[] = {
    {".ulg", "PX4 ULog", &check_ulog_channels, &ulog_record},
    {".bin", "ArduPilot DataFlash log", &check_dataflash_channels, &dataflash_record},
    {"", "CSV", &no_check, &simulation_csv},
};
// clang-format on

}  // namespace

const RecordFormat& record_format_for(const std::filesystem::path& output) {
  std::string extension = output.extension().string();  // .ULG as .ulg
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const RecordFormat& f : kFormats)
    if (f.extension == extension) return f;
  return kFormats[std::size(kFormats) - 1];
}

int channel_index(const GyroConfig& gyro, std::string_view kind, char axis) {
  if (kind == "gyro" && axis == 'x') return -2;
  for (std::size_t i = 0; i < gyro.channels.size(); ++i)
    if (gyro.channels[i].kind->name == kind && (!gyro.channels[i].kind->has_axes || gyro.channels[i].axis == axis))
      return static_cast<int>(i);
  return -1;
}

const std::vector<double>& channel_values(const GyroConfig& gyro, const SimulationResult& r, std::string_view kind,
                                          char axis) {
  const int i = channel_index(gyro, kind, axis);
  return i == -2 ? r.gyro_dph : r.channels.at(static_cast<std::size_t>(i)).value;
}

void require_axes(const GyroConfig& gyro, const std::filesystem::path& gyro_file, std::string_view kind,
                  std::string_view what) {
  std::string missing;
  for (const char axis : {'x', 'y', 'z'})
    if (channel_index(gyro, kind, axis) == -1) missing += fmt::format("{}{} {}", missing.empty() ? "" : ", ", kind, axis);
  if (!missing.empty())
    throw InputError(fmt::format("{}: {} holds the {}'s axes x, y and z, and the gyro file simulates no {}; add a "
                                 "[[channel]] for each (sensor = \"{}\", axis = ...), or write a .csv",
                                 gyro_file.string(), what, kind, missing, kind));
}

}  // namespace gyrotherm::sim

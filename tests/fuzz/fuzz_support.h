#pragma once
// Shared by the libFuzzer targets: the loaders read files, so each input is
// written to a file on a RAM-backed folder (/dev/shm when present) first. Any
// InputError is the expected answer to bad input; anything else escaping
// (another exception, a crash, a sanitizer report) is a bug.

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fit/data/autopilot_log.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fuzz {

inline std::filesystem::path scratch_file(const char* name) {
  const std::filesystem::path dir =
      std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
  return dir / (std::string("gyrotherm_fuzz_") + std::to_string(::getpid()) + "_" + name);
}

inline void write_input(const std::filesystem::path& file, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
}

// The body of an autopilot log reader's target (fit/data/autopilot_log.h;
// `read` is fit::read_ulog or fit::read_dataflash): the input as a file is
// sorted by autopilot_log_format and read for every sensor kind; a file it
// reads must give, for each instance it lists, exactly that many samples to
// a sink (a difference traps), and a description.
template <class Reader>
int read_autopilot_log(const std::filesystem::path& file, Reader read, const std::uint8_t* data, std::size_t size) {
  write_input(file, data, size);
  (void)fit::autopilot_log_format(file);
  for (const fit::SensorKind& kind : fit::sensor_kinds()) {
    try {
      const auto contents = read(file, -1, {}, kind);
      (void)contents.describe();
      for (const auto& sensor : contents.sensors) {
        std::size_t samples = 0;
        read(file, sensor.instance, [&](double, double, double, double, double) { ++samples; }, kind);
        if (samples != sensor.samples) __builtin_trap();
      }
    } catch (const InputError&) {
    }
  }
  return 0;
}

}  // namespace gyrotherm::fuzz

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

}  // namespace gyrotherm::fuzz

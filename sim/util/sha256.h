#pragma once
// SHA-256 (FIPS 180-4), used to fingerprint the scenario, rig and gyro files a
// simulation was made from (the truth JSON records them).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace gyrotherm {

// Lower-case hex digest of a byte string.
std::string sha256_hex(std::string_view bytes);
// Digest of a file's contents; throws InputError if it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& file);

}  // namespace gyrotherm

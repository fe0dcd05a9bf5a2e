#pragma once
// SHA-256 fingerprints of the scenario, rig and gyro files a simulation or a
// campaign was made from (the truth JSON and the scoreboard record them),
// computed by OpenSSL's libcrypto (EVP_Digest with EVP_sha256).

#include <filesystem>
#include <string>
#include <string_view>

namespace gyrotherm {

// Lower-case hex digest of a byte string.
std::string sha256_hex(std::string_view bytes);
// Digest of a file's contents; throws InputError if it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& file);
// Base64 (RFC 4648, with padding) of a byte string, by libcrypto's
// EVP_EncodeBlock: a figure embedded in a self-contained HTML page.
std::string base64(std::string_view bytes);

}  // namespace gyrotherm

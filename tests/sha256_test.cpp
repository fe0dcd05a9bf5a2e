// FIPS 180-4 / NIST CAVP example vectors through the libcrypto wrapper.
#include "sim/util/sha256.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sim/util/input_error.h"

namespace gyrotherm {
namespace {

TEST(Sha256, NistVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, PaddingBoundaries) {
  // 55, 56 and 64 bytes straddle the one-block/two-block padding boundary.
  EXPECT_EQ(sha256_hex(std::string(55, 'a')),
            "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(sha256_hex(std::string(56, 'a')),
            "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
  EXPECT_EQ(sha256_hex(std::string(64, 'a')),
            "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

// A file is hashed in 1 MB blocks: across block boundaries (and empty) it is
// the digest of its bytes at once; a file that is not there is bad input.
TEST(Sha256, AFileIsHashedBlockByBlockAsItsBytes) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("gyrotherm_sha256_" + std::to_string(::getpid()) + ".bin");
  for (const std::size_t size : {std::size_t{0}, std::size_t{1} << 20, (std::size_t{5} << 19) + 7}) {
    std::string bytes(size, '\0');
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>((i * 131) % 251);
    std::ofstream(file, std::ios::binary) << bytes;
    EXPECT_EQ(sha256_file_hex(file), sha256_hex(bytes)) << size;
  }
  std::filesystem::remove(file);
  EXPECT_THROW(sha256_file_hex(file), InputError);
}

}  // namespace
}  // namespace gyrotherm

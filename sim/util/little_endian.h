#pragma once
// Packed little-endian fields, byte by byte whatever the machine's order:
// what the binary log writers (sim/record_format.h) and the tests' log
// writers build their messages from.

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace gyrotherm {

class Packer {
 public:
  template <class T>
  Packer& put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    using U = std::conditional_t<sizeof(T) == 1, std::uint8_t,
                                 std::conditional_t<sizeof(T) == 2, std::uint16_t,
                                                    std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    const auto u = std::bit_cast<U>(value);
    for (std::size_t i = 0; i < sizeof(T); ++i)
      bytes_ += static_cast<char>((static_cast<std::uint64_t>(u) >> (8 * i)) & 0xff);
    return *this;
  }
  // A fixed-size char field, NUL-filled.
  Packer& text(std::string_view s, std::size_t size) {
    if (s.size() > size) throw std::logic_error("text longer than its field");
    bytes_ += s;
    bytes_.append(size - s.size(), '\0');
    return *this;
  }
  Packer& raw(std::string_view s) {
    bytes_ += s;
    return *this;
  }
  Packer& zeros(std::size_t n) {
    bytes_.append(n, '\0');
    return *this;
  }
  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

}  // namespace gyrotherm

#pragma once
// Writers of small binary flight logs for the reader tests
// (fit/data/autopilot_log.h), from the published formats rather than from
// the readers: PX4 ULog (PX4-Autopilot docs/en/dev_log/ulog_file_format.md)
// and ArduPilot DataFlash (libraries/AP_Logger/LogStructure.h). Every number
// is written little-endian byte by byte.

#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include "sim/util/little_endian.h"

namespace gyrotherm::testing {

using gyrotherm::Packer;  // sim/util/little_endian.h

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error("cannot write " + path.string());
  std::fwrite(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
}

// What the two writers share: the bytes written so far.
template <class Writer>
class LogWriter {
 public:
  // Bytes as they are, outside any message (a message cut short, garbage).
  Writer& raw(const std::string& bytes) {
    out_.raw(bytes);
    return static_cast<Writer&>(*this);
  }
  const std::string& bytes() const { return out_.bytes(); }
  std::size_t size() const { return out_.bytes().size(); }
  void save(const std::filesystem::path& path) const { write_bytes(path, bytes()); }

 protected:
  Packer out_;
};

// ULog: the 16-byte header, then messages {uint16 size, uint8 type, payload}.
class ULogWriter : public LogWriter<ULogWriter> {
 public:
  explicit ULogWriter(std::uint8_t version = 1, std::uint64_t start_us = 1000) {
    out_.raw("ULog").put<std::uint8_t>(0x01).put<std::uint8_t>(0x12).put<std::uint8_t>(0x35);
    out_.put(version).put(start_us);
  }
  ULogWriter& message(char type, const std::string& payload) {
    if (payload.size() > 0xffff) throw std::logic_error("ULog message too long");
    out_.put(static_cast<std::uint16_t>(payload.size())).put(static_cast<std::uint8_t>(type)).raw(payload);
    return *this;
  }
  // 'B': compat_flags[8], incompat_flags[8], appended_offsets[3].
  ULogWriter& flag_bits(std::uint8_t incompat0 = 0, std::uint64_t appended0 = 0, std::uint8_t incompat1 = 0) {
    Packer p;
    p.zeros(8).put(incompat0).put(incompat1).zeros(6).put(appended0).put<std::uint64_t>(0).put<std::uint64_t>(0);
    return message('B', p.bytes());
  }
  ULogWriter& format(const std::string& definition) { return message('F', definition); }
  ULogWriter& info(const std::string& key, const std::string& value) {
    Packer p;
    p.put(static_cast<std::uint8_t>(key.size())).raw(key).raw(value);
    return message('I', p.bytes());
  }
  ULogWriter& parameter(const std::string& name, float value) {
    const std::string key = "float " + name;
    Packer p;
    p.put(static_cast<std::uint8_t>(key.size())).raw(key).put(value);
    return message('P', p.bytes());
  }
  ULogWriter& subscribe(std::uint8_t multi_id, std::uint16_t msg_id, const std::string& name) {
    Packer p;
    p.put(multi_id).put(msg_id).raw(name);
    return message('A', p.bytes());
  }
  ULogWriter& data(std::uint16_t msg_id, const Packer& fields) {
    Packer p;
    p.put(msg_id).raw(fields.bytes());
    return message('D', p.bytes());
  }
  ULogWriter& logging(const std::string& text, std::uint64_t time_us) {
    Packer p;
    p.put<std::uint8_t>('6').put(time_us).raw(text);
    return message('L', p.bytes());
  }
  ULogWriter& sync() {
    Packer p;
    for (const int b : {0x2F, 0x73, 0x13, 0x20, 0x25, 0x0C, 0xBB, 0x12}) p.put(static_cast<std::uint8_t>(b));
    return message('S', p.bytes());
  }
  ULogWriter& dropout(std::uint16_t ms) { return message('O', Packer().put(ms).bytes()); }
};

// DataFlash: messages A3 95 type payload; FMT (type 128) defines the others.
class DataFlashWriter : public LogWriter<DataFlashWriter> {
 public:
  DataFlashWriter() { fmt(128, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns"); }

  // The whole message's length from the format characters' sizes.
  static std::size_t length_of(std::string_view format) {
    std::size_t n = 3;
    for (const char c : format) {
      switch (c) {
        case 'b':
        case 'B':
        case 'M':
          n += 1;
          break;
        case 'h':
        case 'H':
        case 'c':
        case 'C':
        case 'g':
          n += 2;
          break;
        case 'i':
        case 'I':
        case 'f':
        case 'e':
        case 'E':
        case 'L':
        case 'n':
          n += 4;
          break;
        case 'd':
        case 'q':
        case 'Q':
          n += 8;
          break;
        case 'N':
          n += 16;
          break;
        case 'Z':
        case 'a':
          n += 64;
          break;
        default:
          throw std::logic_error(std::string("no size for format character ") + c);
      }
    }
    return n;
  }
  DataFlashWriter& fmt(std::uint8_t type, std::string_view name, std::string_view format, std::string_view labels,
                       std::size_t length = 0) {
    Packer p;
    p.put(type).put(static_cast<std::uint8_t>(length != 0 ? length : length_of(format)));
    p.text(name, 4).text(format, 16).text(labels, 64);
    return message(128, p.bytes());
  }
  DataFlashWriter& message(std::uint8_t type, const std::string& payload) {
    out_.put<std::uint8_t>(0xA3).put<std::uint8_t>(0x95).put(type).raw(payload);
    return *this;
  }
};

}  // namespace gyrotherm::testing

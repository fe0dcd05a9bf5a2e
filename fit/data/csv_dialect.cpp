#include "fit/data/csv_dialect.h"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <system_error>

#include "fit/data/measurement.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

namespace {

struct Delimiter {
  const char* name;
  char character;
};
constexpr std::array<Delimiter, 3> kDelimiters = {{{"comma", ','}, {"semicolon", ';'}, {"tab", '\t'}}};

// Numbers eight bytes at a time (SWAR, where eight remain in the field's
// line): the bytes that are not digits are marked, and the leading digits
// combined in three multiplications (D. Lemire's fast_float,
// parse_eight_digits_unrolled). Little-endian: p[0] is the lowest byte.
constexpr std::uint64_t kOnes = 0x0101010101010101ull;
constexpr bool kSwar = std::endian::native == std::endian::little;

std::uint64_t load8(const char* p) {
  std::uint64_t w = 0;
  std::memcpy(&w, p, 8);
  return w;
}

// How many of w's bytes, from the first, are digits. A byte is one when its
// high nibble is 3 and stays 3 with 6 added (a carry out of a byte ≥ 0xFA
// only follows a non-digit, so the count is exact).
int leading_digits(std::uint64_t w) {
  const std::uint64_t high = 0xF0 * kOnes, threes = 0x30 * kOnes;
  const std::uint64_t not_digit = ((w & high) ^ threes) | (((w + 0x06 * kOnes) & high) ^ threes);
  return not_digit == 0 ? 8 : std::countr_zero(not_digit) / 8;
}

// The number the first k (1 to 8) bytes of w write, all digits.
std::uint32_t digits_value(std::uint64_t w, int k) {
  std::uint64_t v = (w - 0x30 * kOnes) << (8 * (8 - k));  // the k digits in the top bytes, zeros before them
  v = v * 10 + (v >> 8);
  v = (((v & 0x000000FF000000FFull) * 0x000F424000000064ull) +
       (((v >> 16) & 0x000000FF000000FFull) * 0x0000271000000001ull)) >> 32;
  return static_cast<std::uint32_t>(v);
}

// The digits from p on, at most to end, appended to `mantissa` (which wraps
// beyond 19 digits: the caller refuses those); returns where they stop.
[[gnu::always_inline]] inline const char* digit_run(const char* p, const char* const end, std::uint64_t& mantissa) {
  static constexpr std::array<std::uint64_t, 9> kScale = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
  if constexpr (kSwar) {
    while (end - p >= 8) {
      const std::uint64_t w = load8(p);
      const int k = leading_digits(w);
      if (k == 0) return p;
      mantissa = mantissa * kScale[static_cast<std::size_t>(k)] + digits_value(w, k);
      p += k;
      if (k < 8) return p;
    }
  }
  for (; p != end && static_cast<unsigned>(*p - '0') < 10u; ++p) mantissa = 10 * mantissa + static_cast<unsigned>(*p - '0');
  return p;
}

// The usual number, digits[<point>digits] of at most 7 digits in all, in one
// word: the point taken out by a second load one byte on. False (p as it was)
// for anything else.
[[gnu::always_inline]] inline bool short_decimal(const char*& p, const char* const end, char point,
                                                 std::uint64_t& mantissa, std::ptrdiff_t& whole,
                                                 std::ptrdiff_t& fraction) {
  if (!kSwar || end - p < 9) return false;
  const std::uint64_t w = load8(p);
  const int k1 = leading_digits(w);
  if (k1 == 0 || k1 == 8) return false;
  if (p[k1] != point) {  // digits alone
    mantissa = digits_value(w, k1);
    whole = k1;
    fraction = 0;
    p += k1;
    return true;
  }
  const std::uint64_t before = (std::uint64_t{1} << (8 * k1)) - 1;
  const std::uint64_t joined = (w & before) | (load8(p + 1) & ~before);  // without the point
  const int k = leading_digits(joined);
  if (k == k1 || k == 8) return false;  // no digit after the point, or perhaps more than 8 digits
  mantissa = digits_value(joined, k);
  whole = k1;
  fraction = k - k1;
  p += k + 1;
  return true;
}

// Clinger's fast path: a plain decimal [-]digits[<point>digits][e[±]digits]
// with a mantissa m of at most 19 digits and below 2⁵³, and a power of ten p
// (the exponent less the fraction's digits) with |p| ≤ 22, is m · 10^p or
// m / 10^−p of two exact doubles, so the one IEEE operation is correctly
// rounded: the value std::from_chars gives. Reads it from p on and returns
// where it stops (the first character that cannot continue it), or nullptr
// for anything else (left to from_chars). Reference: W. D. Clinger, "How to
// read floating point numbers accurately", PLDI 1990.
[[gnu::always_inline]] inline const char* plain_decimal_prefix(const char* p, const char* const end, char point,
                                                              double& value) {
  static constexpr std::array<double, 23> kPow10 = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                    1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                    1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const auto digit = [&] { return p != end && static_cast<unsigned>(*p - '0') < 10u; };
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  std::uint64_t mantissa = 0;
  std::ptrdiff_t whole = 0, fraction = 0;
  if (!short_decimal(p, end, point, mantissa, whole, fraction)) {
    const char* const digits = p;
    p = digit_run(p, end, mantissa);
    whole = p - digits;
    if (p != end && *p == point) {
      const char* const first = ++p;
      p = digit_run(p, end, mantissa);
      fraction = p - first;
      if (fraction == 0) return nullptr;
    }
  }
  if (whole == 0 || whole + fraction > 19 || mantissa > (std::uint64_t{1} << 53)) return nullptr;
  std::ptrdiff_t power = -fraction;
  if (p != end && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool down = p != end && *p == '-';
    if (p != end && (*p == '-' || *p == '+')) ++p;
    const char* const first = p;
    std::ptrdiff_t exponent = 0;
    for (; digit() && p - first < 4; ++p) exponent = 10 * exponent + (*p - '0');
    if (p == first || digit()) return nullptr;  // no digits, or more than 4
    power += down ? -exponent : exponent;
  }
  if (power < -22 || power > 22) return nullptr;
  const double m = static_cast<double>(mantissa);
  const double v = power >= 0 ? m * kPow10[static_cast<std::size_t>(power)] : m / kPow10[static_cast<std::size_t>(-power)];
  value = negative ? -v : v;
  return p;
}

// The whole of `text` as a plain decimal with a '.' (above).
bool parse_plain_decimal(std::string_view text, double& value) {
  const char* const end = text.data() + text.size();
  double read = 0.0;
  if (plain_decimal_prefix(text.data(), end, '.', read) != end) return false;
  value = read;
  return true;
}

// The general case: from_chars, after a leading '+' (which it does not take).
std::string parse_general(std::string_view text, std::string_view as_written, double& value) {
  if (text.empty()) return "empty field, expected a number";
  std::string_view digits = text;
  if (digits.size() > 1 && digits.front() == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
  const char* last = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), last, value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range)
    return fmt::format("{} is out of the range of a double", shown_field(as_written));
  if (ec != std::errc() || ptr != last) return fmt::format("{} is not a number", shown_field(as_written));
  if (!std::isfinite(value)) return fmt::format("{} is not a finite number", shown_field(as_written));
  return {};
}

// Reads `count` digits at text[at] into value; false if any is not a digit.
bool digits_at(std::string_view text, std::size_t at, std::size_t count, int& value) {
  if (at + count > text.size()) return false;
  value = 0;
  for (std::size_t k = at; k < at + count; ++k) {
    if (static_cast<unsigned>(text[k] - '0') >= 10u) return false;
    value = 10 * value + (text[k] - '0');
  }
  return true;
}

}  // namespace

void CsvDialect::validate() const {
  if (!delimiter.empty() && delimiter != "auto") {
    bool known = false;
    for (const Delimiter& d : kDelimiters)
      known = known || delimiter == d.name || delimiter == std::string(1, d.character) ||
              (d.character == '\t' && delimiter == "\\t");
    if (!known)
      throw InputError(fmt::format("--delimiter '{}': expected comma, semicolon, tab or auto", delimiter));
  }
  if (!std::isfinite(rate_hz) || rate_hz < 0.0)
    throw InputError(fmt::format("--rate {}: expected the sample rate in Hz, a number > 0", rate_hz));
}

char CsvDialect::delimiter_for(std::string_view header) const {
  char chosen = ',';
  if (delimiter.empty() || delimiter == "auto") {
    std::array<std::size_t, kDelimiters.size()> count{};
    bool quoted = false;
    for (const char c : header) {
      if (c == '"') quoted = !quoted;
      for (std::size_t k = 0; k < kDelimiters.size(); ++k)
        if (!quoted && c == kDelimiters[k].character) ++count[k];
    }
    std::size_t best = 0;
    for (std::size_t k = 1; k < kDelimiters.size(); ++k)
      if (count[k] > count[best]) best = k;
    chosen = kDelimiters[best].character;
  } else {
    for (const Delimiter& d : kDelimiters)
      if (delimiter == d.name || delimiter == std::string(1, d.character) ||
          (d.character == '\t' && delimiter == "\\t"))
        chosen = d.character;
  }
  // Decimal commas in a comma-separated file: each such number in RFC 4180
  // quotes ("20,5"), which the rows' reader requires there.
  return chosen;
}

std::string CsvDialect::describe(char d) const {
  std::string out = d == ',' ? "" : fmt::format("{}-separated", delimiter_name(d));
  if (decimal_comma) out += out.empty() ? "decimal comma" : ", decimal comma";
  return out;
}

std::string_view delimiter_name(char delimiter) {
  for (const Delimiter& d : kDelimiters)
    if (d.character == delimiter) return d.name;
  return "delimiter";
}

std::string split_fields(std::string_view line, char delimiter, std::vector<std::string_view>& fields) {
  fields.clear();
  const char* p = line.data();
  const char* const end = p + line.size();
  if (std::memchr(p, '"', line.size()) == nullptr) {  // the common case: no quotes
    for (;;) {
      const auto* d = static_cast<const char*>(std::memchr(p, delimiter, static_cast<std::size_t>(end - p)));
      fields.emplace_back(p, static_cast<std::size_t>((d != nullptr ? d : end) - p));
      if (d == nullptr) return {};
      p = d + 1;
    }
  }
  const char* start = p;
  bool quoted = false;
  for (; p != end; ++p) {
    if (*p == '"') quoted = !quoted;  // "" inside quotes toggles twice: stays quoted
    else if (*p == delimiter && !quoted) {
      fields.emplace_back(start, static_cast<std::size_t>(p - start));
      start = p + 1;
    }
  }
  if (quoted)
    return fmt::format("field {} opens a quote that the line does not close (a field spanning lines is "
                       "not read)",
                       fields.size() + 1);
  fields.emplace_back(start, static_cast<std::size_t>(end - start));
  return {};
}

std::string shown_field(std::string_view text) {
  constexpr std::size_t kMaxChars = 40;
  if (text.size() <= kMaxChars) return fmt::format("'{}'", text);
  return fmt::format("'{}…'", text.substr(0, kMaxChars));
}

std::string unquote_field(std::string_view field) {
  const std::string_view s = trim(field);
  if (s.size() < 2 || s.front() != '"' || s.back() != '"') return std::string(s);
  std::string out;
  for (std::size_t k = 1; k + 1 < s.size(); ++k) out += s[k] == '"' && s[k + 1] == '"' && k + 2 < s.size() ? s[k++] : s[k];
  return out;
}

std::string parse_csv_number(std::string_view field, bool decimal_comma, double& value) {
  std::string_view text = trim(field);
  const std::string_view as_written = text;
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = trim(text.substr(1, text.size() - 2));
  if (decimal_comma) {
    // A '.' beside decimal commas separates thousands ("1.234" is 1234): not read.
    if (text.find('.') != std::string_view::npos)
      return fmt::format("{} has a '.' in a file of decimal commas (a thousands separator?): write the number "
                         "without it",
                         shown_field(as_written));
    std::string pointed(text);
    for (char& c : pointed)
      if (c == ',') c = '.';
    if (parse_plain_decimal(pointed, value)) return {};
    return parse_general(pointed, as_written, value);
  }
  if (parse_plain_decimal(text, value)) return {};
  const bool has_comma = text.find(',') != std::string_view::npos;
  std::string problem = parse_general(text, as_written, value);
  if (!problem.empty() && has_comma && !decimal_comma)
    problem += " (a decimal comma? give --decimal-comma)";
  return problem;
}

namespace {

// The first delimiter or quote from p on, or end; eight bytes at a time where
// eight remain (a zero byte of w ^ c·kOnes marks c; the lowest mark is exact).
const char* next_delimiter_or_quote(const char* p, const char* const end, char delimiter) {
  if constexpr (kSwar) {
    const std::uint64_t delimiters = kOnes * static_cast<unsigned char>(delimiter), quotes = kOnes * '"';
    const auto zero_bytes = [](std::uint64_t v) { return (v - kOnes) & ~v & (0x80 * kOnes); };
    for (; end - p >= 8; p += 8) {
      const std::uint64_t w = load8(p);
      if (const std::uint64_t marks = zero_bytes(w ^ delimiters) | zero_bytes(w ^ quotes); marks != 0)
        return p + std::countr_zero(marks) / 8;
    }
  }
  for (; p != end && *p != delimiter && *p != '"'; ++p) {
  }
  return p;
}

}  // namespace

const char* skip_csv_field(const char* p, const char* const end, char delimiter) {
  bool quoted = false;  // as split_fields: "" inside quotes toggles twice
  for (;; ++p) {
    p = next_delimiter_or_quote(p, end, delimiter);
    if (p == end) return quoted ? nullptr : p;
    if (*p == '"') quoted = !quoted;
    else if (!quoted) return p;
  }
}

namespace {

// scan_csv_number for a field with blanks or quotes around the number.
const char* scan_csv_number_around(const char* p, const char* const end, char delimiter, bool decimal_comma,
                                   double& value) {
  // trim's blanks, but never the delimiter: a tab inside quotes is left to split_fields
  const auto skip_blanks = [&] {
    while (p != end && (*p == ' ' || (*p == '\t' && delimiter != '\t'))) ++p;
  };
  skip_blanks();
  const bool quoted = p != end && *p == '"';
  if (quoted) {
    ++p;
    skip_blanks();
  }
  double read = 0.0;
  p = plain_decimal_prefix(p, end, decimal_comma ? ',' : '.', read);
  if (p == nullptr) return nullptr;
  skip_blanks();
  if (quoted) {
    if (p == end || *p != '"') return nullptr;
    ++p;
    skip_blanks();
  }
  if (p != end && *p != delimiter) return nullptr;
  value = read;
  return p;
}

}  // namespace

const char* scan_csv_number(const char* p, const char* const end, char delimiter, bool decimal_comma,
                            double& value) {
  if (p != end && (*p == '-' || static_cast<unsigned>(*p - '0') < 10u)) {  // most fields: the number alone
    double read = 0.0;
    const char* const after = plain_decimal_prefix(p, end, decimal_comma ? ',' : '.', read);
    if (after != nullptr && (after == end || *after == delimiter)) {
      value = read;
      return after;
    }
  }
  return scan_csv_number_around(p, end, delimiter, decimal_comma, value);
}

const char* scan_iso8601_field(const char* p, const char* const end, char delimiter, Timestamp& out) {
  const char* const field_end = skip_csv_field(p, end, delimiter);
  if (field_end == nullptr) return nullptr;
  std::string_view text = trim(std::string_view(p, static_cast<std::size_t>(field_end - p)));
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') {  // unquote_field's text, without a copy
    text = text.substr(1, text.size() - 2);
    if (text.find('"') != std::string_view::npos) return nullptr;
  }
  return parse_iso8601(text, out) ? field_end : nullptr;
}

bool parse_iso8601(std::string_view text, Timestamp& out) {
  // YYYY-MM-DD[T ]hh:mm[:ss[.fff]][Z|±hh[:mm]]
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
  if (!digits_at(text, 0, 4, year) || text.size() < 16 || text[4] != '-' || !digits_at(text, 5, 2, month) ||
      text[7] != '-' || !digits_at(text, 8, 2, day) || (text[10] != 'T' && text[10] != 't' && text[10] != ' ') ||
      !digits_at(text, 11, 2, hour) || text[13] != ':' || !digits_at(text, 14, 2, minute))
    return false;
  std::size_t at = 16;
  double fraction = 0.0;
  if (at < text.size() && text[at] == ':') {
    if (!digits_at(text, at + 1, 2, second) || second > 59) return false;  // no leap second
    at += 3;
    if (at < text.size() && (text[at] == '.' || text[at] == ',')) {
      double scale = 0.1;
      const std::size_t first = ++at;
      for (; at < text.size() && static_cast<unsigned>(text[at] - '0') < 10u; ++at, scale /= 10)
        fraction += (text[at] - '0') * scale;
      if (at == first) return false;
    }
  }
  int offset_minutes = 0;
  if (at < text.size() && (text[at] == 'Z' || text[at] == 'z')) {
    ++at;
  } else if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
    const int sign = text[at] == '-' ? -1 : 1;
    int oh = 0, om = 0;
    if (!digits_at(text, at + 1, 2, oh)) return false;
    at += 3;
    const bool colon = at < text.size() && text[at] == ':';
    if (colon) ++at;
    if (colon || at < text.size()) {  // the minutes: after a ':' they must be there
      if (!digits_at(text, at, 2, om)) return false;
      at += 2;
    }
    if (oh > 23 || om > 59) return false;
    offset_minutes = sign * (60 * oh + om);
  }
  if (at != text.size() || hour > 23 || minute > 59) return false;
  using namespace std::chrono;
  const year_month_day date{std::chrono::year{year}, std::chrono::month{static_cast<unsigned>(month)},
                            std::chrono::day{static_cast<unsigned>(day)}};
  if (!date.ok()) return false;
  const std::int64_t days = sys_days(date).time_since_epoch().count();
  out.seconds = days * 86400 + 3600 * hour + 60 * minute + second - 60 * offset_minutes;
  out.fraction = fraction;
  return true;
}

}  // namespace gyrotherm::fit

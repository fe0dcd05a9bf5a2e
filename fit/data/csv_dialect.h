#pragma once
// How one line of a measurement CSV becomes fields, and a field a number,
// in the forms spreadsheets and loggers write:
//
//   delimiter      comma, semicolon or tab (--delimiter); by default the one
//                  the header line uses most, outside quotes (ties: comma first)
//   quotes         RFC 4180: a field in double quotes may hold the delimiter,
//                  and "" inside it is one quote; a quote that is not closed
//                  on its line is an error (fields spanning lines are not read)
//   decimal comma  "20,5" is 20.5 (--decimal-comma; needs a delimiter other
//                  than the comma); a field with a '.' is refused (beside
//                  decimal commas a '.' separates thousands: not read)
//   time           a number in the time unit, an ISO 8601 timestamp
//                  (2026-11-26T05:38:35.25Z, a space for the T, an offset
//                  +01:00 or none: UTC assumed), read as seconds since the
//                  first row's, or no column at all with --rate HZ (row k at
//                  k / HZ seconds)
//
// Reference: Y. Shafranovich, RFC 4180 (2005), "Common Format and MIME Type
// for CSV Files"; ISO 8601-1:2019 (the extended calendar date and time of day
// forms, as RFC 3339 profiles them).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gyrotherm::fit {

struct CsvDialect {
  std::string delimiter;       // "comma", "semicolon", "tab", or "auto"/"" (from the header)
  bool decimal_comma = false;  // --decimal-comma
  double rate_hz = 0.0;        // --rate: > 0 when the file has no time column

  // Throws InputError naming the option: an unknown delimiter, a rate that is
  // not a finite number > 0 (0 is none).
  void validate() const;
  // The delimiter character to read a file whose header line is `header`
  // with; throws InputError when the decimal comma meets a comma delimiter.
  char delimiter_for(std::string_view header) const;
  // "semicolon-separated, decimal comma" for the forms other than a plain
  // comma-separated file with decimal points ("" for that one).
  std::string describe(char delimiter) const;
};

// The delimiter's name for a message ("comma", "semicolon", "tab").
std::string_view delimiter_name(char delimiter);

// Splits `line` at `delimiter`, outside quotes, into `fields` (cleared first;
// views into `line`, quotes kept: parse_csv_number and unquote_field remove
// them). Returns "" on success, else what is wrong (an unclosed quote).
std::string split_fields(std::string_view line, char delimiter, std::vector<std::string_view>& fields);

// A field as a message shows it: quoted, and cut if very long.
std::string shown_field(std::string_view text);

// A header name as written: trimmed, and the text inside RFC 4180 quotes.
std::string unquote_field(std::string_view field);

// Parses a number field (spaces around, a leading '+', RFC 4180 quotes and,
// with decimal_comma, a ',' for the point are accepted); "" on success, else
// what is wrong, with a hint where the field holds a decimal comma that the
// options do not expect.
std::string parse_csv_number(std::string_view field, bool decimal_comma, double& value);

// The fast path of a data row, field by field without copies: each function
// reads the field that starts at p (the line ends at `end`) and returns where
// it ends (at the delimiter or at `end`), or nullptr for a field it does not
// take, which is then left to split_fields, parse_csv_number and unquote_field
// (they give the same value, or the message). Whatever they take, they read
// as those do, bit for bit.
//
// A field the row does not need, by split_fields' quotes (nullptr: a quote
// left open at the end of the line).
const char* skip_csv_field(const char* p, const char* end, char delimiter);
// A number: blanks, RFC 4180 quotes around it, [-]digits[.digits][e[±]dd]
// (',' for the point with decimal_comma) as Clinger's fast path reads it
// exactly (parse_csv_number's first step); nullptr for anything else (a
// leading '+', more than 19 digits, powers of ten beyond ±22, nan, text).
const char* scan_csv_number(const char* p, const char* end, char delimiter, bool decimal_comma, double& value);
struct Timestamp;
// An ISO 8601 timestamp (parse_iso8601 of unquote_field's text).
const char* scan_iso8601_field(const char* p, const char* end, char delimiter, Timestamp& out);

// An ISO 8601 date and time (above) as whole seconds since 1970-01-01 UTC
// and the fraction of a second; false when `text` is not one.
struct Timestamp {
  std::int64_t seconds = 0;
  double fraction = 0.0;
};
bool parse_iso8601(std::string_view text, Timestamp& out);

}  // namespace gyrotherm::fit

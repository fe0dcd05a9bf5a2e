#pragma once
// The unit a column's name states, as loggers and spreadsheets write it:
//
//   in brackets at the end    "time (ms)", "gyro [rad/s]", "temp (°C)", "T [degC]"
//   as the last word          "gyrox rad/s", "time ms"
//   as the last _-suffix      "time_s", "t_us", "gx_dps", "gyro_dph", "temp_c", "gyro_rad_s"
//
// Each form is matched against the aliases of the column's own quantity
// only (fit/data/units.cpp: "deg/s", "°/s", "dps" are one unit), case
// insensitive. A word or suffix that is no unit of the quantity says nothing
// ("gyro_x", "temp sensor"); a bracketed text is a statement, so one that
// names no unit of the quantity is reported (`unknown`), and raw counts
// ("[LSB]", "(counts)", "(raw)") are recognised as such.
//
// How the unit of each needed column is then decided (resolve_units): the
// option (--time-unit, --gyro-unit, --temp-unit) when given, and it must
// agree with a unit the header states (else an InputError naming both);
// otherwise the header's; otherwise the base unit (s, °/h, °C). The two
// temperature columns share --temp-unit, so their headers must agree.

#include <string>
#include <string_view>

#include "fit/data/measurement.h"
#include "fit/data/units.h"

namespace gyrotherm::fit {

struct HeaderUnit {
  const Unit* unit = nullptr;  // the unit the name states, if one of the quantity's
  std::string said;            // the text that stated it ("ms", "rad/s"); empty: nothing said
  bool raw_counts = false;     // the name says raw counts (LSB, counts, raw, adc)
  bool unknown() const { return unit == nullptr && !raw_counts && !said.empty(); }
};

HeaderUnit unit_in_header(Quantity quantity, std::string_view column);

// The units to read the columns named in `header_names` (time, temp, gyro,
// temp2; temp2 empty when absent) with, from the requested ones (an empty
// unit name: not given) and the header; every unit name of the result is
// set, and its *_from fields say where each came from. Throws InputError
// naming the column, the option and both units on a disagreement,
// and asking for the option when a bracketed unit is unknown or the column
// holds raw counts without a scale.
Units resolve_units(const Units& requested, const std::string& time_column,
                    const std::string& temp_column, const std::string& gyro_column,
                    const std::string& temp2_column);

}  // namespace gyrotherm::fit

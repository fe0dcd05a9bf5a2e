#pragma once
// What the report adds to the other commands' results, as data for its twin:
// the model's 95 % band on the record it was fitted on (fit/model_band.h), the
// model as each firmware stores it with intervals, and the sensors the log
// holds (format, instances, device ids).

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fit/compensation.h"
#include "fit/fit_file.h"
#include "fit/model_band.h"

namespace gyrotherm::studies {

// Why a channel has no band (the twin's band.missing).
enum class BandMissing { none, other_record, engine_not_ols, noise_not_identified };
std::string band_missing_name(BandMissing why);

struct ChannelBand {
  BandMissing missing = BandMissing::none;
  std::optional<fit::CoefficientCovariance> covariance;
  fit::Band band;  // at each window of the compensation
};

// The band of `fit` on the compensation's windows; `same_record`: the fit was
// made on this log (else none: its covariance belongs to another record).
ChannelBand channel_band(const fit::SavedFit& fit, const fit::Compensation& compensated, bool same_record);
// {"missing": null | "other_record" | "noise_not_identified", "method", "dof",
//  "half_width_dph": [smallest, largest]}
nlohmann::ordered_json band_json(const ChannelBand& band);

// The fit's temperature polynomial as PX4 (TC_G*_X0..X3 about TREF, rad/s)
// and ArduPilot (INS_TCAL*_GYR1..3 about 35 °C, ×10⁶ rad/s) store it, with
// 95 % intervals from the band's covariance when it has one. `tref_c`: the
// TREF export writes for this channel. A model with other terms:
// {"expressible": false, "not_expressible": [terms]}.
nlohmann::ordered_json firmware_json(const fit::SavedFit& fit, double tref_c, const ChannelBand& band);
// The TREF `export --format px4` writes for channel k of `fits` (the middle of
// the first three channels' common fitted range; its own range's past those).
double export_tref(const std::vector<fit::SavedFit>& fits, std::size_t k);

// {"format": "ULog v1" | "DataFlash" | "text table", "gyros": [{instance,
// message, device_id, samples, temp_range_c, read}]} (gyros: autopilot logs only).
nlohmann::ordered_json sensors_json(const std::string& log, const fit::SavedFit& fit);

}  // namespace gyrotherm::studies

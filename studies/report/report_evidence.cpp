#include "studies/report/report_evidence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "fit/data/autopilot_log.h"
#include "sim/util/input_error.h"
#include "studies/export/firmware.h"

namespace gyrotherm::studies {

namespace {

using Json = nlohmann::ordered_json;

// The terms the firmwares cannot store (no power of T up to the third): what
// export's polynomial_of leaves out when asked to drop them.
std::vector<std::string> not_expressible(const fit::SavedFit& fit) { return polynomial_of(fit, true, "").dropped; }

// The weights on θ = (b0, b_1..b_m) of the re-expanded coefficient a_k about
// r (B(r + d) = Σ a_k d^k): a_k = Σ_n C(n, k)·r^(n−k)·c_n, c_n the sum of the
// coefficients of T^n (c_0 the intercept).
Eigen::VectorXd reexpanded_weights(const fit::SavedFit& fit, double r, int k) {
  const auto binomial = [](int n, int j) { return n == 3 && (j == 1 || j == 2) ? 3.0 : n == 2 && j == 1 ? 2.0 : 1.0; };
  Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(fit.terms.size()) + 1);
  if (k == 0) w[0] = 1.0;
  for (std::size_t j = 0; j < fit.terms.size(); ++j) {
    const int n = fit.terms[j]->temperature_power;
    if (n >= k) w[static_cast<Eigen::Index>(j) + 1] = binomial(n, k) * std::pow(r, n - k);
  }
  return w;
}

// Values and, with a covariance, 95 % intervals of the re-expanded
// coefficients `first`..3 about r, each × scale.
Json coefficient_block(const fit::SavedFit& fit, const ChannelBand& band, double r, int first,
                       const std::vector<float>& values, double scale) {
  Json v = Json::array(), i = Json::array();
  for (int k = first; k <= kCubic; ++k) {
    const double value = values[static_cast<std::size_t>(k - first)];
    v.push_back(value);
    if (!band.covariance) continue;
    const double half = band.covariance->half_width(reexpanded_weights(fit, r, k)) * scale;
    i.push_back({value - half, value + half});
  }
  return {{"values", v}, {"intervals_95", band.covariance ? i : Json()}};
}

}  // namespace

std::string band_missing_name(BandMissing why) {
  switch (why) {
    case BandMissing::other_record: return "other_record";
    case BandMissing::engine_not_ols: return "engine_not_ols";
    case BandMissing::noise_not_identified: return "noise_not_identified";
    case BandMissing::none: break;
  }
  return "";
}

ChannelBand channel_band(const fit::SavedFit& fit, const fit::Compensation& c, bool same_record) {
  ChannelBand band;
  if (!same_record) {
    band.missing = BandMissing::other_record;
    return band;
  }
  if (fit.engine != "ols") {  // the least-squares covariance is ols's; another engine's estimate is not its centre
    band.missing = BandMissing::engine_not_ols;
    return band;
  }
  band.covariance = fit::coefficient_covariance(c.data, fit.terms, fit.parameters);
  if (!band.covariance) {
    band.missing = BandMissing::noise_not_identified;
    return band;
  }
  band.band = fit::model_band(*band.covariance, c.data, fit.terms, fit.parameters);
  return band;
}

Json band_json(const ChannelBand& band) {
  Json j{{"missing", band.missing == BandMissing::none ? Json() : Json(band_missing_name(band.missing))}};
  const std::vector<double>& half = band.band.half_width_dph;
  if (!band.covariance || half.empty()) return j;
  const auto [lo, hi] = std::minmax_element(half.begin(), half.end());
  j["method"] = "least-squares covariance under the identified noise (the widest of the noise models the record "
                "supports), intercept included; Student t at each point's Satterthwaite dof";
  j["dof"] = band.band.smallest_dof;
  j["half_width_dph"] = {*lo, *hi};
  return j;
}

double export_tref(const std::vector<fit::SavedFit>& fits, std::size_t k) {
  std::array<AxisModel, 3> axes;
  const auto usable = [](const fit::SavedFit& f) { return f.temp_range_c && not_expressible(f).empty(); };
  for (std::size_t i = 0; i < std::min<std::size_t>(3, fits.size()); ++i) {
    if (!usable(fits[i])) continue;
    axes[i].present = true;
    axes[i].temp_min_c = fits[i].temp_range_c->first;
    axes[i].temp_max_c = fits[i].temp_range_c->second;
  }
  if (k < 3 && usable(fits[k])) {
    try {
      return export_range(axes).tref_c;
    } catch (const InputError&) {  // ranges that do not overlap: export refuses; the channel's own
    }
  }
  return fits[k].temp_range_c ? 0.5 * (fits[k].temp_range_c->first + fits[k].temp_range_c->second) : NAN;
}

Json firmware_json(const fit::SavedFit& fit, double tref_c, const ChannelBand& band) {
  const std::vector<std::string> others = not_expressible(fit);
  if (!others.empty() || !std::isfinite(tref_c))
    return {{"expressible", false}, {"not_expressible", others}, {"no_range", others.empty()}};
  AxisModel axis;
  axis.present = true;
  axis.model = polynomial_of(fit, false, "");
  const float tref = static_cast<float>(tref_c);  // as PX4 stores it
  const fit::SensorKind& gyro = fit::sensor_kind("gyro");  // report reads a gyro's fit only
  const std::array<float, kQuintic + 1> x = px4_coefficients(axis, tref, gyro);
  const std::array<float, 3> g = ardupilot_coefficients(axis, gyro);
  Json px4 = coefficient_block(fit, band, tref, 0, {x.begin(), x.begin() + kCubic + 1}, kRadPerSecPerDegPerHour);
  px4["tref_c"] = tref;
  px4["temp_range_c"] = {fit.temp_range_c->first, fit.temp_range_c->second};
  Json ardupilot = coefficient_block(fit, band, kArduPilotReferenceC, 1, {g.begin(), g.end()}, kRadPerSecPerDegPerHour * 1e6);
  ardupilot["reference_c"] = kArduPilotReferenceC;
  return {{"expressible", true}, {"px4", px4}, {"ardupilot", ardupilot}};
}

Json sensors_json(const std::string& log, const fit::SavedFit& fit) {
  const fit::LogFormat* format = fit::log_format_of(log);
  if (format == nullptr) return {{"format", "text table"}, {"gyros", Json::array()}};
  const fit::LogContents contents = format->read(log, -1, {}, fit::sensor_kind("gyro"));
  const int read = fit.pipeline.columns.imu.value_or(contents.default_instance());
  Json gyros = Json::array();
  for (const fit::LogSensor& g : contents.sensors)
    gyros.push_back({{"instance", g.instance},
                     {"message", g.message},
                     {"device_id", g.device_id},
                     {"samples", g.samples},
                     {"temp_range_c", {std::isfinite(g.temp_min_c) ? Json(g.temp_min_c) : Json(), std::isfinite(g.temp_max_c) ? Json(g.temp_max_c) : Json()}},
                     {"read", g.instance == read}});
  return {{"format", contents.format}, {"gyros", gyros}};
}

}  // namespace gyrotherm::studies

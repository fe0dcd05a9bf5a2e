#pragma once
// The renderers' words for the noise coefficients of a sensor
// (studies/allan/noise_coefficients.h holds what was read, as numbers).
//
// What a sensor's coefficients are called and in which unit they are
// reported (fit/data/sensor_kind.h). The coefficients are read in the gyro's
// convention, whatever the sensor: N the −½ line's value at τ = 1 h (base
// unit), B in the base unit, K the +½ line's at τ = 3 h (base unit/√h), Q the
// −1 line's (base unit·s: a gyro's (°/h)·s is 1″). A gyro's are ARW °/√h,
// bias instability °/h, RRW °/h/√h, quantisation ″; an accelerometer's
// white noise is the velocity random walk, 3600·N m/s/√h (the sensor kind's
// factor × 60), a barometer's and a magnetometer's a density, 60·N Pa·√s
// (gauss·√s); their random walks K in the base unit/√h as the gyro's.

#include <string>

#include "fit/data/sensor_kind.h"

namespace gyrotherm::studies {

struct NoiseCoefficient;

struct CoefficientLabel {
  std::string name;      // "angle random walk", "velocity random walk"
  std::string short_name;  // "ARW", "VRW"
  std::string unit;      // as the text writes it: "°/√h", "m/s/√h"
  std::string json_key;  // "arw_dpsh" (a gyro's, as it always was), "vrw"
  double scale = 1.0;    // reported = scale × the value read
};
struct CoefficientLabels {
  CoefficientLabel white, bias_instability, random_walk, quantization;
  std::string adev_unit;  // the Allan deviation's: the base unit
};
CoefficientLabels coefficient_labels(const fit::SensorKind& kind);
// k in its reported unit: value, interval and bound times the label's scale.
NoiseCoefficient reported(NoiseCoefficient k, const CoefficientLabel& label);

}  // namespace gyrotherm::studies

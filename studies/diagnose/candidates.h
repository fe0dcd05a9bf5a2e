#pragma once
// The candidates diagnose tries against a model (step 3 of
// studies/diagnose/diagnosis.h):
//
//  * every registered effect not in the model whose columns exist;
//  * every numeric column of the log, NAME, and its rate d(NAME): a quantity
//    the user logged (case or chamber temperature, supply voltage, field),
//    never the record's own time, temperature and gyro columns (all the
//    --gyro-col channels), nor the simulator's truth column bias_true_dph,
//    nor, unless named in --candidates, another motion sensor's channel of
//    the same log (sensor_channel(): the other gyro axes, accelerometer and
//    magnetometer axes: they move with the platform, not with the bias's
//    physical causes);
//  * the bias steps the model's residual shows (studies/diagnose/steps.h),
//    as step@TIME terms.
//
// --candidates changes the set: a list of names is exactly those (the word
// "step" for the steps found); entries starting with + or − add to or remove
// from the default set.

#include <cstdint>
#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/model/terms.h"
#include "studies/diagnose/steps.h"

namespace gyrotherm::studies {

struct CandidateSet {
  std::vector<const fit::Term*> terms;      // to be tried, registry first, then columns, then steps
  std::vector<std::string> skipped;    // what could not be a candidate, and why
  std::vector<StepCandidate> steps;    // the steps found in the residual
  std::vector<std::string> columns;    // the log's columns tried (each with its rate)
};

// Whether a column is a motion sensor's channel by its name: a gyro unit in
// it ("gy_dph", "gyroy rad/s"), a name that starts with gyr, acc, mag or
// omega ("GyrX", "accel_y", "mag1x [T]"), an axis name ("gx", "ay", "m1z",
// "wz") or MAVLink's ("xgyro", "yacc", "zmag").
bool sensor_channel(const std::string& column);

// The columns that are never candidates besides the record's own roles.
inline const std::vector<std::string> kNeverCandidates = {"bias_true_dph"};

// parameters: the model's fitted nonlinear parameters; seed: of the step
// test's bootstrap.
CandidateSet candidate_set(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                           const std::vector<double>& parameters,
                           const std::vector<std::string>& requested,
                           const std::vector<std::string>& excluded_columns, std::uint64_t seed);

}  // namespace gyrotherm::studies

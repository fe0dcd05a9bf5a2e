#pragma once
// The files of `gyrotherm plan --out DIR` (studies/plan/plan.h): the scenario,
// its rig and gyro files, the chamber programme as CSV and the figure. All are
// made in memory first and then each written atomically, so a failure (a
// folder that cannot be made, gnuplot missing) leaves no half-written file.

#include "studies/plan/design_precision.h"
#include "studies/plan/plan.h"
#include "studies/plan/plan_setup.h"

namespace gyrotherm::studies::plan {

// Writes the files and sets r's *_file fields.
void write_plan_files(PlanResult& r, const PlanSetup& setup, const PrecisionDetail& detail);

// The chamber programme: time_s, setpoint_c every `step_s` seconds and at
// every segment's end (a controller interpolates linearly between rows).
std::string setpoint_csv(const ChamberProfile& profile, double step_s = 10.0);

}  // namespace gyrotherm::studies::plan

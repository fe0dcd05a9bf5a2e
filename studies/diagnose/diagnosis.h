#pragma once
// Diagnosis: where a bias model fails on measured data, and which physical
// effect it is missing (`gyrotherm diagnose`).
//
//  1. Compare. Fit the model; the instability after is set against the noise
//     floor, what a perfect model would leave, estimated from the data alone:
//     a robust Hadamard deviation of the window means y_p,
//        floor² = median_p (y_{p+1} − 2y_p + y_{p−1})² / (6 · 0.4549),
//     (0.4549 = median of χ²₁), over the triples of equally spaced windows
//     (within 10 %) of one gap-free run, or across gaps no farther apart than
//     the derivatives' span, so a bursty record's burst means count too. Second differences cancel the
//     locally linear thermal trends of soaks; the median ignores the ramps'
//     transients. For white noise it equals the standard deviation of the
//     window means. With fewer than 10 such triples the floor comes from the
//     scatter inside the windows instead: the standard error of each window
//     mean, s_p²·(1 + ρ_p)/((1 − ρ_p)·n_p) with ρ_p the lag-1
//     autocorrelation of its samples (an AR(1) correction, ρ held in
//     [−0.5, 0.95]), pooled as the root mean square. That one sees only noise
//     faster than a window; slower noise (bias instability) then shows as
//     excess, and the report says which estimate was used.
//  2. Where it fails. The record is split by its own temperature: the first
//     30 min (turn-on), heating (dT/dt > r), cooling (< −r), soak (|dT/dt| ≤ r),
//     r = max(2e-4 °C/s, 5 % of the largest |dT/dt|), runs shorter than 3
//     windows merged into their neighbour; and four equal temperature bands.
//     Each is ranked by the RMS of the residual over the floor.
//  3. Which effect is missing. Every candidate (studies/diagnose/candidates.h:
//     the registry's terms not in the model, the log's columns that may be
//     causes, and a bias step at every position) is tested by likelihood
//     under the record's identified noise (likelihood_test.h): whitened by
//     the noise's covariance, the share of the residual each removes, at
//     its best parameter value or step position, with a p-value calibrated
//     by a parametric bootstrap from that noise that every candidate shares.
//     The noise is identified (REML) twice a round: under the model as it
//     stands, to find the round's leading candidate, and then with that
//     candidate as a fixed effect too, so that an effect (a mode hop, a slow
//     lag) is not first read as noise (random walk, Gauss–Markov) and then
//     tested against itself; every candidate of the round is tested under
//     the second, and under each noise model the record supports alike
//     (the largest p). The family-wise error over the candidates is held
//     step-down over the rounds (Holm): each registry term and the step
//     family weigh one, the log's columns together one, so logged columns
//     never dilute the physical candidates. A candidate is significant when
//     p ≤ w·(1 − (1 − α)^{1/W_eff}) (W_eff the effective number of tests of
//     the candidates still untested, from the same draws: likelihood_test.h)
//     and it removes at least 10 % of the excess. Ranking is greedy (forward
//     selection): the significant candidate with the largest likelihood gain
//     joins the model and the others are tested again, so a second hidden
//     effect is judged on what the first leaves; the reductions are shares
//     of the original excess. Before the best joins, every candidate of its
//     round that removes at least 80 % as much is fitted together with it
//     (GLS under the round's noise): if neither adds significantly to the
//     other, the record cannot tell them apart and they form one group (the
//     one with fewer fitted parameters stands for it; a rival that only
//     encompasses it without passing the test alone joins the group too); if
//     only the rival adds, and it passed the test too, the rival joins
//     instead. Block cross-validation of each candidate (blocks of 10
//     windows) is kept as a check of its out-of-sample gain, not as the test.
//  4. What it cannot tell apart (confounding.h), the steps found with their
//     sizes, what remains, and the verdict: all as data (below); the words
//     are the renderers' (studies/diagnose/diagnose_text.h).
//
// References: IEEE Std 952-1997 Annex C (Allan and Hadamard variances);
// Arlot & Celisse, "A survey of cross-validation procedures for model
// selection", Statistics Surveys 4 (2010) §8 (dependent data: block CV);
// Holm, Scand. J. Statistics 6 (1979) 65–70 (step-down; weighted: Holm's
// own §5); Patterson & Thompson, Biometrika 58 (1971) 545–554 (REML).

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fit/data/column_role.h"
#include "fit/data/sensor_kind.h"
#include "fit/pipeline.h"

namespace gyrotherm::studies {

// A record with fewer windows cannot be diagnosed.
inline constexpr std::size_t kMinBlocks = 8;
// A model with every significant candidate still above this many times the
// floor leaves structure no candidate explains (the verdict says where).
inline constexpr double kStructureRemains = 1.5;

struct DiagnosisOptions {
  double alpha = 0.05;             // family-wise significance over the candidates
  double min_reduction_pct = 10.0; // a significant effect removes at least this share of the excess
  int draws = 400;                 // of the likelihood test's bootstrap (likelihood_test.h)
  std::uint64_t seed = 1;          // of its draws
  std::size_t block_windows = 10;  // windows per block of the cross-validation check
  // --candidates (studies/diagnose/candidates.h): empty for the default set.
  std::vector<std::string> candidates;
  // Log columns that are never candidates (the other gyro channels).
  std::vector<std::string> excluded_columns;
  // Called at each stage of a diagnosis ("scoring 14 candidates, round 1", …); may be empty.
  std::function<void(const std::string& stage)> stage;
};

// A bias step in the record, located by the step family of candidates.
struct StepEvent {
  double time_s = 0;          // since the start of the record
  double log_time_s = 0;      // the same on the log's own clock
  double size_dph = 0;        // GLS with the final model, under the final noise
  fit::Interval size_interval_dph;  // 95 %
  double p_value = 1;         // the step family's own p-value (before the family correction)
  bool significant = false;   // it passed the candidates' test and joined the suggested model
};

enum class SegmentKind { turn_on, heating, cooling, soak, band };
const char* to_string(SegmentKind kind);  // "turn-on", "heating", "cooling", "soak", "band"

struct SegmentReport {
  SegmentKind kind = SegmentKind::soak;
  double start_s = 0, end_s = 0;  // window centres, since the start of the record
  double temp_min_c = 0, temp_max_c = 0;
  std::size_t windows = 0;
  double rms_dph = 0;
  double ratio_to_floor = 0;
};

struct CandidateReport {
  const fit::Term* term = nullptr;
  double parameter = std::numeric_limits<double>::quiet_NaN();  // its fitted parameter; NaN when it has none
  // Added alone to the model as it stood in its round (the model given, and
  // the candidates that joined before it), at `parameter`: its GLS
  // coefficient (Term::coefficient_unit()) under the round's noise, and the
  // 95 % interval.
  double coefficient = std::numeric_limits<double>::quiet_NaN();
  fit::Interval coefficient_interval;
  double instability_after_dph = 0;    // in-sample least squares, with the term added
  double reduction_pct = 0;            // of the excess variance over the floor
  double likelihood_share = 0;         // of the whitened residual it removes (likelihood_test.h)
  double p_value = 1;                  // over its own grid, before the family correction
  double p_bootstrap = 1;              // the share of the bootstrap's draws at least as large (a check)
  double tests = 1;                    // its grid's effective number of independent tests
  double level = 0;                    // the level p was compared with: w·(1 − (1 − α)^{1/W_eff})
  double cv_gain_pct = std::numeric_limits<double>::quiet_NaN();  // block cross-validated SSE gain (a check)
  int round = 1;                       // the round of forward selection that scored it
  bool significant = false;
  // Its group (terms this record cannot tell apart) passed the test, through
  // whichever member stood for it (set for every member).
  bool group_significant = false;
  std::vector<std::string> confounded_with;  // terms this record cannot tell it from ("1": an offset)
  // It passed the test: alone, or, in a group, through its group.
  bool passed() const { return confounded_with.empty() ? significant : group_significant; }
};

// What could not be a candidate, and why.
enum class SkipReason {
  needs_temp2,      // a term that needs a second temperature column
  unwritable_name,  // a column whose name cannot be written in a model
  column_role,      // a column that is no cause (role: another sensor, a status, a counter)
  too_few_windows,  // too few windows left for it and its parameter
  not_fitted,       // the model with it cannot be fitted (error: why)
};
struct Skipped {
  std::string name;                 // the term or column
  SkipReason reason = SkipReason::not_fitted;
  fit::ColumnRole role = fit::ColumnRole::cause;  // column_role
  std::size_t windows = 0;          // too_few_windows
  std::string error;                // not_fitted: the FitError's message, as thrown
};

enum class FloorMethod { hadamard, within_window };
// The estimate of step 1 and how it was made.
struct NoiseFloor {
  double dph = 0;               // the floor used
  FloorMethod method = FloorMethod::hadamard;
  std::size_t triples = 0;      // equally spaced triples for the Hadamard estimate
  double hadamard_dph = 0;      // 0 when there were too few triples
  double within_dph = 0;        // from the scatter inside the windows (0 if unknown)
};
inline constexpr std::size_t kMinHadamardTriples = 10;

// Why a group of terms cannot be told apart on this record (confounding.h).
enum class ConfoundingReason {
  temperature_follows_time,  // temperature and time move together (correlation, direction)
  constant_rate,             // the rate hardly changes: a rate effect acts as an offset (rate_c_per_h)
  settling_curve,            // temperature settles along one curve: temperature and rate look alike
  narrow_range,              // temperature powers nearly proportional over the range (temp_min_c..temp_max_c)
  lag_follows_temperature,   // a lagged temperature moves with T at this record's rates (fastest_rate_c_per_min)
  proportional,              // regressors nearly proportional over this record
  same_part,                 // fitted together, neither adds significantly (a, b with their intervals)
  encompasses,               // a encompasses b on this record, but did not pass the test alone
};
enum class Direction { cools, heats, both };
struct ConfoundingEvidence {
  ConfoundingReason reason = ConfoundingReason::proportional;
  double correlation = 0;            // temperature_follows_time: r(T, t)
  Direction direction = Direction::both;
  double rate_c_per_h = 0;           // constant_rate
  double temp_min_c = 0, temp_max_c = 0;  // narrow_range
  double fastest_rate_c_per_min = 0;      // lag_follows_temperature: the largest |dT/dt| of the windows
  std::string a, b;                  // same_part, encompasses
  fit::Interval interval_a, interval_b;   // same_part: 95 %, fitted together
};
struct ConfoundingGroup {
  std::vector<std::string> members;  // term names; "1": the intercept (a constant offset)
  std::vector<ConfoundingEvidence> evidence;  // one per reason found
  bool holds(const std::string& term) const;
};

enum class VerdictKind {
  nothing_to_try,  // every available term is in the model
  found,           // significant candidates that stand alone
  group,           // the first passed, but the record cannot tell it from others
  none,            // nothing significant
};
struct Verdict {
  VerdictKind kind = VerdictKind::none;
  std::vector<std::size_t> found;  // found: indices into candidates, in the order they joined
  double removed_pct = 0;          // found: their shares of the excess, summed; group: the first's
  std::size_t group = 0;           // group: index into confounded
  bool limited = false;            // some candidates were not tried (skipped: too few windows)
};

// Structure no candidate explains: the model with the significant candidates
// (or the first of their group) still above kStructureRemains × the floor.
struct Remaining {
  bool with_candidates = false;    // the model had significant candidates added
  double ratio_to_floor = 0;
  SegmentReport worst;             // its worst segment
};

struct Diagnosis {
  const fit::SensorKind* sensor = &fit::sensor_kinds().front();  // whose bias (its unit); the gyro's by default
  fit::ModelFit fit;                      // the model as given
  double noise_floor_dph = 0;
  NoiseFloor floor;                       // how noise_floor_dph was estimated
  double excess_ratio() const { return fit.instability_after_dph / noise_floor_dph; }
  std::vector<SegmentReport> segments;    // in time order
  std::vector<SegmentReport> bands;       // by temperature
  std::vector<std::size_t> window_segment;  // per window: index into segments
  std::vector<CandidateReport> candidates;  // best first
  // Every candidate as the first round scored it: added alone to the model
  // given, in the order tried. The verdict's group takes its members' sizes
  // from here (the plan command, report.h).
  std::vector<CandidateReport> first_round;
  std::vector<Skipped> skipped;           // what could not be tried, and why
  std::vector<std::string> columns_tried;  // the log's columns tried as causes (each with its rate)
  std::vector<ConfoundingGroup> confounded;  // terms this record cannot tell apart
  std::vector<StepEvent> events;          // bias steps, in time order
  std::optional<Remaining> remaining;
  Verdict verdict;
  std::vector<const fit::Term*> suggested;  // the model with the significant candidates, or empty
  // The record's noise identified with the model and every significant
  // candidate as fixed effects (a step is not read as random walk).
  std::shared_ptr<const fit::NoiseContext> noise;
  // Segments and bands, worst first (indices into segments / bands).
  std::vector<std::size_t> worst_segments() const;
  const std::vector<double>& residual_dph() const { return fit.residual_dph; }
  const std::vector<double>& model_dph() const { return fit.fitted_dph; }
};

NoiseFloor estimate_noise_floor(const fit::AveragedSeries& series, double span_s);
// The Hadamard estimate alone (throws InputError with fewer than 5 triples).
double robust_noise_floor(const fit::AveragedSeries& series);

Diagnosis diagnose(const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                   const fit::EngineInfo& engine, const fit::EngineSettings& settings,
                   const DiagnosisOptions& options = {});

// A share at or above this reads "all of the excess" (the fit goes below the floor as estimated).
inline constexpr double kBelowFloorPct = 100.5;

// Per-segment RMS of a residual, for before/after tables.
std::vector<SegmentReport> segment_rms(const Diagnosis& d, const std::vector<double>& residual);

}  // namespace gyrotherm::studies

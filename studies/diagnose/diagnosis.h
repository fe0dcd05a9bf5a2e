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
//  3. Which effect is missing. Every registry term not in the model whose
//     columns exist is added in turn (nonlinear parameters by variable
//     projection) and ranked by the share of the excess variance
//     (after² − floor²) it removes. Significance by block cross-validation,
//     which autocorrelated residuals cannot fool: the windows are cut into
//     contiguous blocks of 10; each block is predicted by both models fitted
//     without it (a candidate's own parameter, a filter's time constant,
//     chosen again in every fold on the training rows from a grid of 41
//     log-spaced values, so the block it predicts never tunes it); the per-block gains d_k = SSE_base − SSE_with are tested by
//     a one-sided sign-flip randomisation test (20 000 seeded draws), with a
//     Bonferroni correction over the candidates. A candidate is significant
//     when p < α/n, its cross-validated gain is positive, and it removes at
//     least 10 % of the excess. Ranking is greedy (forward selection): a
//     significant best term joins the model and the others are scored again,
//     so a second hidden effect is judged on what the first leaves; the
//     reductions are shares of the original excess. Before the best joins,
//     every candidate of its round that removes at least 80 % as much is
//     fitted together with it (confounding.h, separate(): ols under the
//     record's identified noise): if neither adds significantly to the
//     other, the record cannot tell them apart and they form one group (the
//     one with fewer fitted parameters stands for it; a rival that only
//     encompasses it without passing the test alone joins the group too);
//     if only the rival adds, and it passed the test too, the rival joins
//     instead.
//
// References: IEEE Std 952-1997 Annex C (Allan and Hadamard variances);
// Arlot & Celisse, "A survey of cross-validation procedures for model
// selection", Statistics Surveys 4 (2010) §8 (dependent data: block CV);
// Good, Permutation, Parametric and Bootstrap Tests of Hypotheses (2005).

#include <array>
#include <functional>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fit/pipeline.h"

namespace gyrotherm::studies {

// A record with fewer windows cannot be diagnosed: a sign-flip test on fewer
// blocks cannot reach significance.
inline constexpr std::size_t kMinBlocks = 8;
// A model with every significant candidate still above this many times the
// floor leaves structure no candidate explains (the verdict says where).
inline constexpr double kStructureRemains = 1.5;

struct DiagnosisOptions {
  std::size_t block_windows = 10;  // windows per cross-validation block
  double alpha = 0.05;             // family-wise significance over the candidates
  double min_reduction_pct = 10.0; // a significant effect removes at least this share of the excess
  int permutations = 20000;        // sign-flip draws
  std::uint64_t seed = 1;          // of the sign flips
  // --candidates (studies/diagnose/candidates.h): empty for the default set.
  std::vector<std::string> candidates;
  // Log columns that are never candidates (the other gyro channels).
  std::vector<std::string> excluded_columns;
  // Called at each stage of a diagnosis ("scoring 14 candidates, round 1", …); may be empty.
  std::function<void(const std::string& stage)> stage;
};

// A bias step found in the model's residual, after scoring (--json events).
struct StepEvent {
  double time_s = 0;          // since the start of the record
  double size_dph = 0;        // least squares with the model
  fit::Interval size_interval_dph;  // 95 %, ols
  double p_value = 1;         // of the bootstrap test that found it (steps.h)
  bool significant = false;   // it passed the candidates' test and joined the suggested model
};

struct SegmentReport {
  std::string kind;  // turn-on, heating, cooling, soak, band
  double start_s = 0, end_s = 0;
  double temp_min_c = 0, temp_max_c = 0;
  std::size_t windows = 0;
  double rms_dph = 0;
  double ratio_to_floor = 0;
};

struct CandidateReport {
  const fit::Term* term = nullptr;
  double parameter = 0;                // NaN when the term has none
  // Its least-squares coefficient (°/h per the regressor's unit,
  // Term::coefficient_unit()) in the fit this row reports: the term added
  // alone to the model as it stood in its round (the model given, and the
  // candidates that joined before it), at `parameter`. No interval: the
  // ranking fits by least squares only, and an interval would need the
  // noise identified again on each candidate's residual (fit_model).
  double coefficient = std::numeric_limits<double>::quiet_NaN();
  double instability_after_dph = 0;    // in-sample, with the term added
  double reduction_pct = 0;            // of the excess variance over the floor
  double cv_gain_pct = 0;              // of the cross-validated SSE
  double p_value = 1;                  // sign-flip test, before the correction
  bool significant = false;
  // Its group (terms this record cannot tell apart) passed the test, through
  // whichever member stood for it (set for every member).
  bool group_significant = false;
  std::vector<std::string> confounded_with;  // terms this record cannot tell it from ("1": an offset)
  // It passed the test: alone, or, in a group, through its group.
  bool passed() const { return confounded_with.empty() ? significant : group_significant; }
};

// The estimate of step 1 and how it was made.
struct NoiseFloor {
  double dph = 0;               // the floor used
  std::string method;           // "hadamard" or "within-window scatter"
  std::size_t triples = 0;      // equally spaced triples for the Hadamard estimate
  double hadamard_dph = 0;      // 0 when there were too few triples
  double within_dph = 0;        // from the scatter inside the windows (0 if unknown)
  std::string description() const;
};
inline constexpr std::size_t kMinHadamardTriples = 10;

struct Diagnosis {
  fit::ModelFit fit;                           // the model as given
  double noise_floor_dph = 0;
  NoiseFloor floor;                       // how noise_floor_dph was estimated
  double excess_ratio() const { return fit.instability_after_dph / noise_floor_dph; }
  std::vector<SegmentReport> segments;    // in time order
  std::vector<SegmentReport> bands;       // by temperature
  std::vector<std::size_t> window_segment;  // per window: index into segments
  std::vector<double> residual_dph;       // per window
  std::vector<double> model_dph;          // per window
  std::vector<CandidateReport> candidates;  // best first
  // Every candidate as the first round scored it: added alone to the model
  // given, in the order tried. The verdict's group (around the first
  // candidate, the first round's) takes its members' sizes from here (the
  // plan command, report.h): their rows in `candidates` may come from a
  // later round, fitted after the group's leader joined.
  std::vector<CandidateReport> first_round;
  std::vector<std::string> skipped;       // terms that could not be tried, and why
  std::vector<std::string> columns_tried;  // the log's columns tried as causes (each with its rate)
  bool limited = false;                   // the record supported fewer tests than there were candidates
  std::vector<std::vector<std::string>> confounded;  // groups of terms this record cannot tell apart
  std::vector<std::string> confounding_notes;        // why, in plain words, one per group
  // Candidates that explain the same part of the bias though not collinear
  // (confounding.h, separate()): {a, b, note}, found during the ranking.
  std::vector<std::array<std::string, 3>> inseparable;
  std::vector<StepEvent> events;          // bias steps, in time order
  std::string remaining;                  // where structure remains that no candidate explains, or ""
  std::string verdict;
  std::string suggested_model;            // the model with the best significant term, or ""
  // Segments and bands, worst first (indices into segments / bands).
  std::vector<std::size_t> worst_segments() const;
};


NoiseFloor estimate_noise_floor(const fit::AveragedSeries& series, double span_s);
// The Hadamard estimate alone (throws InputError with fewer than 5 triples).
double robust_noise_floor(const fit::AveragedSeries& series);

Diagnosis diagnose(const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                   const fit::EngineInfo& engine, const fit::EngineSettings& settings,
                   const DiagnosisOptions& options = {});

// A share of the excess over the floor that a candidate removes, for people:
// "45 % of the excess", or, where it rounds above 100 % (the fit goes below
// the floor as estimated), "all of the excess (103 %, below the estimated
// floor)". kBelowFloorPct: from where a share reads so.
inline constexpr double kBelowFloorPct = 100.5;
std::string excess_share_text(double reduction_pct);

// Per-segment RMS of a residual, for before/after tables.
std::vector<SegmentReport> segment_rms(const Diagnosis& d, const std::vector<double>& residual);

}  // namespace gyrotherm::studies

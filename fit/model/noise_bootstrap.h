#pragma once
// A parametric bootstrap of the least-squares coefficients from the record's
// identified noise (fit/model/noise_model.h): ols's `intervals=bootstrap`.
//
// For the identified model and for each alternative structure the record
// supports about as well (Akaike's criterion within 2, NoiseModel::
// alternatives), `draws` draws, each:
//
//   1. the amplitudes: log-normal about the structure's estimate, with the
//      REML covariance carried to the logs (a component the record does not
//      pin down is capped at its 95 % bound, τ_c kept between the window and
//      the record's span);
//   2. the windows' noise e* from that model (NoiseModel::draw, exact for
//      every kernel through windows and gaps), and the error of the
//      coefficients δ* = (X̃ᵀX̃)⁻¹X̃ᵀe* on the centred design.
//
// The 95 % interval of each structure is the basic bootstrap one,
// [β̂ − δ*₀.₉₇₅, β̂ − δ*₀.₀₂₅], and the two-sided p-value of β = 0 is
// (1 + #{|δ*| ≥ |β̂|}) / (1 + draws) (Davison & Hinkley, Bootstrap Methods
// and their Application (1997) §2.4, §4.2). Each coefficient takes the
// widest interval (and the largest p-value) among the structures, as the
// analytic intervals take the widest variance: the record cannot tell which
// structure holds. Step 1 is what makes it differ from the sandwich: the
// spread of δ* is that of the estimate under a noise the record is
// uncertain about, so the tails are heavier where the amplitudes are
// poorly known. Every draw comes from `seed`.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "fit/model/noise_model.h"

namespace gyrotherm::fit {

// The structure `model` with its amplitudes drawn as in step 1 above (its
// alternatives dropped). `normal` gives independent N(0, 1) draws.
NoiseModel plausible_noise(const NoiseModel& model, const WindowGrid& grid,
                           const std::function<double()>& normal);

struct NoiseBootstrap {
  // One draws × m matrix per structure (the model's first): δ* of each
  // coefficient of the centred design.
  std::vector<Eigen::MatrixXd> errors;
  // The widest basic bootstrap interval of coefficient j estimated at
  // `estimate` among the structures, at the two-sided level `level`.
  std::pair<double, double> interval(Eigen::Index j, double estimate, double level = 0.95) const;
  // The largest two-sided p-value of coefficient j being 0 among the structures.
  double p_value(Eigen::Index j, double estimate) const;
};

// Where ols's default (intervals=auto) takes the bootstrap rather than the
// analytic sandwich: a short record (fewer than kShortRecordWindows windows,
// where Student-t with Satterthwaite's dof is the roughest approximation) or
// noise whose random walk makes more than half of some coefficient's
// variance (in the model or an alternative structure). On the simulated
// cycle both give 93–99 % there (results/ols_coverage.md).
inline constexpr std::size_t kShortRecordWindows = 200;
bool bootstrap_by_default(const NoiseModel& model, const WindowGrid& grid, const Eigen::MatrixXd& centred);

// `draws` errors per structure of the least-squares coefficients of the
// centred design `centred` (l × m, the grid's windows).
NoiseBootstrap noise_bootstrap(const NoiseModel& model, const WindowGrid& grid,
                               const Eigen::MatrixXd& centred, int draws, std::uint64_t seed);

}  // namespace gyrotherm::fit

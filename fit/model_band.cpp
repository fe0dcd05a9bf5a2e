#include "fit/model_band.h"

#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>

#include "fit/model/formula.h"
#include "fit/model/linear_problem.h"
#include "fit/model/noise_model.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

double CoefficientCovariance::half_width(const Eigen::VectorXd& weights, double* dof) const {
  const Eigen::VectorXd w = to_physical.transpose() * weights;  // on p
  // The noise model that gives the combination the largest variance, at its
  // dof: as noise_sandwich chooses for each coefficient.
  const SandwichParts* widest = &parts.front();
  for (const SandwichParts& part : parts)
    if (part.variance(w) > widest->variance(w)) widest = &part;
  const double d = widest->dof(w);
  if (dof != nullptr) *dof = d;
  const double t95 = boost::math::quantile(boost::math::complement(boost::math::students_t(d), 0.025));
  return t95 * std::sqrt(std::max(0.0, widest->variance(w)));
}

std::optional<CoefficientCovariance> coefficient_covariance(const PreparedData& data,
                                                            const std::vector<const Term*>& terms,
                                                            const std::vector<double>& parameters) {
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                                              static_cast<Eigen::Index>(data.series.size()));
  try {
    const LinearProblem problem(design_matrix(data.derived, terms, parameters), y, term_names(terms));
    const std::shared_ptr<const NoiseContext> noise = identify_record_noise(data, problem);
    if (!noise) return std::nullopt;
    // The centred, scaled design with a column of ones in front: its
    // coefficients p = (α, β) give the physical ones by θ = A·p
    // (b_j = β_j/s_j, b0 = α − Σ β_j·x̄_j/s_j).
    const Eigen::MatrixXd& scaled = problem.scaled_design();
    const Eigen::Index l = scaled.rows(), m = scaled.cols();
    Eigen::MatrixXd x(l, m + 1);
    x.col(0).setOnes();
    x.rightCols(m) = scaled;
    const Eigen::VectorXd mean = problem.design().colwise().mean().transpose();
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m + 1, m + 1);
    a(0, 0) = 1.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      a(0, j + 1) = -mean[j] / problem.scale()[j];
      a(j + 1, j + 1) = 1.0 / problem.scale()[j];
    }
    std::vector<SandwichParts> parts = sandwich_parts(noise->model, noise->grid, x);
    for (SandwichParts& part : parts) part.max_dof += 1.0;  // l − m − 1 with the ones column counted once
    return CoefficientCovariance{std::move(parts), a};
  } catch (const InputError&) {  // a design that cannot be fitted here (FitError), or collinear terms
    return std::nullopt;
  }
}

Band model_band(const CoefficientCovariance& covariance, const PreparedData& data,
                const std::vector<const Term*>& terms, const std::vector<double>& parameters) {
  const Eigen::MatrixXd design = design_matrix(data.derived, terms, parameters);
  Band out;
  out.half_width_dph.resize(static_cast<std::size_t>(design.rows()));
  out.smallest_dof = INFINITY;
  Eigen::VectorXd w(design.cols() + 1);
  w[0] = 1.0;
  for (Eigen::Index p = 0; p < design.rows(); ++p) {
    w.tail(design.cols()) = design.row(p).transpose();
    double dof = 0.0;
    out.half_width_dph[static_cast<std::size_t>(p)] = covariance.half_width(w, &dof);
    out.smallest_dof = std::min(out.smallest_dof, dof);
  }
  return out;
}

}  // namespace gyrotherm::fit

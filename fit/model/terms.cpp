#include "fit/model/terms.h"

#include <cmath>
#include <limits>
#include <span>

namespace gyrotherm::fit {

Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters) {
  const auto l = static_cast<Eigen::Index>(derived.size());
  Eigen::MatrixXd x(l, static_cast<Eigen::Index>(terms.size()));
  for (std::size_t j = 0; j < terms.size(); ++j)
    terms[j]->compute(derived, parameters[j],
                        std::span<double>(x.col(static_cast<Eigen::Index>(j)).data(),
                                          static_cast<std::size_t>(l)));
  return x;
}

std::vector<double> default_parameters(const std::vector<const Term*>& terms) {
  std::vector<double> p(terms.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t j = 0; j < terms.size(); ++j)
    if (terms[j]->parameter) p[j] = std::sqrt(terms[j]->parameter->lower * terms[j]->parameter->upper);
  return p;
}

}  // namespace gyrotherm::fit

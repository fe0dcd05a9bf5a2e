#include "fit/data/prepare.h"

namespace gyrotherm::fit {

PreparedData prepare_data(const Measurement& m, const PipelineOptions& options) {
  PreparedData d;
  d.file = m.file;
  d.raw_samples = m.size();
  std::vector<unsigned char> valid(m.size(), 1);
  if (options.remove_outliers) d.outliers = flag_outliers(m, options.outliers, valid);
  d.series = average_windows(m, valid, options.averaging, &d.averaging);
  d.derived = derive(d.series, options.derivative);
  return d;
}

PreparedData prepare_data(const std::filesystem::path& csv, const PipelineOptions& options) {
  return prepare_data(read_measurement_csv(csv, options.columns), options);
}

}  // namespace gyrotherm::fit

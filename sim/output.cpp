#include "sim/output.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "sim/record_format.h"
#include "sim/util/atomic_file.h"
#include "sim/util/fast_number.h"
#include "sim/util/gnuplot.h"
#include "sim/effects/effect.h"
#include "sim/util/sha256.h"

namespace gyrotherm::sim {
namespace {

nlohmann::json file_entry(const std::filesystem::path& file) {
  if (file.empty()) return nullptr;
  return {{"file", file.string()}, {"sha256", sha256_file_hex(file)}};
}

}  // namespace

std::filesystem::path truth_path_for(const std::filesystem::path& csv) {
  std::filesystem::path out = csv;
  out.replace_extension(".truth.json");
  return out;
}

std::string simulation_csv(const Simulator& simulator, const SimulationResult& r) {
  fmt::memory_buffer out;
  const Scenario& sc = simulator.scenario();
  fmt::format_to(std::back_inserter(out), "# gyrotherm simulate: scenario {}, seed {}\n",
                 sc.name, r.seed);
  fmt::format_to(std::back_inserter(out),
                 "# truth (noise-free bias, true coefficients) in the .truth.json beside this file\n");
  fmt::format_to(std::back_inserter(out), "time_s,chamber_c,case_c,temp_c,temp2_c,gyro_dph,bias_true_dph");
  for (const ChannelConfig& ch : simulator.gyro().channels)
    fmt::format_to(std::back_inserter(out), ",{},{}", ch.column(), ch.truth_column());
  fmt::format_to(std::back_inserter(out), "\n");
  // Each row formatted by hand into one buffer, the digits of
  // "{:.10g},{:.5f},{:.5f},{:.5f},{:.5f},{:.6f},{:.9f}" (sim/util/fast_number.h),
  // then each channel's reading and true value to 10 significant digits.
  std::string text = fmt::to_string(out);
  const std::size_t head = text.size();
  const std::size_t row = 96 + 36 * r.channels.size();
  const std::size_t kRowRoom = (7 + 2 * r.channels.size()) * 350;  // the worst case of every field
  text.resize(head + r.rows() * row + kRowRoom);
  char* p = text.data() + head;
  for (std::size_t k = 0; k < r.rows(); ++k) {
    if (static_cast<std::size_t>(text.data() + text.size() - p) < kRowRoom) {
      const std::size_t used = static_cast<std::size_t>(p - text.data());
      text.resize(text.size() + (r.rows() - k) * row + kRowRoom);
      p = text.data() + used;
    }
    p = write_general(p, r.time_s[k], 10);
    *p++ = ',';
    p = write_fixed(p, r.chamber_c[k], 5);
    *p++ = ',';
    p = write_fixed(p, r.case_c[k], 5);
    *p++ = ',';
    p = write_fixed(p, r.temp_c[k], 5);
    *p++ = ',';
    p = write_fixed(p, r.temp2_c[k], 5);
    *p++ = ',';
    p = write_fixed(p, r.gyro_dph[k], 6);
    *p++ = ',';
    p = write_fixed(p, r.bias_true_dph[k], 9);
    for (const SimulationResult::Channel& ch : r.channels) {
      *p++ = ',';
      p = write_general(p, ch.value[k], 10);
      *p++ = ',';
      p = write_general(p, ch.truth[k], 10);
    }
    *p++ = '\n';
  }
  text.resize(static_cast<std::size_t>(p - text.data()));
  return text;
}

std::string truth_json(const Simulator& simulator, const SimulationResult& r, const RecordIdentity& record) {
  const Scenario& sc = simulator.scenario();
  const GyroConfig& gyro = simulator.gyro();
  const NoiseConfig& nz = gyro.noise;
  nlohmann::ordered_json j;
  j["generator"] = "gyrotherm simulate";
  j["seed"] = r.seed;
  j["scenario"] = {{"name", sc.name}};
  if (!sc.file.empty()) {
    j["scenario"]["file"] = sc.file.string();
    j["scenario"]["sha256"] = sha256_file_hex(sc.file);
  }
  j["rig"] = file_entry(sc.rig_file);
  j["gyro"] = file_entry(sc.gyro_file);
  if (!record.sha256.empty()) j["record"] = {{"file", record.file}, {"sha256", record.sha256}};
  j["sample_rate_hz"] = sc.sample_rate_hz;
  j["rows"] = r.rows();
  j["duration_s"] = r.rows() > 0 ? r.time_s.back() : 0.0;
  j["temperature"] =
      "T is the true anode-side block temperature (the sensor location), degC; dT in degC/s";

  // The true coefficients (sim/gyro_config.h), in registry order.
  const std::map<std::string, double> truth = true_coefficients(gyro);
  nlohmann::ordered_json coefficients;
  coefficients["1"] = truth.at("1");
  nlohmann::ordered_json hidden = nlohmann::ordered_json::object();
  for (const effects::Effect* e : effects::registry()) {
    const auto it = truth.find(std::string(e->name));
    if (it == truth.end()) continue;
    coefficients[std::string(e->name)] = it->second;
    if (!e->hidden()) continue;
    nlohmann::ordered_json h = {{"coefficient", it->second},
                                {"unit", e->coefficient_unit()},
                                {"meaning", std::string(e->meaning)}};
    if (e->parameter) h[std::string(e->parameter->name)] = gyro.parameter_of(*e);
    hidden[std::string(e->name)] = h;
  }
  j["coefficients"] = coefficients;
  j["hidden"] = hidden;
  if (!gyro.channels.empty()) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (const ChannelConfig& ch : gyro.channels) {
      nlohmann::ordered_json c = {{"sensor", std::string(ch.kind->name)}};
      if (ch.kind->has_axes) c["axis"] = std::string(1, ch.axis);
      c["column"] = ch.column();
      c["truth_column"] = ch.truth_column();
      c["unit"] = std::string(ch.kind->unit);
      c["coefficients"] = ch.true_coefficients();
      c["white_noise"] = ch.white_noise;
      channels.push_back(c);
    }
    j["channels"] = channels;
  }
  j["noise"] = {{"arw_deg_per_sqrt_h", nz.arw_deg_per_sqrt_h},
                {"bias_instability_dph", nz.bias_instability_dph},
                {"flicker_tau_min_s", nz.flicker_tau_min_s},
                {"flicker_tau_max_s", nz.flicker_tau_max_s},
                {"flicker_processes", nz.flicker_processes},
                {"rrw_dph_per_sqrt_h", nz.rrw_dph_per_sqrt_h},
                {"quantization_arcsec", nz.quantization_arcsec},
                {"glitch_rate_per_h", nz.glitch_rate_per_h},
                {"glitch_size_dph", nz.glitch_size_dph},
                {"arw_temp_ref_c", nz.arw_temp_ref_c},
                {"arw_temp_coeff_per_c2", nz.arw_temp_coeff_per_c2},
                {"temp_sensor_noise_c", simulator.rig().sensor.noise_c},
                {"temp_sensor_resolution_c", simulator.rig().sensor.resolution_c}};
  const SolverStatistics& st = r.solver;
  j["solver"] = {{"integrator", "CVODE BDF, dense direct linear solver"},
                 {"steps", st.steps},
                 {"rhs_evaluations", st.rhs_evaluations},
                 {"jacobian_evaluations", st.jacobian_evaluations},
                 {"linear_setups", st.linear_setups},
                 {"nonlinear_iterations", st.nonlinear_iterations},
                 {"nonlinear_failures", st.nonlinear_failures},
                 {"error_test_failures", st.error_test_failures},
                 {"restarts", st.restarts}};
  j["energy_j"] = {{"stored_change", r.energy.stored_change_j},
                   {"heater", r.energy.heater_j},
                   {"self_heating", r.energy.self_heating_j},
                   {"lost", r.energy.lost_j},
                   {"residual", r.energy.residual_j()}};
  return j.dump(2) + "\n";
}

void write_simulation(const std::filesystem::path& csv, const Simulator& simulator,
                      const SimulationResult& result) {
  // Render both first (this reads and hashes the input files), then write.
  const std::string csv_text = record_format_for(csv).render(simulator, result);
  const std::string json_text =
      truth_json(simulator, result, {csv.filename().string(), sha256_hex(csv_text)});
  AtomicFile csv_file(csv);
  AtomicFile json_file(truth_path_for(csv));
  csv_file.stream() << csv_text;
  json_file.stream() << json_text;
  json_file.commit();
  csv_file.commit();
}

void plot_simulation(const std::filesystem::path& png, const Simulator& simulator,
                     const SimulationResult& r) {
  const std::size_t window = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::lround(100.0 * simulator.scenario().sample_rate_hz)));
  std::vector<double> hours(r.rows());
  for (std::size_t k = 0; k < r.rows(); ++k) hours[k] = r.time_s[k] / 3600.0;
  const std::vector<double> t_avg = window_means(hours, window);
  const std::vector<double> gyro_avg = window_means(r.gyro_dph, window);
  const std::vector<double> bias_avg = window_means(r.bias_true_dph, window);
  const std::vector<double> temp_avg = window_means(r.temp_c, window);
  const std::vector<double> chamber_avg = window_means(r.chamber_c, window);
  const std::vector<double> case_avg = window_means(r.case_c, window);
  const std::vector<double> temp2_avg = window_means(r.temp2_c, window);

  GnuplotFigure fig(png, 1400, 1000);
  fig.data("t", {"time_h", "chamber_c", "case_c", "temp_c", "temp2_c"},
           {t_avg, chamber_avg, case_avg, temp_avg, temp2_avg});
  fig.data("g", {"time_h", "gyro_dph", "bias_true_dph"}, {t_avg, gyro_avg, bias_avg});
  const std::string title = fmt::format("gyrotherm simulate: {} (seed {})",
                                        simulator.scenario().name, r.seed);
  fig.commands(fmt::format(
      "set multiplot layout 2,1 title '{}'\n"
      "set ylabel 'temperature (°C)'\nset key outside right\n"
      "plot $t using 1:2 with lines lw 1.5 title 'chamber air', "
      "$t using 1:3 with lines lw 1.5 title 'case / shield', "
      "$t using 1:4 with lines lw 2 title 'gyro (Pt800)', "
      "$t using 1:5 with lines lw 1 dt 2 title 'gyro far side'\n"
      "set xlabel 'time (h)'\nset ylabel 'gyro output, 100 s averages (°/h)'\n"
      "plot $g using 1:2 with points pt 7 ps 0.4 title 'measured', "
      "$g using 1:3 with lines lw 2 title 'true bias'\n"
      "unset multiplot",
      title));
  fig.render();
}

}  // namespace gyrotherm::sim

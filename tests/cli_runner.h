#pragma once
// Runs the built gyrotherm binary in a scratch folder and captures its exit
// code, stdout and stderr, for tests of the command-line contract.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

namespace gyrotherm::testing {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A fresh folder per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    // The process id keeps two test runs at once (two work trees) out of each other's folders.
    path_ = std::filesystem::temp_directory_path() / ("gyrotherm_test_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  std::size_t file_count() const {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(path_),
                                                  std::filesystem::directory_iterator{}));
  }

 private:
  std::filesystem::path path_;
};

// Runs `command` with the shell in dir, capturing exit code, stdout and stderr.
inline CliResult run_shell(const ScratchDir& dir, const std::string& command) {
  const auto out = dir / ".stdout", err = dir / ".stderr";
  const std::string full = "cd '" + dir.path().string() + "' && " + command + " > '" +
                           out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(full.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// args are passed to the shell as written (quote them yourself).
inline CliResult run_cli(const ScratchDir& dir, const std::string& args) {
  return run_shell(dir, std::string("'") + GYROTHERM_CLI + "' " + args);
}

// `args` is refused as bad input: exit code 2 and a message holding `expected`.
inline void expect_refused(const ScratchDir& dir, const std::string& args, const std::string& expected) {
  const CliResult r = run_cli(dir, args);
  EXPECT_EQ(r.exit_code, 2) << args;
  EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
}

// A 1 Hz log of `hours` whose temperature ramps from `from_c` to `to_c`, with
// one gyro channel per entry of `slopes` (°/h per °C, header `columns` after
// time_s,temp_c) and white noise of 0.5 °/h, from `seed`.
inline void write_ramp_log(const std::filesystem::path& csv, const std::string& columns,
                           const std::vector<double>& slopes, double hours, double from_c, double to_c,
                           unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::ofstream out(csv);
  out << "time_s,temp_c," << columns << "\n";
  const int rows = static_cast<int>(hours * 3600.0);
  for (int k = 0; k < rows; ++k) {
    const double temp = from_c + (to_c - from_c) * k / static_cast<double>(rows);
    out << k << "," << temp;
    for (const double slope : slopes) out << "," << slope * temp + noise(rng);
    out << "\n";
  }
}

// Whether diagnose's `confounded` groups put terms a and b in one group.
inline bool in_one_group(const nlohmann::json& groups, const std::string& a, const std::string& b) {
  for (const nlohmann::json& g : groups) {
    const auto names = g.get<std::vector<std::string>>();
    if (std::find(names.begin(), names.end(), a) != names.end() && std::find(names.begin(), names.end(), b) != names.end())
      return true;
  }
  return false;
}

inline std::string source_path(const std::string& relative) {
  return std::string(GYROTHERM_SOURCE_DIR) + "/" + relative;
}

// `gyrotherm simulate scenarios/NAME.toml EXTRA -o OUT` in dir; fails the test
// (with simulate's message) if it fails.
inline void simulate_shipped(const ScratchDir& dir, const std::string& name, const std::string& extra,
                             const std::string& out) {
  const CliResult r = run_cli(dir, "simulate " + source_path("scenarios/" + name + ".toml") + " " +
                                       extra + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

// A log made from a simulated record `from` (its columns time_s, chamber_c,
// case_c, temp_c, temp2_c, gyro_dph, … are $1 … in awk): time_s, temp_c and
// one column per (name, awk expression), e.g. {"gx", "$6"}, {"gy", "-$6"}.
inline void write_columns(const ScratchDir& dir, const std::string& from, const std::string& to,
                          const std::vector<std::pair<std::string, std::string>>& columns) {
  std::string names, values;
  for (const auto& [name, expression] : columns) {
    names += ",\"" + name + "\"";
    values += "," + expression;
  }
  const CliResult r = run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"} /^#/{next} /^time/{print $1,$4" + names +
                                         ";next} {print $1,$4" + values + "}' " + from + " | tee " + to);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

// A 2.3 h profile (20 → 60 → −20 °C with 30 min holds) on the shipped shield
// rig: enough 100 s windows to fit, a few ms to simulate. `extra` is appended
// (e.g. a [spread] table).
inline std::string short_scenario_text(int seed, const std::string& gyro_file,
                                       const std::string& extra = "") {
  return "name = \"short\"\nseed = " + std::to_string(seed) + "\nstart_c = 20.0\nrig = \"" +
         source_path("scenarios/rig_shield.toml") + "\"\ngyro = \"" + gyro_file + "\"\n" +
         "[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = 30\n"
         "[[segment]]\nkind = \"ramp\"\ntarget_c = 60.0\nrate_c_per_min = 5.0\n"
         "[[segment]]\nkind = \"hold\"\ntemp_c = 60.0\nduration_min = 30\n"
         "[[segment]]\nkind = \"ramp\"\ntarget_c = -20.0\nrate_c_per_min = 5.0\n"
         "[[segment]]\nkind = \"hold\"\ntemp_c = -20.0\nduration_min = 30\n" +
         extra;
}

}  // namespace gyrotherm::testing

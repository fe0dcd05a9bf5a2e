#include "fit/engines/engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

const char* to_string(Termination t) {
  switch (t) {
    case Termination::exact: return "exact";
    case Termination::target_reached: return "target_reached";
    case Termination::budget_exhausted: return "budget_exhausted";
    case Termination::max_iterations: return "max_iterations";
    case Termination::converged: return "converged";
    case Termination::stopped: return "stopped";
  }
  return "?";
}

std::string FitResult::brief_report() const {
  return fmt::format("{}: sigma {:.6g}, {} evaluations, {} iterations, {:.3g} s, {} ({})", engine,
                     objective, evaluations, iterations, seconds, to_string(termination), message);
}

Evaluator::Evaluator(const LinearProblem& problem, long max_evaluations, double target_objective)
    : problem_(problem),
      max_evaluations_(max_evaluations),
      target_(target_objective),
      best_z_(problem.dimension(), 0.0),
      clamped_(problem.dimension(), 0.0) {}

double Evaluator::operator()(std::span<const double> z) {
  for (std::size_t j = 0; j < clamped_.size(); ++j) clamped_[j] = std::clamp(z[j], -1.0, 1.0);
  const double f = problem_.objective(clamped_);
  ++evaluations_;
  if (f < best_) {
    best_ = f;
    best_z_ = clamped_;
    history_.push_back({evaluations_, f});
  }
  return f;
}

FitResult Evaluator::result(std::string engine, long iterations, Termination fallback,
                            std::string message) const {
  FitResult r;
  r.engine = std::move(engine);
  r.z = best_z_;
  r.objective = best_;
  r.evaluations = evaluations_;
  r.iterations = iterations;
  r.history = history_;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  if (target_reached())
    r.termination = Termination::target_reached;
  else if (!budget_left())
    r.termination = Termination::budget_exhausted;
  else
    r.termination = fallback;
  r.message = std::move(message);
  return r;
}

const std::vector<EngineInfo>& engine_registry() {
  static const std::vector<EngineInfo> registry = [] {
    std::vector<EngineInfo> r = {ols_engine_info(), stepwise_engine_info(), afsa_engine_info(),
                                 iafsa_engine_info()};
    for (EngineInfo& info : pagmo_engine_infos()) r.push_back(std::move(info));
    return r;
  }();
  return registry;
}

const EngineInfo& find_engine(std::string_view name) {
  for (const EngineInfo& info : engine_registry())
    if (info.name == name) return info;
  std::string known;
  for (const EngineInfo& info : engine_registry()) known += (known.empty() ? "" : ", ") + info.name;
  throw InputError(fmt::format("unknown engine '{}' (known engines: {})", name, known));
}

OptionReader::OptionReader(std::string engine, const std::map<std::string, std::string>& options)
    : engine_(std::move(engine)), options_(options) {}

namespace {
double parse_number(const std::string& engine, const std::string& key, const std::string& text) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
    throw InputError(fmt::format("{} option {}={}: expected a number", engine, key, text));
  return v;
}
}  // namespace

void OptionReader::integer(const std::string& key, int& value, int lo, int hi) {
  known_.push_back(key);
  const auto it = options_.find(key);
  if (it == options_.end()) return;
  const double v = parse_number(engine_, key, it->second);
  if (v != std::floor(v) || v < lo || v > hi)
    throw InputError(fmt::format("{} option {}={}: must be a whole number from {} to {}", engine_,
                                 key, it->second, lo, hi));
  value = static_cast<int>(v);
}

void OptionReader::integer_or_auto(const std::string& key, int& value, int lo, int hi) {
  const auto it = options_.find(key);
  if (it != options_.end() && it->second == "auto") {
    known_.push_back(key);
    value = 0;
    return;
  }
  try {
    integer(key, value, lo, hi);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{} (or auto)", e.what()));
  }
}

void OptionReader::real(const std::string& key, double& value, double lo, double hi,
                        bool lo_open) {
  known_.push_back(key);
  const auto it = options_.find(key);
  if (it == options_.end()) return;
  const double v = parse_number(engine_, key, it->second);
  if ((lo_open ? v <= lo : v < lo) || v > hi)
    throw InputError(fmt::format("{} option {}={}: must be {} {} and <= {}", engine_, key,
                                 it->second, lo_open ? ">" : ">=", lo, hi));
  value = v;
}

void OptionReader::choice(const std::string& key, std::string& value,
                          const std::vector<std::string>& allowed) {
  known_.push_back(key);
  const auto it = options_.find(key);
  if (it == options_.end()) return;
  if (std::find(allowed.begin(), allowed.end(), it->second) == allowed.end()) {
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw InputError(fmt::format("{} option {}={}: must be one of {}", engine_, key, it->second, list));
  }
  value = it->second;
}

void OptionReader::finish() const {
  for (const auto& [key, value] : options_) {
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::string list;
    for (const std::string& k : known_) list += (list.empty() ? "" : ", ") + k;
    throw InputError(fmt::format("{} has no option '{}' (its options: {})", engine_, key,
                                 list.empty() ? "none" : list));
  }
}

void check_stopping_rules(std::string_view engine, long max_evaluations, double target_objective) {
  if (max_evaluations < 1)
    throw InputError(
        fmt::format("{} max_evaluations={}: must be at least 1", engine, max_evaluations));
  if (!(target_objective >= 0.0) || !std::isfinite(target_objective))
    throw InputError(fmt::format("{} target_objective={}: must be a finite number >= 0", engine,
                                 target_objective));
}

}  // namespace gyrotherm::fit

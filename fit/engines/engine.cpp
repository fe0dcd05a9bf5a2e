#include "fit/engines/engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

KeyValue parse_key_value(const std::string& text, const std::string& option, bool scoped) {
  KeyValue kv;
  std::size_t from = 0;
  if (scoped) {
    const auto colon = text.find(':');
    if (colon != std::string::npos && colon > 0 && colon < text.find('=')) {
      kv.scope = text.substr(0, colon);
      from = colon + 1;
    }
  }
  const auto eq = text.find('=', from);
  if ((scoped && kv.scope.empty()) || eq == std::string::npos || eq == from)
    throw InputError(fmt::format("{} {}: expected {}KEY=VALUE (see 'gyrotherm engines')", option, text,
                                 scoped ? "ENGINE:" : ""));
  kv.key = text.substr(from, eq - from);
  kv.value = text.substr(eq + 1);
  return kv;
}

EngineSettings engine_settings(std::uint64_t seed, long budget, double target,
                               const std::vector<std::string>& key_values) {
  EngineSettings s;
  s.seed = seed;
  if (budget < 0) throw InputError(fmt::format("--budget {}: must be >= 0", budget));
  s.max_evaluations = budget;
  if (!(target >= 0.0) || !std::isfinite(target))
    throw InputError(fmt::format("--target {}: must be a finite sigma >= 0", target));
  s.target_objective = target;
  for (const std::string& text : key_values) {
    const KeyValue kv = parse_key_value(text, "--option", false);
    s.options[kv.key] = kv.value;
  }
  return s;
}

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
    std::vector<EngineInfo> r = {ols_engine_info(), gls_engine_info(), stepwise_engine_info(), afsa_engine_info(),
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

void check_stopping_rules(std::string_view engine, long max_evaluations, double target_objective) {
  if (max_evaluations < 1)
    throw InputError(
        fmt::format("{} max_evaluations={}: must be at least 1", engine, max_evaluations));
  if (!(target_objective >= 0.0) || !std::isfinite(target_objective))
    throw InputError(fmt::format("{} target_objective={}: must be a finite number >= 0", engine,
                                 target_objective));
}

}  // namespace gyrotherm::fit

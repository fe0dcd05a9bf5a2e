#include "fit/engines/engine.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "fit/model/noise_model.h"
#include "sim/util/input_error.h"
#include "sim/util/format.h"

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
  // In the enum's order.
  static constexpr std::array<const char*, 6> names = {"exact",          "target_reached", "budget_exhausted",
                                                       "max_iterations", "converged",      "stopped"};
  return names[static_cast<std::size_t>(t)];
}

const char* to_string(IntervalKind k) {
  // In the enum's order.
  static constexpr std::array<const char*, 6> names = {"none", "noise_bootstrap", "noise_covariance",
                                                       "gls",  "newey_west",      "cosine"};
  return names[static_cast<std::size_t>(k)];
}

std::string interval_method_text(const IntervalMethod& m, const NoiseModel* noise) {
  const std::string model = noise ? noise->description() : std::string("none");
  std::string out;
  switch (m.kind) {
    case IntervalKind::none: return "";
    case IntervalKind::noise_bootstrap:
      out = fmt::format("parametric bootstrap, {} draws from each noise structure the record supports ({}), "
                        "amplitudes drawn from their uncertainty; the widest basic interval",
                        m.draws, model);
      break;
    case IntervalKind::noise_covariance:
      out = fmt::format("least-squares covariance under the identified noise ({}); Student t with "
                        "Satterthwaite dof {:.3g}", model, m.dof);
      break;
    case IntervalKind::gls:
      out = fmt::format("generalised least squares under the identified noise ({}); the variance {}; Student t "
                        "with Satterthwaite dof {:.3g}", model,
                        m.widest_of > 0
                            ? fmt::format("the widest under the {} noise models the record supports alike", m.widest_of)
                            : std::string("under that model"),
                        m.dof);
      break;
    case IntervalKind::newey_west:
    case IntervalKind::cosine:
      out = fmt::format("{}{}; Student t with {:g} dof",
                        m.no_noise_model ? "no noise model could be identified on this record (too few windows for "
                                           "the terms): " : "",
                        m.kind == IntervalKind::newey_west
                            ? fmt::format("Newey-West HAC pre-whitened by a VAR(1) (Andrews-Monahan), Bartlett kernel "
                                          "with {} by Andrews' AR(1) rule", counted(static_cast<std::size_t>(m.lags), "lag"))
                            : fmt::format("equal-weighted cosine long-run variance (Lazarus, Lewis, Stock & Watson "
                                          "2018) on the {} lowest frequencies", m.lags),
                        m.dof);
      break;
  }
  if (m.has_lag1) out += fmt::format("; residual lag-1 autocorrelation {:.2f}", m.lag1_autocorrelation);
  if (m.linearised_parameters) out += "; with the fitted parameters' uncertainty (linearised)";
  return out;
}

std::string run_text(const FitResult& r) {
  const RunDetail& d = r.detail;
  switch (d.kind) {
    case RunDetail::Kind::qr: return "least squares by column-pivoting QR";
    case RunDetail::Kind::gls: return "generalised least squares by the noise's semi-separable Cholesky factor";
    case RunDetail::Kind::gls_without_noise:
      return "no noise model identified on this record (too few windows for the terms): ordinary least squares";
    case RunDetail::Kind::stepwise: {
      std::string steps;
      for (const RunDetail::Step& s : d.steps)
        steps += s.entered ? fmt::format("{}+{}", steps.empty() ? "" : ", ", s.term) : fmt::format(", -{}", s.term);
      return fmt::format("kept {} (steps: {})", d.kept.empty() ? "no terms" : fmt::format("{}", fmt::join(d.kept, ", ")),
                         steps.empty() ? "none" : steps);
    }
    case RunDetail::Kind::fish_swarm:
      return fmt::format("{} fish, {} of {} iterations; Visual {:.3g}, Step {:.3g} (box widths)", d.fish,
                         r.iterations, d.iteration_limit, d.visual, d.step);
    case RunDetail::Kind::pagmo: {
      std::string text = fmt::format("pagmo {}, population {}, seed {}", r.engine, d.population, d.seed);
      switch (d.end) {
        case RunDetail::End::budget_or_target: break;
        case RunDetail::End::generation_limit: text += fmt::format("; generation limit {}", d.generation_limit); break;
        case RunDetail::End::collapsed: text += "; population collapsed (xtol/ftol)"; break;
        case RunDetail::End::non_finite:
          text += "; the algorithm proposed a non-finite point (step size underflow)";
          break;
        case RunDetail::End::observer: text += "; stopped by the observer"; break;
      }
      return text;
    }
  }
  return {};
}

std::string FitResult::brief_report() const {
  return fmt::format("{}: sigma {:.6g}, {} evaluations, {} iterations, {:.3g} s, {} ({})", engine,
                     objective, evaluations, iterations, seconds, to_string(termination), run_text(*this));
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

FitResult Evaluator::result(std::string engine, long iterations, Termination fallback, RunDetail detail) const {
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
  r.detail = std::move(detail);
  return r;
}

const std::vector<EngineInfo>& engine_registry() {
  static const std::vector<EngineInfo> registry = [] {
    std::vector<EngineInfo> r;
    const auto add = [&r](std::vector<EngineInfo> infos) {
      for (EngineInfo& info : infos) r.push_back(std::move(info));
    };
#define ENGINE(name) add({name##_engine_info()});
#define ENGINE_FAMILY(name) add(name##_engine_infos());
#include "fit/engines/engines.def"
#undef ENGINE
#undef ENGINE_FAMILY
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

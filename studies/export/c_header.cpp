#include "studies/export/c_header.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "fit/model/formula.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {
namespace {

std::string number(double v) { return fmt::format("{:.17g}", v); }

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

// A term's C form with its parameter written in: {theta} → the value.
std::string c_text(std::string_view form, double parameter) {
  return fmt::format(fmt::runtime(form), fmt::arg("theta", number(parameter)));
}

// The statements that set x[j], the j-th term's regressor at a window
// (sim/effects/effect.h, CForm).
std::string c_statement(const fit::Term& term, std::size_t j, double parameter) {
  if (term.c_form.expression.empty())
    throw InputError(fmt::format("--format c: the term '{}' has no C form{}", term.name,
                                 term.column.empty() ? "" : " (a log column: the C interface has no such input)"));
  if (!term.c_form.stateful()) return fmt::format("  x[{}] = {};\n", j, c_text(term.c_form.expression, parameter));
  return fmt::format(
      "  if (first) {{\n    x[{0}] = {1};\n  }} else {{\n    const double prev = x[{0}];\n    x[{0}] = {2};\n  }}\n", j,
      c_text(term.c_form.initial, parameter), c_text(term.c_form.expression, parameter));
}

constexpr const char* kTemplate = R"C(
#ifndef @GUARD@
#define @GUARD@

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define @P@_GLITCH_CAPACITY @CAPACITY@

typedef struct {
  /* the glitch rule's trailing window (a ring buffer) */
  double recent_t[@P@_GLITCH_CAPACITY], recent_x[@P@_GLITCH_CAPACITY], scratch[@P@_GLITCH_CAPACITY];
  size_t recent_first, recent_count;
  /* the window being filled */
  int started;
  double start_time, last_time, run_start, window_end;
  size_t run, window_samples, window_valid;
  double sum_time, sum_temp, sum_temp2;
  /* the latest closed window, and each term's regressor there */
  int has_window;
  double bias, prev_time, prev_rel, prev_temp, prev_rate;
  size_t prev_run;
  double x[@SLOTS@];
} @P@_state;

static inline void @P@_init(@P@_state *s) {
  size_t i;
  for (i = 0; i < @P@_GLITCH_CAPACITY; ++i) s->recent_t[i] = s->recent_x[i] = s->scratch[i] = 0.0;
  s->recent_first = s->recent_count = 0;
  s->started = 0;
  s->start_time = s->last_time = s->run_start = s->window_end = 0.0;
  s->run = s->window_samples = s->window_valid = 0;
  s->sum_time = s->sum_temp = s->sum_temp2 = 0.0;
  s->has_window = 0;
  s->bias = s->prev_time = s->prev_rel = s->prev_temp = s->prev_rate = 0.0;
  s->prev_run = 0;
  for (i = 0; i < @SLOTS@; ++i) s->x[i] = 0.0;
}

/* The k-th smallest of a[0..n) (0-based); a is reordered so that a[0..k) are
   no larger. Hoare's selection. */
static inline double @P@_select(double *a, size_t n, size_t k) {
  size_t lo = 0, hi = n - 1;
  while (lo < hi) {
    const double pivot = a[lo + (hi - lo) / 2];
    size_t i = lo, j = hi;
    while (i <= j) {
      while (a[i] < pivot) ++i;
      while (a[j] > pivot) --j;
      if (i <= j) {
        const double t = a[i];
        a[i] = a[j];
        a[j] = t;
        ++i;
        if (j == 0) break;
        --j;
      }
    }
    if (k <= j) hi = j;
    else if (k >= i) lo = i;
    else break;
  }
  return a[k];
}

/* The median (the mean of the two middle values for an even count). */
static inline double @P@_median(double *a, size_t n) {
  const size_t half = n / 2;
  const double upper = @P@_select(a, n, half);
  double lower;
  size_t i;
  if (n % 2 == 1) return upper;
  lower = a[0];
  for (i = 1; i < half; ++i)
    if (a[i] > lower) lower = a[i];
  return 0.5 * (lower + upper);
}

/* Hampel's test on the trailing window: 1 if the sample is a glitch. */
static inline int @P@_glitch(@P@_state *s, double t, double x) {
  size_t i, n;
  double median, deviation, scale;
  while (s->recent_count > 0 && t - s->recent_t[s->recent_first] > @OUTLIER_WINDOW@) {
    s->recent_first = (s->recent_first + 1) % @P@_GLITCH_CAPACITY;
    --s->recent_count;
  }
  if (s->recent_count == @P@_GLITCH_CAPACITY) {
    s->recent_first = (s->recent_first + 1) % @P@_GLITCH_CAPACITY;
    --s->recent_count;
  }
  i = (s->recent_first + s->recent_count) % @P@_GLITCH_CAPACITY;
  s->recent_t[i] = t;
  s->recent_x[i] = x;
  n = ++s->recent_count;
  if (n < 3) return 0;
  for (i = 0; i < n; ++i) s->scratch[i] = s->recent_x[(s->recent_first + i) % @P@_GLITCH_CAPACITY];
  median = @P@_median(s->scratch, n);
  deviation = fabs(x - median);
  if (!(deviation > @THRESHOLD@ * @FLOOR@)) return 0;
  for (i = 0; i < n; ++i) s->scratch[i] = fabs(s->recent_x[(s->recent_first + i) % @P@_GLITCH_CAPACITY] - median);
  scale = 1.4826 * @P@_median(s->scratch, n);
  if (scale < @FLOOR@) scale = @FLOOR@;
  return deviation > @THRESHOLD@ * scale;
}

/* The model at a window (T, T2: its temperatures, °C; rate, accel: their
   backward derivatives; rel: s since the first sample). x holds each term's
   regressor, set here; a term with a state reads its value at the previous
   window there first (h: s since that window, slope: (T - prev_T) / h;
   first: there is none). */
static inline double @P@_model(double *x, int first, double T, double T2, double rate, double accel, double rel,
                               double h, double slope, double prev_T) {
  double B = @INTERCEPT@;
  (void)x; (void)first; (void)T; (void)T2; (void)rate; (void)accel; (void)rel; (void)h; (void)slope; (void)prev_T;
@TERMS@  return B;
}

/* A window closes: its backward derivatives and bias. */
static inline void @P@_close(@P@_state *s, double t, double T, double T2, size_t run) {
  const double rel = t - s->start_time;
  double rate = 0.0, accel = 0.0, h = 0.0, slope = 0.0;
  if (s->has_window) {
    h = rel - s->prev_rel;
    slope = (T - s->prev_temp) / h;
    if (s->prev_run == run || t - s->prev_time <= @SPAN@) {
      rate = (T - s->prev_temp) / (t - s->prev_time);
      accel = (rate - s->prev_rate) / (t - s->prev_time);
    }
  }
  s->bias = @P@_model(s->x, !s->has_window, T, T2, rate, accel, rel, h, slope, s->prev_temp);
  s->has_window = 1;
  s->prev_time = t;
  s->prev_rel = rel;
  s->prev_temp = T;
  s->prev_rate = rate;
  s->prev_run = run;
}

static inline void @P@_close_window(@P@_state *s) {
  double needed;
  if (s->window_samples == 0) return;
  needed = @BURSTS@ ? @MIN_FILL@ * (double)s->window_samples : @MIN_VALID@;
  if (s->window_valid > 0 && (double)s->window_valid >= needed) {
    const double n = (double)s->window_valid;
    @P@_close(s, s->run_start + s->sum_time / n, s->sum_temp / n, s->sum_temp2 / n, s->run);
  }
  s->window_samples = s->window_valid = 0;
  s->sum_time = s->sum_temp = s->sum_temp2 = 0.0;
}

static inline void @P@_start_window(@P@_state *s, double t) {
  double j;
  if (@BURSTS@) {
    s->window_end = HUGE_VAL;
    return;
  }
  j = floor((t - s->run_start) / @WINDOW@);
  while (s->run_start + (j + 1.0) * @WINDOW@ <= t) j += 1.0;
  while (j > 0.0 && s->run_start + j * @WINDOW@ > t) j -= 1.0;
  s->window_end = s->run_start + (j + 1.0) * @WINDOW@;
}

static inline double @P@_step(@P@_state *s, double t, double T, double T2, int valid) {
  if (!s->started) {
    s->started = 1;
    s->start_time = s->run_start = t;
    @P@_start_window(s, t);
  } else {
    const double step = t - s->last_time;
    if (step > @GAP_FACTOR@ * @DT@ || step > @WINDOW@) {
      @P@_close_window(s);
      ++s->run;
      s->run_start = t;
      @P@_start_window(s, t);
    } else if (t >= s->window_end) {
      @P@_close_window(s);
      @P@_start_window(s, t);
    }
  }
  s->last_time = t;
  ++s->window_samples;
  if (valid) {
    ++s->window_valid;
    s->sum_time += t - s->run_start;
    s->sum_temp += T;
    s->sum_temp2 += T2;
  }
  if (s->has_window) return s->bias;
  /* Before any window closes: this sample as a window of its own. */
  {
    double own[@SLOTS@] = {0.0};
    return @P@_model(own, 1, T, T2, 0.0, 0.0, t - s->start_time, 0.0, 0.0, T);
  }
}

/* The model's bias (°/h) for this sample; no glitch rule (no gyro input). */
static inline double @P@_update(@P@_state *s, double time_s, double temp_c, double temp2_c) {
  return @P@_step(s, time_s, temp_c, temp2_c, 1);
}

/* The same with the gyro output (°/h): the fit's glitch rule applies. */
static inline double @P@_update_gyro(@P@_state *s, double time_s, double temp_c, double temp2_c, double gyro_dph) {
  const int glitch = @REMOVE_OUTLIERS@ ? @P@_glitch(s, time_s, gyro_dph) : 0;
  return @P@_step(s, time_s, temp_c, temp2_c, !glitch);
}

#endif
)C";

}  // namespace

std::string c_header(const fit::SavedFit& fit, const fit::CausalSettings& settings, const std::string& prefix,
                     const ExportHeader& header) {
  if (prefix.empty() || !(std::isalpha(static_cast<unsigned char>(prefix[0])) || prefix[0] == '_') ||
      !std::all_of(prefix.begin(), prefix.end(),
                   [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }))
    throw InputError(fmt::format("--prefix '{}': expected a C identifier (letters, digits, _)", prefix));
  std::string terms;
  std::string coefficients;
  // Outside the fitted range the temperature terms read the range's edge
  // (fit/model/terms.h design_matrix_held), in a block whose T and prev_T
  // are the held ones.
  if (settings.hold_c)
    terms += fmt::format(
        "  const double T_held = T < {0} ? {0} : (T > {1} ? {1} : T);\n"
        "  const double prev_T_held = prev_T < {0} ? {0} : (prev_T > {1} ? {1} : prev_T);\n"
        "  (void)T_held; (void)prev_T_held;\n",
        number(settings.hold_c->first), number(settings.hold_c->second));
  for (std::size_t j = 0; j < fit.terms.size(); ++j) {
    const fit::Term& t = *fit.terms[j];
    const bool held = settings.hold_c && fit::reads_temperature_level(&t);
    if (held)
      terms += "  {\n    const double T = T_held, prev_T = prev_T_held;\n    (void)T; (void)prev_T;\n" +
               c_statement(t, j, fit.parameters[j]) + "  }\n";
    else
      terms += c_statement(t, j, fit.parameters[j]);
    terms += fmt::format("  B += {} * x[{}];\n", number(fit.coefficients.b[j]), j);
    coefficients += fmt::format(" *   {:<10} {:>24} {}{}\n", t.name, number(fit.coefficients.b[j]),
                                t.coefficient_unit(),
                                t.parameter ? fmt::format("  ({} = {})", t.parameter->name, number(fit.parameters[j]))
                                            : "");
  }
  const fit::AveragingOptions& a = fit.pipeline.averaging;
  const double buffer = std::ceil(2.0 * fit.pipeline.outliers.window_s / settings.sample_interval_s) + 8.0;
  std::string range = "not saved in the fit";
  if (fit.temp_range_c)
    range = fmt::format("{:.2f} to {:.2f} °C (the window temperatures it was fitted on; outside, its "
                        "temperature terms read the range's edge, as compensate and the firmwares hold them)",
                        fit.temp_range_c->first, fit.temp_range_c->second);
  std::string out = fmt::format(
      "/*\n"
      " * gyrotherm export: a real-time gyro bias compensator, generated from a saved fit.\n"
      " *\n"
      " * Fit {} (SHA-256 {}), engine {}, exported {}.\n"
      " * Model: B = b0 + {} (°/h), evaluated on the averaging windows:\n"
      " *   b0         {:>24} °/h\n{}"
      " * Valid: {}.\n"
      " * Windows of {} s (gap above {} x {} s or {} s; a window needs {} of its samples), backward\n"
      " * differences across gaps up to {} s, {}glitch rule: {}.\n"
      " *\n"
      " * Each sample gets B of the latest window closed before it (before any: of the sample itself):\n"
      " * the real-time compensator of gyrotherm's fit/causal_compensator.h, as `gyrotherm compensate\n"
      " * --causal` runs it. @P@_update(state, time_s, temp_c, temp2_c) returns B in °/h (no glitch rule:\n"
      " * it does not see the gyro); @P@_update_gyro(..., gyro_dph) also applies the glitch rule.\n"
      " * Start with @P@_init(&state) on a @P@_state.\n"
      " * Compensated output = gyro - B. Time in s, temperatures in °C; C99, no allocation, no I/O.\n"
      " */\n",
      header.fit_file, header.fit_sha256, header.engine, header.date_utc, fit::formula_text(fit.terms),
      number(fit.coefficients.intercept), coefficients, range, a.window_s, a.gap_factor,
      fmt::format("{:.6g}", settings.sample_interval_s), a.window_s, settings.bursts ? "half" : fmt::format("{:g} %", 100.0 * a.min_fill),
      fit.pipeline.derivative_span_s, settings.bursts ? "bursts (each gap-free run one window), " : "",
      fit.pipeline.remove_outliers
          ? fmt::format("trailing {} s, {} robust sigmas, floor {} °/h", fit.pipeline.outliers.window_s,
                        fit.pipeline.outliers.threshold, number(settings.outlier_floor_dph))
          : "none");
  out += kTemplate;
  std::string guard = prefix + "_H";
  std::transform(guard.begin(), guard.end(), guard.begin(),
                 [](char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); });
  replace_all(out, "@GUARD@", guard);
  replace_all(out, "@CAPACITY@", fmt::format("{}", static_cast<long>(buffer)));
  replace_all(out, "@OUTLIER_WINDOW@", number(fit.pipeline.outliers.window_s));
  replace_all(out, "@THRESHOLD@", number(fit.pipeline.outliers.threshold));
  replace_all(out, "@FLOOR@", number(settings.outlier_floor_dph));
  replace_all(out, "@INTERCEPT@", number(fit.coefficients.intercept));
  replace_all(out, "@TERMS@", terms);
  replace_all(out, "@SLOTS@", fmt::format("{}", std::max<std::size_t>(1, fit.terms.size())));
  replace_all(out, "@SPAN@", number(fit.pipeline.derivative_span_s));
  replace_all(out, "@BURSTS@", settings.bursts ? "1" : "0");
  replace_all(out, "@MIN_FILL@", number(a.min_fill));
  replace_all(out, "@MIN_VALID@", number(a.min_fill * a.window_s / settings.sample_interval_s));
  replace_all(out, "@WINDOW@", number(a.window_s));
  replace_all(out, "@GAP_FACTOR@", number(a.gap_factor));
  replace_all(out, "@DT@", number(settings.sample_interval_s));
  replace_all(out, "@REMOVE_OUTLIERS@", fit.pipeline.remove_outliers ? "1" : "0");
  replace_all(out, "@P@", prefix);
  return out;
}

ExporterInfo c_exporter() {
  return {"c", "a C99 header (the whole model, as compensate --causal runs it, sample by sample)",
          [](const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
            // Another sensor's fit is refused before a channel is asked for: none of its channels would do.
            if (const fit::SensorKind& kind = fits.front().pipeline.columns.units.kind(); !kind.is_gyro)
              throw InputError(fmt::format("{}: the {}'s fit: the C compensator is a gyro's (°/h), so far; export "
                                           "it with --format px4",
                                           r.fit_file, kind.noun));
            const fit::SavedFit& f = chosen_channel(r, fits);
            if (!f.sample_interval_s || !f.bursts || (f.pipeline.remove_outliers && !f.outlier_floor_dph))
              throw InputError(fmt::format("{}: the fit lacks data.sample_interval_s, data.bursts or "
                                           "data.outlier_floor_dph (written by an earlier gyrotherm); fit again to "
                                           "export it in C",
                                           r.fit_file));
            fit::CausalSettings settings;
            settings.sample_interval_s = *f.sample_interval_s;
            settings.bursts = *f.bursts;
            settings.outlier_floor_dph = f.outlier_floor_dph.value_or(0.0);
            settings.hold_c = f.temp_range_c;  // held at the range's edge, as compensate holds it
            ExportOutput out;
            out.text = c_header(f, settings, r.prefix, export_header(r, f));
            out.lines.push_back(fmt::format(
                "wrote {}: {}_update() gives B = b0 + {} (°/h) sample by sample, as compensate --causal{}", r.output,
                r.prefix, fit::formula_text(f.terms),
                f.pipeline.remove_outliers ? fmt::format("; {}_update_gyro() also applies the glitch rule", r.prefix)
                                           : ""));
            warn_if_little_compensation(f, f.instability_after_dph, &out);
            return out;
          },
          "//", true};
}

}  // namespace gyrotherm::studies

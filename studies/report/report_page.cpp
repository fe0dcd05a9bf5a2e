#include "studies/report/report_page.h"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <map>

#include "sim/util/input_error.h"
#include "sim/util/sha256.h"
#include "studies/export/exporter.h"

#ifndef GYROTHERM_VERSION
#define GYROTHERM_VERSION "unknown"
#endif

namespace gyrotherm::studies {

namespace {

using Json = nlohmann::ordered_json;

std::string escape(std::string_view s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A JSON pointer's element of the twin ("/channels/0/fit/coefficients/T").
const Json* at(const Json& twin, const std::string& pointer) {
  const Json::json_pointer p(pointer);
  return twin.contains(p) ? &twin.at(p) : nullptr;
}

// The number the cell shows, as the twin holds it (6 significant digits).
std::string number_text(const Json* v) {
  if (v == nullptr || !v->is_number()) return "—";
  if (v->is_number_unsigned()) return fmt::format("{}", v->get<std::uint64_t>());  // counts, ids
  if (v->is_number_integer()) return fmt::format("{}", v->get<std::int64_t>());
  return fmt::format("{:.6g}", v->get<double>());
}

// A table cell with the twin's number at `pointer`, naming it.
std::string cell(const Json& twin, const std::string& pointer) {
  return fmt::format("<td class=\"n\" data-json=\"{}\">{}</td>", escape(pointer), number_text(at(twin, pointer)));
}

std::string text_of(const Json* v) { return v != nullptr && v->is_string() ? escape(v->get<std::string>()) : "—"; }

// The element of a per-channel JSON (a fit file, diagnose --json): the whole
// for one channel, else channels[k].
Json channel_part(const Json& all, std::size_t k) {
  if (all.contains("channels") && all["channels"].is_array() && k < all["channels"].size()) return all["channels"][k];
  return all;
}

Json log_summary(const ReportRequest& o, const CompensateRun& compensated) {
  const fit::Compensation& c = compensated.channels.front();
  const std::vector<double>& t = c.data.series.time_s;
  const std::vector<double>& temp = c.data.series.temp_c;
  double heat = 0.0, cool = 0.0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double rate = (temp[i] - temp[i - 1]) / (t[i] - t[i - 1]) * 60.0;
    heat = std::max(heat, rate);
    cool = std::min(cool, rate);
  }
  const auto [lo, hi] = std::minmax_element(temp.begin(), temp.end());
  Json j{{"file", o.data},
         {"sha256", sha256_file_hex(o.data)},
         {"units", c.data.units.used()},
         {"samples", c.data.raw_samples},
         {"windows", t.size()},
         {"duration_h", t.empty() ? 0.0 : (t.back() - t.front()) / 3600.0},
         {"temp_range_c", {*lo, *hi}},
         {"span_c", *hi - *lo},
         {"heating_c_per_min", heat},
         {"cooling_c_per_min", cool},
         {"cautions", fit::caution_texts(c.data.cautions)}};
  return j;
}

}  // namespace

std::vector<ReportLimit> parse_limits(const std::string& text, std::optional<double> max_residual_dph) {
  std::vector<ReportLimit> out;
  if (max_residual_dph) out.push_back({"residual", *max_residual_dph});
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    begin = comma + 1;
    const std::size_t eq = item.find('=');
    const std::string name = item.substr(0, eq);
    double value = 0.0;
    const char* end = item.data() + item.size();
    const bool number = eq != std::string::npos && std::from_chars(item.data() + eq + 1, end, value).ptr == end;
    if (!number || (name != "residual" && name != "span" && name != "ratio") || !(value > 0.0) || !std::isfinite(value))
      throw InputError(fmt::format("--limits '{}': expected NAME=VALUE items, NAME residual (°/h), span (°C) or ratio, "
                                   "VALUE a number above 0",
                                   item));
    if (std::any_of(out.begin(), out.end(), [&](const ReportLimit& l) { return l.name == name; }))
      throw InputError(fmt::format("--limits: {} given twice (or with --max-residual)", name));
    out.push_back({name, value});
  }
  return out;
}

Json judged_limits(const std::vector<ReportLimit>& limits, const Json& twin) {
  Json out = Json::array();
  for (const ReportLimit& l : limits) {
    double value = 0.0;
    bool passed = true;
    if (l.name == "span") {
      value = twin["log"]["span_c"].get<double>();
      passed = value >= l.value;
    } else if (l.name == "ratio") {
      value = INFINITY;
      for (const Json& c : twin["channels"]) value = std::min(value, c["compensate"]["ratio"].get<double>());
      passed = value >= l.value;
    } else {  // residual: the check's worst axis; one it cannot show (null) does not pass
      value = 0.0;
      for (const Json& a : twin["check"]["axes"])
        value = a["residual_dph"].is_number() ? std::max(value, a["residual_dph"].get<double>()) : NAN;
      passed = value <= l.value;
    }
    out.push_back({{"name", l.name}, {"limit", l.value}, {"value", std::isnan(value) ? Json() : Json(value)},
                   {"passed", passed}});
  }
  return out;
}

Json report_twin(const ReportRequest& o, const std::vector<fit::SavedFit>& fits, const Json& fit_json,
                 const CompensateRun& compensated, const std::vector<AllanStudy>& allan, const Json& diagnosis,
                 const std::optional<CheckResult>& check, const std::vector<ChannelBand>& bands) {
  Json j;
  j["tool"] = "gyrotherm " GYROTHERM_VERSION;
  j["created"] = fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
  j["fit"] = o.fit_file.empty() ? Json("made by report: " + fit::formula_text(fits.front().terms)) : Json(o.fit_file);
  j["log"] = log_summary(o, compensated);
  j["log"]["sensors"] = sensors_json(o.data, fits.front());
  j["channels"] = Json::array();
  for (std::size_t k = 0; k < fits.size(); ++k) {
    Json c{{"channel", channel_name(fits[k])}, {"model", fit::formula_text(fits[k].terms)}};
    c["fit"] = channel_part(fit_json, k);
    c["band"] = band_json(bands[k]);
    c["firmware"] = firmware_json(fits[k], export_tref(fits, k), bands[k]);
    c["compensate"] = compensated.channel_json[k];
    c["allan"] = allan_json(allan[k]);
    c["diagnosis"] = channel_part(diagnosis, k);
    j["channels"].push_back(std::move(c));
  }
  j["check"] = check ? check_json(*check) : Json();
  j["max_residual_dph"] = o.max_residual_dph ? Json(*o.max_residual_dph) : Json();
  j["limits"] = judged_limits(parse_limits(o.limits, o.max_residual_dph), j);
  bool passed = !j["limits"].empty();
  for (const Json& l : j["limits"]) passed = passed && l["passed"].get<bool>();
  j["passed"] = !j["limits"].empty() ? Json(passed) : Json();
  return j;
}

namespace {

constexpr const char* kStyle = R"(
body { font-family: sans-serif; max-width: 1100px; margin: 1.5em auto; color: #222; line-height: 1.35; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; } h2 { border-bottom: 2px solid #ccc; margin-top: 1.6em; }
table { border-collapse: collapse; margin: 0.6em 0; } td, th { border: 1px solid #ccc; padding: 0.2em 0.6em; }
th { background: #f2f2f2; text-align: left; } td.n { text-align: right; font-variant-numeric: tabular-nums; }
figure { margin: 0.8em 0; } figure img { width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 0.9em; color: #555; } .caution { color: #8a4b00; } .pass { color: #1a7f37; font-weight: bold; }
.fail { color: #b42318; font-weight: bold; } code { background: #f5f5f5; padding: 0 0.2em; }
@media print { @page { size: A4; margin: 14mm; } body { max-width: none; margin: 0; font-size: 10pt; }
  section, figure, table { page-break-inside: avoid; } }
)";

std::string figure(const std::string& data_uri, const std::string& alt, const std::string& caption) {
  if (data_uri.empty()) return "";
  return fmt::format("<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n", data_uri,
                     escape(alt), caption);
}

// An autopilot log's gyros: instance, device id, samples, temperatures, which one was read.
std::string sensors_html(const Json& twin) {
  const Json* gyros = at(twin, "/log/sensors/gyros");
  if (gyros == nullptr || gyros->empty()) return "";
  std::string h = "<table><tr><th>gyro instance</th><th>message</th><th>device id</th><th>samples</th>"
                  "<th>lowest (°C)</th><th>highest (°C)</th><th></th></tr>\n";
  for (std::size_t i = 0; i < gyros->size(); ++i) {
    const std::string p = fmt::format("/log/sensors/gyros/{}", i);
    h += fmt::format("<tr>{}<td>{}</td>{}{}{}{}<td>{}</td></tr>\n", cell(twin, p + "/instance"),
                     text_of(at(twin, p + "/message")), cell(twin, p + "/device_id"), cell(twin, p + "/samples"),
                     cell(twin, p + "/temp_range_c/0"), cell(twin, p + "/temp_range_c/1"),
                     (*gyros)[i]["read"].get<bool>() ? "the one read" : "");
  }
  return h + "</table>\n";
}

std::string header_html(const Json& twin, const std::string& temperature) {
  std::string h = "<h1>Gyro thermal calibration report</h1>\n<table>\n";
  h += fmt::format("<tr><th>log</th><td>{}</td></tr>\n", text_of(at(twin, "/log/file")));
  h += fmt::format("<tr><th>SHA-256</th><td><code>{}</code></td></tr>\n", text_of(at(twin, "/log/sha256")));
  h += fmt::format("<tr><th>format</th><td>{}</td></tr>\n", text_of(at(twin, "/log/sensors/format")));
  h += fmt::format("<tr><th>read as</th><td>{}</td></tr>\n", text_of(at(twin, "/log/units")));
  h += fmt::format("<tr><th>model</th><td>{}</td></tr>\n", text_of(at(twin, "/fit")));
  h += fmt::format("<tr><th>tool, date</th><td>{}, {}</td></tr>\n</table>\n", text_of(at(twin, "/tool")),
                   text_of(at(twin, "/created")));
  h += "<table><tr><th>samples</th><th>windows</th><th>duration (h)</th><th>lowest (°C)</th><th>highest (°C)</th>"
       "<th>span (°C)</th><th>fastest heating (°C/min)</th><th>fastest cooling (°C/min)</th></tr>\n<tr>";
  for (const char* p : {"/log/samples", "/log/windows", "/log/duration_h", "/log/temp_range_c/0", "/log/temp_range_c/1",
                        "/log/span_c", "/log/heating_c_per_min", "/log/cooling_c_per_min"})
    h += cell(twin, p);
  h += "</tr></table>\n";
  h += sensors_html(twin);
  if (const Json* cautions = at(twin, "/log/cautions"); cautions != nullptr)
    for (const Json& c : *cautions) h += fmt::format("<p class=\"caution\">caution: {}</p>\n", escape(c.get<std::string>()));
  h += figure(temperature, "gyro temperature against time",
              "The test's temperature: look for the span, the levels held and the rates of the legs (heating red, "
              "cooling blue); a model is only as good as the temperatures it saw.");
  return h;
}

std::string coefficients_html(const Json& twin, std::size_t k) {
  const std::string base = fmt::format("/channels/{}/fit", k);
  std::string h = "<table><tr><th>term</th><th>coefficient</th><th>95 % interval, low</th><th>high</th></tr>\n";
  if (const Json* coefficients = at(twin, base + "/coefficients"); coefficients != nullptr)
    for (const auto& [term, value] : coefficients->items()) {
      std::string key;  // the term as a JSON pointer token (RFC 6901: ~ and / escaped)
      for (const char c : term) key += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
      h += fmt::format("<tr><td>{}</td>{}{}{}</tr>\n", escape(term), cell(twin, base + "/coefficients/" + key),
                       cell(twin, base + "/intervals_95/" + key + "/0"), cell(twin, base + "/intervals_95/" + key + "/1"));
    }
  // Two logs where the fit was made on another: this one, compensated with
  // the fit, and the fit's own data; each row names its log.
  const auto instability_row = [&](const std::string& label, const std::string& from) {
    std::string row = "<tr><td>" + label + "</td>";
    for (const char* f : {"/instability_before_dph", "/instability_after_dph", "/ratio"}) row += cell(twin, from + f);
    return row + "</tr>";
  };
  const Json* fitted_on = at(twin, base + "/data/file");
  h += "</table>\n<table><tr><th>instability</th><th>before (°/h)</th><th>after (°/h)</th><th>ratio</th></tr>\n" +
       instability_row("this log, compensated with the fit", fmt::format("/channels/{}/compensate", k)) + "\n" +
       instability_row(fmt::format("the data the fit was made on ({})",
                                   escape(fitted_on != nullptr && fitted_on->is_string() ? fitted_on->get<std::string>()
                                                                                         : "?")),
                       base) +
       "</table>\n";
  if (const Json* flags = at(twin, base + "/record/flags"); flags != nullptr && flags->is_object())
    for (const auto& [term, why] : flags->items())
      h += fmt::format("<p class=\"caution\">caution, {}: {}</p>\n", escape(term), escape(why.is_string() ? why.get<std::string>() : why.dump()));
  return h;
}

// The model's band, or why it has none.
std::string band_html(const Json& twin, std::size_t k) {
  const std::string base = fmt::format("/channels/{}/band", k);
  if (at(twin, base + "/half_width_dph") != nullptr)
    return "<table><tr><th>95 % band of the model, narrowest (°/h)</th><th>widest (°/h)</th><th>t's dof</th></tr><tr>" +
           cell(twin, base + "/half_width_dph/0") + cell(twin, base + "/half_width_dph/1") + cell(twin, base + "/dof") +
           "</tr></table>\n";
  const Json* missing = at(twin, base + "/missing");
  const std::string why = missing != nullptr && missing->is_string() ? missing->get<std::string>() : "";
  return fmt::format("<p class=\"caution\">No band for the model: {}.</p>\n",
                     why == "other_record"     ? "the fit was made on another record, whose noise its uncertainty belongs to"
                     : why == "engine_not_ols" ? "the fit's engine is not ols, and the band is the least-squares covariance's"
                                               : "this record has too few windows to identify its noise");
}

// The model as PX4 and ArduPilot store it, with intervals.
std::string firmware_html(const Json& twin, std::size_t k) {
  const std::string base = fmt::format("/channels/{}/firmware", k);
  const Json* expressible = at(twin, base + "/expressible");
  if (expressible == nullptr || !expressible->get<bool>()) {
    std::string terms;
    if (const Json* others = at(twin, base + "/not_expressible"); others != nullptr)
      for (const Json& t : *others) terms += (terms.empty() ? "" : ", ") + t.get<std::string>();
    if (terms.empty())
      return "<p>The fit file holds no fitted temperature range (written by an earlier gyrotherm): the firmwares' "
             "TMIN/TMAX/TREF cannot be set; fit again.</p>\n";
    return fmt::format("<p>The firmwares store a cubic in temperature; this model's {} cannot be stored "
                       "(<code>export --format c</code> writes the whole model).</p>\n", escape(terms));
  }
  static constexpr const char* kPower[] = {"", "/°C", "/°C²", "/°C³"};
  std::string h = "<table><tr><th>as the firmware stores it</th><th>value</th><th>95 % interval, low</th><th>high</th></tr>\n";
  for (int n = 0; n <= 3; ++n) {
    const std::string p = fmt::format("{}/px4/", base);
    h += fmt::format("<tr><td>PX4 TC_G*_X{}_axis (rad/s{}) about TREF {} °C</td>{}{}{}</tr>\n", n, kPower[n],
                     number_text(at(twin, p + "tref_c")), cell(twin, fmt::format("{}values/{}", p, n)),
                     cell(twin, fmt::format("{}intervals_95/{}/0", p, n)), cell(twin, fmt::format("{}intervals_95/{}/1", p, n)));
  }
  for (int n = 1; n <= 3; ++n) {
    const std::string p = fmt::format("{}/ardupilot/", base);
    h += fmt::format("<tr><td>ArduPilot INS_TCAL*_GYR{}_axis (10⁻⁶ rad/s{}) about 35 °C</td>{}{}{}</tr>\n", n, kPower[n],
                     cell(twin, fmt::format("{}values/{}", p, n - 1)), cell(twin, fmt::format("{}intervals_95/{}/0", p, n - 1)),
                     cell(twin, fmt::format("{}intervals_95/{}/1", p, n - 1)));
  }
  return h + "</table>\n";
}

std::string allan_html(const Json& twin, std::size_t k) {
  const std::string base = fmt::format("/channels/{}/allan/series", k);
  std::string h = "<table><tr><th>series</th><th>ARW (°/√h)</th><th>bias instability (°/h)</th><th>RRW (°/h/√h)</th>"
                  "<th>bias instability read from</th></tr>\n";
  const Json* series = at(twin, base);
  for (std::size_t s = 0; series != nullptr && s < series->size(); ++s) {
    const std::string p = fmt::format("{}/{}/coefficients", base, s);
    h += fmt::format("<tr><td>{}</td>", text_of(at(twin, fmt::format("{}/{}/name", base, s))));
    for (const char* c : {"/arw_dpsh", "/bias_instability_dph", "/rrw_dph_per_sqrt_h"}) {
      const Json* shown = at(twin, p + c + "/shown");
      h += shown != nullptr && shown->get<bool>() ? cell(twin, p + c + "/value")
                                                  : fmt::format("<td class=\"n\">&lt; {}</td>", number_text(at(twin, p + c + "/upper_bound")));
    }
    // The method, and what makes the figure a value or a bound (allan's support).
    static const std::map<std::string, std::string> kWords = {
        {"curve_flat", "the curve's flat part"},
        {"noise_model", "the noise model's flicker floor"},
        {"plateau", "a plateau (the curve falls past it)"},
        {"gauss_markov", "a Gauss–Markov process in the noise model"},
        {"flicker", "flicker in the noise model"},
        {"not_in_model", "a bound: the noise model names no slow noise at the flat part"},
        {"no_model", "a bound: too short for a noise model"},
        {"no_flat_part", "a bound: no flat part"},
        {"beyond_record", "a bound: the curve still falls, a flat part lies beyond the record"},
        {"too_few_taus", "too few τ to tell"}};
    const auto words = [&](const std::string& key) {
      const auto it = kWords.find(key);
      return it == kWords.end() ? key : it->second;
    };
    // A value: its method, and what supports it where that adds (a plateau, a
    // Gauss–Markov process); a bound: why it is one.
    const Json* shown_b = at(twin, p + "/bias_instability_dph/shown");
    const bool value = shown_b != nullptr && shown_b->get<bool>();
    const std::string support = text_of(at(twin, fmt::format("{}/{}/bias_instability_support", base, s)));
    std::string read = value ? words(text_of(at(twin, p + "/bias_instability_dph/method"))) : words(support);
    if (value && (support == "plateau" || support == "gauss_markov")) read += "; " + words(support);
    h += fmt::format("<td>{}</td></tr>\n", read);
  }
  return h + "</table>\n";
}

std::string diagnosis_html(const Json& twin, std::size_t k) {
  const std::string base = fmt::format("/channels/{}/diagnosis", k);
  std::string h = "<h3>Diagnosis</h3>\n<table><tr><th>model ÷ noise floor</th>" + cell(twin, base + "/ratio_to_floor") +
                  "</tr></table>\n";
  h += fmt::format("<p><b>verdict:</b> {}</p>\n", text_of(at(twin, base + "/verdict")));
  if (const Json* groups = at(twin, base + "/confounded"); groups != nullptr && groups->is_array() && !groups->empty()) {
    std::string told;  // the groups of terms this record cannot tell apart
    for (const Json& g : *groups) {
      std::string one;
      for (const Json& t : g) one += (one.empty() ? "" : " / ") + t.get<std::string>();
      told += (told.empty() ? "" : "; ") + one;
    }
    h += fmt::format("<p>what this record cannot tell apart (terms that explain the same part of the bias here): {}</p>\n",
                     escape(told));
  }
  if (const Json* next = at(twin, base + "/next_command"); next != nullptr && next->is_string() && !next->get<std::string>().empty())
    h += fmt::format("<p>next: <code>{}</code></p>\n", escape(next->get<std::string>()));
  if (const Json* plan = at(twin, base + "/plan_command"); plan != nullptr && plan->is_string() && !plan->get<std::string>().empty())
    h += fmt::format("<p>a test that would tell what this record cannot: <code>{}</code></p>\n", escape(plan->get<std::string>()));
  return h;
}

std::string check_html(const Json& twin) {
  const Json* check = at(twin, "/check");
  if (check == nullptr || check->is_null()) return "";
  std::string h = fmt::format("<section><h2>Calibration check: {}</h2>\n<p>{} ({}), applied as the firmware applies it.</p>\n",
                              text_of(at(twin, "/check/parameters")), text_of(at(twin, "/check/calibration")),
                              text_of(at(twin, "/check/format")));
  h += "<table><tr><th>axis</th><th>raw (°/h)</th><th>compensated (°/h)</th><th>residual against temperature (°/h)</th>"
       "<th>share outside TMIN..TMAX</th></tr>\n";
  for (std::size_t a = 0; a < (*check)["axes"].size(); ++a) {
    const std::string p = fmt::format("/check/axes/{}", a);
    h += fmt::format("<tr><td>{}</td>{}{}{}{}</tr>\n", text_of(at(twin, p + "/axis")), cell(twin, p + "/before_dph"),
                     cell(twin, p + "/after_dph"), cell(twin, p + "/residual_dph"), cell(twin, p + "/outside_share"));
  }
  h += "</table>\n";
  for (const Json& f : (*check)["findings"])
    h += fmt::format("<p class=\"caution\">finding ({}): {}</p>\n", escape(f["issue"].get<std::string>()),
                     escape(f.value("text", std::string())));
  return h + "</section>\n";
}

std::string limits_html(const Json& twin) {
  const Json* limits = at(twin, "/limits");
  if (limits == nullptr || limits->empty()) return "";
  std::string h = "<section><h2>Acceptance</h2>\n<table><tr><th>limit</th><th>required</th><th>found</th><th></th></tr>\n";
  for (std::size_t i = 0; i < limits->size(); ++i) {
    const std::string p = fmt::format("/limits/{}", i);
    const std::string name = (*limits)[i]["name"].get<std::string>();
    const bool ok = (*limits)[i]["passed"].get<bool>();
    const char* what = name == "span" ? "temperature span, °C, at least"
                       : name == "ratio" ? "instability ratio of every channel, at least"
                                         : "residual against temperature of every axis (check), °/h, at most";
    h += fmt::format("<tr><td>{}</td>{}{}<td class=\"{}\">{}</td></tr>\n", what, cell(twin, p + "/limit"), cell(twin, p + "/value"),
                     ok ? "pass" : "fail", ok ? "PASS" : "FAIL");
  }
  const bool passed = twin["passed"].get<bool>();
  return h + fmt::format("</table>\n<p class=\"{}\">{}</p></section>\n", passed ? "pass" : "fail", passed ? "PASS" : "FAIL");
}

}  // namespace

std::string report_html(const ReportContent& content) {
  const Json& twin = content.twin;
  std::string style = kStyle;  // one line in the page
  std::replace(style.begin(), style.end(), '\n', ' ');
  std::string h = fmt::format("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>gyrotherm report: {}</title>\n<style>{}</style></head><body>\n",
                              text_of(at(twin, "/log/file")), style);
  h += "<section>\n" + header_html(twin, content.temperature) + "</section>\n";
  for (std::size_t k = 0; k < content.channels.size(); ++k) {
    const ChannelFigures& f = content.channels[k];
    const std::string channel = text_of(at(twin, fmt::format("/channels/{}/channel", k)));
    h += fmt::format("<section><h2>Channel {}: B = b0 + {}</h2>\n", channel, text_of(at(twin, fmt::format("/channels/{}/model", k))));
    h += coefficients_html(twin, k);
    h += firmware_html(twin, k);
    h += band_html(twin, k);
    h += figure(f.bias, "bias against temperature, " + channel,
                "Each window's mean output against its temperature: where heating and cooling legs part, the bias "
                "depends on more than the temperature (hysteresis, a rate or a lag); the model's points should run "
                "through the cloud over the whole fitted range (dashed), the grey bars their 95 % band: where the "
                "band is wide the record pins the model down poorly.");
    h += figure(f.time, "output against time, " + channel,
                "Uncompensated and compensated window means: what is left after the model should look like noise, "
                "with no trace of the temperature (right axis); with a checked calibration (green), what the "
                "firmware's rule leaves of it.");
    h += figure(f.allan, "Allan deviation, " + channel,
                "Allan deviation raw and compensated (real-time compensation): the compensation should lower the "
                "long τ and leave the short τ (white noise) as it was.");
    h += allan_html(twin, k);
    h += diagnosis_html(twin, k);
    h += "</section>\n";
  }
  h += check_html(twin);
  h += limits_html(twin);
  h += "<p style=\"font-size:0.85em;color:#666\">Every number on this page is in the JSON twin beside it, at the JSON "
       "pointer its cell names (data-json).</p>\n</body></html>\n";
  return h;
}

}  // namespace gyrotherm::studies

#pragma once
// `gyrotherm report LOG [--fit FILE | --model F] [--params FILE] -o report.html`:
// one self-contained HTML page an engineer shares, and its JSON twin
// (report.json beside it) holding every number on the page.
//
// Built from the same structured results the other commands report — the
// fit (its fit file), `compensate`, `allan --fit`, `diagnose` with the fit's
// model and, with --params, `check` on this log — never from their text: the
// page's tables read the twin's numbers (each cell names its JSON pointer in
// data-json), its figures are gnuplot PNGs embedded as base64 (no network, no
// scripts, no fonts: it opens from a mail attachment), with a print
// stylesheet for A4. A refused input leaves neither file.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {

struct ReportRequest {
  std::string data;          // the log
  std::string fit_file;      // --fit: a saved fit; "" to fit here with --model and the data options
  ModelOptions model;        // --model (without --fit)
  DataOptions data_options;  // columns, units, --avg … (without --fit; with it, the fit's own)
  std::string params;        // --params: a calibration to check on this log (check), or ""
  std::optional<double> max_residual_dph;  // --max-residual: PASS/FAIL of the check's residual
  // --limits NAME=VALUE,…: the user's acceptance limits, each judged on the
  // page: residual (°/h, the check's; needs --params, as --max-residual),
  // span (°C, the log's temperature span at least), ratio (every channel's
  // instability ratio at least).
  std::string limits;
  std::string output;        // the HTML page; the JSON twin is OUTPUT with .json
  // Progress on stderr (step, share done); empty: none.
  std::function<void(const std::string& step, double fraction)> progress;
};

struct ReportRun {
  std::string html;            // the page, as written
  std::string twin;            // the JSON twin's text
  std::string html_file, twin_file;
  std::string text;            // what the terminal prints
};

// Runs the studies, writes OUTPUT and its twin atomically (both or neither).
ReportRun run_report(const ReportRequest& request);

// The twin's file: OUTPUT with its extension replaced by .json.
std::string report_twin_file(const std::string& output);

}  // namespace gyrotherm::studies

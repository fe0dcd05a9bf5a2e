#pragma once
// The report of `gyrotherm reproduce` (studies/reproduce/reproduce.h): the
// paper's Table 1 beside ours as table1.json (docs/contracts.md's fields:
// cycle, test1, test2, paper, seeds) and table1.md (with a short, factual section on
// what an engine can and cannot change), and figures in the spirit of the
// paper's Figs. 2–9 (gnuplot).

#include <chrono>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "studies/reproduce/reproduce.h"

namespace gyrotherm::studies {

// table1.json; with_times adds the run times (seconds: the engines' and the
// whole job's), which the file leaves out so that a run leaves it unchanged.
nlohmann::ordered_json table_json(const ReproduceResult& r, bool with_times);
std::string table_markdown(const ReproduceResult& r);
void plot_figures(const std::filesystem::path& dir, const ReproduceResult& r);

// Everything into `dir` (created if need be): the figures, then table1.json
// and table1.md, each written atomically, the same bytes on every run of the
// same seeds; progress (may be empty) from kReproduceComputedShare to "done"
// at 1, once all is written. Returns the JSON with the run times
// (total_seconds: since `started`, figures included) for the terminal.
nlohmann::ordered_json write_reproduce_report(const std::filesystem::path& dir,
                                              const ReproduceResult& r,
                                              std::chrono::steady_clock::time_point started,
                                              const std::function<void(const std::string&, double)>& progress = {});

// The summary for the terminal.
std::string reproduce_text(const ReproduceResult& r, const std::string& dir, double total_seconds);

// The engine whose compensation the tests' figures and summaries show:
// iafsa (the paper's) when it ran, else the first.
std::string shown_engine(const ReproduceResult& r);

}  // namespace gyrotherm::studies

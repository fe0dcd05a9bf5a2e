#pragma once
// The scoreboard's reports: the `score --json` object (docs/contracts.md's
// fields and more), a Markdown page, a text table for the terminal, and the convergence
// curves as CSV and as a figure.

#include <filesystem>
#include <string>
#include <vector>

#include "studies/score/campaign.h"

namespace gyrotherm::studies {

// The scoreboard as one JSON object (the `score --json` contract of
// docs/contracts.md, and more); +∞ ("not reached") is written as null.
std::string scoreboard_json(const Scoreboard& board);
// A Markdown page: the campaign and one table row per engine.
std::string scoreboard_markdown(const Scoreboard& board);
// engine, evaluations, gap_q25, gap_median, gap_q75 (empty cell: +∞).
std::string convergence_csv(const Scoreboard& board);


// One row per engine for the terminal.
std::string scoreboard_text(const Scoreboard& board);
// score's report for the terminal: the campaign, the medians, the table,
// the time taken.
std::string score_text(const Scoreboard& board);
// Log–log median and quartiles of the gap against evaluations, with the target.
void plot_convergence(const std::filesystem::path& png, const Scoreboard& board);
// scoreboard.json, scoreboard.md, convergence.csv and convergence.png into
// `dir` (created if need be), each atomically; returns the paths written.
std::vector<std::string> write_score_files(const std::filesystem::path& dir, const Scoreboard& board);

}  // namespace gyrotherm::studies

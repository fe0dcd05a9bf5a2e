#pragma once
// The scoreboard's reports: the `score --json` object (DESIGN.md's fields and
// more), a Markdown page, and the convergence curves as CSV.

#include <string>

#include "studies/score/campaign.h"

namespace gyrotherm::fit {

// The scoreboard as one JSON object (the `score --json` contract of
// DESIGN.md, and more); +∞ ("not reached") is written as null.
std::string scoreboard_json(const Scoreboard& board);
// A Markdown page: the campaign and one table row per engine.
std::string scoreboard_markdown(const Scoreboard& board);
// engine, evaluations, gap_q25, gap_median, gap_q75 (empty cell: +∞).
std::string convergence_csv(const Scoreboard& board);


}  // namespace gyrotherm::fit

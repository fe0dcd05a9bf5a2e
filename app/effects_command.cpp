// gyrotherm effects [--json]   (fit/model/term_listing.h)

#include "app/commands.h"
#include "fit/model/term_listing.h"

namespace gyrotherm::app {

void add_effects_command(CLI::App& app, Run* run) {
  add_listing_command(app, run, "effects", "List the model terms (physical effects)", fit::effects_text, fit::effects_json);
}

}  // namespace gyrotherm::app

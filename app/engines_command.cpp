// gyrotherm engines [--json]   (fit/engines/engine_listing.h)

#include "app/commands.h"
#include "fit/engines/engine_listing.h"

namespace gyrotherm::app {

void add_engines_command(CLI::App& app, Run* run) {
  add_listing_command(app, run, "engines", "List the fitting engines and their options", fit::engines_text, fit::engines_json);
}

}  // namespace gyrotherm::app

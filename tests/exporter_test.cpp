// The export registry (studies/export/exporter.h): every format complete and
// reachable by name, an unknown one refused with the list, and every format
// run on a saved fit writes its file or refuses it, never half of it.

#include "studies/export/exporter.h"

#include <gtest/gtest.h>

#include <set>

#include "cli_runner.h"
#include "expect_input_error.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;

TEST(Exporters, EveryEntryIsCompleteAndFoundByName) {
  std::set<std::string> names;
  for (const ExporterInfo& e : exporter_registry()) {
    SCOPED_TRACE(e.name);
    EXPECT_FALSE(e.name.empty());
    EXPECT_TRUE(names.insert(e.name).second) << "a name used twice";
    EXPECT_FALSE(e.description.empty());
    EXPECT_TRUE(static_cast<bool>(e.write));
    EXPECT_EQ(&find_exporter(e.name), &e);
    EXPECT_NE(exporter_names().find(e.name), std::string::npos);
  }
  EXPECT_EQ(names, (std::set<std::string>{"c", "px4", "ardupilot"}));
  expect_input_error([] { find_exporter("betaflight"); }, {"--format betaflight: expected " + exporter_names()});
}

// Every format on the paper's cubic-free model of the cycle: C writes it, the
// firmware formats refuse dT by name and write nothing; with
// --drop-unsupported they write it and say what dropping costs, on the
// console and in the file.
TEST(Exporters, EveryFormatWritesOrRefusesWholly) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  ASSERT_EQ(run_cli(dir, "fit d.csv -o fit.json").exit_code, 0);
  for (const ExporterInfo& e : exporter_registry()) {
    SCOPED_TRACE(e.name);
    const std::string out = "out_" + e.name;
    const CliResult r = run_cli(dir, "export fit.json --format " + e.name + " -o " + out);
    const bool whole = e.name == "c";
    EXPECT_EQ(r.exit_code, whole ? 0 : 2) << r.err;
    EXPECT_EQ(std::filesystem::exists(dir / out), whole);
    if (whole) continue;
    EXPECT_NE(r.err.find("(dT)"), std::string::npos) << r.err;
    const CliResult dropped = run_cli(dir, "export fit.json --drop-unsupported --format " + e.name + " -o " + out);
    EXPECT_EQ(dropped.exit_code, 0) << dropped.err;
    EXPECT_NE(dropped.out.find("dropped dT"), std::string::npos) << dropped.out;
    EXPECT_GT(std::filesystem::file_size(dir / out), 100u);
    // The file itself says its model is not the fit's (it outlives the console).
    const std::string text = slurp(dir / out);
    EXPECT_NE(text.find("without dT (--drop-unsupported:"), std::string::npos) << text.substr(0, 1500);
  }
}

}  // namespace
}  // namespace gyrotherm::studies

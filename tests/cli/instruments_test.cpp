// A test of several instruments through the program (docs/cli.md, "Several instruments in one test"): simulate
// writes one folder for all of them (the sample examples/daq/two_instruments, bit for bit), reduce gives each
// and, with --instrument, one of them alone; the commands of one instrument ask for it, an unknown id is named,
// and an output of one instrument's table is refused for several. One instrument's statement carries its own
// serial number to its history.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

const std::string kDaq = CCAL_SOURCE_DIR + "/examples/daq";
const std::string kTwo = kDaq + "/two_short.toml";

class SeveralInstruments : public Cli {};

TEST_F(SeveralInstruments, ATestIsSimulatedToOneFolderAndReducedForEachInstrument) {
  const Result sim = run("simulate " + kTwo + " --draw-truth --seed 7 --logs-out logs -o /dev/null");
  ASSERT_EQ(sim.code, 0) << sim.err;
  // The sample folder is this command's (scripts/make_daq_examples.sh): the same files, bit for bit.
  for (const char* name : {"5g.csv", "10g.csv", "20g.csv", "30g.csv", "manifest.toml"})
    EXPECT_EQ(read(dir_ / "logs" / name), read(kDaq + "/two_instruments/" + name)) << name;
  const Result all = run("reduce " + kTwo + " --logs logs --format json");
  ASSERT_EQ(all.code, 0) << all.err;
  const auto j = nlohmann::json::parse(all.out);
  ASSERT_EQ(j["instruments"].size(), 2u);
  EXPECT_EQ(j["instruments"][1]["id"], "B");
  // B alone, from its column of the same folder: its section's numbers.
  const Result b = run("reduce " + kTwo + " --logs logs --instrument B --format json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(nlohmann::json::parse(b.out)["identification"], j["instruments"][1]["identification"]);
  // A warning of the shared logs (a run's control as the encoders show it) is said once, not once per instrument.
  EXPECT_EQ(all.err.find("instrument A: run '10g'"), std::string::npos) << all.err;
}

TEST_F(SeveralInstruments, CommandsOfOneInstrumentAskForItAndAnUnknownIdIsNamed) {
  expect_bad_input(run("budget " + kTwo + " --instrument C"),
                   {"--instrument: C is no instrument of " + kTwo + "; accepted: A, B"});
  expect_bad_input(run("force " + kTwo),
                   {"--instrument: missing: " + kTwo + " holds a test of 2 instruments (A, B), and force answers for "
                    "one at a time; accepted: one of A, B"});
  expect_bad_input(run("montecarlo " + kLab + " --instrument A"),
                   {"--instrument: A names an instrument, but " + kLab + " has one [instrument] and no ids"});
  expect_bad_input(run("budget " + kTwo + " --instrument ''"), {"--instrument: the id is empty; accepted: an "
                                                                  "instrument's id"});
  expect_bad_input(run("budget " + kTwo + " --instrument A --instrument B"), {"--instrument: given 2 times"});
  const Result force = run("force " + kTwo + " --instrument B --format json");
  ASSERT_EQ(force.code, 0) << force.err;
  write("obs.csv", read(CCAL_SOURCE_DIR + "/examples/xy_sigma.csv"));
  expect_bad_input(run("identify obs.csv --instrument B"), {"--instrument: 'B'", "accepted: with --config CONFIG"});
}

TEST_F(SeveralInstruments, AnOutputOfOneInstrumentsTableIsRefusedForSeveral) {
  expect_bad_input(run("simulate " + kTwo + " --observations-out o.csv"),
                   {"--observations-out:", "holds 2 instruments", "--instrument ID for one of them"});
  expect_bad_input(run("simulate " + kTwo + " --format csv"), {"--format: csv is one table", "accepted: --format text or json, or --instrument ID"});
  expect_bad_input(run("simulate " + kTwo + " --truth " + kLabTruth),
                   {"--truth:", "is a test of 2 instruments", "one instrument chosen with --instrument"});
  EXPECT_FALSE(fs::exists(dir_ / "o.csv"));
  const Result b = run("simulate " + kTwo + " --instrument B --observations-out b.csv -o /dev/null");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_TRUE(fs::exists(dir_ / "b.csv"));
}

// Observations of one instrument given for another of the same test are named as the first's.
TEST_F(SeveralInstruments, AnotherInstrumentsObservationsAreNamedAsTheirs) {
  const Result a = run("reduce " + kTwo + " --logs " + kDaq + "/two_instruments --instrument A "
                       "--observations-out a.csv -o /dev/null");
  ASSERT_EQ(a.code, 0) << a.err;
  expect_bad_input(run("identify a.csv --config " + kTwo + " --instrument B --statement"),
                   {"--instrument: B is not the instrument of a.csv: it holds instrument A's observations of " +
                    kTwo + "; accepted: A"});
  EXPECT_EQ(run("identify a.csv --config " + kTwo + " --instrument A --statement --statement-trials 1000 "
                "-o /dev/null").code, 0);
}

// Logs of a test of several read for one [instrument], a manifest's id the test does not have, and a layout
// file's [instruments] (as a manifest's) for simulate's logs.
TEST_F(SeveralInstruments, ATestsLogsAreReadOnlyForItsInstruments) {
  expect_bad_input(run("reduce " + quote(kLab) + " --logs " + kDaq + "/two_instruments"),
                   {"manifest.toml: [instruments] names the output columns of instruments A, B, and " + kLab +
                    " has one [instrument]"});
  fs::create_directories(dir_ / "M");
  for (const char* run : {"5g", "10g", "20g", "30g"})
    fs::copy_file(kDaq + "/two_instruments/" + run + ".csv", dir_ / "M" / (std::string(run) + ".csv"));
  std::string manifest = read(kDaq + "/two_instruments/manifest.toml");
  manifest.replace(manifest.find("\nA = "), 5, "\na = ");
  write("M/manifest.toml", manifest);
  expect_bad_input(run("reduce " + kTwo + " --logs M"), {"[instruments]: 'a' is no instrument of " + kTwo +
                                                         "; accepted: the ids of its [[instruments]] (A, B)"});
  write("layout.toml", "[instruments]\nA = { pulses = \"piga_a\" }\nB = { pulses = \"piga_b\" }\n");
  ASSERT_EQ(run("simulate " + kTwo + " --logs-out L --log-layout layout.toml -o /dev/null").code, 0);
  EXPECT_EQ(read(dir_ / "L" / "5g.csv").substr(0, 31), "time,piga_a,piga_b,theta1,gamma");
  EXPECT_EQ(run("reduce " + kTwo + " --logs L -o /dev/null").code, 0);
}

// One instrument's statement carries its [[instruments]] serial number: its history is its own.
TEST_F(SeveralInstruments, OneInstrumentsStatementGoesToItsOwnHistory) {
  const Result b = run("reduce " + kTwo + " --logs " + kDaq + "/two_instruments --instrument B --statement "
                       "--statement-trials 2000 --statement-out b.json -o /dev/null");
  ASSERT_EQ(b.code, 0) << b.err;
  const Result added = run("history add b.json --db h.sqlite");
  ASSERT_EQ(added.code, 0) << added.err;
  EXPECT_NE(added.out.find("Recorded calibration 1 of SN 0816"), std::string::npos) << added.out;
}

}  // namespace
}  // namespace ccal::test

// End-to-end tests of `ccal reduce`: logs recorded from the exact model of a centrifuge with errors, reduced
// and identified, give what `ccal simulate` identifies from the same model; bad logs and options are refused
// with their place.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/reduction/run_average.hpp"
#include "cli_support.hpp"
#include "test_constants.hpp"

namespace {

using namespace ccal::test;
using ccal::test::kPi;

// The bundled example with centrifuge errors, known and compensated: the model of the runs then equals their
// truth, and the identification recovers the instrument.
std::string config_text() {
  std::string text = read(kExample);
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("# dthz5 = \"2 arcsec\"       # instrument azimuth (IA) zero error",
          "dthz5 = \"2 arcsec\"\ndthy1t = \"3 arcsec\"\ndomega = \"2e-6 rad/s\"\ndOmega = \"-1e-6 rad/s\"");
  replace("# dx3_c1 = \"5 um\"", "dx3_c1 = \"5 um\"");
  replace("compensate = false", "compensate = true");
  return text;
}

// Logs of every run of `cfg` as its truth produces them: cumulative pulses of `weight_deg` degrees (the mean
// output times t, exact at the ends, which is all the reduction reads), and optionally the encoder angles
// wrapped to [0, 2π), every 0.2 s.
std::vector<std::string> write_logs(const ccal::Config& cfg, const fs::path& dir, double weight_deg,
                                    bool encoders) {
  const ccal::Experiment ex = cfg.experiment();
  const Eigen::VectorXd& e = cfg.centrifuge.errors;
  std::vector<std::string> args;
  for (std::size_t r = 0; r < cfg.plan.runs.size(); ++r) {
    const ccal::Run& run = cfg.plan.runs[r];
    const double mean =
        ccal::average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}).output;
    const double rate = ccal::nominal_rate(run, ex.geometry, ex.site) + e[ccal::ch::domega];
    const double gamma_rate = -(rate + e[ccal::ch::dOmega]);
    const double phi0 = ccal::initial_phase(run, ex.geometry, ex.site);
    const double w = weight_deg * kPi / 180;
    auto wrap = [](double a) { return std::fmod(std::fmod(a, 2 * kPi) + 2 * kPi, 2 * kPi); };
    std::string text = encoders ? "time,pulses,theta1,gamma\n" : "time,pulses\n";
    const int n = int(std::lround(run.duration / 0.2));
    for (int k = 0; k <= n; ++k) {
      const double t = run.duration * k / n;
      text += fmt::format("{:.17g},{:.17g}", t, mean * t / w);
      if (encoders)
        text +=
            fmt::format(",{:.17g},{:.17g}", wrap(run.arm_azimuth + rate * t), wrap(phi0 + gamma_rate * t));
      text += "\n";
    }
    const std::string name = fmt::format("run{}.csv", r + 1);
    std::ofstream(dir / name) << text;
    args.push_back(fmt::format("--log {}={}", run.name, name));
  }
  return args;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) s += " " + a;
  return s;
}

class Reduce : public Cli {};

TEST_F(Reduce, PulseLogsGiveTheSimulatedIdentification) {
  // Without encoders the model of each run is the plan's, exactly as `simulate` computes it; the outputs
  // differ only by the 17-digit pulse counts (relative 1e-16 of ~1e6 pulses): the coefficients agree to
  // 1e-11 of their values (K3 is fitted from outputs ~1e5 times larger than its effect).
  write("config.toml", config_text());
  const ccal::Config cfg = ccal::load_config(dir_ / "config.toml");
  const auto args = write_logs(cfg, dir_, 1e-3, false);
  const Result sim = run("simulate config.toml --format json");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const Result red = run("reduce config.toml --format json --pulse-weight 1e-3" + joined(args));
  ASSERT_EQ(red.code, 0) << red.err;
  const auto s = nlohmann::json::parse(sim.out), r = nlohmann::json::parse(red.out);
  EXPECT_EQ(r["command"], "reduce");
  ASSERT_EQ(r["runs"].size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(r["runs"][k]["name"], s["runs"][k]["name"]);
    EXPECT_EQ(r["runs"][k]["output_from"], "pulses");
    EXPECT_NEAR(double(r["runs"][k]["output"]), double(s["runs"][k]["output"]),
                1e-13 * std::abs(double(s["runs"][k]["output"])));
    EXPECT_FALSE(r["runs"][k].contains("main_encoder"));
  }
  for (const char* k : {"K0", "K2", "K3"}) {
    const double a = s["identification"]["coefficients"][k]["value"];
    const double b = r["identification"]["coefficients"][k]["value"];
    EXPECT_NEAR(b, a, 1e-11 * std::abs(a)) << k;
  }
}

TEST_F(Reduce, EncoderLogsMeasureTheDriveErrors) {
  // With both encoders the model takes the measured rate (Ω + Δω) and phases and the measured ΔΩ instead of
  // the configured drive errors: the same model up to the line fits' round-off (~1e-13 rad in the phases),
  // so the same coefficients to 1e-9 of their values; and the log's drive errors are reported.
  write("config.toml", config_text());
  const ccal::Config cfg = ccal::load_config(dir_ / "config.toml");
  const auto args = write_logs(cfg, dir_, 1e-3, true);
  const Result sim = run("simulate config.toml --format json");
  const Result red = run("reduce config.toml --format json --pulse-weight 1e-3" + joined(args));
  ASSERT_EQ(red.code, 0) << red.err;
  const auto s = nlohmann::json::parse(sim.out), r = nlohmann::json::parse(red.out);
  const ccal::Experiment ex = cfg.experiment();
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& x = r["runs"][k];
    const double planned = ccal::nominal_rate(cfg.plan.runs[k], ex.geometry, ex.site);
    EXPECT_NEAR(double(x["planned_rate_rad_per_s"]), planned, 1e-15);
    EXPECT_NEAR(double(x["rate_rad_per_s"]) - planned, 2e-6, 1e-12);
    EXPECT_NEAR(double(x["platform_mismatch_rad_per_s"]), -1e-6, 1e-12);
    EXPECT_NEAR(double(x["platform_encoder"]["initial_phase_rad"]),
                ccal::initial_phase(cfg.plan.runs[k], ex.geometry, ex.site), 1e-10);
  }
  for (const char* k : {"K0", "K2", "K3"}) {
    const double a = s["identification"]["coefficients"][k]["value"];
    const double b = r["identification"]["coefficients"][k]["value"];
    EXPECT_NEAR(b, a, 1e-9 * std::abs(a)) << k;
  }
  // The text report names the logs; the CSV is the observations file `ccal identify` reads.
  const Result text = run("reduce config.toml --pulse-weight 1e-3" + joined(args));
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("run3.csv"), std::string::npos);
  const Result csv =
      run("reduce config.toml --pulse-weight 1e-3 --format csv --observations-out obs.csv" + joined(args));
  ASSERT_EQ(csv.code, 0) << csv.err;
  EXPECT_EQ(read(dir_ / "obs.csv"), csv.out);
  const Result id = run("identify obs.csv --format json");
  ASSERT_EQ(id.code, 0) << id.err;
  EXPECT_EQ(nlohmann::json::parse(id.out)["coefficients"], r["identification"]["coefficients"]);
}

TEST_F(Reduce, BadLogsAndOptionsAreRefused) {
  write("config.toml", config_text());
  write("good.csv", "time,pulses\n0,0\n450,1000\n");
  write("good2.csv", "time,pulses\n0,0\n450,2000\n");  // each run its own log (one log for two is refused)
  write("good3.csv", "time,pulses\n0,0\n450,3000\n");
  write("bad.csv", "time,pulses\n0,0\n450,x\n");
  const std::string base = "reduce config.toml --pulse-weight 1e-3 ";
  expect_bad_input(run(base + "--log 20g=bad.csv --log 25g=good2.csv --log 30g=good3.csv"),
                   {"bad.csv:3:2", "pulses", "not a number"});
  expect_bad_input(run(base + "--log 21g=good.csv"), {"--log", "21g", "20g"});
  expect_bad_input(run(base + "--log 20g=good.csv --log 4=good.csv"), {"logged twice"});
  // The same file for two runs: refused by its bytes, whatever the names (a copy made under another name).
  write("copy.csv", read(dir_ / "good.csv"));
  expect_bad_input(run(base + "--log 20g=good.csv --log 25g=copy.csv --log 30g=good3.csv"),
                   {"run '25g' has the same log as run '20g'", "good.csv", "copy.csv"});
  expect_bad_input(run(base + "--log 20g"), {"RUN=FILE"});
  expect_bad_input(run(base + "--log 20g=missing.csv"), {"missing.csv"});
  expect_bad_input(run("reduce config.toml --pulse-weight -1 --log 20g=good.csv"), {"--pulse-weight"});
  // fewer logged runs than free terms
  expect_bad_input(run(base + "--log 20g=good.csv --log 25g=good.csv"),
                   {"--log", "2 logged run", "K0, K2, K3"});
  const Result unit = run(base + "--angle-unit grad --log 20g=good.csv");
  EXPECT_EQ(unit.code, 2) << unit.err;
  EXPECT_NE(unit.err.find("--angle-unit"), std::string::npos) << unit.err;
  const Result mode = run(base + "--mode approximate --log 20g=good.csv");
  EXPECT_EQ(mode.code, 2) << mode.err;
  EXPECT_NE(mode.err.find("--mode"), std::string::npos) << mode.err;
  expect_bad_input(run(base + "--log 20g=good.csv --log 25g=good2.csv --log 30g=good3.csv -o same.csv "
                              "--observations-out same.csv"),
                   {"--observations-out", "same.csv", "two different files"});
  EXPECT_FALSE(fs::exists(dir_ / "same.csv"));
  // platform encoder samples too far apart for the unwrapping
  write("coarse.csv", "time,pulses,gamma\n0,0,0\n1,1,1\n");
  expect_bad_input(run(base + "--log 20g=coarse.csv --log 25g=good2.csv --log 30g=good3.csv"),
                   {"coarse.csv:3", "gamma", "0.75π"});
  const Result none = run("reduce config.toml");
  EXPECT_EQ(none.code, 2) << none.err;
  EXPECT_NE(none.err.find("--log"), std::string::npos) << none.err;
}

TEST_F(Reduce, PulseWeightTakesAUnitOfTheOutputTimesSeconds) {
  // The output is in deg/s, so a pulse weighs an angle: "1e-3 deg" reduces the same logs to
  // the same bytes as the bare 1e-3 (deg); a length is a wrong unit, said as such with the accepted units,
  // where it was "'1 m' is not a finite number".
  write("config.toml", config_text());
  const ccal::Config cfg = ccal::load_config(dir_ / "config.toml");
  const auto args = write_logs(cfg, dir_, 1e-3, false);
  const Result bare = run("reduce config.toml --format json --pulse-weight 1e-3" + joined(args));
  ASSERT_EQ(bare.code, 0) << bare.err;
  const Result degrees = run("reduce config.toml --format json --pulse-weight '1e-3 deg'" + joined(args));
  ASSERT_EQ(degrees.code, 0) << degrees.err;
  EXPECT_EQ(degrees.out, bare.out);
  expect_bad_input(run("reduce config.toml --pulse-weight '1 m'" + joined(args)),
                   {"--pulse-weight: '1 m': unit 'm' is a length, expected an angle (accepted: rad, mrad",
                    "deg", "or a bare number in deg/s·s"});
  expect_bad_input(run("reduce config.toml --pulse-weight '0 deg'" + joined(args)),
                   {"--pulse-weight: 0 deg is not a positive weight"});
}

}  // namespace

namespace {

// The sample DAQ folders (examples/daq): the semicolon folder by its manifest, and its files one by one with
// --log-layout, give the same coefficients; a layout with --logs and a delimiter left out of the layout are
// refused with what to set.
TEST_F(Reduce, DaqFoldersAndTheirFilesWithALogLayout) {
  const std::string daq = CCAL_SOURCE_DIR + "/examples/daq";
  const std::string config = daq + "/lab_short.toml";
  const Result folder = run("reduce " + config + " --logs " + daq + "/semicolon --format json");
  ASSERT_EQ(folder.code, 0) << folder.err;
  std::string logs;
  for (const char* r : {"5g", "10g", "20g", "30g"}) logs += fmt::format(" --log {}={}/semicolon/{}.csv", r, daq, r);
  const Result files = run("reduce " + config + logs + " --log-layout " + daq + "/semicolon_layout.toml --format json");
  ASSERT_EQ(files.code, 0) << files.err;
  const auto a = nlohmann::json::parse(folder.out), b = nlohmann::json::parse(files.out);
  EXPECT_EQ(a["identification"]["coefficients"], b["identification"]["coefficients"]);
  EXPECT_EQ(a["runs"][2]["gaps"]["count"], 1);
  EXPECT_NEAR(a["runs"][2]["gaps"]["missing_s"].get<double>(), 5.0, 0.08);  // 5 s to a step (72 ms)
  expect_bad_input(run("reduce " + config + " --logs " + daq + "/semicolon --log-layout " + daq +
                       "/semicolon_layout.toml"),
                   {"--log-layout: the folder's manifest has the layout"});
  write("no_preamble.toml", "[format]\nheader_line = 3\n[columns]\ntime = \"t_ms\"\n");
  expect_bad_input(run("reduce " + config + logs + " --log-layout no_preamble.toml"),
                   {"5g.csv:3:1: the header is one name, 't_ms;piga_count;enc_main;enc_platform'",
                    "the delimiter is probably ';'", "delimiter = \"semicolon\""});
}

}  // namespace

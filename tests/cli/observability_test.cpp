// The observability of each term on the command line (docs/cli.md, docs/model.md §14): a plan of whole
// revolutions is refused for K3 by simulate, budget and identify; the paper's plan passes and reports its
// minimum detectable K3; a noisy plan warns of a weak K3; aliased terms keep the fit's messages.
#include <cmath>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

using nlohmann::json;

// The bundled example with `from` replaced by `to` (once).
std::string example_replacing(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The paper's plan with every run lasting the whole number of platform revolutions nearest 450 s,
// T_j = n_j·2π/Ω_j with Ω_j = √(A_j g/R0) (g = 9.8 m/s², R0 = 2.5 m as in the example), from the fixed
// initial phase π.
std::string whole_revolution_example() {
  std::string text =
      example_replacing(read(kExample), "terminal_phase = \"180 deg\"", "initial_phase = \"180 deg\"");
  for (int a = 5; a <= 30; a += 5) {
    const double omega = std::sqrt(a * 9.8 / 2.5);
    const double n = std::round(450 * omega / (2 * std::numbers::pi));
    char line[96];
    std::snprintf(line, sizeof line, "g_level = \"%d g\"\nduration = \"%.17g s\"", a,
                  n * 2 * std::numbers::pi / omega);
    text = example_replacing(text, "g_level = \"" + std::to_string(a) + " g\"", line);
  }
  return text;
}

const std::vector<std::string> kWholeRevolutionHints = {
    "the test plan cannot observe K3: its regressor <a_i^3> averages to round-off in every run",
    "every run lasts a whole number of platform revolutions on a counter-rotating platform",
    "end the runs part-way through a revolution", "or fix K3"};

// ‖h3 − projection on (h0, h2)‖ by the 2×2 normal equations in long double (independent of ccal).
double projected_k3(const json& runs) {
  long double aa = 0, ab = 0, bb = 0, ah = 0, bh = 0, hh = 0;
  for (const auto& run : runs) {
    const long double a = run["regressors"]["K0"].get<double>(), b = run["regressors"]["K2"].get<double>(),
                      h = run["regressors"]["K3"].get<double>();
    aa += a * a, ab += a * b, bb += b * b, ah += a * h, bh += b * h, hh += h * h;
  }
  const long double det = aa * bb - ab * ab;
  const long double ca = (bb * ah - ab * bh) / det, cb = (aa * bh - ab * ah) / det;
  long double sum = 0;
  for (const auto& run : runs) {
    const long double r = run["regressors"]["K3"].get<double>() - ca * run["regressors"]["K0"].get<double>() -
                          cb * run["regressors"]["K2"].get<double>();
    sum += r * r;
  }
  return double(std::sqrt(sum));
}

TEST_F(Cli, WholeRevolutionPlanIsRefusedForK3) {
  const auto expect_whole_revolution_refusal = [](const Result& r, const std::string& file) {
    expect_bad_input(r, {file + ": "});
    for (const auto& h : kWholeRevolutionHints)
      EXPECT_NE(r.err.find(h), std::string::npos) << h << " in " << r.err;
  };
  write("whole.toml", whole_revolution_example());
  const Result s = run("simulate whole.toml -o out.txt --observations-out obs.csv");
  expect_whole_revolution_refusal(s, "whole.toml");
  EXPECT_FALSE(fs::exists(dir_ / "out.txt"));
  EXPECT_FALSE(fs::exists(dir_ / "obs.csv"));
  expect_whole_revolution_refusal(run("simulate whole.toml --format json"), "whole.toml");
  expect_whole_revolution_refusal(run("budget whole.toml"), "whole.toml");
  expect_whole_revolution_refusal(run("budget whole.toml --mode paper --format json"), "whole.toml");
}

TEST_F(Cli, HalfRevolutionsEndingAtPiHideK3Too) {
  // With the paper's terminal phase ψ = π, F(ψ) = 0 and ⟨cos³γ⟩ = F(φ0)/ΩT (F(x) = sin x − sin³x/3), which
  // vanishes when φ0 = (π + ΩT) mod 2π is 0 or π: runs of n + 1/2 revolutions (docs/model.md §14). Refused,
  // with the vanishing column but not the whole-revolution reason.
  std::string text = read(kExample);
  for (int a = 5; a <= 30; a += 5) {
    const double omega = std::sqrt(a * 9.8 / 2.5);
    const double n = std::round(450 * omega / (2 * std::numbers::pi));
    char line[96];
    std::snprintf(line, sizeof line, "g_level = \"%d g\"\nduration = \"%.17g s\"", a,
                  (n + 0.5) * 2 * std::numbers::pi / omega);
    text = example_replacing(text, "g_level = \"" + std::to_string(a) + " g\"", line);
  }
  write("half.toml", text);
  const Result r = run("simulate half.toml");
  expect_bad_input(r,
                   {"half.toml: the test plan cannot observe K3: its regressor <a_i^3> averages to round-off",
                    "so that <a_i^3> does not average out, or fix K3"});
  EXPECT_EQ(r.err.find("whole number"), std::string::npos) << r.err;
}

TEST_F(Cli, IdentifyRefusesAVanishingColumnOfAnObservationsFile) {
  // The same plan with K3 held fixed can be simulated; fitting K3 from its file is refused. The file does not
  // record durations, so ccal names the vanishing column without the whole-revolution reason.
  std::string cfg = example_replacing(whole_revolution_example(), "terms = [\"K0\", \"K2\", \"K3\"]",
                                      "terms = [\"K0\", \"K2\"]");
  cfg = example_replacing(cfg, "fixed = [\"K1\"]", "fixed = [\"K1\", \"K3\"]");
  write("fixed_k3.toml", cfg);
  const Result made = run("simulate fixed_k3.toml --observations-out obs.csv -o sim.txt");
  ASSERT_EQ(made.code, 0) << made.err;
  const Result i = run("identify obs.csv --terms K0,K2:K2,K3:K3 --fix K1:K1=505.2097");
  expect_bad_input(
      i,
      {"obs.csv: the test plan cannot observe K3: its regressor <a_i^3> averages to round-off", "or fix K3"});
  EXPECT_EQ(i.err.find("whole number"), std::string::npos) << i.err;
}

TEST_F(Cli, PaperPlanPassesAndReportsItsMinimumDetectableK3) {
  const Result s = run("simulate --format json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_TRUE(s.err.empty()) << s.err;
  const json j = json::parse(s.out);
  const json& o = j["identification"]["observability"];
  EXPECT_EQ(o["detection_factor"], 3.0);
  EXPECT_FALSE(o["whole_revolutions"].get<bool>());
  for (const char* k : {"K0", "K2", "K3"}) EXPECT_EQ(o["terms"][k]["status"], "ok") << k;
  const json& k3 = o["terms"]["K3"];
  EXPECT_EQ(k3["unit"], "deg/s/g^3");
  // Noise-free: only the floating-point resolution limits it; its sensitivity is the projected K3 column.
  const double s3 = projected_k3(j["runs"]);
  EXPECT_NEAR(k3["sensitivity"].get<double>(), s3, 1e-9 * s3);  // two projections of the same 17-digit data
  const double limit = k3["min_detectable"].get<double>();
  EXPECT_GT(limit, 0.0);
  EXPECT_LT(limit, 1e-9);  // far below K3 = 0.003 deg/s/g^3
  EXPECT_NEAR(limit, 3 * k3["standard_error"].get<double>(), 1e-15 * limit);

  const Result text = run("simulate");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("observability (resolution of the run means"), std::string::npos);
  EXPECT_NE(text.out.find("min detectable"), std::string::npos);

  const Result b = run("budget --format json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(json::parse(b.out)["observability"]["terms"]["K3"]["status"], "ok");

  const Result made = run("simulate --observations-out obs.csv -o sim.txt");
  ASSERT_EQ(made.code, 0) << made.err;
  const Result i = run("identify obs.csv --format json");
  ASSERT_EQ(i.code, 0) << i.err;
  const json ij = json::parse(i.out);
  EXPECT_NE(ij["observability"]["resolution_basis"].get<std::string>().find("residual standard deviation"),
            std::string::npos);
  EXPECT_EQ(ij["observability"]["terms"]["K3"]["status"], "ok");
}

TEST_F(Cli, ANoisyPlanWarnsOfAWeakK3) {
  // N = 0.3 deg/s/√Hz over T = 450 s: σ = 0.3/√450 = 0.0141 deg/s in every run (the floating-point term,
  // ~1e-11, is negligible), so δK3 = 3σ/‖P⊥h3‖ ≈ 0.016 deg/s/g³: above K3 = 0.003 (budget) and the fitted
  // value (seed 1), while δK0 ≈ 0.033 deg/s stays below K0 = 0.062 and δK2 ≈ 1.6e-4 below K2 = 0.02. One
  // warning on standard error, the same in the JSON, exit 0.
  write("noisy.toml", example_replacing(read(kExample), "noise_density = \"0 deg/s/rtHz\"",
                                        "noise_density = \"0.3 deg/s/rtHz\""));
  const Result s = run("simulate noisy.toml --format json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_TRUE(s.err.starts_with("ccal: warning: K3 is weak: the smallest change the plan can detect is "))
      << s.err;
  const json j = json::parse(s.out);
  const json& o = j["identification"]["observability"];
  EXPECT_EQ(o["terms"]["K3"]["status"], "weak");
  ASSERT_EQ(o["warnings"].size(), 1u);
  EXPECT_NE(o["warnings"][0].get<std::string>().find("K3 is weak"), std::string::npos);
  const double expected = 3 * (0.3 / std::sqrt(450.0)) / projected_k3(j["runs"]);
  // σ: the noise term alone to 1e-20 relative; the projection to 1e-9 (as above).
  EXPECT_NEAR(o["terms"]["K3"]["min_detectable"].get<double>(), expected, 1e-9 * expected);
  EXPECT_EQ(o["terms"]["K2"]["status"], "ok");
  EXPECT_EQ(o["terms"]["K0"]["status"], "ok");

  const Result b = run("budget noisy.toml --format json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.err.find("ccal: warning: K3 is weak"), std::string::npos) << b.err;
  EXPECT_EQ(json::parse(b.out)["observability"]["terms"]["K3"]["status"], "weak");
}

// Pulse logs (time, cumulative pulses of 1e-3 deg) with the given mean outputs [deg/s] over the given spans
// [s], two samples each (the mean of a pulse log needs only its ends), and the --log options naming them.
std::string write_pulse_logs(
    const Cli& cli, const std::vector<double>& outputs, const std::vector<double>& spans,
    const std::function<std::string(const std::string&, const std::string&)>& write) {
  (void)cli;
  std::string args;
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const std::string name = std::to_string(5 * (k + 1)) + "g";
    char text[128];
    std::snprintf(text, sizeof text, "time,pulses\n0,0\n%.17g,%.17g\n", spans[k],
                  outputs[k] * spans[k] / 1e-3);
    args += " --log " + name + "=" + write(name + ".csv", text);
  }
  return args + " --pulse-weight 1e-3";
}

TEST_F(Cli, ReduceReportsAndRefusesAsSimulateDoes) {
  const auto writer = [this](const std::string& name, const std::string& text) { return write(name, text); };
  // The paper's plan: the simulated mean outputs as logs of 450 s reduce to an observable K3.
  const Result s = run("simulate --format json");
  ASSERT_EQ(s.code, 0) << s.err;
  std::vector<double> outputs, spans;
  const json simulated = json::parse(s.out);
  for (const auto& r : simulated["runs"]) {
    outputs.push_back(r["output"].get<double>());
    spans.push_back(r["duration_s"].get<double>());
  }
  const Result red = run("reduce --format json" + write_pulse_logs(*this, outputs, spans, writer));
  ASSERT_EQ(red.code, 0) << red.err;
  EXPECT_EQ(json::parse(red.out)["identification"]["observability"]["terms"]["K3"]["status"], "ok");
  // Logs of whole revolutions (the spans of whole.toml's runs): the runs as measured are refused for K3.
  write("whole.toml", whole_revolution_example());
  spans.clear();
  for (int a = 5; a <= 30; a += 5) {
    const double omega = std::sqrt(a * 9.8 / 2.5);
    spans.push_back(std::round(450 * omega / (2 * std::numbers::pi)) * 2 * std::numbers::pi / omega);
  }
  const Result whole = run("reduce whole.toml" + write_pulse_logs(*this, outputs, spans, writer));
  expect_bad_input(whole,
                   {"whole.toml: the test plan cannot observe K3", "whole number of platform revolutions"});
}

TEST_F(Cli, AliasedTermsKeepTheFitsMessages) {
  // K_oo with K0 (a_o = 1 g in every run of the IA-horizontal plan: exactly dependent columns) and K2 with
  // K_pp (correlated beyond 0.99999) are refused with the fit's messages, not as unobservable single terms.
  write("oo.toml", example_replacing(read(kExample), "terms = [\"K0\", \"K2\", \"K3\"]",
                                     "terms = [\"K0\", \"K2\", \"K3\", \"K_oo\"]"));
  for (const char* verb : {"simulate", "budget"}) {
    const Result r = run(std::string(verb) + " oo.toml");
    expect_bad_input(r, {"cannot separate K0 and K_oo"});
    EXPECT_EQ(r.err.find("cannot observe"), std::string::npos) << r.err;
  }
  write("pp.toml", example_replacing(read(kExample), "terms = [\"K0\", \"K2\", \"K3\"]",
                                     "terms = [\"K0\", \"K2\", \"K3\", \"K_pp\"]"));
  for (const char* verb : {"simulate", "budget"}) {
    const Result r = run(std::string(verb) + " pp.toml");
    expect_bad_input(r, {"cannot separate K2 and K_pp"});
    EXPECT_EQ(r.err.find("cannot observe"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace ccal::test

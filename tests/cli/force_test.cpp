// End-to-end tests of the ccal program: exit codes, one-line error messages with file:line, text and JSON
// output of `ccal force`, and -o writing the file only on success.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;
namespace fs = std::filesystem;

TEST_F(Cli, VersionAndHelp) {
  const Result v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("ccal 0."), std::string::npos) << v.out;
  const Result h = run("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("force"), std::string::npos);
  const Result fh = run("force --help");
  EXPECT_EQ(fh.code, 0);
  EXPECT_NE(fh.out.find("Examples:"), std::string::npos) << fh.out;
  EXPECT_NE(fh.out.find("--time"), std::string::npos);
  expect_bad_input(run(""), {"needs a command", "accepted: budget"});
  expect_bad_input(run("frobnicate"), {"frobnicate"});
}

TEST_F(Cli, ForceDefaultIsRunOneOfTheBundledExample) {
  const Result r = run("force");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("'5g'"), std::string::npos) << r.out;
  // At t = 0, error-free, Earth rotating (model.md §1, §5.2): a_IA = −(A + C) cos φ0 with A = 5 g, the
  // Coriolis amplitude C = 2 ω_e R0 Ω sin φ / g (ω_e = 7.2921150e-5 rad/s, R0 = 2.5 m, φ = 45.75°,
  // g = 9.8 m/s², Ω = √(A g/R0)) = 1.18e-4 g, and φ0 = (π + ΩT) mod 2π, T = 450 s (ψ = π). The text prints 8
  // significant digits (4.4688017): tolerance 1e-7 g, a thousandth of the Coriolis term.
  const double g = 9.8, R0 = 2.5, A = 5.0, rate = std::sqrt(A * g / R0);
  const double phi0 = std::fmod(std::numbers::pi + rate * 450.0, 2 * std::numbers::pi);
  const double C = 2 * 7.2921150e-5 * R0 * rate * std::sin(45.75 * std::numbers::pi / 180) / g;
  const double expected = -(A + C) * std::cos(phi0);
  const auto at = r.out.find("specific force [g]");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double f_ia = std::stod(r.out.substr(at + std::string("specific force [g]").size()));
  EXPECT_NEAR(f_ia, expected, 1e-7) << r.out;
  EXPECT_NE(r.out.find("first-order total"), std::string::npos);
  EXPECT_NE(r.out.find("remainder"), std::string::npos);
}

TEST_F(Cli, ForceJsonHasTheDocumentedKeys) {
  const Result r = run("force --run 20g --time '10 s' --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("command"), "force");
  EXPECT_EQ(j.at("mode"), "exact");
  const auto& run = j.at("run");
  EXPECT_EQ(run.at("name"), "20g");
  EXPECT_EQ(run.at("index"), 4);
  EXPECT_DOUBLE_EQ(run.at("g_level_g").get<double>(), 20.0);
  EXPECT_NEAR(run.at("rate_rad_per_s").get<double>(), 8.854377, 1e-6);
  EXPECT_NEAR(run.at("initial_phase_rad").get<double>(), 4.0720, 1e-4);
  EXPECT_DOUBLE_EQ(run.at("duration_s").get<double>(), 450.0);
  EXPECT_DOUBLE_EQ(run.at("time_s").get<double>(), 10.0);
  for (const char* key :
       {"theta1_rad", "theta1_rate_rad_per_s", "beta_rad", "gamma_rad", "gamma_rate_rad_per_s"})
    EXPECT_TRUE(j.at("joint_state").contains(key)) << key;
  for (const char* axis : {"IA", "PA", "OA"}) {
    EXPECT_TRUE(j.at("specific_force_g").at(axis).is_number()) << axis;
    EXPECT_TRUE(j.at("angular_rate_deg_per_s").at(axis).is_number()) << axis;
  }
  // Error-free chain at 20 g, t = 10 s, counter-rotating, Earth on (model.md §1), written out: Ω = √(A g/R0),
  // φ0 = (π + ΩT) mod 2π, γ = φ0 − Ωt, θ1 = Ωt; the Coriolis force of the tangential velocity R0 Ω adds
  // C = 2 ω_e R0 Ω sin φ / g inward and 2 ω_e R0 Ω cos φ sin θ1 / g upward:
  //   IA = −(A + C) cos γ, PA = (A + C) sin γ, OA = 1 + 2 ω_e R0 Ω cos φ sin θ1 / g;
  // the platform keeps its heading ψ = φ0, so the sensed rate is the Earth's: ω_e (cos φ sin ψ, cos φ cos ψ,
  // sin φ) on IA, PA, OA. JSON carries 17 digits; the phase Ωt ≈ 88 rad carries ~1e-14 rad of round-off:
  // tolerances 1e-11 g and 1e-12 deg/s. (The Coriolis terms are 2.4e-4 g and 1.3e-4 g.)
  {
    const double g = 9.8, R0 = 2.5, A = 20.0, t = 10.0, we = 7.2921150e-5;
    const double lat = 45.75 * std::numbers::pi / 180, rate = std::sqrt(A * g / R0);
    const double phi0 = std::fmod(std::numbers::pi + rate * 450.0, 2 * std::numbers::pi);
    const double gamma = phi0 - rate * t, theta1 = rate * t;
    const double B = A + 2 * we * R0 * rate * std::sin(lat) / g;
    const auto& f = j.at("specific_force_g");
    EXPECT_NEAR(f["IA"].get<double>(), -B * std::cos(gamma), 1e-11);
    EXPECT_NEAR(f["PA"].get<double>(), B * std::sin(gamma), 1e-11);
    EXPECT_NEAR(f["OA"].get<double>(), 1 + 2 * we * R0 * rate * std::cos(lat) * std::sin(theta1) / g, 1e-11);
    const auto& w = j.at("angular_rate_deg_per_s");
    const double to_deg = 180 / std::numbers::pi;
    EXPECT_NEAR(w["IA"].get<double>(), we * std::cos(lat) * std::sin(phi0) * to_deg, 1e-12);
    EXPECT_NEAR(w["PA"].get<double>(), we * std::cos(lat) * std::cos(phi0) * to_deg, 1e-12);
    EXPECT_NEAR(w["OA"].get<double>(), we * std::sin(lat) * to_deg, 1e-12);
  }
  EXPECT_TRUE(j.at("contributions").is_array());
  EXPECT_TRUE(j.at("contributions").empty());  // the example's [errors] are all zero
  for (const char* part : {"nominal", "total", "exact", "remainder"}) {
    EXPECT_TRUE(j.at("first_order").at(part).at("f_IA_g").is_number()) << part;
    EXPECT_TRUE(j.at("first_order").at(part).at("w_IA_deg_per_s").is_number()) << part;
  }
  EXPECT_DOUBLE_EQ(j["first_order"]["exact"]["f_IA_g"].get<double>(),
                   j["specific_force_g"]["IA"].get<double>());
}

TEST_F(Cli, ForceContributionsOfConfiguredErrors) {
  const int line = line_of(read(kExample), "[errors]");
  ASSERT_GT(line, 0);
  const std::string cfg = write(
      "e.toml",
      example_with_line(line, "[errors]\ndthz5 = \"2 arcsec\"\ndx3_c1 = \"5 um\"\ndomega = \"1e-6 rad/s\""));
  for (const char* mode : {"exact", "paper"}) {
    const Result r = run("force e.toml --run 3 --time 12.5 --format json --mode " + std::string(mode));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("mode"), mode);
    const auto& c = j.at("contributions");
    ASSERT_EQ(c.size(), 3u) << mode;
    EXPECT_EQ(c[0].at("id"), "dthz5");
    EXPECT_EQ(c[0].at("unit"), "rad");
    EXPECT_NEAR(c[0].at("value_si").get<double>(), 2 * std::numbers::pi / 648000, 1e-15);
    EXPECT_EQ(c[1].at("id"), "domega");
    EXPECT_EQ(c[1].at("unit"), "rad/s");
    EXPECT_EQ(c[2].at("id"), "dx3_c1");
    EXPECT_EQ(c[2].at("unit"), "m");
    double sum = j["first_order"]["nominal"]["f_IA_g"].get<double>();
    for (const auto& item : c) {
      EXPECT_TRUE(item.at("f_IA_g").is_number());
      EXPECT_TRUE(item.at("w_IA_deg_per_s").is_number());
      sum += item["f_IA_g"].get<double>();
    }
    EXPECT_NEAR(sum, j["first_order"]["total"]["f_IA_g"].get<double>(), 1e-12);
    const double remainder = j["first_order"]["remainder"]["f_IA_g"].get<double>();
    EXPECT_NEAR(
        remainder,
        j["first_order"]["exact"]["f_IA_g"].get<double>() - j["first_order"]["total"]["f_IA_g"].get<double>(),
        1e-12);
    // Exact model: what is left is second order in ~1e-5 errors. (Paper mode leaves its model error too.)
    if (std::string(mode) == "exact") {
      EXPECT_LT(std::abs(remainder), 1e-8) << remainder;
    }
    // The IA-azimuth error moves f_IA by about A·δ·sin γ: at most 15 g × 9.7e-6 rad.
    EXPECT_LT(std::abs(c[0]["f_IA_g"].get<double>()), 15 * 1e-5);
    EXPECT_GT(std::abs(c[0]["f_IA_g"].get<double>()), 0.0);
  }
  // Text output lists them too.
  const Result t = run("force e.toml --run 3 --time 12.5");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("dthz5"), std::string::npos);
  EXPECT_NE(t.out.find("dx3_c1"), std::string::npos);
}

TEST_F(Cli, BadConfigIsExitCodeTwoWithFileAndLine) {
  const std::string text = read(kExample);
  const int radius = line_of(text, "radius = ");
  ASSERT_GT(radius, 0);
  expect_bad_input(
      run("force " + write("a.toml", example_with_line(radius, "radious = \"2.5 m\""))),
      {"a.toml:" + std::to_string(radius) + ":", "centrifuge.radious", "did you mean 'radius'?"});
  expect_bad_input(run("force " + write("b.toml", example_with_line(radius, "radius = \"2.5 s\""))),
                   {"b.toml:" + std::to_string(radius) + ":", "centrifuge.radius", "expected a length"});
  expect_bad_input(run("force " + write("c.toml", example_with_line(radius, "radius = \"-2.5 m\""))),
                   {"c.toml:" + std::to_string(radius) + ":", "centrifuge.radius", "must be positive"});
  expect_bad_input(run("force " + write("d.toml", example_with_line(radius, "radius = \"nan m\""))),
                   {"d.toml:" + std::to_string(radius) + ":", "not a finite number"});
  expect_bad_input(
      run("force " + write("e.toml", example_with_line(radius, "radius = 2.5"))),
      {"e.toml:" + std::to_string(radius) + ":", "expected a quantity string such as \"2.5 m\""});
  expect_bad_input(run("force " + write("f.toml", "[site\n")), {"f.toml:1:", "TOML syntax error"});
  expect_bad_input(run("force missing.toml"), {"missing.toml: cannot read"});
}

TEST_F(Cli, BadRunAndTime) {
  expect_bad_input(run("force --run 7"), {"--run: '7' is no run", "1..6"});
  expect_bad_input(run("force --run 0"), {"--run"});
  expect_bad_input(run("force --run 35g"), {"--run", "5g, 10g"});
  expect_bad_input(run("force --time 451"), {"--time", "outside run '5g'", "0 to 450 s"});
  expect_bad_input(run("force --time '-1 s'"), {"--time", "outside"});
  expect_bad_input(run("force --time '10 m'"), {"--time", "expected a time"});
  expect_bad_input(run("force --time abc"), {"--time"});
  expect_bad_input(run("force --mode fast"), {"--mode"});
  expect_bad_input(run("force --format xml"), {"--format", "xml"});
  // Boundaries are accepted; a bare number is seconds, a unit converts.
  EXPECT_EQ(run("force --time 450").code, 0);
  EXPECT_EQ(run("force --time '7.5 min'").code, 0);
  EXPECT_EQ(run("force --run 30g --time 0").code, 0);
}

TEST_F(Cli, OutputFileOnlyOnSuccess) {
  const Result ok = run("force --format json -o out.json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(ok.out.empty());
  ASSERT_TRUE(fs::exists(dir_ / "out.json"));
  const nlohmann::json j = nlohmann::json::parse(read(dir_ / "out.json"));
  EXPECT_EQ(j.at("run").at("name"), "5g");

  const std::string bad =
      write("bad.toml", "[site]\nlatitude = \"45 deg\"\n[centrifuge]\nradius = \"-1 m\"\n");
  const Result failed = run("force " + bad + " -o failed.json");
  expect_bad_input(failed, {"bad.toml:4:"});
  EXPECT_FALSE(fs::exists(dir_ / "failed.json"));
  const Result bad_time = run("force --time 1000 -o failed.json");
  EXPECT_EQ(bad_time.code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "failed.json"));
  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  // An unwritable destination is a bad input too.
  expect_bad_input(run("force -o /nonexistent-dir/x.json"), {"-o", "/nonexistent-dir/x.json"});
}

}  // namespace

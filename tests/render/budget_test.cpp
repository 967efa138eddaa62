// The text, JSON and CSV of `ccal budget` as an engineer reads them (render/budget.hpp): lines within 100
// columns, UTF-8 names aligned by displayed width, tolerances in the configuration's units with u(x_i) and
// c_i, the further columns of a GUM budget (EA-4/02: x_i, divisor, type, ν_i, the unit of c_i) in text, JSON
// and CSV, round-off below the stated floor shown as 0, CSV totals equal to the JSON, and the bias of
// uncompensated known errors equal to the coefficient shift `ccal simulate` shows for the same errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/core/constants.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/simulate.hpp"
#include "ccal/render/table.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/simulate.hpp"
#include "test_paths.hpp"

namespace ccal {
namespace {

std::string example_text() {
  std::ifstream in(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The example with `from` replaced by `to` (once; the text must hold `from`).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The line holding `needle`, and the header of its table: the line above the first rule above it.
std::pair<std::string, std::string> row_and_header(const std::string& text, const std::string& needle) {
  const std::vector<std::string> lines = lines_of(text);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].find(needle) == std::string::npos) continue;
    for (std::size_t r = k; r-- > 1;)
      if (lines[r].find_first_not_of(" -") == std::string::npos && lines[r].find('-') != std::string::npos)
        return {lines[k], lines[r - 1]};
  }
  return {};
}

TEST(BudgetText, NoLineOver100ColumnsByDefault) {
  const verbs::BudgetResult exact = verbs::budget(bundled_example());
  BudgetOptions paper_options;
  paper_options.mode = ModelMode::paper;
  const verbs::BudgetResult paper = verbs::budget(bundled_example(), paper_options);
  render::BudgetTextOptions top3;
  top3.top = 3;
  for (const std::string& text : {render::text(exact), render::text(paper), render::text(exact, top3)})
    for (const std::string& line : lines_of(text)) EXPECT_LE(render::display_width(line), 100u) << line;
  // A 90-column terminal gets 90 columns: the names give way (down to their header's width).
  render::BudgetTextOptions narrow;
  narrow.width = 90;
  for (const std::string& line : lines_of(render::text(exact, narrow)))
    EXPECT_LE(render::display_width(line), 90u) << line;
  // --wide cuts nothing: the catalogue's full names are there.
  render::BudgetTextOptions wide;
  wide.wide = true;
  EXPECT_NE(render::text(exact, wide).find("perpendicularity of azimuth axis to horizontal axis"),
            std::string::npos);
}

TEST(BudgetText, AnswerTopRowsAndNextSteps) {
  const verbs::BudgetResult r = verbs::budget(bundled_example());
  render::BudgetTextOptions o;
  o.top = 4;
  const std::string text = render::text(r, o);
  EXPECT_NE(text.find("The answer"), std::string::npos);
  EXPECT_NE(text.find("  K3: U = "), std::string::npos);
  // 52 sources and 2 rate noises per coefficient: 4 listed, 50 in the summed row.
  EXPECT_NE(text.find("50 more, root-sum-square"), std::string::npos) << text;
  const std::vector<std::string> lines = lines_of(text);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_NE(lines[lines.size() - 3].find("ccal allocate --target"), std::string::npos);
  EXPECT_NE(lines[lines.size() - 2].find("ccal design"), std::string::npos);
  EXPECT_NE(lines.back().find("ccal montecarlo --digits 2"), std::string::npos);
}

TEST(BudgetText, Utf8GroupAndRunNamesAlign) {
  // A group and a run named with non-ASCII letters: each row is as wide, in displayed characters, as its
  // table's header (the last column is right-aligned), which byte counts would miss by one per "ä" or "µ".
  std::string text =
      replaced(example_text(), "dR_s = \"25 um\"", "dR_s = { bound = \"25 µm\", group = \"Längen-µ\" }");
  text = replaced(text, "dy2t = \"25 um\"", "dy2t = { bound = \"25 µm\", group = \"Längen-µ\" }");
  text = replaced(text, "name = \"5g\"", "name = \"Lauf-ä-5g\"");
  const Config cfg = parse_config(text, "utf8.toml");
  render::BudgetTextOptions wide;
  wide.wide = true;  // every source listed
  const std::string budget = render::text(verbs::budget(cfg), wide);
  const auto [row, header] = row_and_header(budget, "dR_s (Längen-µ)");
  ASSERT_FALSE(row.empty()) << budget;
  EXPECT_EQ(render::display_width(row), render::display_width(header)) << row << "\n" << header;
  EXPECT_NE(row.size(), header.size());  // bytes differ: the check above is not vacuous
  const std::string simulate = render::text(verbs::simulate(cfg));
  const auto [run_row, run_header] = row_and_header(simulate, "Lauf-ä-5g");
  ASSERT_FALSE(run_row.empty()) << simulate;
  EXPECT_EQ(render::display_width(run_row), render::display_width(run_header)) << run_row << "\n"
                                                                               << run_header;
}

TEST(BudgetText, ToleranceInTheConfigurationsUnitWithUAndC) {
  const Config cfg =
      parse_config(replaced(example_text(), "dthz5 = \"1e-5 rad\"", "dthz5 = \"2 arcsec\""), "arcsec.toml");
  const verbs::BudgetResult r = verbs::budget(cfg);
  const auto j = nlohmann::json::parse(render::json(r));
  bool found = false;
  for (const auto& s : j["sources"]) {
    // c_i u(x_i) = u_i(y) for every source and coefficient: relative 1e-12 (one product in double).
    for (const auto& [k, effect] : s["effect"].items()) {
      const double c = s["sensitivity"][k], u = s["standard_uncertainty"];
      EXPECT_NEAR(c * u, effect.get<double>(), 1e-12 * std::abs(effect.get<double>()) + 1e-300) << s["id"];
    }
    if (s["id"] != "dthz5") continue;
    found = true;
    EXPECT_EQ(s["unit"], "arcsec");
    EXPECT_NEAR(s["bound"].get<double>(), 2, 1e-13);  // arcsec → rad → arcsec: round-off only
    EXPECT_EQ(s["name"], "instrument azimuth (IA) zero error");
  }
  EXPECT_TRUE(found);
  render::BudgetTextOptions all;
  all.top = 100;
  const auto [row, header] = row_and_header(render::text(r, all), "  dthz5");
  EXPECT_NE(row.find("2 arcsec"), std::string::npos) << row;
  EXPECT_NE(header.find("u(x_i)"), std::string::npos) << header;
  EXPECT_NE(header.find("c_i"), std::string::npos) << header;
}

// The CSV's cells by column name, for the row whose source is `source`.
std::map<std::string, std::string> csv_row(const std::string& csv, const std::string& source) {
  const std::vector<std::string> lines = lines_of(csv);
  auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        cells.push_back(std::exchange(cell, ""));
      else
        cell += c;
    }
    cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> header = split(lines.at(0));
  for (const std::string& line : lines) {
    const std::vector<std::string> cells = split(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    if (cells.size() > 1 && cells[1] == source) {
      std::map<std::string, std::string> row;
      for (std::size_t c = 0; c < header.size() && c < cells.size(); ++c) row[header[c]] = cells[c];
      return row;
    }
  }
  return {};
}

TEST(BudgetText, CsvTotalsEqualTheJson) {
  BudgetOptions o;
  o.coverage_factor = 3;
  const verbs::BudgetResult r = verbs::budget(bundled_example(), o);
  const auto j = nlohmann::json::parse(render::json(r));
  const std::string csv = render::csv(r);
  const auto u = csv_row(csv, "total_standard_uncertainty");
  const auto U = csv_row(csv, "expanded_uncertainty");
  ASSERT_FALSE(u.empty()) << csv;
  ASSERT_FALSE(U.empty()) << csv;
  EXPECT_EQ(U.at("distribution"), "k = 3 (stated), p = 99.73 % for a normal quantity");  // its coverage
  for (const auto& c : j["coefficients"]) {
    std::string unit = c["unit"].get<std::string>();  // deg/s/g^2 → deg_s_g2 in the column's name
    unit.erase(std::remove(unit.begin(), unit.end(), '^'), unit.end());
    std::replace(unit.begin(), unit.end(), '/', '_');
    // Appended, not "d" + id + ...: GCC 12 misreads that inlined here (-Wrestrict).
    std::string column = "d";
    column.append(c["id"].get<std::string>()).append("_").append(unit);
    // Both are the same double printed to 17 digits: equal after parsing.
    EXPECT_EQ(std::stod(u.at(column)), c["standard_uncertainty"].get<double>()) << column;
    EXPECT_EQ(std::stod(U.at(column)), c["expanded_uncertainty"].get<double>()) << column;
  }
  // c_i is there too: c_K3 × u_x = dK3 for the first-ranked source, relative 1e-12.
  const auto first = csv_row(csv, j["sources"][0]["id"]);
  EXPECT_NEAR(std::stod(first.at("c_K3_deg_s_g3_per_unit")) * std::stod(first.at("u_x")),
              std::stod(first.at("dK3_deg_s_g3")), 1e-12 * std::abs(std::stod(first.at("dK3_deg_s_g3"))));
}

// The example with a tolerance written in arcsec and one of each distribution in um, and known [errors].
Config gum_example() {
  std::string text = replaced(example_text(), "dthz5 = \"1e-5 rad\"", "dthz5 = \"2 arcsec\"");
  text = replaced(text, "dR_s = \"25 um\"", "dR_s = { bound = \"30 um\", distribution = \"uniform\" }");
  text = replaced(text, "dx5 = \"25 um\"", "dx5 = { bound = \"60 um\", distribution = \"triangular\" }");
  text = replaced(text, "# dthz5 = \"2 arcsec\"", "dthz5 = \"1.5 arcsec\"");
  text = replaced(text, "# dx3_c1 = \"5 um\"", "dx3_c1 = \"5 um\"");
  return parse_config(text, "gum.toml");
}

// The columns of EA-4/02 per source: x_i and u(x_i) in the unit the tolerance was written in, the divisor of
// its distribution, Type B (a drive's rate noise Type A), ν_i = ∞, the unit of c_i.
TEST(BudgetText, GumColumnsInTheUnitsAsWritten) {
  const verbs::BudgetResult r = verbs::budget(gum_example());
  const auto j = nlohmann::json::parse(render::json(r));
  std::map<std::string, nlohmann::json> by_id;
  for (const auto& s : j["sources"]) by_id[s["id"]] = s;
  // "2 arcsec", normal: u = 2 arcsec, divisor 1, x_i = the [errors] 1.5 arcsec (arcsec → rad → arcsec:
  // round-off only, 1e-13).
  const auto& z = by_id.at("dthz5");
  EXPECT_EQ(z["unit"], "arcsec");
  EXPECT_NEAR(z["standard_uncertainty"].get<double>(), 2, 1e-13);
  EXPECT_NEAR(z["estimate"].get<double>(), 1.5, 1e-13);
  EXPECT_NEAR(z["estimate_si"].get<double>(), 1.5 * constants::arcsec, 1e-20);
  EXPECT_EQ(z["divisor"].get<double>(), 1.0);
  EXPECT_EQ(z["type"], "B");
  EXPECT_TRUE(z["dof"].is_null());  // ∞
  EXPECT_EQ(z["sensitivity_unit"]["K3"], "deg/s/g^3 per arcsec");
  EXPECT_EQ(by_id.at("dx3_c1")["estimate"].get<double>(), 5.0);  // "5 um" of [errors] in the tolerance's um
  EXPECT_EQ(by_id.at("dy5")["estimate"].get<double>(), 0.0);     // not in [errors]
  // The divisors, exactly those σ is computed with (setup/tolerance.hpp), and u(x_i) = bound / divisor to
  // the rounding of one division (relative 1e-15).
  EXPECT_EQ(by_id.at("dR_s")["divisor"].get<double>(), std::sqrt(3.0));
  EXPECT_NEAR(by_id.at("dR_s")["standard_uncertainty"].get<double>(), 30 / std::sqrt(3.0), 1e-15 * 30);
  EXPECT_EQ(by_id.at("dx5")["divisor"].get<double>(), std::sqrt(6.0));
  EXPECT_NEAR(by_id.at("dx5")["standard_uncertainty"].get<double>(), 60 / std::sqrt(6.0), 1e-15 * 60);
  EXPECT_EQ(by_id.at("ripple1_c1")["divisor"].get<double>(), std::sqrt(2.0));
  for (const auto& [id, s] : by_id)
    EXPECT_NEAR(s["standard_uncertainty"].get<double>() * s["divisor"].get<double>(), s["bound"].get<double>(),
                1e-15 * s["bound"].get<double>())
        << id;
  // The drives' rate noise: Type A, ν = ∞, u(x_i) = N in ppm/rtHz, c_i u(x_i) = u_i(y) (relative 1e-15).
  ASSERT_EQ(j["rate_noise"].size(), 2u);
  for (const auto& n : j["rate_noise"]) {
    EXPECT_EQ(n["type"], "A");
    EXPECT_TRUE(n["dof"].is_null());
    EXPECT_EQ(n["unit"], "ppm/rtHz");
    EXPECT_NEAR(n["standard_uncertainty"].get<double>(), n["density_per_rtHz"].get<double>() * 1e6, 1e-15);
    const double u = n["u"]["K3"], c = n["sensitivity"]["K3"];
    EXPECT_NEAR(c * n["standard_uncertainty"].get<double>(), u, 1e-15 * u);
  }
  // The text: the compact table has the divisor (every line listed: 120 columns keep it); --wide adds x_i
  // (as configured), the type, ν_i and the unit of c_i (the K0 table comes first).
  render::BudgetTextOptions all;
  all.top = 100;
  all.width = 120;
  EXPECT_NE(row_and_header(render::text(r, all), "  dR_s ").first.find("√3"), std::string::npos);
  const auto [row, header] = row_and_header(render::text(r, all), "  dthz5 ");
  EXPECT_NE(row.find("2 arcsec"), std::string::npos) << row;
  EXPECT_NE(header.find("÷"), std::string::npos) << header;
  render::BudgetTextOptions wide;
  wide.wide = true;
  const auto [wide_row, wide_header] = row_and_header(render::text(r, wide), "  dthz5 ");
  for (const char* cell : {"1.5 arcsec", "2 arcsec", " B ", "∞", "deg/s per arcsec"})
    EXPECT_NE(wide_row.find(cell), std::string::npos) << cell << "\n" << wide_row;
  for (const char* column : {"type", "x_i", "ν_i", "unit of c_i"})
    EXPECT_NE(wide_header.find(column), std::string::npos) << column;
  // The CSV: the same fields at the end of each row.
  const auto csv = csv_row(render::csv(r), "dthz5");
  EXPECT_EQ(csv.at("type"), "B");
  EXPECT_EQ(csv.at("dof"), "inf");
  EXPECT_EQ(std::stod(csv.at("divisor")), 1.0);
  EXPECT_NEAR(std::stod(csv.at("estimate")), 1.5, 1e-13);
  EXPECT_EQ(csv.at("c_K3_unit"), "deg/s/g^3 per arcsec");
  EXPECT_EQ(csv_row(render::csv(r), "main_rate_noise").at("type"), "A");
}

// A contribution below 1e-12 of its coefficient's u is round-off: the tables show it, its c_i and its share as
// 0, JSON and CSV keep it and state the floor. In the bundled example dthx4 and dthx5 turn the instrument about
// its IA and move nothing; the linearised derivatives leave them 1e-18 u instead of 0.
TEST(BudgetText, RoundOffBelowTheFloorIsShownAsZero) {
  const verbs::BudgetResult r = verbs::budget(bundled_example());
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["round_off_floor_relative"].get<double>(), 1e-12);
  for (const auto& c : j["coefficients"])  // one product's rounding: relative 1e-15
    EXPECT_NEAR(c["round_off_floor"].get<double>(), 1e-12 * c["standard_uncertainty"].get<double>(),
                1e-15 * c["round_off_floor"].get<double>());
  const auto floor_row = csv_row(render::csv(r), "round_off_floor");
  ASSERT_FALSE(floor_row.empty());
  EXPECT_EQ(std::stod(floor_row.at("dK3_deg_s_g3")), j["coefficients"][2]["round_off_floor"].get<double>());
  int below = 0, above = 0;
  for (const auto& s : j["sources"])
    for (const auto& [k, flag] : s["below_round_off_floor"].items()) {
      const double ratio = std::abs(s["effect"][k].get<double>()) /
                           j["coefficients"][k == "K0" ? 0 : k == "K2" ? 1 : 2]["round_off_floor"].get<double>();
      EXPECT_EQ(flag.get<bool>(), ratio < 1) << s["id"] << " " << k;
      (flag ? below : above)++;
    }
  EXPECT_GT(below, 0);
  EXPECT_GT(above, 0);
  const nlohmann::json* tilt = nullptr;
  for (const auto& s : j["sources"])
    if (s["id"] == "dthx4") tilt = &s;
  ASSERT_TRUE(tilt);
  EXPECT_NE((*tilt)["effect"]["K3"].get<double>(), 0.0);  // kept in the JSON…
  EXPECT_TRUE((*tilt)["below_round_off_floor"]["K3"].get<bool>());
  render::BudgetTextOptions wide;
  wide.wide = true;
  const std::string text = render::text(r, wide);
  const auto [row, header] = row_and_header(text, "  dthx4 ");
  // …and 0 in the table: c_i, u_i(y) and the share (K0's table first), where u_i(y) would be -2.9e-20.
  const std::regex zeros("∞ +0 +deg/s per rad +0 +0 %");
  EXPECT_TRUE(std::regex_search(row, zeros)) << row;
  EXPECT_EQ(row.find("e-2"), std::string::npos) << row;
  // A small contribution above the floor keeps its numbers: dz1_c1's 3e-9 u on K0.
  const std::string small = row_and_header(text, "  dz1_c1 ").first;
  EXPECT_FALSE(std::regex_search(small, zeros)) << small;
  EXPECT_TRUE(std::regex_search(small, std::regex("e-1[0-9] +0\\.0 %"))) << small;
}

TEST(BudgetText, BiasRowEqualsSimulatesShift) {
  // Known errors not compensated: the budget's bias of each coefficient is what `ccal simulate` identifies
  // with the errors minus what it identifies without them (the same plan, no instrument noise).
  const std::string with_errors =
      replaced(replaced(example_text(), "# dthz5 = \"2 arcsec\"", "dthz5 = \"2 arcsec\""),
               "# dx3_c1 = \"5 um\"", "dx3_c1 = \"5 um\"");
  const Config cfg = parse_config(with_errors, "errors.toml");
  const verbs::BudgetResult b = verbs::budget(cfg);
  ASSERT_EQ(b.known_error_bias.size(), 3);
  const verbs::SimulateResult shifted = verbs::simulate(cfg);
  const verbs::SimulateResult clean = verbs::simulate(bundled_example());
  const auto j = nlohmann::json::parse(render::json(b));
  for (std::size_t k = 0; k < b.budget.coefficients.size(); ++k) {
    const auto i = Eigen::Index(k);
    const double shift = shifted.identification.fit.value[i] - clean.identification.fit.value[i];
    const double bias = j["known_error_bias"][b.budget.coefficients[k]];
    // Two routes (the observations file and its fit against the direct least squares): the shift is the
    // difference of two coefficients of size |K|, so round-off of 1e-13 |K| bounds the disagreement.
    const double size = std::abs(clean.identification.fit.value[i]);
    EXPECT_NEAR(bias, shift, 1e-13 * size + 1e-9 * std::abs(shift)) << b.budget.coefficients[k];
    EXPECT_NE(shift, 0.0);
  }
  const auto [row, header] = row_and_header(render::text(b), "bias of known [errors]");
  EXPECT_FALSE(row.empty());
  // Compensated: no bias.
  const Config compensated =
      parse_config(replaced(with_errors, "compensate = false", "compensate = true"), "compensated.toml");
  EXPECT_EQ(verbs::budget(compensated).known_error_bias.size(), 0);
}

TEST(Table, DisplayWidthAndCutting) {
  EXPECT_EQ(render::display_width("abc"), 3u);
  EXPECT_EQ(render::display_width("µm"), 2u);  // U+00B5: 2 bytes, 1 column
  EXPECT_EQ(render::display_width("Läufe"), 5u);
  EXPECT_EQ(render::display_width("e\xCC\x81"), 1u);     // e + combining acute
  EXPECT_EQ(render::display_width("\xE6\xBC\xA2"), 2u);  // 漢: wide
  EXPECT_EQ(render::truncate_to_width("azimuth-axis wobble", 8), "azimuth…");
  EXPECT_EQ(render::display_width(render::truncate_to_width("Längen-µ-Gruppe", 6)), 6u);
  EXPECT_EQ(render::wrap_words("aa bb cc", 5, "  "), "aa bb\n  cc\n");
}

// An optional column goes only when cutting the shrinkable one to its header is not enough, and then the
// shrinkable column gets back what the optional one freed.
TEST(Table, AnOptionalColumnGoesOnlyWhenTheWidthNeedsIt) {
  render::Table t({"id", "name", "x", "div", "u"});
  t.align_left(1);
  t.shrink(1);
  t.optional(3);
  t.add_row({"a1", "a long descriptive name", "10", "√3", "5.774"});
  // Natural: 2 (indent) + 2 + 23 + 2 + 3 + 5 + 4 gaps of 3 = 49 columns.
  EXPECT_EQ(lines_of(t.render("  ", 49))[2], "  a1   a long descriptive name   10    √3   5.774");
  // 40: the name gives 9 and every column stays.
  EXPECT_EQ(lines_of(t.render("  ", 40))[2], "  a1   a long descri…   10    √3   5.774");
  // 28: the name down to its header (4) would still be 30 wide, so "div" goes (6 with its gap) and the name
  // gets 8.
  const std::vector<std::string> narrow = lines_of(t.render("  ", 28));
  EXPECT_EQ(narrow[0], "  id   name        x       u");
  EXPECT_EQ(narrow[2], "  a1   a long…    10   5.774");  // cut at a space: "a long" and "…" in 8
  for (const std::string& line : narrow) EXPECT_EQ(render::display_width(line), 28u) << line;
}

// A run named with 10 MB of text padded every row of a table to 10 MB (240 MB of output): a cell wider than
// kMaxPaddedWidth is printed whole in its own row and leaves the other rows as if it were not there.
TEST(Table, AHugeCellDoesNotPadTheOtherRows) {
  const std::string huge(1000000, 'n');
  render::Table t({"run", "value"});
  t.add_row({"5g", "1.0"});
  t.add_row({huge, "2.0"});
  t.add_row({"15g", "3.0"});
  const std::string text = t.render();
  const auto lines = lines_of(text);
  ASSERT_EQ(lines.size(), 5u);  // header, rule, three rows
  // "run" (3 wide, left-aligned) and "value" (5, right-aligned) set the widths, 3 spaces apart.
  EXPECT_EQ(lines[2], "  5g      1.0");
  EXPECT_EQ(lines[4], "  15g     3.0");
  EXPECT_EQ(lines[3], "  " + huge + "     2.0");  // the huge cell whole, nothing cut
  EXPECT_LT(text.size(), huge.size() + 200);      // the huge cell once, not once per row
  // A cell at the limit still sets its column's width.
  render::Table edge({"run", "value"});
  edge.add_row({std::string(render::kMaxPaddedWidth, 'w'), "1"});
  edge.add_row({"5g", "2"});
  EXPECT_EQ(lines_of(edge.render())[3].size(), 2 + render::kMaxPaddedWidth + 3 + 5);
}

}  // namespace
}  // namespace ccal

// A calibration statement's JSON read as a history entry (history/history_store.hpp, history_entry): its
// coefficients, certificate and what it shares with other calibrations on its set-up.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/units.hpp"
#include "ccal/history/history_store.hpp"
#include "history_shared_json.hpp"
#include "history_text.hpp"

namespace ccal {

namespace {

// A serial number is looked up by its exact text: one that is blank or holds control characters (a line
// break, a tab) could not be told apart or typed again, and one that is not valid UTF-8 (Latin-1 bytes from
// another system's shell) could not be written into an export's or a report's JSON. given: from the caller (the serial option), else
// from the statement's certificate. Empty: checked by the caller (missing).
void check_serial(const std::string& serial, bool given, const std::string& source) {
  if (serial.empty()) return;
  const char* problem = nullptr;
  if (detail::history_blank(serial))
    problem = "is blank";
  else if (detail::has_control_character(serial))
    problem = "holds a control character (a line break, a tab)";
  else if (!detail::valid_utf8(serial))
    problem = "is not valid UTF-8 text (a byte of another encoding; shown as \\xNN)";
  else if (serial.front() == ' ' || serial.back() == ' ')  // " SN 0815" would be another instrument's history
    problem = "begins or ends with a blank, which would make it another serial number than the one without";
  if (!problem) return;
  const std::string accepted =
      "accepted: the instrument's serial number, printable characters and not blank, without blanks around it, e.g. "
      "SN 0815";
  if (given)
    throw OptionError("serial", detail::history_shown(serial), fmt::format("{}; {}", problem, accepted));
  throw InputError(fmt::format("{}: serial number ([certificate] serial_number) {} {}; {}", source,
                               detail::history_shown(serial), problem, accepted));
}

[[noreturn]] void refuse_shared(const std::string& source, const std::string& what) {
  throw InputError(
      fmt::format("{}: the statement's shared part: {}; accepted: a statement as reduce writes it (its "
                  "statement_out option)",
                  source, what));
}

// A certificate field as text: a string as written, a number as JSON writes it, absent or null as "".
std::string certificate_text(const nlohmann::json& certificate, const char* key) {
  if (!certificate.contains(key) || certificate[key].is_null()) return "";
  return certificate[key].is_string() ? certificate[key].get<std::string>() : certificate[key].dump();
}

// A calibration is recorded once it is done: a date after today (UTC) is a typing error (9999-12-31, a year
// ahead) that would make every later drift line and prediction wrong. given: from the caller (the date option),
// else from the statement's certificate.
void check_not_future(std::int64_t day, const std::string& date, bool given, const std::string& source) {
  using namespace std::chrono;
  const sys_days today = floor<days>(system_clock::now());
  if (day <= today.time_since_epoch().count()) return;
  const year_month_day ymd{today};
  const std::string today_text =
      fmt::format("{:04}-{:02}-{:02}", int(ymd.year()), unsigned(ymd.month()), unsigned(ymd.day()));
  if (given)
    throw OptionError("date", date,
                      fmt::format("is after today ({}, UTC), and a calibration is recorded once it is done; "
                                  "accepted: its date, YYYY-MM-DD, up to {}",
                                  today_text, today_text));
  throw InputError(fmt::format("{}: date of calibration '{}' ([certificate] date_of_calibration) is after today "
                               "({}, UTC); accepted: a statement of a calibration done by {}, or its date given",
                               source, date, today_text, today_text));
}

}  // namespace

namespace detail {

std::optional<SharedPart> shared_part_of(const nlohmann::json& st, const std::string& source) {
  if (!st.contains("setup_sha256") || !st["setup_sha256"].is_string()) return std::nullopt;
  SharedPart p;
  p.setup_sha256 = st["setup_sha256"].get<std::string>();
  const nlohmann::json inputs = st.value("inputs", nlohmann::json::array());
  if (!inputs.is_array()) refuse_shared(source, "\"inputs\" is not a list");
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const nlohmann::json& in = inputs[i];
    if (!in.is_object() || !in.contains("id") || !in["id"].is_string() ||
        !in.value("effect", nlohmann::json()).is_object())
      refuse_shared(source, fmt::format("inputs[{}] has no \"id\" and \"effect\"", i));
    SharedInput s;
    s.id = in["id"].get<std::string>();
    s.measured = in.value("measured", false);
    s.group = in.value("group", std::string());
    for (const auto& [coefficient, effect] : in["effect"].items()) {
      if (!effect.is_number() || !std::isfinite(effect.get<double>()))
        refuse_shared(source,
                      fmt::format("inputs[{}] ({}) effect on {} is not a number", i, s.id, coefficient));
      s.effect[coefficient] = effect.get<double>();
    }
    p.inputs.push_back(std::move(s));
  }
  const nlohmann::json pairs = st.value("input_correlations", nlohmann::json::array());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const nlohmann::json& c = pairs[i];
    if (!c.is_array() || c.size() != 3 || !c[0].is_string() || !c[1].is_string() || !c[2].is_number() ||
        !(std::abs(c[2].get<double>()) <= 1))
      refuse_shared(source,
                    fmt::format("input_correlations[{}] is not [id_a, id_b, rho] with |rho| <= 1", i));
    p.correlations.push_back({c[0].get<std::string>(), c[1].get<std::string>(), c[2].get<double>()});
  }
  const nlohmann::json covariance = st.value("covariance", nlohmann::json::object());
  // Absent or empty (a statement written without it): no Type B covariance kept.
  if (covariance.is_object() && covariance.contains("order") && covariance.contains("type_b") &&
      !(covariance["order"].empty() && covariance["type_b"].empty())) {
    const nlohmann::json &order = covariance["order"], &m = covariance["type_b"];
    const std::size_t n = order.is_array() ? order.size() : 0;
    if (n == 0 || !m.is_array() || m.size() != n)
      refuse_shared(source, "covariance.type_b is not a square matrix of covariance.order's coefficients");
    p.covariance_b.resize(Eigen::Index(n), Eigen::Index(n));
    for (std::size_t r = 0; r < n; ++r) {
      if (!order[r].is_string() || !m[r].is_array() || m[r].size() != n)
        refuse_shared(source, "covariance.type_b is not a square matrix of covariance.order's coefficients");
      p.order.push_back(order[r].get<std::string>());
      for (std::size_t c = 0; c < n; ++c) {
        if (!m[r][c].is_number())
          refuse_shared(source, fmt::format("covariance.type_b[{}][{}] is not a number", r, c));
        p.covariance_b(Eigen::Index(r), Eigen::Index(c)) = m[r][c].get<double>();
      }
    }
  }
  return p;
}

std::string shared_part_text(const SharedPart& p) {
  nlohmann::ordered_json j;
  j["setup_sha256"] = p.setup_sha256;
  j["inputs"] = nlohmann::ordered_json::array();
  for (const SharedInput& s : p.inputs)
    j["inputs"].push_back({{"id", s.id}, {"measured", s.measured}, {"group", s.group}, {"effect", s.effect}});
  j["input_correlations"] = nlohmann::ordered_json::array();
  for (const SharedCorrelation& c : p.correlations)
    j["input_correlations"].push_back({c.first, c.second, c.r});
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (Eigen::Index r = 0; r < p.covariance_b.rows(); ++r) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (Eigen::Index c = 0; c < p.covariance_b.cols(); ++c) row.push_back(p.covariance_b(r, c));
    rows.push_back(row);
  }
  j["covariance"] = {{"order", p.order}, {"type_b", rows}};
  return j.dump();
}

}  // namespace detail

namespace {

// The file's JSON: a statement alone, or a reduction's or an identification's with its "statement"; its CSV
// form and a test of several instruments (one statement each, the choice the user's) are refused.
nlohmann::json statement_file_json(const std::string& json_text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    if (json_text.starts_with("coefficient,unit,corrected_estimate,") || source.ends_with(".csv"))
      throw InputError(
          fmt::format("{}: the statement's CSV form; history keeps the statement's JSON form; accepted: the "
                      "statement as JSON (a .json statement file)",
                      source));
    throw InputError(
        fmt::format("{}: not JSON ({}); accepted: a calibration statement's JSON (alone, or as the "
                    "\"statement\" of a reduction's or an identification's JSON)",
                    source, detail::json_problem(e.what())));
  }
  // A reduction (or simulation) of a test of several instruments holds one statement per instrument: which
  // one is recorded is the user's choice, not ours.
  if (j.is_object() && !j.contains("statement") && j.contains("instruments") && j["instruments"].is_array()) {
    std::vector<std::string> ids;
    for (const auto& i : j["instruments"])
      if (i.is_object() && i.contains("statement")) ids.push_back(i.value("id", std::string("?")));
    if (!ids.empty())
      throw InputError(fmt::format(
          "{}: holds the statements of {} instruments ({}) of a test of several; accepted: one instrument's "
          "statement alone (its reduction with the instrument chosen, or its statement file)",
          source, ids.size(), fmt::format("{}", fmt::join(ids, ", "))));
  }
  return j;
}

[[noreturn]] void refuse_statement(const std::string& source, const std::string& what) {
  throw InputError(
      fmt::format("{}: not a calibration statement: {}; accepted: a calibration statement's JSON "
                  "(alone, or as the \"statement\" of a reduction's or an identification's JSON)",
                  source, what));
}

// One coefficient of the statement: its corrected estimate, U and k (numbers, finite, U ≥ 0, k > 0), its
// ν_eff (∞ when not a number), at the statement's coverage probability p.
HistoryCoefficient statement_coefficient(const std::string& name, const nlohmann::json& c, double p,
                                         const std::string& source) {
  for (const char* key : {"corrected_estimate", "expanded_uncertainty", "coverage_factor"})
    if (!c.contains(key) || !c[key].is_number())
      refuse_statement(source, fmt::format("coefficient {} has no number \"{}\"", name, key));
  HistoryCoefficient h;
  h.name = name;
  h.unit = c.value("unit", std::string());
  // The history compares a coefficient's calibrations in its unit: one ccal cannot read ("furlong", a typing
  // error in a statement edited by hand) would be recorded and compared as text.
  if (!h.unit.empty()) try {
      (void)parse_unit(h.unit);
    } catch (const InputError&) {
      refuse_statement(source, fmt::format("coefficient {}'s unit '{}' is no unit ccal reads (e.g. deg/s, "
                                           "deg/s/g^2, mA)",
                                           name, h.unit));
    }
  h.value = c["corrected_estimate"].get<double>();
  h.expanded = c["expanded_uncertainty"].get<double>();
  h.coverage_factor = c["coverage_factor"].get<double>();
  h.coverage_probability = p;
  h.effective_dof = c.contains("effective_dof") && c["effective_dof"].is_number()
                        ? c["effective_dof"].get<double>()
                        : std::numeric_limits<double>::infinity();
  if (!(std::isfinite(h.value) && std::isfinite(h.expanded) && h.expanded >= 0 &&
        std::isfinite(h.coverage_factor) && h.coverage_factor > 0))
    refuse_statement(
        source,
        fmt::format(
            "coefficient {} has no finite value, finite U ≥ 0 and finite k > 0 (value {}, U {}, k {})", name,
            c["corrected_estimate"].dump(), c["expanded_uncertainty"].dump(), c["coverage_factor"].dump()));
  return h;
}

}  // namespace

std::optional<std::int64_t> calendar_day(std::string_view date) {
  using namespace std::chrono;
  if (date.size() != 10 || date[4] != '-' || date[7] != '-') return std::nullopt;
  int y = 0;
  unsigned m = 0, d = 0;
  const char* s = date.data();
  if (std::from_chars(s, s + 4, y).ptr != s + 4 || std::from_chars(s + 5, s + 7, m).ptr != s + 7 ||
      std::from_chars(s + 8, s + 10, d).ptr != s + 10)
    return std::nullopt;
  const year_month_day ymd{year{y}, month{m}, day{d}};
  if (!ymd.ok()) return std::nullopt;
  return sys_days(ymd).time_since_epoch().count();
}

HistoryEntry history_entry(const std::string& json_text, const std::string& source, const std::string& serial,
                           const std::string& date) {
  const nlohmann::json j = statement_file_json(json_text, source);
  const nlohmann::json& st = j.is_object() && j.contains("statement") ? j["statement"] : j;
  if (!st.is_object() || !st.contains("coefficients") || !st["coefficients"].is_object() ||
      st["coefficients"].empty())
    refuse_statement(source, "no \"coefficients\"");
  HistoryEntry e;
  e.statement_json = st.dump();
  e.ccal_version = j.value("ccal_version", st.value("ccal_version", std::string("unknown")));
  e.config = st.value("budget_config", j.value("config", std::string()));
  const double p = st.value("coverage_probability", 0.0);
  if (st.contains("coverage_probability") && !(p > 0 && p < 1))
    refuse_statement(source, fmt::format("coverage_probability {} is not a probability in (0, 1)",
                                         st["coverage_probability"].dump()));
  for (const auto& [name, c] : st["coefficients"].items()) {
    e.coefficients.push_back(statement_coefficient(name, c, p, source));
  }
  const nlohmann::json certificate =
      st.value("certificate", j.value("certificate", nlohmann::json::object()));
  e.serial = !serial.empty() ? serial : certificate.value("serial_number", std::string());
  e.date = !date.empty() ? date : certificate.value("date_of_calibration", std::string());
  e.instrument = certificate.value("instrument", std::string());
  e.certificate_number = certificate_text(certificate, "number");
  e.replaces = certificate_text(certificate, "replaces");
  e.shared = detail::shared_part_of(st, source);
  check_serial(e.serial, !serial.empty(), source);
  // What the caller did not give and the statement does not name: an option of the call (OptionError, worded
  // by each front end).
  if (e.serial.empty())
    throw OptionError("serial", "",
                      fmt::format("{} names no serial number ([certificate] serial_number); accepted: the "
                                  "instrument's serial number",
                                  source));
  if (e.date.empty())
    throw OptionError("date", "",
                      fmt::format("{} names no date of calibration ([certificate] date_of_calibration); "
                                  "accepted: the date, YYYY-MM-DD",
                                  source));
  const std::optional<std::int64_t> day = calendar_day(e.date);
  if (!day)
    throw InputError(fmt::format(
        "{}: date of calibration '{}' is not a date; accepted: YYYY-MM-DD, e.g. 2026-11-30", source, e.date));
  check_not_future(*day, e.date, !date.empty(), source);
  return e;
}

}  // namespace ccal

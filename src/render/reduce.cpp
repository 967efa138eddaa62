#include "ccal/render/reduce.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "ccal/core/errors.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"
#include "parts.hpp"
#include "statement_part.hpp"

namespace ccal::render {
namespace {

std::string or_dash(bool has, double v, int digits = 9) { return has ? number(v, digits) : "-"; }

// The measured ripple of each run's drives [ppm] and the platform control its encoders look like.
std::string ripple_text(const Config& cfg, const verbs::ReduceResult& r) {
  const bool any = std::any_of(r.logs.runs.begin(), r.logs.runs.end(), [](const LoggedRun& lr) {
    return !lr.main_ripple.empty() || !lr.platform_ripple.empty() ||
           lr.control.look != ControlLook::not_tested;
  });
  if (!any) return "";
  std::vector<std::string> columns{"run"};
  const std::vector<std::string> main = verbs::ripple_ids(cfg, "ripple1"),
                                 platform = verbs::ripple_ids(cfg, "ripple3");
  for (const auto& id : main) columns.push_back(id + " [ppm]");
  for (const auto& id : platform) columns.push_back(id + " [ppm]");
  for (const char* c : {"control looks", "lambda", "|p| [rad]", "threshold [rad]"}) columns.push_back(c);
  Table t(columns);
  for (const LoggedRun& lr : r.logs.runs) {
    std::vector<std::string> row{lr.measured.name};
    for (std::size_t i = 0; i < main.size(); ++i)
      row.push_back(i < lr.main_ripple.size() ? number(1e6 * lr.main_ripple[i], 6) : "-");
    for (std::size_t i = 0; i < platform.size(); ++i)
      row.push_back(i < lr.platform_ripple.size() ? number(1e6 * lr.platform_ripple[i], 6) : "-");
    const ControlEvidence& c = lr.control;
    const bool decided = c.look == ControlLook::speed || c.look == ControlLook::phase_locked;
    row.push_back(c.look == ControlLook::not_tested ? "-" : std::string(control_look_name(c.look)));
    row.push_back(decided ? number(c.following, 4) : "-");
    row.push_back(c.look == ControlLook::not_tested ? "-" : number(c.main_in_gamma, 3));
    row.push_back(c.look == ControlLook::not_tested ? "-" : number(c.threshold, 3));
    t.add_row(row);
  }
  return "  drive rate ripple measured by the encoders (model.md §13.1; '-': configured value used)\n" +
         t.render() +
         "\n  (control looks: the platform angle's share lambda of the main axis's ripple, 1 phase_locked,\n"
         "   0 speed; undetermined when the main axis's ripple |p| is below the threshold, model.md "
         "§13.2)\n\n";
}

std::string text_of(const Config& cfg, const verbs::ReduceResult& r) {
  const std::string& unit = cfg.instrument.output_unit;
  const Geometry& geometry = cfg.centrifuge.geometry;
  const Site& site = cfg.site;
  std::string out =
      fmt::format("ccal reduce: {} logged runs of {} ({} planned); {} model\n\n", r.logs.runs.size(),
                  cfg.source, cfg.plan.runs.size(), std::string(mode_name(r.mode)));
  Table logs({"run", "log", "samples", "T [s]", "Omega plan [rad/s]", "Omega log [rad/s]", "dOmega [rad/s]",
              "phi0 [rad]", "psi [rad]", fmt::format("output [{}]", unit)});
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
    const LoggedRun& lr = r.logs.runs[k];
    logs.add_row({lr.measured.name, r.files[k], std::to_string(lr.log.samples), number(lr.log.duration),
                  number(lr.planned_rate), or_dash(lr.log.has_theta1, lr.log.theta1_rate, 12),
                  number(lr.mismatch, 6), number(initial_phase(lr.measured, geometry, site)),
                  or_dash(lr.log.has_gamma, lr.log.gamma_end),
                  number(lr.log.mean_output / r.output_unit_si, 12)});
  }
  out += logs.render() + "\n";
  for (const LoggedRun& lr : r.logs.runs)
    if (lr.log.gaps > 0)
      out += fmt::format("  run '{}': {} gap(s) in the log, the longest {} s between samples; {} s of its {} s "
                         "missing\n",
                         lr.measured.name, lr.log.gaps, number(lr.log.longest_gap), number(lr.log.missing),
                         number(lr.log.duration));
  for (const LoggedRun& lr : r.logs.runs)
    if (lr.log.gaps > 0) {
      out += '\n';
      break;
    }
  out +=
      "  (Omega log, psi: line fits of the encoder angles, '-' when not logged; phi0: the model's initial "
      "phase,\n"
      "   the platform encoder's or the plan's; dOmega: the model's platform mismatch, measured when both\n"
      "   encoders are logged, else the configured one)\n\n";
  out += ripple_text(cfg, r);
  out += "  identification of these observations\n";
  out += identification_text(r.identification.id);
  if (r.statement) {
    out += '\n';
    out += statement_text(*r.statement);
  }
  return out;
}

nlohmann::ordered_json json_object(const Config& cfg, const verbs::ReduceResult& r) {
  nlohmann::ordered_json j;
  j["command"] = "reduce";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = std::string(mode_name(r.mode));
  j["output_unit"] = cfg.instrument.output_unit;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
    const LoggedRun& lr = r.logs.runs[k];
    nlohmann::ordered_json x;
    x["name"] = lr.measured.name;
    x["log"] = r.files[k];
    x["log_sha256"] = lr.log.sha256;
    x["samples"] = lr.log.samples;
    x["duration_s"] = lr.log.duration;
    x["gaps"] = {{"count", lr.log.gaps}, {"longest_s", lr.log.longest_gap}, {"missing_s", lr.log.missing}};
    x["output"] = lr.log.mean_output / r.output_unit_si;
    x["output_from"] = lr.log.pulses ? "pulses" : "output";
    x["planned_rate_rad_per_s"] = lr.planned_rate;
    x["rate_rad_per_s"] = lr.rate;
    if (lr.log.has_theta1)
      x["main_encoder"] = {{"rate_rad_per_s", lr.log.theta1_rate},
                           {"theta1_start_rad", lr.log.theta1_start},
                           {"rms_rad", lr.log.theta1_rms}};
    if (lr.log.has_gamma)
      x["platform_encoder"] = {{"rate_rad_per_s", lr.log.gamma_rate},
                               {"initial_phase_rad", lr.log.gamma_start},
                               {"terminal_phase_rad", lr.log.gamma_end},
                               {"rms_rad", lr.log.gamma_rms}};
    x["platform_mismatch_rad_per_s"] = lr.mismatch;
    auto ripple = [](const std::vector<std::string>& ids, const std::vector<double>& values) {
      nlohmann::ordered_json o = nlohmann::ordered_json::object();
      for (std::size_t i = 0; i < ids.size() && i < values.size(); ++i) o[ids[i]] = values[i];
      return o;
    };
    if (!lr.main_ripple.empty())
      x["main_encoder"]["ripple"] = ripple(verbs::ripple_ids(cfg, "ripple1"), lr.main_ripple);
    if (!lr.platform_ripple.empty())
      x["platform_encoder"]["ripple"] = ripple(verbs::ripple_ids(cfg, "ripple3"), lr.platform_ripple);
    if (lr.control.look != ControlLook::not_tested) {
      nlohmann::ordered_json c;
      c["looks_like"] = control_look_name(lr.control.look);
      c["following"] = lr.control.following;
      c["main_ripple_in_gamma_rad"] = lr.control.main_in_gamma;
      c["threshold_rad"] = lr.control.threshold;
      x["platform_control"] = c;
    }
    runs.push_back(x);
  }
  j["runs"] = runs;
  j["identification"] = identification_json(r.identification.id);
  if (r.statement) j["statement"] = statement_json(*r.statement);
  return j;
}

}  // namespace

std::string text(const verbs::ReduceResult& r) {
  if (r.instruments.empty()) return text_of(r.config, r);
  std::string out = fmt::format("ccal reduce: a test of {} instruments ({})\n\n", r.instruments.size(),
                                r.config.source);
  for (const verbs::ReduceResult& one : r.instruments)
    out += fmt::format("=== instrument {} ===\n", one.config.instrument_id) + text_of(one.config, one) + "\n";
  if (r.covariance) out += covariance_text(*r.covariance);
  return out;
}

std::string json(const verbs::ReduceResult& r) {
  if (r.instruments.empty()) return json_object(r.config, r).dump(2) + "\n";
  nlohmann::ordered_json j;
  j["command"] = "reduce";
  j["ccal_version"] = version();
  j["config"] = r.config.source;
  nlohmann::ordered_json each = nlohmann::ordered_json::array();
  for (const verbs::ReduceResult& one : r.instruments)
    each.push_back(instrument_part_json(one.config.instrument_id, json_object(one.config, one)));
  j["instruments"] = each;
  if (r.covariance) j["covariance"] = covariance_json(*r.covariance);
  return j.dump(2) + "\n";
}

std::string csv(const verbs::ReduceResult& r) {
  if (!r.instruments.empty())
    throw OptionError("format", "csv",
                      "is one table, and a test of several instruments has one observations table per instrument; "
                      "accepted: " + OptionError::name("format") + " text or json, or " + OptionError::name("instrument") +
                      " ID for one of them");
  return r.identification.csv;
}

}  // namespace ccal::render

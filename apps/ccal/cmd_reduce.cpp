// ccal reduce: recorded run logs (time, pulse count or output, encoder angles) to run means, the model's
// regressors for the runs as measured, and the identification of the [identification] terms (docs/cli.md).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "ccal/config.hpp"
#include "ccal/observation_csv.hpp"
#include "ccal/render/identification.hpp"
#include "ccal/run_log.hpp"
#include "ccal/simulate.hpp"
#include "ccal/verbs/identification.hpp"
#include "ccal/version.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct ReduceOptions {
  std::string config;
  std::vector<std::string> logs;  // RUN=FILE
  std::string angle_unit = "rad";
  std::string pulse_weight;  // in the output unit × s; empty: the instrument's quantum
  std::string mode;          // empty: the configuration's
  std::string observations_out;
  OutputOptions output;
};

struct Reduction {
  ModelMode mode = ModelMode::exact;
  double unit = 1;                 // SI size of one output unit
  std::vector<std::string> files;  // per logged run
  LogReduction logs;
  verbs::FileIdentification identification;
};

// A log file that cannot be opened, refused as the reader refuses it.
void check_readable(const std::string& name) {
  std::error_code ec;
  if (std::ifstream(name, std::ios::binary) && !std::filesystem::is_directory(name, ec)) return;
  throw CsvError(name, 0, 0, "", "cannot read the file; check the path and permissions");
}

Reduction reduce(const Config& cfg, const ReduceOptions& o) {
  Reduction r;
  r.mode = o.mode.empty() ? cfg.mode : (o.mode == "paper" ? ModelMode::paper : ModelMode::exact);
  r.unit = output_unit_si(cfg.instrument.output_unit);
  RunLogOptions lo;
  lo.output_scale = r.unit;
  lo.angle_scale = o.angle_unit == "deg" ? std::numbers::pi / 180 : 1.0;
  lo.pulse_weight = cfg.instrument.quantum;
  if (!o.pulse_weight.empty()) {
    const std::optional<double> w = parse_number(o.pulse_weight);
    if (!w || !(*w > 0))
      throw InputError(
          fmt::format("--pulse-weight: '{}' is not a positive number; accepted: the integrated "
                      "output per pulse in {}·s, e.g. 2.5e-5",
                      o.pulse_weight, cfg.instrument.output_unit));
    lo.pulse_weight = *w * r.unit;
  }
  std::vector<std::pair<std::size_t, std::filesystem::path>> logs;
  std::map<std::size_t, std::string> files;
  for (const std::string& item : o.logs) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw InputError(
          fmt::format("--log: '{}' is not RUN=FILE; accepted: a run name or 1-based index, '=', "
                      "the log file, e.g. 20g=run20.csv",
                      item));
    const std::size_t index = select_run(cfg.plan, item.substr(0, eq), "--log");
    if (files.count(index))
      throw InputError(fmt::format("--log: run '{}' is logged twice; accepted: one log per run",
                                   cfg.plan.runs[index].name));
    files[index] = item.substr(eq + 1);
    note_input(files[index]);
    check_readable(files[index]);  // a missing file before the count of logs, as when logs were read whole
    logs.emplace_back(index, files[index]);
  }
  check_log_count(cfg.identification, logs.size(), "--log");
  r.logs = reduce_log_files(cfg, logs, lo, r.mode);  // each log streamed in one pass
  for (const LoggedRun& lr : r.logs.runs) r.files.push_back(files[lr.index]);
  std::vector<Run> measured;
  std::vector<double> rates;
  for (const LoggedRun& lr : r.logs.runs) {
    measured.push_back(lr.measured);
    rates.push_back(lr.rate);
  }
  const verbs::DataResolution resolution =
      verbs::run_resolution(measured, rates, r.logs.observations, cfg.identification, cfg.instrument);
  r.identification = verbs::identify_observations(r.logs.observations, cfg.identification, cfg.instrument,
                                                  cfg.source, &resolution);
  return r;
}

std::string or_dash(bool has, double v, int digits = 9) { return has ? number(v, digits) : "-"; }

// Parameter ids of a drive's ripple channel up to the configuration's order: ripple1_c1, ripple1_s1, …
std::vector<std::string> ripple_ids(const Config& cfg, std::string_view channel) {
  std::vector<std::string> ids;
  for (int k = 1; k <= cfg.centrifuge.layout.harmonic_order(); ++k)
    for (const char* part : {"c", "s"}) ids.push_back(fmt::format("{}_{}{}", channel, part, k));
  return ids;
}

// The measured ripple of each run's drives [ppm] and the platform control its encoders look like.
std::string ripple_text(const Config& cfg, const Reduction& r) {
  const bool any = std::any_of(r.logs.runs.begin(), r.logs.runs.end(), [](const LoggedRun& lr) {
    return !lr.main_ripple.empty() || !lr.platform_ripple.empty() ||
           lr.control.look != ControlLook::not_tested;
  });
  if (!any) return "";
  std::vector<std::string> columns{"run"};
  const std::vector<std::string> main = ripple_ids(cfg, "ripple1"), platform = ripple_ids(cfg, "ripple3");
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

// A warning on stderr for each run whose encoders contradict the configured platform control.
void warn_about_control(const Config& cfg, const Reduction& r) {
  const PlatformControl configured = cfg.centrifuge.geometry.platform_control;
  const std::string_view name = configured == PlatformControl::speed ? "speed" : "phase_locked";
  for (const LoggedRun& lr : r.logs.runs) {
    const ControlLook look = lr.control.look;
    if (look != ControlLook::speed && look != ControlLook::phase_locked) continue;
    if ((look == ControlLook::speed) == (configured == PlatformControl::speed)) continue;
    std::cerr << fmt::format(
        "ccal: warning: run '{}': the encoders look like platform_control = \"{}\" (the platform angle "
        "carries lambda = {:.3g} of the main axis's ripple), the configuration has \"{}\" (model.md §13.2)\n",
        lr.measured.name, control_look_name(look), lr.control.following, name);
  }
}

std::string to_text(const Config& cfg, const Reduction& r) {
  const std::string& unit = cfg.instrument.output_unit;
  const Geometry& geometry = cfg.centrifuge.geometry;
  const Site& site = cfg.site;
  std::string out =
      fmt::format("ccal reduce: {} logged runs of {} ({} planned); {} model\n\n", r.logs.runs.size(),
                  cfg.source, cfg.plan.runs.size(), r.mode == ModelMode::exact ? "exact" : "paper");
  Table logs({"run", "log", "samples", "T [s]", "Omega plan [rad/s]", "Omega log [rad/s]", "dOmega [rad/s]",
              "phi0 [rad]", "psi [rad]", fmt::format("output [{}]", unit)});
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
    const LoggedRun& lr = r.logs.runs[k];
    logs.add_row({lr.measured.name, r.files[k], std::to_string(lr.log.samples), number(lr.log.duration),
                  number(lr.planned_rate), or_dash(lr.log.has_theta1, lr.log.theta1_rate, 12),
                  number(lr.mismatch, 6), number(initial_phase(lr.measured, geometry, site)),
                  or_dash(lr.log.has_gamma, lr.log.gamma_end), number(lr.log.mean_output / r.unit, 12)});
  }
  out += logs.render() + "\n";
  out +=
      "  (Omega log, psi: line fits of the encoder angles, '-' when not logged; phi0: the model's initial "
      "phase,\n"
      "   the platform encoder's or the plan's; dOmega: the model's platform mismatch, measured when both\n"
      "   encoders are logged, else the configured one)\n\n";
  out += ripple_text(cfg, r);
  out += "  identification of these observations\n";
  return out + render::text(r.identification.id);
}

std::string to_json(const Config& cfg, const Reduction& r) {
  nlohmann::ordered_json j;
  j["command"] = "reduce";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = r.mode == ModelMode::exact ? "exact" : "paper";
  j["output_unit"] = cfg.instrument.output_unit;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
    const LoggedRun& lr = r.logs.runs[k];
    nlohmann::ordered_json x;
    x["name"] = lr.measured.name;
    x["log"] = r.files[k];
    x["samples"] = lr.log.samples;
    x["duration_s"] = lr.log.duration;
    x["output"] = lr.log.mean_output / r.unit;
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
      x["main_encoder"]["ripple"] = ripple(ripple_ids(cfg, "ripple1"), lr.main_ripple);
    if (!lr.platform_ripple.empty())
      x["platform_encoder"]["ripple"] = ripple(ripple_ids(cfg, "ripple3"), lr.platform_ripple);
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
  j["identification"] = nlohmann::ordered_json::parse(render::json(r.identification.id));
  return j.dump(2) + "\n";
}

}  // namespace

Command add_reduce(CLI::App& app) {
  auto o = std::make_shared<ReduceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reduce",
      "Recorded run logs (time and pulse count or output, optionally encoder angles) to run means, the "
      "model's regressors for the runs as measured, and the identification of the [identification] terms.");
  add_config_argument(*cmd, o->config);
  cmd->add_option("--log", o->logs,
                  "RUN=FILE: the log of a run of the plan (its name or 1-based index); repeat for each run. "
                  "CSV columns: time [s]; pulses (cumulative) or output (in the instrument's output unit); "
                  "optionally theta1 and gamma, the encoder angles")
      ->required()
      ->allow_extra_args(false)
      ->type_name("RUN=FILE");
  cmd->add_option("--angle-unit", o->angle_unit, "Unit of the encoder columns")
      ->capture_default_str()
      ->check(CLI::IsMember({"rad", "deg"}));
  cmd->add_option("--pulse-weight", o->pulse_weight,
                  "Integrated output per pulse, in the output unit × s (e.g. deg for deg/s); default: the "
                  "instrument's quantum")
      ->type_name("W");
  cmd->add_option(
         "--mode", o->mode,
         "Model of the regressors: exact (full chain) or paper; default: [identification] mode of the "
         "configuration")
      ->check(CLI::IsMember({"exact", "paper"}));
  add_observations_out_option(*cmd, o->observations_out);
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal reduce my.toml --log 5g=run05.csv --log 10g=run10.csv --log 15g=run15.csv --log 20g=run20.csv\n"
      "      mean outputs of four logged runs and the identified terms of my.toml\n"
      "  ccal reduce my.toml --log 1=a.csv --log 2=b.csv --log 3=c.csv --angle-unit deg --format json\n");

  return {cmd, [o] {
            const Config cfg = load_config_or_example(o->config);
            check_observations_out(o->observations_out, o->output);
            const Reduction r = reduce(cfg, *o);
            print_warnings(r.identification.id.observability.warnings);
            warn_about_control(cfg, r);
            const std::string& f = o->output.format;
            const std::string text = f == "json"  ? to_json(cfg, r)
                                     : f == "csv" ? r.identification.csv
                                                  : to_text(cfg, r);
            std::vector<ExtraFile> extra;
            if (!o->observations_out.empty())
              extra.push_back({"--observations-out", o->observations_out, r.identification.csv});
            write_outputs(o->output, text, extra);
          }};
}

}  // namespace ccal::cli

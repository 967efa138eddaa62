// ccal reduce: recorded run logs (time, pulse count or output, encoder angles) to run means, the model's
// regressors for the runs as measured, and the identification of the [identification] terms (docs/cli.md).
#include <fmt/format.h>

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
  std::vector<std::pair<std::size_t, CsvTable>> logs;
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
    logs.emplace_back(index, read_csv_file(files[index]));
  }
  check_log_count(cfg.identification, logs.size(), "--log");
  r.logs = reduce_logs(cfg, logs, lo, r.mode);
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

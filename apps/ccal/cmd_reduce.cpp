// ccal reduce: recorded run logs (time, pulse count or output, encoder angles) to run means, the model's
// regressors for the runs as measured, and the identification of the [identification] terms (docs/cli.md).
#include <fmt/format.h>

#include <memory>

#include "ccal/intake/log_manifest.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/reduce.hpp"
#include "ccal/verbs/reduce.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct ReduceCli {
  ConfigChoice config;
  std::vector<std::string> logs;  // RUN=FILE
  std::string log_folder;         // DIR with a manifest (intake/log_manifest.hpp)
  std::string log_layout;         // with --log: the logs' format and columns (a manifest's [format], [columns])
  verbs::ReduceOptions options;   // its table's flags are bound to it
  std::string pulse_weight;       // --pulse-weight as written: converted with the configuration's output unit
  bool old_budget = false;        // --budget, refused: a flag here, a file in identify; now --statement
  std::string observations_out;
  std::string statement_out;
  OutputOptions output;
};

// The logs of --log RUN=FILE (with --log-layout) or of --logs DIR (by its manifest), into the options.
void gather_logs(const ReduceCli& cli, verbs::ReduceOptions& ro) {
  const ReduceCli* o = &cli;
  if (o->logs.empty() == o->log_folder.empty())
    throw InputError(o->logs.empty()
                         ? "--log or --logs is required; accepted: --log RUN=FILE for each "
                           "run, or --logs DIR for a folder with its manifest.toml"
                         : "--log and --logs: give one of them (the folder's manifest names "
                           "its runs' files)");
  if (!o->log_layout.empty()) {
    if (!o->log_folder.empty())
      throw InputError("--log-layout: the folder's manifest has the layout; accepted: --log-layout with "
                       "--log RUN=FILE, or the [format] and [columns] tables in the manifest of --logs");
    note_input(o->log_layout);
    ro.layout = read_log_layout(o->log_layout);
  }
  if (!o->log_folder.empty()) {
    note_input(o->log_folder + "/" + std::string(kLogManifestName));
    const LogManifest manifest = read_log_manifest(o->log_folder);  // located errors name the file
    ro.layout = manifest.layout;
    ro.logs = verbs::manifest_logs(manifest);
    for (const verbs::LogFile& log : ro.logs) note_input(log.path);
  }
  for (const std::string& item : o->logs) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw InputError(
          fmt::format("--log: '{}' is not RUN=FILE; accepted: a run name or 1-based index, '=', "
                      "the log file, e.g. 20g=run20.csv",
                      item));
    ro.logs.push_back({item.substr(0, eq), item.substr(eq + 1)});
    note_input(ro.logs.back().path);
  }
}

// Runs `ccal reduce` and writes its output and the files asked for.
void run_reduce(ReduceCli& o) {
  const Config cfg = load_config_or_example(o.config);
  check_observations_out(o.observations_out, o.output);
  check_statement_out(o.statement_out, o.options.statement, o.output);
  if (!o.observations_out.empty()) verbs::check_single_instrument_output(cfg, "observations_out");
  if (!o.statement_out.empty()) verbs::check_single_instrument_output(cfg, "statement_out");
  if (o.old_budget)
    throw InputError(
        "--budget: no longer accepted, as it was a flag here and took a file in identify; accepted: "
        "--statement for the calibration statement with this configuration's tolerances");
  verbs::ReduceOptions ro = o.options;
  if (!o.pulse_weight.empty()) ro.pulse_weight = verbs::pulse_weight_from_text(cfg, o.pulse_weight);
  gather_logs(o, ro);
  const verbs::ReduceResult r = verbs::reduce(cfg, ro);
  const std::string& f = o.output.format;
  const std::string text = f == "json" ? render::json(r) : f == "csv" ? render::csv(r) : render::text(r);
  std::vector<ExtraFile> extra;
  if (!o.observations_out.empty())
    extra.push_back({"--observations-out", o.observations_out, r.identification.csv});
  add_statement_out_file(extra, o.statement_out, r.statement);
  write_outputs(o.output, text, extra);
  print_warnings(r.warnings);  // after the outputs: an output refused is the one line said
}

}  // namespace

Command add_reduce(CLI::App& app) {
  auto o = std::make_shared<ReduceCli>();
  CLI::App* cmd = app.add_subcommand(
      "reduce",
      "Recorded run logs (time and pulse count or output, optionally encoder angles) to run means, the "
      "model's regressors for the runs as measured, and the identification of the [identification] terms.");
  add_config_argument(*cmd, o->config);
  cmd->add_option("--log", o->logs,
                  "RUN=FILE: the log of a run of the plan (its name or 1-based index); repeat for each run. "
                  "CSV columns: time [s]; pulses (cumulative) or output (in the instrument's output unit); "
                  "optionally theta1 and gamma, the encoder angles")
      ->allow_extra_args(false)
      ->type_name("RUN=FILE");
  cmd->add_option("--logs", o->log_folder,
                  "DIR: a folder of logs with its manifest.toml, which names each run's file and how the "
                  "columns read (names, time unit, encoder unit or counts per revolution); `ccal simulate "
                  "--logs-out DIR` writes one")
      ->type_name("DIR");
  cmd->add_option("--log-layout", o->log_layout,
                  "FILE: with --log, how the logs are written, a TOML file with a manifest's [format] and "
                  "[columns] tables (delimiter, decimal separator, header, units row, gaps, column names, units)")
      ->type_name("FILE");
  add_option_flags(*cmd, o->options, option_table<verbs::ReduceOptions>(), {"pulse_weight"});
  // --pulse-weight W or "W UNIT": its unit is the configuration's output unit × s, known after the parse.
  for (const auto& row : option_table<verbs::ReduceOptions>())
    if (row.field == "pulse_weight")
      cmd->add_option(
             "--pulse-weight", o->pulse_weight,
             option_help(row.help, row.range) + "; a bare number, or a quantity with its unit (e.g. \"2.5e-5 deg\")")
          ->type_name(std::string(row.value_name));
  cmd->add_flag("--budget", o->old_budget)->group("");  // refused with a message, not in --help
  add_observations_out_option(*cmd, o->observations_out);
  add_statement_out_option(*cmd, o->statement_out);
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal reduce my.toml --log 5g=run05.csv --log 10g=run10.csv --log 15g=run15.csv --log 20g=run20.csv\n"
      "      mean outputs of four logged runs and the identified terms of my.toml\n"
      "  ccal reduce my.toml --logs logs --statement\n"
      "      the logs of a folder, by its manifest.toml (as ccal simulate --logs-out writes it)\n"
      "  ccal reduce my.toml --log 1=a.csv --log 2=b.csv --log 3=c.csv --angle-unit deg --format json\n"
      "  ccal reduce my.toml --log 1=a.csv --log 2=b.csv --log 3=c.csv --log-layout daq.toml\n"
      "      logs as a data acquisition system writes them (delimiter, units row, …: a manifest's tables)\n"
      "  ccal reduce my.toml --log 1=a.csv --log 2=b.csv --log 3=c.csv --log 4=d.csv --statement\n"
      "      with the calibration statement: each coefficient with its U and interval\n"
      "  ccal reduce my.toml --log 1=a.csv --log 2=b.csv --log 3=c.csv --log 4=d.csv --statement \\\n"
      "      --statement-out statement.csv    the statement also as CSV, with the covariance\n");

  return {cmd, [o] { run_reduce(*o); }};
}

}  // namespace ccal::cli

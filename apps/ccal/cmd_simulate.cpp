// ccal simulate: the run means a test plan produces (truth: the exact chain with the configured [errors]) and
// the regressors the analyst computes (with zero errors, or the [errors] values when compensating), written
// as an observations file and identified as `ccal identify` would (docs/cli.md).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <system_error>
#include <utility>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/render/simulate.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"
#include "atomic_file.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct SimulateCli {
  ConfigChoice config;
  verbs::SimulateOptions options;  // its table's flags are bound to it
  std::string observations_out;
  std::string logs_out;  // folder for one run log per run
  std::string truth;     // the simulated machine's errors (io/truth_file.hpp); empty: the configuration's
  std::string log_layout;  // the logs' columns and units (intake/log_manifest.hpp); empty: ccal's own
  OutputOptions output;
};

// Runs `ccal simulate` and writes its output and the files asked for.
void run_simulate(SimulateCli& o) {
  const Config cfg = load_config_or_example(o.config);
  check_observations_out(o.observations_out, o.output);
  if (!o.observations_out.empty()) verbs::check_single_instrument_output(cfg, "observations_out");
  if (!o.log_layout.empty() && o.logs_out.empty())
    throw InputError("--log-layout: is read only for the logs; accepted: with --logs-out DIR");
  LogLayout layout;
  if (!o.log_layout.empty()) {
    note_input(o.log_layout);
    layout = read_log_layout(o.log_layout);
  }
  verbs::SimulateOptions so = o.options;
  if (!o.truth.empty()) {
    note_input(o.truth);
    so.truth = load_truth(o.truth, cfg);
  }
  const verbs::SimulateResult s = verbs::simulate(cfg, so);
  print_warnings(s.identification.observability.warnings);
  const std::string& f = o.output.format;
  const std::string text = f == "json" ? render::json(s) : f == "csv" ? render::csv(s) : render::text(s);
  std::vector<ExtraFile> extra;
  if (!o.observations_out.empty())
    extra.push_back({"--observations-out", o.observations_out, s.observations_csv});
  std::optional<OutputFolder> folder;  // made for the logs; gone again if the write is refused
  if (!o.logs_out.empty()) {
    folder.emplace("--logs-out", o.logs_out);
    for (RunLogFile& file : verbs::simulation_logs(s, layout))
      extra.push_back(
          {"--logs-out", (std::filesystem::path(o.logs_out) / file.name).string(), std::move(file.text)});
  }
  write_outputs(o.output, text, extra);
  if (folder) folder->keep();
}

}  // namespace

Command add_simulate(CLI::App& app) {
  auto o = std::make_shared<SimulateCli>();
  CLI::App* cmd =
      app.add_subcommand("simulate",
                         "Simulated run means of the test plan (exact chain with the machine's errors: those "
                         "of --truth, else the configured [errors]; instrument noise), their "
                         "regressors, and the identification of the [identification] terms from them.");
  add_config_argument(*cmd, o->config);
  add_option_flags(*cmd, o->options, option_table<verbs::SimulateOptions>());
  cmd->add_option("--truth", o->truth,
                  "The errors the simulated machine really has, a TOML file with an [errors] table as a "
                  "configuration's; the configuration's [errors] are then only what the lab measured (default: "
                  "the machine has the configured [errors])")
      ->type_name("FILE");
  add_observations_out_option(*cmd, o->observations_out);
  refuse_empty_path(cmd->add_option("--logs-out", o->logs_out,
                                    "Also write one run log per run into folder DIR (created if missing), named "
                                    "after the run: time, pulses (or output), theta1, gamma, as `ccal reduce` "
                                    "reads them"),
                    "--logs-out", "a folder path, e.g. logs")
      ->type_name("DIR");
  cmd->add_option("--log-layout", o->log_layout,
                  "With --logs-out: write the logs in this layout, a TOML file with a manifest's [columns] table "
                  "(column names, time unit, encoders in an angle unit or in counts per revolution), as a data "
                  "acquisition system writes them")
      ->type_name("FILE");
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal simulate\n"
      "      the bundled paper example: run means and the identified K0, K2, K3\n"
      "  ccal simulate my.toml --observations-out obs.csv && ccal identify obs.csv\n"
      "  ccal simulate my.toml --mode paper --format json -o sim.json\n"
      "  ccal simulate --format csv > obs.csv\n"
      "  ccal simulate my.toml --logs-out logs\n"
      "      also the runs' logs, logs/5g.csv, … and logs/manifest.toml, for `ccal reduce my.toml --logs logs`\n"
      "  ccal simulate my.toml --truth my-truth.toml --logs-out logs\n"
      "      the machine with the truth file's errors, which the lab does not know (my.toml's [errors]: what\n"
      "      it measured)\n"
      "  ccal simulate my.toml --logs-out logs --log-layout daq.toml\n"
      "      the logs in a data acquisition system's columns and units (daq.toml: a manifest's [columns])\n");

  return {cmd, [o] { run_simulate(*o); }};
}

}  // namespace ccal::cli

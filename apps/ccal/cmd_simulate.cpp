// ccal simulate: the run means a test plan produces (truth: the exact chain with the configured [errors]) and
// the regressors the analyst computes (with zero errors, or the [errors] values when compensating), written
// as an observations file and identified as `ccal identify` would (docs/cli.md).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <system_error>

#include "ccal/core/errors.hpp"
#include "ccal/io/run_log_writer.hpp"
#include "ccal/render/simulate.hpp"
#include "ccal/verbs/simulate.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct SimulateCli {
  std::string config;
  verbs::SimulateOptions options;  // its table's flags are bound to it
  std::string observations_out;
  std::string logs_out;  // folder for one run log per run
  OutputOptions output;
};

}  // namespace

Command add_simulate(CLI::App& app) {
  auto o = std::make_shared<SimulateCli>();
  CLI::App* cmd =
      app.add_subcommand("simulate",
                         "Simulated run means of the test plan (exact chain with the configured [errors], "
                         "instrument noise), their "
                         "regressors, and the identification of the [identification] terms from them.");
  add_config_argument(*cmd, o->config);
  add_option_flags(*cmd, o->options, option_table<verbs::SimulateOptions>());
  add_observations_out_option(*cmd, o->observations_out);
  cmd->add_option("--logs-out", o->logs_out,
                  "Also write one run log per run into folder DIR (created if missing), named after the run: "
                  "time, pulses (or output), theta1, gamma, as `ccal reduce` reads them")
      ->type_name("DIR");
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal simulate\n"
      "      the bundled paper example: run means and the identified K0, K2, K3\n"
      "  ccal simulate my.toml --observations-out obs.csv && ccal identify obs.csv\n"
      "  ccal simulate my.toml --mode paper --format json -o sim.json\n"
      "  ccal simulate --format csv > obs.csv\n"
      "  ccal simulate my.toml --logs-out logs\n"
      "      also the runs' logs, logs/5g.csv, …, for `ccal reduce my.toml --log 5g=logs/5g.csv …`\n");

  return {
      cmd, [o] {
        const Config cfg = load_config_or_example(o->config);
        check_observations_out(o->observations_out, o->output);
        const verbs::SimulateResult s = verbs::simulate(cfg, o->options);
        print_warnings(s.identification.observability.warnings);
        const std::string& f = o->output.format;
        const std::string text = f == "json"  ? render::json(s)
                                 : f == "csv" ? render::csv(s)
                                              : render::text(s);
        std::vector<ExtraFile> extra;
        if (!o->observations_out.empty())
          extra.push_back({"--observations-out", o->observations_out, s.observations_csv});
        if (!o->logs_out.empty()) {
          std::error_code ec;
          std::filesystem::create_directories(o->logs_out, ec);
          if (ec)
            throw InputError("--logs-out: cannot create the folder '" + o->logs_out + "': " + ec.message());
          const Eigen::VectorXd& means = s.observations.output;
          for (auto& log :
               write_run_logs(cfg, {means.data(), means.data() + means.size()}, default_log_step(cfg)))
            extra.push_back(
                {"--logs-out", (std::filesystem::path(o->logs_out) / log.name).string(), log.text});
        }
        write_outputs(o->output, text, extra);
      }};
}

}  // namespace ccal::cli

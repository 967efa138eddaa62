// ccal simulate: the run means a test plan produces (truth: the exact chain with the configured [errors]) and
// the regressors the analyst computes (with zero errors, or the [errors] values when compensating), written
// as an observations file and identified as `ccal identify` would (docs/cli.md).
#include <cstdint>
#include <memory>

#include "ccal/render/simulate.hpp"
#include "ccal/verbs/simulate.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct SimulateCli {
  std::string config;
  std::string mode;  // empty: the configuration's
  std::uint64_t seed = 1;
  std::string observations_out;
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
  cmd->add_option("--mode", o->mode,
                  "Reduction of a run: exact (full chain) or paper (Wang & Ren's first order); default: "
                  "[identification] mode of the configuration")
      ->check(CLI::IsMember({"exact", "paper"}));
  cmd->add_option("--seed", o->seed, "Seed of the output noise (used only if the instrument has noise)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)  // a negative seed would wrap to 2^64 - 1 silently
      ->type_name("S");
  add_observations_out_option(*cmd, o->observations_out);
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal simulate\n"
      "      the bundled paper example: run means and the identified K0, K2, K3\n"
      "  ccal simulate my.toml --observations-out obs.csv && ccal identify obs.csv\n"
      "  ccal simulate my.toml --mode paper --format json -o sim.json\n"
      "  ccal simulate --format csv > obs.csv\n");

  return {cmd, [o] {
            const Config cfg = load_config_or_example(o->config);
            check_observations_out(o->observations_out, o->output);
            verbs::SimulateOptions so;
            if (!o->mode.empty()) so.mode = parse_mode(o->mode);
            so.seed = o->seed;
            const verbs::SimulateResult s = verbs::simulate(cfg, so);
            print_warnings(s.identification.observability.warnings);
            const std::string& f = o->output.format;
            const std::string text = f == "json"  ? render::json(s)
                                     : f == "csv" ? render::csv(s)
                                                  : render::text(s);
            std::vector<ExtraFile> extra;
            if (!o->observations_out.empty())
              extra.push_back({"--observations-out", o->observations_out, s.observations_csv});
            write_outputs(o->output, text, extra);
          }};
}

}  // namespace ccal::cli

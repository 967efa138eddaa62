// ccal design: the test plan under which the centrifuge's errors cost the identified coefficients least
// (ccal/verbs/design.hpp, docs/model.md §15), with the designed configuration file.
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>

#include "ccal/core/errors.hpp"
#include "ccal/render/design.hpp"
#include "ccal/verbs/design.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct DesignCli {
  std::string config;
  std::string objective;  // empty: the configuration's
  std::vector<std::string> targets;
  int starts = -1;  // -1: the configuration's
  std::int64_t seed = -1;
  int threads = 0;
  std::int64_t verify = 0;
  std::vector<double> tradeoff;
  std::string plan_out;
  OutputOptions output;
};

}  // namespace

Command add_design(CLI::App& app) {
  auto o = std::make_shared<DesignCli>();
  CLI::App* cmd = app.add_subcommand(
      "design",
      "Test-plan design: the plan within the [design] space under which the centrifuge's tolerances cost the "
      "identified coefficients least, re-scored by the full budget");
  add_config_argument(*cmd, o->config);
  cmd->add_option("--objective", o->objective,
                  "uncertainty (U of the chosen coefficients from tolerances and noise), d_optimal or "
                  "a_optimal (the instrument's noise alone); default: [design] objective")
      ->check(CLI::IsMember({"uncertainty", "d_optimal", "a_optimal"}));
  cmd->add_option("--target", o->targets,
                  "COEFF=U: the objective counts U(COEFF)/U against this target instead of the configured "
                  "plan's U, e.g. K3=1e-4 or \"K3=1e-4 deg/s/g^3\"; repeat for each coefficient")
      ->allow_extra_args(false)
      ->type_name("COEFF=U");
  cmd->add_option("--starts", o->starts, "Random starts of the search (besides the configured plan)")
      ->check(CLI::Range(0, 1000))
      ->type_name("N");
  cmd->add_option("--seed", o->seed, "Seed of the random starts")
      ->check(CLI::NonNegativeNumber)
      ->type_name("S");
  cmd->add_option("--threads", o->threads, "Threads (0: the OpenMP default)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->type_name("K");
  cmd->add_option("--verify", o->verify, "Monte Carlo trials checking the designed plan's budget (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->type_name("N");
  cmd->add_option("--tradeoff", o->tradeoff,
                  "Factors of the total test time for a trade-off curve (total time against U), e.g. "
                  "--tradeoff 0.5,0.75,1")
      ->delimiter(',')
      ->type_name("F,...");
  cmd->add_option("--plan-out", o->plan_out,
                  "Write the whole configuration with the designed [plan] to this TOML file (atomically; "
                  "never over an input)")
      ->type_name("FILE.toml");
  add_output_options(*cmd, o->output, {"text", "json"});
  cmd->footer(
      "Examples:\n"
      "  ccal design\n"
      "      the bundled example: six runs, at most the paper plan's 2700 s, g within 5-30 g\n"
      "  ccal design my.toml --plan-out designed.toml && ccal budget designed.toml\n"
      "  ccal design --target K3=1e-4 --tradeoff 0.5,1 --verify 2000 --format json -o design.json\n");
  return {cmd, [o] {
            verbs::DesignOptions d;
            if (o->objective == "uncertainty") d.objective = DesignObjective::uncertainty;
            if (o->objective == "d_optimal") d.objective = DesignObjective::d_optimal;
            if (o->objective == "a_optimal") d.objective = DesignObjective::a_optimal;
            d.targets = o->targets;
            if (o->starts >= 0) d.starts = o->starts;
            if (o->seed >= 0) d.seed = std::uint64_t(o->seed);
            d.threads = o->threads;
            d.verify_trials = o->verify;
            d.tradeoff = o->tradeoff;
            if (!o->plan_out.empty() && o->plan_out == o->output.path)
              throw InputError("--plan-out: '" + o->plan_out +
                               "' is also the -o file; accepted: two different files");
            const Config config = load_config_or_example(o->config);
            const verbs::DesignResult r = verbs::design(config, d);
            print_warnings(r.after.observability.warnings);
            const std::string report = o->output.format == "json" ? render::json(r) : render::text(r);
            std::vector<ExtraFile> extra;
            if (!o->plan_out.empty())
              extra.push_back({"--plan-out", o->plan_out,
                               render::config_with_plan(config_file_text(o->config), r.designed)});
            write_outputs(o->output, report, extra);
          }};
}

}  // namespace ccal::cli

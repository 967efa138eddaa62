// ccal montecarlo: propagation of the configured tolerances to the identified coefficients by the Monte Carlo
// method of JCGM 101 (the engine of ccal/uncertainty/montecarlo.hpp), with the LPU of `ccal budget` for its
// validation.
#include <fmt/format.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/render/montecarlo.hpp"
#include "ccal/render/montecarlo_samples.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct MonteCarloCli {
  ConfigChoice config;
  verbs::MonteCarloOptions options;  // its table's flags are bound to it
  std::string old_coverage;          // --coverage, refused: it meant a factor in one verb and a probability here
  std::string samples_out;
  OutputOptions output;
};

// --samples-out: the kept values, streamed block by block into the (atomically replaced) file.
ExtraFile samples_file(const std::string& path, const verbs::MonteCarloResult& r) {
  const render::SampleFileFormat format = render::sample_file_format(path);
  return {"--samples-out", path, "", [&r, format](const std::function<bool(std::string_view)>& write) {
            return render::write_samples(r, format, write);
          }};
}

}  // namespace

Command add_montecarlo(CLI::App& app) {
  auto o = std::make_shared<MonteCarloCli>();
  CLI::App* cmd = app.add_subcommand(
      "montecarlo",
      "Monte Carlo propagation (JCGM 101) of the configured tolerances to the identified coefficients, with "
      "the validation of the LPU");
  add_config_argument(*cmd, o->config);
  add_option_flags(*cmd, o->options, option_table<verbs::MonteCarloOptions>());
  cmd->add_option("--coverage", o->old_coverage)->group("");  // refused with a message, not in --help
  refuse_empty_path(cmd->add_option("--samples-out", o->samples_out,
                                    "Also write every trial's coefficients to FILE: CSV, or NumPy .npy by the "
                                    "extension"),
                    "--samples-out", "a file path, FILE.csv or FILE.npy")
      ->type_name("FILE");
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal montecarlo --trials 2000\n"
      "      2000 trials of the bundled paper example\n"
      "  ccal montecarlo my.toml --trials 100000 --seed 7 --threads 2 --format json -o mc.json\n"
      "  ccal montecarlo --digits 2\n"
      "      the adaptive procedure: stages of 10000 trials until u(y) is stable to 2 digits\n"
      "  ccal montecarlo --samples-out samples.npy\n"
      "      also every trial's K0, K2, K3 (numpy.load reads it)\n");
  return {
      cmd, [o] {
        if (!o->old_coverage.empty())
          throw InputError(
              "--coverage: no longer accepted, as it meant the factor k in one command and a probability in "
              "others; accepted: --coverage-probability p (e.g. 0.95) for the intervals");
        if (!o->samples_out.empty() && o->samples_out == o->output.path)
          throw InputError(fmt::format(
              "--samples-out: '{}' is also the -o file; accepted: two different files", o->samples_out));
        verbs::MonteCarloOptions mo = o->options;
        mo.propagation.progress = true;  // drawn only when standard error is a terminal
        mo.propagation.keep_samples = !o->samples_out.empty();
        const verbs::MonteCarloResult r = verbs::monte_carlo(load_config_or_example(o->config), mo);
        const std::string& f = o->output.format;
        std::vector<ExtraFile> extra;
        if (!o->samples_out.empty()) extra.push_back(samples_file(o->samples_out, r));
        write_outputs(o->output,
                      f == "json"  ? render::json(r)
                      : f == "csv" ? render::csv(r)
                                   : render::text(r),
                      extra);
      }};
}

}  // namespace ccal::cli

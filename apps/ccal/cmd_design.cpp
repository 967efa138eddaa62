// ccal design: the test plan under which the centrifuge's errors cost the identified coefficients least
// (ccal/verbs/design.hpp, docs/model.md §15), with the designed configuration file.
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "ccal/core/errors.hpp"
#include "ccal/render/design.hpp"
#include "ccal/verbs/design.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "terminal.hpp"
#include "output.hpp"

namespace ccal::cli {

namespace {

// A job's set-up as the plan written to `plan_out` must name it: its path from that file's folder, when that
// is another folder than the job's (a relative `setup` is read from the job's folder); "" to keep it as written.
std::string setup_from(const std::string& job, const std::string& setup_source, const std::string& plan_out) {
  if (setup_source.empty()) return {};
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path setup = fs::weakly_canonical(fs::absolute(setup_source), ec);
  const fs::path folder = fs::weakly_canonical(fs::absolute(plan_out).parent_path(), ec);
  if (ec) return fs::absolute(setup_source).string();
  if (fs::weakly_canonical(fs::absolute(job).parent_path(), ec) == folder) return {};  // as written
  if (setup.parent_path() == folder) return setup.filename().string();
  const fs::path relative = setup.lexically_relative(folder);
  return relative.empty() ? setup.string() : relative.string();
}

// FILE.toml, the extension in any case (a configuration is read as TOML whatever its name).
bool is_toml_name(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".toml";
}

}  // namespace
namespace {

struct DesignCli {
  ConfigChoice config;
  verbs::DesignOptions options;  // its table's flags are bound to it
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
  add_option_flags(*cmd, o->options, option_table<verbs::DesignOptions>());
  add_renamed_option(*cmd, "--verify", "renamed: give the trials of the check as --verify-trials N (e.g. 2000)");
  refuse_empty_path(cmd->add_option("--plan-out", o->plan_out,
                                    "Write the whole configuration with the designed [plan] to this TOML file "
                                    "(atomically; never over an input)"),
                    "--plan-out", "a file path, e.g. designed.toml")
      ->type_name("FILE.toml");
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal design\n"
      "      the bundled example: six runs, at most the paper plan's 2700 s, g within 5-30 g\n"
      "  ccal design my.toml --plan-out designed.toml && ccal budget designed.toml\n"
      "  ccal design --target K3=1e-4 --tradeoff 0.5,1 --verify-trials 2000 --format json -o design.json\n");
  return {cmd, [o] {
            verbs::DesignOptions d = o->options;
            d.progress = true;  // drawn only when standard error is a terminal
            // The plan is a configuration, which is read as TOML whatever its name: a plan.json would be TOML
            // under a name that says JSON.
            if (!o->plan_out.empty() && !is_toml_name(o->plan_out))
              throw InputError("--plan-out: '" + o->plan_out +
                               "' has no .toml extension, and the plan is written as a TOML configuration; "
                               "accepted: FILE.toml, e.g. designed.toml");
            if (!o->plan_out.empty() && o->plan_out == o->output.path)
              throw InputError("--plan-out: '" + o->plan_out +
                               "' is also the -o file; accepted: two different files");
            const Config config = load_config_or_example(o->config);
            // A design takes minutes: an output that cannot be written is refused before it, not after.
            if (!o->plan_out.empty()) check_outputs(o->output, {{"--plan-out", o->plan_out, ""}});
            const verbs::DesignResult r = verbs::design(config, d);
            print_warnings(r.after.observability.warnings);
            const std::string& f = o->output.format;
            const std::string report = f == "json"  ? render::json(r)
                                       : f == "csv" ? render::csv(r)
                                                    : render::text(r);
            std::vector<ExtraFile> extra;
            if (!o->plan_out.empty())
              extra.push_back({"--plan-out", o->plan_out,
                               render::config_with_plan(config_file_text(o->config.path), r.designed,
                                                        setup_from(o->config.path, config.setup_source, o->plan_out))});
            write_outputs(o->output, report, extra);
          }};
}

}  // namespace ccal::cli

// ccal identify: least-squares identification of calibration coefficients from a CSV file of observations,
// either an observations file of `ccal simulate` (which records its terms) or any table with an input and an
// output column (docs/cli.md).
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <utility>

#include "ccal/io/observation_csv.hpp"
#include "ccal/render/identify.hpp"
#include "ccal/verbs/identify.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct IdentifyCli {
  std::string file;
  verbs::IdentifyOptions options;     // its table's flags are bound to it
  ConfigChoice config;                 // --config: the statement's configuration
  std::string statement_out;          // --statement-out FILE.json|FILE.csv
  std::string old_budget;             // --budget, refused: it took a file here and was a flag in reduce
  std::string old_input, old_weight;  // --input, --weight: now --input-column, --weight-column
  OutputOptions output;
};

// The columns of the table, for the refusal of an -o/--output that names one (the former --output COL).
bool is_column(const CsvTable& table, const std::string& name) { return table.find(name).has_value(); }

// Runs `ccal identify` on the observations file and writes its output and the files asked for.
void run_identify(IdentifyCli& o) {
  if (!o.old_budget.empty())
    throw InputError(
        "--budget: no longer accepted, as it took a file here and was a flag in reduce; accepted: "
        "--statement --config " +
        o.old_budget + " for the calibration statement");
  if (!o.old_input.empty() || !o.old_weight.empty())
    throw InputError(
        fmt::format("{0}: no longer accepted; accepted: {0}-column COL (the column of "
                    "the table), as -o/--output names the file written",
                    o.old_input.empty() ? "--weight" : "--input"));
  check_statement_out(o.statement_out, o.options.statement, o.output);
  note_input(o.file);
  const CsvTable table = read_csv_file(o.file);
  if (!o.output.path.empty() && is_column(table, o.output.path) && !std::filesystem::exists(o.output.path))
    throw InputError(fmt::format(
        "-o/--output: '{0}' is a column of {1}, but -o/--output names the file written; accepted: "
        "--output-column {0} for the output column, or ./{0} for a file of that name",
        o.output.path, o.file));
  verbs::IdentifyOptions io = o.options;
  if (!o.config.instrument.empty() && o.config.path.empty())
    throw InputError(
        fmt::format("--instrument: '{}' names an instrument of the configuration, and "
                    "there is none; accepted: with --config CONFIG",
                    o.config.instrument));
  if (!o.config.path.empty()) {
    io.config = load_config_or_example(o.config);
  }
  const verbs::IdentifyResult r = verbs::identify(table, io);
  print_warnings(r.identification.fit.warnings);  // also on standard error: the CSV has no place
  print_warnings(r.identification.observability.warnings);
  const std::string& f = o.output.format;
  std::vector<ExtraFile> extra;
  add_statement_out_file(extra, o.statement_out, r.statement);
  write_outputs(o.output,
                f == "json"  ? render::json(r)
                : f == "csv" ? render::csv(r)
                             : render::text(r),
                extra);
}

}  // namespace

Command add_identify(CLI::App& app) {
  auto o = std::make_shared<IdentifyCli>();
  CLI::App* cmd = app.add_subcommand(
      "identify",
      "Least-squares identification of calibration coefficients from a CSV file: an observations file of "
      "'ccal simulate' or any table of input and output.");
  cmd->add_option("file", o->file, "CSV file: a header row, then one row per observation")
      ->required()
      ->type_name("FILE.csv");
  add_option_flags(*cmd, o->options, option_table<verbs::IdentifyOptions>());
  // An empty --weight-column (an unset shell variable) would be taken as none given: an unweighted fit.
  cmd->get_option("--weight-column")->each(
      [](const std::string& column) { verbs::refuse_empty_weight_column(column); });
  cmd->add_option(
         "--config", o->config.path,
         "CONFIG: with --statement, the configuration whose tolerances give the Type B part and whose "
         "known [errors] give the correction")
      ->type_name("CONFIG");
  add_instrument_option(*cmd, o->config);
  for (auto [flag, target] : {std::pair{"--budget", &o->old_budget}, std::pair{"--input", &o->old_input},
                              std::pair{"--weight", &o->old_weight}})
    cmd->add_option(flag, *target)->group("");  // refused with a message, not in --help
  add_statement_out_option(*cmd, o->statement_out);
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal simulate --observations-out obs.csv && ccal identify obs.csv\n"
      "      the paper's K0, K2, K3 from the simulated run means (terms, fixed K1 and the rate term from the "
      "file)\n"
      "  ccal identify obs.csv --terms K0,K2:K2,K3:K3 --fix K1=505.2097 --format json\n"
      "  ccal identify data.csv --input-column x --output-column y --terms K0,K1,K2 --weight-column sigma\n"
      "      polynomial y = K0 + K1 x + K2 x^2 of a plain table\n"
      "  ccal identify obs.csv --statement --config my.toml -o statement.json --format json\n"
      "      with the calibration statement: Type A from the fit, Type B from my.toml's tolerances\n");

  return {cmd, [o] { run_identify(*o); }};
}

}  // namespace ccal::cli

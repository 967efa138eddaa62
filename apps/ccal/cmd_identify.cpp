// ccal identify: least-squares identification of calibration coefficients from a CSV file of observations,
// either an observations file of `ccal simulate` (which records its terms) or any table with an input and an
// output column (docs/cli.md).
#include <memory>

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
  std::vector<std::string> terms, fix, known;
  std::string input = verbs::IdentifyOptions{}.input;  // the library's defaults
  std::string output_column = verbs::IdentifyOptions{}.output;
  std::string weight;
  std::string budget;  // configuration of the statement's Type B part; empty: no statement
  verbs::StatementOptions statement;  // its table's flags are bound to it
  OutputOptions output;
  CLI::Option* terms_option = nullptr;
  CLI::Option* fix_option = nullptr;
  CLI::Option* known_option = nullptr;
};

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
  o->terms_option =
      cmd->add_option(
             "--terms", o->terms,
             "Free terms, comma-separated: Kn is the coefficient of input^n; <term>:<column> takes the "
             "column as the term's regressor (needed for K_p ... K_w). Default: the file's "
             "'# ccal observations' line")
          ->delimiter(',')
          ->type_name("TERMS");
  o->fix_option =
      cmd->add_option("--fix", o->fix,
                      "Terms held at known values, comma-separated <term>[:<column>]=<value>, the value "
                      "in the file's output unit per input unit^n (or with a unit). Default: the "
                      "file's fixed terms")
          ->delimiter(',')
          ->type_name("TERM=VALUE");
  cmd->add_option("--input", o->input, "Column of the input x of the power terms")
      ->capture_default_str()
      ->type_name("COL");
  cmd->add_option("--output", o->output_column, "Column of the output y")
      ->capture_default_str()
      ->type_name("COL");
  cmd->add_option("--weight", o->weight, "Column of the standard deviations sigma of y (weights 1/sigma^2)")
      ->type_name("COL");
  o->known_option =
      cmd->add_option("--known", o->known,
                      "Columns subtracted from the output, comma-separated, or 'none'. Default: the "
                      "file's known columns")
          ->delimiter(',')
          ->type_name("COL[,COL]");
  cmd->add_option("--budget", o->budget,
                  "CONFIG: also the calibration statement (JCGM 100 §7), with the Type B part from this "
                  "configuration's tolerances and the correction for its known [errors]")
      ->type_name("CONFIG");
  add_option_flags(*cmd, o->statement, option_table<verbs::StatementOptions>());
  add_output_options(*cmd, o->output, {"text", "json"}, false);  // --output names the output column
  cmd->footer(
      "Examples:\n"
      "  ccal simulate --observations-out obs.csv && ccal identify obs.csv\n"
      "      the paper's K0, K2, K3 from the simulated run means (terms, fixed K1 and the rate term from the "
      "file)\n"
      "  ccal identify obs.csv --terms K0,K2:K2,K3:K3 --fix K1=505.2097 --format json\n"
      "  ccal identify data.csv --input x --output y --terms K0,K1,K2 --weight sigma\n"
      "      polynomial y = K0 + K1 x + K2 x^2 of a plain table\n"
      "  ccal identify obs.csv --budget my.toml\n"
      "      with the calibration statement: Type A from the fit, Type B from my.toml's tolerances\n");

  return {cmd, [o] {
            note_input(o->file);
            const CsvTable table = read_csv_file(o->file);
            verbs::IdentifyOptions io;
            if (o->terms_option->count() > 0) io.terms = o->terms;
            if (o->fix_option->count() > 0) io.fix = o->fix;
            if (o->known_option->count() > 0) io.known = o->known;
            io.input = o->input;
            io.output = o->output_column;
            io.weight = o->weight;
            if (!o->budget.empty()) {
              note_input(o->budget);
              io.budget = load_config_or_example(o->budget);
            }
            io.statement = o->statement;
            const verbs::IdentifyResult r = verbs::identify(table, io);
            print_warnings(r.identification.observability.warnings);
            write_output(o->output, o->output.format == "json" ? render::json(r) : render::text(r));
          }};
}

}  // namespace ccal::cli

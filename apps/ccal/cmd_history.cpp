// ccal history: an instrument's calibration history (docs/cli.md): `add` records a calibration statement in
// the store, `show` lists a serial number's calibrations with the agreement of successive ones and the drift.
#include <memory>

#include "ccal/render/history.hpp"
#include "ccal/verbs/history.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct HistoryCli {
  std::string statement;
  verbs::HistoryAddOptions add;
  OutputOptions add_output;
  std::string serial;
  verbs::HistoryShowOptions show;
  OutputOptions show_output;
};

}  // namespace

Command add_history(CLI::App& app) {
  auto o = std::make_shared<HistoryCli>();
  CLI::App* cmd = app.add_subcommand(
      "history",
      "An instrument's calibration history: record calibration statements, show drift and agreement");
  cmd->require_subcommand(1);
  CLI::App* add = cmd->add_subcommand("add", "Record a calibration statement in the history store");
  add->add_option("STATEMENT", o->statement,
                  "Statement file (`ccal reduce --statement-out FILE`), or reduce's JSON (`--format json`)")
      ->required()
      ->type_name("FILE");
  add_option_flags(*add, o->add, option_table<verbs::HistoryAddOptions>());
  add_output_options(*add, o->add_output, {"text", "json"});
  CLI::App* show = cmd->add_subcommand(
      "show",
      "A serial number's calibrations: per coefficient E_n of successive ones, the drift and a prediction");
  show->add_option("SERIAL", o->serial, "Serial number, as recorded")->required()->type_name("S");
  add_option_flags(*show, o->show, option_table<verbs::HistoryShowOptions>());
  add_output_options(*show, o->show_output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal reduce lab.toml --log … --statement --statement-out statement.json\n"
      "  ccal history add statement.json                serial and date from the [certificate]\n"
      "  ccal history add old.json --serial \"SN 0815\" --date 2024-11-28\n"
      "  ccal history show \"SN 0815\" --at 2027-12-01     drift, E_n and the value predicted then\n");

  return {cmd, [o, add, show] {
            if (add->parsed()) {
              note_input(o->statement);
              const verbs::HistoryAddResult r = verbs::history_add(o->statement, o->add);
              write_output(o->add_output, o->add_output.format == "json" ? render::json(r) : render::text(r));
            } else if (show->parsed()) {
              const verbs::HistoryShowResult r = verbs::history_show(o->serial, o->show);
              const std::string& f = o->show_output.format;
              write_output(o->show_output, f == "json"  ? render::json(r)
                                           : f == "csv" ? render::csv(r)
                                                        : render::text(r));
            }
          }};
}

}  // namespace ccal::cli

// ccal history: an instrument's calibration history (docs/cli.md): `add` records a calibration statement in
// the store, `show` lists a serial number's calibrations with the agreement of successive ones and the drift,
// `list` the store's serial numbers.
#include <fmt/format.h>

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
  std::string id_text;  // ID as typed: read by verbs::history_record_id
  verbs::HistorySupersedeOptions supersede;
  std::string export_serial;
  verbs::HistoryStoreOptions export_store;
  OutputOptions export_output;
  std::string import_file;
  verbs::HistoryStoreOptions import_store;
  verbs::HistoryStoreOptions list_store;
  OutputOptions list_output;
};

// Each command's own examples (a command of commands inherits the top level's footer otherwise).
void add_history_examples(CLI::App& add, CLI::App& show, CLI::App& list, CLI::App& supersede,
                          CLI::App& exported, CLI::App& imported) {
  add.footer(
      "Examples:\n"
      "  ccal reduce lab.toml --log … --statement --statement-out statement.json\n"
      "  ccal history add statement.json\n"
      "      serial number and date from the statement's [certificate]\n"
      "  ccal history add old.json --serial \"SN 0815\" --date 2024-11-28 --db lab.sqlite\n");
  show.footer(
      "Examples:\n"
      "  ccal history show \"SN 0815\"\n"
      "      every calibration, E_n of successive ones and the drift\n"
      "  ccal history show \"SN 0815\" --at 2027-12-01\n"
      "      with the value predicted then and its uncertainty\n"
      "  ccal history show \"SN 0815\" --format csv -o sn0815.csv\n");
  list.footer(
      "Examples:\n"
      "  ccal history list\n"
      "      serial numbers, their calibrations and last date\n"
      "  ccal history list --db lab.sqlite --format json\n");
  supersede.footer(
      "Examples:\n"
      "  ccal history supersede 3 --by 4 --reason \"mounting screw loose; test repeated\"\n"
      "      record 3 kept, but left out of the drift and E_n (ids: ccal history show)\n");
  exported.footer(
      "Examples:\n"
      "  ccal history export \"SN 0815\" -o sn0815.json\n"
      "      the instrument's whole history, for another lab's store (ccal history import)\n");
  imported.footer(
      "Examples:\n"
      "  ccal history import sn0815.json --db other.sqlite\n"
      "      adds what is new; a calibration already there is counted, not added again\n");
}

// The subcommands of `ccal history`, each with its operands and options.
struct HistoryCommands {
  CLI::App *add, *show, *list, *supersede, *exported, *imported;
};

HistoryCommands add_history_subcommands(CLI::App* cmd, HistoryCli& o) {
  CLI::App* add = cmd->add_subcommand("add", "Record a calibration statement in the history store");
  add->add_option(
         "STATEMENT", o.statement,
         "The calibration statement's JSON file (`ccal reduce --statement --statement-out FILE.json`; "
         "not its CSV form), or reduce's JSON output (`--format json`)")
      ->required()
      ->type_name("FILE");
  add_option_flags(*add, o.add, option_table<verbs::HistoryAddOptions>());
  add_output_options(*add, o.add_output, {"text", "json"});
  CLI::App* show = cmd->add_subcommand(
      "show",
      "A serial number's calibrations: per coefficient E_n of successive ones, the drift and a prediction");
  show->add_option("SERIAL", o.serial, "Serial number, as recorded")->required()->type_name("SERIAL");
  add_option_flags(*show, o.show, option_table<verbs::HistoryShowOptions>());
  add_output_options(*show, o.show_output, {"text", "json", "csv"});
  CLI::App* list = cmd->add_subcommand(
      "list", "The store's serial numbers: each one's calibrations (superseded ones too) and last date");
  add_option_flags(*list, o.list_store, option_table<verbs::HistoryStoreOptions>());
  add_output_options(*list, o.list_output, {"text", "json", "csv"});
  CLI::App* supersede = cmd->add_subcommand(
      "supersede",
      "Mark a record superseded (a wrong statement, a repeated test): kept, left out of drift and E_n");
  supersede->add_option("ID", o.id_text, "The record's id, as `ccal history show` lists it")
      ->required()
      ->type_name("ID");
  add_option_flags(*supersede, o.supersede, option_table<verbs::HistorySupersedeOptions>());
  CLI::App* exported = cmd->add_subcommand("export", "A serial number's history as one JSON file");
  exported->add_option("SERIAL", o.export_serial, "Serial number, as recorded")
      ->required()
      ->type_name("SERIAL");
  add_option_flags(*exported, o.export_store, option_table<verbs::HistoryStoreOptions>());
  add_output_options(*exported, o.export_output, {"json"});
  CLI::App* imported = cmd->add_subcommand("import", "Record the calibrations of an exported history file");
  imported->add_option("FILE", o.import_file, "A file of `ccal history export`")
      ->required()
      ->type_name("FILE");
  add_option_flags(*imported, o.import_store, option_table<verbs::HistoryStoreOptions>());
  add_history_examples(*add, *show, *list, *supersede, *exported, *imported);
  return {add, show, list, supersede, exported, imported};
}

// Runs the subcommand that was parsed.
void run_history(HistoryCli& o, const HistoryCommands& c) {
  if (c.add->parsed()) {
    note_input(o.statement);
    note_input(verbs::history_store_path(o.add.db));
    // All or nothing: the output is checked before the store is touched, and written before the
    // store's transaction commits, whose failure to write it leaves the calibration unrecorded.
    check_outputs(o.add_output);
    verbs::history_add(o.statement, o.add, [&](const verbs::HistoryAddResult& r) {
      write_output(o.add_output, o.add_output.format == "json" ? render::json(r) : render::text(r));
    });
  } else if (c.show->parsed()) {
    note_input(verbs::history_store_path(o.show.db));
    const verbs::HistoryShowResult r = verbs::history_show(o.serial, o.show);
    const std::string& f = o.show_output.format;
    write_output(o.show_output, f == "json"  ? render::json(r)
                                : f == "csv" ? render::csv(r)
                                             : render::text(r));
  } else if (c.list->parsed()) {
    note_input(verbs::history_store_path(o.list_store.db));
    const verbs::HistoryListResult r = verbs::history_list(o.list_store);
    const std::string& f = o.list_output.format;
    write_output(o.list_output, f == "json"  ? render::json(r)
                                : f == "csv" ? render::csv(r)
                                             : render::text(r));
  } else if (c.supersede->parsed()) {
    const std::int64_t id = verbs::history_record_id(o.id_text);
    verbs::history_supersede(id, o.supersede);
    write_output(OutputOptions{}, fmt::format("Calibration {} superseded.\n", id));
  } else if (c.exported->parsed()) {
    note_input(verbs::history_store_path(o.export_store.db));
    write_output(o.export_output, verbs::history_export(o.export_serial, o.export_store));
  } else if (c.imported->parsed()) {
    note_input(o.import_file);
    const HistoryImport r = verbs::history_import(o.import_file, o.import_store);
    write_output(OutputOptions{},
                 fmt::format("Imported the history of {}: {} calibration{} added, {} already there, {} "
                             "supersession{} recorded.\n",
                             r.serial, r.added, r.added == 1 ? "" : "s", r.present, r.superseded,
                             r.superseded == 1 ? "" : "s"));
  }
}

}  // namespace

Command add_history(CLI::App& app) {
  auto o = std::make_shared<HistoryCli>();
  CLI::App* cmd = app.add_subcommand(
      "history",
      "An instrument's calibration history: record calibration statements, show drift and agreement");
  cmd->require_subcommand(1);
  const HistoryCommands commands = add_history_subcommands(cmd, *o);
  cmd->footer(
      "Examples:\n"
      "  ccal reduce lab.toml --log … --statement --statement-out statement.json\n"
      "  ccal history add statement.json                serial and date from the [certificate]\n"
      "  ccal history add old.json --serial \"SN 0815\" --date 2024-11-28\n"
      "  ccal history list                              serial numbers, calibrations, last date\n"
      "  ccal history show \"SN 0815\" --at 2027-12-01     drift, E_n and the value predicted then\n"
      "  ccal history supersede 3 --by 4 --reason \"mounting screw loose; test repeated\"\n"
      "  ccal history export \"SN 0815\" -o sn0815.json; ccal history import sn0815.json --db "
      "other.sqlite\n");
  return {cmd, [o, commands] { run_history(*o, commands); }};
}

}  // namespace ccal::cli

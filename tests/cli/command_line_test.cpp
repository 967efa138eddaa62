// The command line as people expect it: help that names values as users write them, each command's own
// examples, -V, completion for bash, zsh and fish with the values of every choice option, `report` refusing
// to pour its page into a terminal, and every file written named on standard error.
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/design.hpp"
#include "ccal/verbs/simulate.hpp"
#include "cli_support.hpp"

namespace ccal::test {
namespace {

// Every command and command of commands, as typed after `ccal`.
const std::vector<std::string> kCommandPaths = {"budget",         "force",
                                                "simulate",       "identify",
                                                "reduce",         "montecarlo",
                                                "allocate",       "design",
                                                "report",         "history",
                                                "history add",    "history show",
                                                "history list",   "history supersede",
                                                "history export", "history import"};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::set<std::string> set_of(const std::vector<std::string>& words) { return {words.begin(), words.end()}; }

class CommandLine : public Cli {
 protected:
  // Runs a shell command in the test's folder: its exit code and both streams.
  Result shell(const std::string& command) const {
    const fs::path out = dir_ / "shell_out.txt", err = dir_ / "shell_err.txt";
    const std::string line = "cd " + quote(dir_.string()) + " && ( " + command + " ) >" +
                             quote(out.string()) + " 2>" + quote(err.string());
    const int status = std::system(line.c_str());
    Result r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read(out), read(err)};
    fs::remove(out);
    fs::remove(err);
    return r;
  }
  static bool have(const std::string& program) {
    return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
  }
  // The completion script of a shell, written into the test's folder as `name`.
  void write_completion(const std::string& shell_name, const std::string& name) const {
    const Result r = run("--completion " + shell_name);
    ASSERT_EQ(r.code, 0) << r.err;
    write(name, r.out);
  }
  // What bash's completion function offers for the words (the last one being completed).
  std::vector<std::string> bash_offers(const std::string& words) const {
    const Result r =
        shell("bash -c " + quote("source ccal.bash; COMP_WORDS=(" + words +
                                 "); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _ccal; "
                                 "((${#COMPREPLY[@]} == 0)) || printf '%s\\n' \"${COMPREPLY[@]}\""));
    EXPECT_EQ(r.code, 0) << r.err;
    return lines_of(r.out);
  }
  // What fish offers for a command line (the words before the cursor), without the descriptions.
  std::vector<std::string> fish_offers(const std::string& line) const {
    const Result r = shell("fish --no-config -c " + quote("source ccal.fish; complete -C " + quote(line)));
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<std::string> words;
    for (const std::string& l : lines_of(r.out)) words.push_back(l.substr(0, l.find('\t')));
    return words;
  }
};

// The enumeration rows of an options table: their flags and the names of their values (the library's one
// list of them, which the help and the completions must show).
template <class Options>
std::vector<std::pair<std::string, std::vector<std::string>>> choice_rows() {
  std::vector<std::pair<std::string, std::vector<std::string>>> rows;
  for (const OptionSpec<Options>& row : option_table<Options>())
    if (const auto* e = std::get_if<OptionEnum<Options>>(&row.member)) {
      std::string flag = "--" + std::string(row.field);
      for (char& c : flag)
        if (c == '_') c = '-';
      rows.push_back({flag, std::vector<std::string>(e->names.begin(), e->names.end())});
    }
  return rows;
}

TEST_F(CommandLine, HelpNamesValuesAsUsersWriteThem) {
  for (const std::string& path : kCommandPaths) {
    const Result r = run(path + " --help");
    ASSERT_EQ(r.code, 0) << path << ": " << r.err;
    // None of the parser's own words: its type names, a validator's description, "=default", REQUIRED.
    for (const char* parser_word : {"TEXT:", "REQUIRED", ":{", "INT in", "UINT", "FLOAT", "=text", "=json"})
      EXPECT_EQ(r.out.find(parser_word), std::string::npos)
          << "ccal " << path << " --help: " << parser_word << "\n"
          << r.out;
  }
  const Result budget = run("budget --help");
  EXPECT_NE(budget.out.find("--format {text,json,csv}"), std::string::npos) << budget.out;
  EXPECT_NE(budget.out.find("Output format (default: text)"), std::string::npos) << budget.out;
  EXPECT_NE(budget.out.find("Usage: ccal budget [OPTIONS] [CONFIG]"), std::string::npos) << budget.out;
  for (const auto& [flag, names] : choice_rows<BudgetOptions>()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ",") + n;
    EXPECT_NE(budget.out.find(flag + " {" + list + "}"), std::string::npos) << flag << "\n" << budget.out;
  }
  const Result show = run("history show --help");
  EXPECT_NE(show.out.find("SERIAL"), std::string::npos) << show.out;
  EXPECT_EQ(show.out.find("SERIAL S"), std::string::npos) << show.out;
}

TEST_F(CommandLine, EachCommandsHelpEndsWithItsOwnExamples) {
  const Result top = run("--help");
  ASSERT_EQ(top.code, 0) << top.err;
  const std::string top_examples = top.out.substr(top.out.find("Examples:"));
  for (const std::string& path : kCommandPaths) {
    const Result r = run(path + " --help");
    const std::size_t at = r.out.find("Examples:");
    ASSERT_NE(at, std::string::npos) << path << "\n" << r.out;
    const std::string examples = r.out.substr(at);
    EXPECT_NE(examples, top_examples) << path;
    EXPECT_NE(examples.find("ccal " + path + " "), std::string::npos) << path << "\n" << examples;
  }
}

TEST_F(CommandLine, ShortAndLongVersionFlagsPrintTheVersion) {
  const Result shortflag = run("-V"), longflag = run("--version");
  EXPECT_EQ(shortflag.code, 0) << shortflag.err;
  EXPECT_TRUE(shortflag.out.starts_with("ccal ")) << shortflag.out;
  EXPECT_EQ(shortflag.out, longflag.out);
  EXPECT_TRUE(shortflag.err.empty()) << shortflag.err;
}

TEST_F(CommandLine, NoCommandOrAnUnknownFirstOptionListsTheCommands) {
  expect_bad_input(run(""), {"'ccal …' needs a command; accepted: budget, force", "run 'ccal --help'"});
  expect_bad_input(run("--bogus"), {"unknown option '--bogus' before a command", "-V, --version",
                                    "accepted: budget, force"});
}

TEST_F(CommandLine, ManPageNamesTheProgramOnceAndTheInstalledDocs) {
  const Result man = run("--man-page");
  ASSERT_EQ(man.code, 0) << man.err;
  EXPECT_NE(man.out.find(".SH NAME\nccal \\- precision\\-centrifuge calibration of accelerometers\n"),
            std::string::npos)
      << man.out.substr(0, 300);
  EXPECT_NE(man.out.find("share/doc/ccal/docs"), std::string::npos);
}

TEST_F(CommandLine, BashCompletesTheValuesOfChoiceOptions) {
  write_completion("bash", "ccal.bash");
  const std::set<std::string> formats{"text", "json", "csv"};
  EXPECT_EQ(set_of(bash_offers("ccal budget --format ''")), formats);
  EXPECT_EQ(set_of(bash_offers("ccal history show --format ''")), formats);
  EXPECT_EQ(set_of(bash_offers("ccal history export --format ''")), std::set<std::string>{"json"});
  for (const auto& [flag, names] : choice_rows<verbs::DesignOptions>())
    EXPECT_EQ(set_of(bash_offers("ccal design " + flag + " ''")), set_of(names)) << flag;
  for (const auto& [flag, names] : choice_rows<verbs::SimulateOptions>())
    EXPECT_EQ(set_of(bash_offers("ccal simulate " + flag + " ''")), set_of(names)) << flag;
  EXPECT_EQ(set_of(bash_offers("ccal --completion ''")), (std::set<std::string>{"bash", "zsh", "fish"}));
  // Commands, a command's commands and flags; files where a file goes, nothing after a number's flag.
  EXPECT_EQ(bash_offers("ccal bud"), std::vector<std::string>{"budget"});
  EXPECT_EQ(set_of(bash_offers("ccal history s")), (std::set<std::string>{"show", "supersede"}));
  EXPECT_EQ(bash_offers("ccal montecarlo --tri"), std::vector<std::string>{"--trials"});
  write("lab-obs.csv", "x\n");
  EXPECT_EQ(bash_offers("ccal identify lab-o"), std::vector<std::string>{"lab-obs.csv"});
  EXPECT_EQ(bash_offers("ccal budget -o lab-o"), std::vector<std::string>{"lab-obs.csv"});
  EXPECT_TRUE(bash_offers("ccal montecarlo --trials ''").empty());
}

TEST_F(CommandLine, ZshCompletionIsValidAndRegisters) {
  if (!have("zsh")) GTEST_SKIP() << "zsh is not installed (scripts/setup.sh installs it)";
  write_completion("zsh", "_ccal");
  const Result syntax = shell("zsh -n _ccal");
  EXPECT_EQ(syntax.code, 0) << syntax.err;
  // Sourced after compinit, it registers itself for ccal.
  const Result loaded = shell(
      "zsh -f -c 'autoload -U compinit && compinit -u -D && source ./_ccal && print "
      "${_comps[ccal]}'");
  EXPECT_EQ(loaded.code, 0) << loaded.err;
  EXPECT_EQ(loaded.out, "_ccal\n") << loaded.err;
  // Every choice's values are in the _arguments specification of its option.
  EXPECT_NE(read(dir_ / "_ccal").find("[Output format]:FORMAT:(text json csv)"), std::string::npos);
}

TEST_F(CommandLine, FishCompletesTheValuesOfChoiceOptions) {
  if (!have("fish")) GTEST_SKIP() << "fish is not installed (scripts/setup.sh installs it)";
  write_completion("fish", "ccal.fish");
  const Result syntax = shell("fish --no-config -n ccal.fish");
  EXPECT_EQ(syntax.code, 0) << syntax.err;
  const std::set<std::string> formats{"text", "json", "csv"};
  EXPECT_EQ(set_of(fish_offers("ccal budget --format ")), formats);
  EXPECT_EQ(set_of(fish_offers("ccal history show --format ")), formats);
  for (const auto& [flag, names] : choice_rows<verbs::DesignOptions>())
    EXPECT_EQ(set_of(fish_offers("ccal design " + flag + " ")), set_of(names)) << flag;
  const std::vector<std::string> commands = fish_offers("ccal ");
  for (const char* c : {"budget", "report", "history"})
    EXPECT_NE(std::find(commands.begin(), commands.end(), c), commands.end()) << c;
  EXPECT_EQ(set_of(fish_offers("ccal history su")), std::set<std::string>{"supersede"});
}

// The program run with its standard output (and error) on a new terminal: exit code and what it printed.
Result run_on_terminal(const fs::path& dir, const std::vector<std::string>& args) {
  int terminal = -1;
  const pid_t child = forkpty(&terminal, nullptr, nullptr, nullptr);
  if (child == 0) {
    if (::chdir(dir.c_str()) != 0) _exit(127);
    std::vector<char*> argv{const_cast<char*>(kProgram.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(kProgram.c_str(), argv.data());
    _exit(127);
  }
  Result r;
  char buffer[4096];
  for (ssize_t n; (n = ::read(terminal, buffer, sizeof buffer)) > 0;) r.out.append(buffer, std::size_t(n));
  int status = 0;
  ::waitpid(child, &status, 0);
  ::close(terminal);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST_F(CommandLine, ReportRefusesToWriteItsPageToATerminal) {
  ASSERT_EQ(fs::path(kProgram).is_absolute(), true);
  const Result r = run_on_terminal(dir_, {"report"});
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("ccal: error: report: the HTML page (about 1 MB) would be written to the terminal"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("-o FILE.html"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("<html"), std::string::npos);
  // Another command's text still goes to the terminal.
  const Result budget = run_on_terminal(dir_, {"budget", "--top", "1"});
  EXPECT_EQ(budget.code, 0) << budget.out;
}

TEST_F(CommandLine, ReportWritesItsPageToAFileOrPipe) {
  const Result r = run("report --trials 2000");
  if (r.err.find("charting library") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out.starts_with("<!DOCTYPE html>")) << r.out.substr(0, 100);
  EXPECT_TRUE(r.err.empty()) << r.err;  // standard output is no file to name
}

TEST_F(CommandLine, EveryFileWrittenIsNamedOnStandardError) {
  const Result r = run("simulate -o report.txt --observations-out obs.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "ccal: wrote report.txt (" + std::to_string(fs::file_size(dir_ / "report.txt")) +
                       " bytes)\nccal: wrote obs.csv (" + std::to_string(fs::file_size(dir_ / "obs.csv")) +
                       " bytes)\n");
  // Standard output and a device are not files to name.
  EXPECT_EQ(run("budget -o -").err, "");
  EXPECT_EQ(run("budget -o /dev/null").err, "");
}

// The budget's CSV header: one plain word per column, the unit in the name.
TEST_F(CommandLine, BudgetCsvHeaderIsPlainNames) {
  const Result r = run("budget --format csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string header = r.out.substr(0, r.out.find('\n'));
  std::istringstream in(header);
  for (std::string name; std::getline(in, name, ',');)
    EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"),
              std::string::npos)
        << name;
  for (const char* name :
       {",dK0_deg_s,", ",dK2_force_deg_s_g2,", ",dK3_rate_deg_s_g3,", ",c_K3_deg_s_g3_per_unit,"})
    EXPECT_NE(header.find(name), std::string::npos) << name << " in " << header;
}

// CSV rows split into fields (quotes kept), enough for ccal's own files.
std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& line : lines_of(text)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted)
        fields.emplace_back();
      else
        fields.back() += c;
    }
    rows.push_back(fields);
  }
  return rows;
}

// `design --format csv` is the run sheet of the JSON: rpm, seconds and degrees, the same numbers.
TEST_F(CommandLine, DesignCsvIsTheRunSheetInRpmSecondsAndDegrees) {
  const Result csv = run("design --format csv"), json = run("design --format json");
  ASSERT_EQ(csv.code, 0) << csv.err;
  ASSERT_EQ(json.code, 0) << json.err;
  const auto rows = csv_rows(csv.out);
  const auto sheet = nlohmann::json::parse(json.out).at("run_sheet").at("runs");
  ASSERT_EQ(rows.size(), sheet.size() + 1);
  const std::vector<std::string> header{"order",           "run",
                                        "g_level_g",       "main_speed_rpm",
                                        "platform",        "platform_speed_rpm",
                                        "duration_s",      "turns",
                                        "arm_azimuth_deg", "start_phase_deg",
                                        "stop_phase_deg",  "sets",
                                        "mounting",        "mounting_axes"};
  EXPECT_EQ(rows[0], header);
  for (std::size_t i = 0; i < sheet.size(); ++i)
    for (std::size_t c = 0; c < header.size(); ++c) {
      const auto& value = sheet[i].at(header[c]);
      if (value.is_number()) {  // the shortest digits of the same double: equal after parsing
        EXPECT_EQ(std::stod(rows[i + 1][c]), value.get<double>()) << header[c] << " of run " << i + 1;
      }
    }
  // A speed in rpm (not rad/s): the bundled example's runs turn between 10 and 200 rpm.
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GT(std::stod(rows[i][3]), 10.0) << rows[i][1];
    EXPECT_LT(std::stod(rows[i][3]), 200.0) << rows[i][1];
  }
}

// statement.csv's rounded figures are quoted text, as the statement's JSON writes them (trailing zeros kept).
TEST_F(CommandLine, StatementCsvQuotesItsRoundedFigures) {
  ASSERT_EQ(run("simulate --observations-out obs.csv").code, 0);
  const Result r = run("identify obs.csv --statement --statement-trials 0 --config " + quote(kExample) +
                       " --statement-out st.csv --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = csv_rows(read(dir_ / "st.csv"));
  const auto statement = nlohmann::json::parse(r.out).at("statement").at("coefficients");
  ASSERT_EQ(rows.size(), statement.size() + 1);
  const auto column = [&](const std::string& name) {
    return std::size_t(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& row = rows[i];
    const auto& rounded = statement.at(row.at(0)).at("rounded");  // the coefficient's id
    EXPECT_EQ(row.at(column("rounded_estimate")), "\"" + rounded.at("estimate").get<std::string>() + "\"");
    EXPECT_EQ(row.at(column("rounded_expanded_uncertainty")),
              "\"" + rounded.at("expanded_uncertainty").get<std::string>() + "\"");
    EXPECT_EQ(row.at(column("rounded_low")), "\"" + rounded.at("interval")[0].get<std::string>() + "\"");
    EXPECT_EQ(row.at(column("rounded_high")), "\"" + rounded.at("interval")[1].get<std::string>() + "\"");
  }
  // K2 of the bundled example: 0.02000 as written, its trailing zeros kept.
  EXPECT_EQ(rows.at(2).at(0), "K2");
  EXPECT_EQ(rows.at(2).at(column("rounded_estimate")), "\"0.02000\"");
}

}  // namespace
}  // namespace ccal::test

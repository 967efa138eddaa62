#pragma once
// Observation files (docs/cli.md, "The observations CSV"): the file `ccal simulate --observations-out` writes
// and `ccal identify` reads, and a reader for any CSV table whose problems are reported with their place.
//
// An observations file is a comment line recording what the columns mean, a header row and one row per run:
//     # ccal observations v1; terms=K0:K0,K2:K2,K3:K3; fixed=K1:K1=505.2097 deg/s/g; known=rate;
//     output_unit=deg/s run,a_i,output,rate,K0,K1,K2,K3 5g,...
// a_i is the run mean of the IA input [g], output the mean output and rate the known rate term s_ω⟨ω_IA⟩
// (both in output_unit), then one regressor column per term, named by its id (⟨a_iⁿ⟩ in gⁿ, ⟨ω_IA⟩ in rad/s
// for K_w). Values are written with 17 significant digits, so they read back as the same doubles.
//
// The fit of a table: a term Kn (n = 0…10) is the coefficient of inputⁿ, input being a chosen column, so any
// polynomial calibration y = Σ Kn xⁿ can be fitted from a plain x,y file; a term bound to a column ("K2:Z2")
// takes that column as its regressor instead (needed for run means, where ⟨a_i²⟩ ≠ ⟨a_i⟩², and for the named
// terms K_p … K_w).

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/setup/tolerance.hpp"

namespace ccal {

// A CSV file ccal cannot use. The message is one line:
//     <file>:<line>:<column>: <column name>: <problem>; <what is accepted>
// line is 1-based; column is the 1-based position of the field in its row (0 when the problem concerns a
// whole line, and then left out of the message, as is a line of 0).
// The message of an error at a place in a file with every NUL byte (echoed from the file) shown as \x00, as
// the program shows every control character: what() is read as a C string, which a NUL would end.
std::string with_nul_shown(std::string message);

class CsvError : public LocatedInputError {
 public:
  CsvError(std::string source, int line, int column, std::string column_name, std::string problem);

  const std::string& column_name() const noexcept { return item(); }
};

// A CSV table: '#' comment lines and blank lines anywhere are skipped; the first other line is the header
// naming the columns (non-empty, unique); every further line is a row with exactly as many fields. Fields are
// separated by commas, surrounding blanks are trimmed, and a field may be quoted ("a,b" with "" for a quote).
// Cells stay text until a column is asked for as numbers.
struct CsvTable {
  struct Comment {
    int line = 0;
    std::string text;  // after the '#', trimmed
  };
  std::string source;  // file name for messages
  std::string text_sha256;  // SHA-256 of the text it was parsed from: the file's fingerprint in a report
  std::vector<Comment> comments;
  int header_line = 0;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> row_lines;  // 1-based line of each row

  std::optional<std::size_t> find(std::string_view column) const;
  // The column's cells as finite numbers. Throws CsvError at the header if there is no such column
  // (`needed_by` says what wanted it) and at the first cell that is empty, not a number, or NaN/infinite.
  Eigen::VectorXd numbers(std::string_view column, std::string_view needed_by) const;
  // A CsvError at a row's cell (row and column 0-based).
  CsvError error_at(std::size_t row, std::size_t column, std::string problem) const;
};

// Parses CSV text; `source` names it in messages. Throws CsvError (empty file, no header, bad header, ragged
// row, unterminated quote).
CsvTable parse_csv(std::string_view text, std::string_view source);
// Reads and parses a file. Throws CsvError (also when the file cannot be read).
CsvTable read_csv_file(const std::filesystem::path& path);

// The pieces of parse_csv, for readers that stream a file line by line (csv_stream.hpp) and must refuse what
// parse_csv refuses, with the same messages and places.
using CsvFieldProblem = std::optional<std::pair<std::size_t, std::string>>;  // 0-based field, problem
// One line's trimmed fields, quotes removed; a malformed quote is reported in `bad`.
std::vector<std::string> split_csv_fields(std::string_view line, CsvFieldProblem& bad);
// Throws the CsvError of a bad header line (malformed quote, empty or duplicate name, numbers only).
void check_csv_header(const std::vector<std::string>& fields, const CsvFieldProblem& bad,
                      const std::string& source, int line);
// Throws the CsvError of a bad row (malformed quote, ragged).
void check_csv_row(std::size_t field_count, const CsvFieldProblem& bad,
                   const std::vector<std::string>& header, const std::string& source, int line);
// The error of a text without a header after `lines` lines (0: an empty file).
CsvError no_csv_header(const std::string& source, int lines);
// Why a cell is not a finite number ("" if it is one): the problem text of CsvTable::numbers.
std::string number_cell_problem(std::string_view cell);

// A finite decimal number, the whole text (blanks around it allowed; a leading '+' too); nullopt otherwise.
std::optional<double> parse_number(std::string_view text);

// A term's value as text, "K1=505.2 deg/s/g": split at the first '='; the term is what precedes it, the value
// the first word after it and the unit the rest ("" when there is none), each without the blanks (spaces,
// tabs) around it. nullopt when there is no '='. The parts are not checked (the term may be empty, the value
// not a number): the caller says what it accepts.
struct TermAssignment {
  std::string term;
  std::string value;
  std::string unit;
};
std::optional<TermAssignment> split_term_assignment(std::string_view text);

// The `# ccal observations v1; ...` comment of an observations file.
struct ObservationsHeader {
  struct Term {
    std::string id;      // term id, e.g. "K2"
    std::string column;  // the column holding its regressor
  };
  struct Fixed {
    Term term;
    double value = 0;  // in `unit`
    std::string unit;  // as written; coefficient_unit(output_unit, term) when ccal wrote it
  };
  std::vector<Term> terms;  // free terms
  std::vector<Fixed> fixed;
  std::vector<std::string> known;  // columns of known contributions, subtracted from the output
  std::string output_unit;         // unit of the output column ("" if not recorded)
  // SHA-256 of the configuration whose test the file holds (Config::numbers_sha256, what changes the numbers;
  // Config::text_sha256 in files written before it; "" if not recorded): the calibration statement refuses a
  // configuration of another fingerprint.
  std::string config_sha256;
  // The run logs the observations were reduced from (`ccal reduce`), each on a comment line of its own after
  // the header, "# ccal log v1; run=5g; sha256=<64 hex digits>; file=logs/5g.csv" (the file name last: it may
  // hold any character but a line end): the provenance of a filed result down to the recorded data.
  struct Log {
    std::string run;     // the plan's run name
    std::string sha256;  // of the log file's bytes, as read
    std::string file;    // as given to `ccal reduce`
    double duration = 0;  // the logged span T [s] ("; duration=…" before the file); 0: not recorded
    bool operator==(const Log&) const = default;
  };
  std::vector<Log> logs;
  // The inputs the logs measured (intake/measured_inputs.hpp), each on a line "# ccal measured v1; id=domega;
  // u=<SI, 17 digits>; resolved=true; how=<words>" after the logs: what the calibration statement of these
  // observations charges in place of those inputs' tolerances.
  std::vector<MeasuredInput> measured;
  int line = 0;                    // where the comment was read
};

// The comment line (with its leading "# "), and a line for each log after it (no line end after the last).
std::string format_observations_header(const ObservationsHeader& header);
// The table's `# ccal observations` comment, if it has one. Throws CsvError, at the comment's line, for an
// unsupported version or a malformed entry (unknown key, bad term id, term both free and fixed, bad value).
std::optional<ObservationsHeader> observations_header(const CsvTable& table);

// Size of one output unit in SI ("deg/s" → π/180; a pulse counts as 1, so "pulse/s" → 1). Throws UnitError.
double output_unit_si(std::string_view output_unit);

// The header observations_csv writes for a spec: each free and fixed term on its own regressor column, the
// fixed values in the output unit, the rate term known.
ObservationsHeader observations_file_header(const IdentificationSpec& spec,
                                            const InstrumentModel& instrument,
                                            std::string_view config_sha256 = {},
                                            const std::vector<ObservationsHeader::Log>& logs = {},
                                            const std::vector<MeasuredInput>& measured = {});

// The observations file of simulated observations: values in the instrument's output unit (regressors in gⁿ,
// K_w's in rad/s), fixed values in coefficient units, regressor columns in canonical term order.
std::string observations_csv(const Observations<double>& obs, const IdentificationSpec& spec,
                             const InstrumentModel& instrument, std::string_view config_sha256 = {},
                             const std::vector<ObservationsHeader::Log>& logs = {},
                             const std::vector<MeasuredInput>& measured = {});

// What to fit from a table. Values are in the file's units (output column per column unit).
struct TableTerm {
  std::string id;      // term id
  std::string column;  // regressor column; empty: a power Kn of the input column (n = 0 needs no column)
};
struct TableFixed {
  TableTerm term;
  double value = 0;
};
struct TableFitSpec {
  std::vector<TableTerm> terms;  // free, in this order
  std::vector<TableFixed> fixed;
  std::string input = "a_i";
  std::string output = "output";
  std::string weight;  // column of standard deviations σ of the output (weights 1/σ²); empty: none
  std::vector<std::string> known;  // columns subtracted from the output
};

// The least-squares problem of a table: y = output − Σ known, H = the free then the fixed terms' regressors,
// row labels from a "run" column if there is one (else "line <n>"). Term ids must be valid and distinct and
// named terms bound (std::invalid_argument otherwise: the caller checks its options). Throws CsvError for a
// missing column, a bad cell, a σ that is not positive, or fewer rows than free terms.
FitProblem table_fit_problem(const CsvTable& table, const TableFitSpec& spec);

}  // namespace ccal

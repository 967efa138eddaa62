#pragma once
// `ccal identify` as a library call: the least-squares identification of calibration coefficients from a
// table, either an observations file of `ccal simulate` / `ccal reduce` (which records its terms, fixed
// terms, known columns and output unit) or any table with an input and an output column (docs/cli.md).

#include <optional>
#include <string>
#include <vector>

#include "ccal/io/observation_csv.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/verbs/identification.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::verbs {

struct IdentifyOptions {
  // Free terms, "K2" or "K2:Z2" (a term bound to its regressor column); unset: the file's.
  std::optional<std::vector<std::string>> terms;
  // Held terms, "<term>[:<column>]=<value> [unit]"; unset: the file's (except those freed by `terms`).
  std::optional<std::vector<std::string>> fix;
  // Columns subtracted from the output ({"none"}: none); unset: the file's.
  std::optional<std::vector<std::string>> known;
  std::string input_column = "a_i";      // column of the input x of the power terms
  std::string output_column = "output";  // column of the output y
  std::string weight_column;             // column of the σ of y (weights 1/σ²); empty: unweighted
  bool statement = false;                // also the calibration statement, with `config`'s budget
  StatementOptions statement_options;    // of the statement (its rows are this table's)
  // The configuration whose tolerances give the statement's Type B part (and its known [errors] the
  // correction). Not a row of the table: each front end reads it (the command line: --config FILE).
  std::optional<Config> config;
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<IdentifyOptions> options_of(std::type_identity<IdentifyOptions>);

// A weight column given empty (an unset shell variable, or "" meant as "no weights") would be taken for none
// given, an unweighted fit: OptionError naming weight_column. Each front end calls it for a column it was given.
void refuse_empty_weight_column(std::string_view given);

struct IdentifyResult {
  std::string source;  // the table's name, as in messages
  std::size_t rows = 0;
  TableFitSpec spec;  // what was fitted
  Identification identification;
  std::optional<CalibrationStatement> statement;  // with options.budget
};

// Throws OptionError naming the field (terms, fix, known, statement, config, …) or CsvError naming the file's
// place.
IdentifyResult identify(const CsvTable& table, const IdentifyOptions& options = {});

// Throws OptionError of `field`, naming both SHA-256s, when the observations file records the fingerprint of
// a configuration (config_sha256) and `config` is from another text: its statement would carry the wrong
// budget. Nothing is checked when either fingerprint is unknown.
void check_observations_configuration(const CsvTable& table, const Config& config, std::string_view field);

}  // namespace ccal::verbs

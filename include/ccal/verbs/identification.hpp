#pragma once
// The identification shared by `ccal identify` and `ccal simulate`: the fit of an observations table, its
// units for display, the hint added to an ill-posed fit, and its text and JSON reports (docs/cli.md).

#include <string>
#include <string_view>
#include <vector>

#include "ccal/io/observation_csv.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/verbs/observability_report.hpp"

namespace ccal::verbs {

// How the columns of a table are measured, for the units of the coefficients.
struct ColumnUnits {
  // The output's unit when the table is a ccal observations file with a recorded output unit and the output
  // is its `output` column; else empty, and units are written with the column names ("y/x^2").
  std::string output_unit;
  std::string output_column = "output";
  std::string input_column = "a_i";
  bool input_in_g = false;  // the input column is a ccal file's a_i (in g)
  std::string g_symbol = "g";  // the g of a_i: "g" local, "gn" standard gravity (InstrumentModel::g_symbol)
};

struct Identification {
  FitResult fit;
  std::vector<std::string> units;  // per free term
  struct Fixed {
    std::string id;
    double value = 0;
    std::string unit;
  };
  std::vector<Fixed> fixed;
  std::vector<std::string> known;       // columns subtracted from the output
  std::vector<std::string> row_labels;  // one per row, unique
  std::string output_unit;              // "" when not known
  std::string residual_unit;            // unit of the residuals (the output's unit or column name)
  bool weighted = false;
  ObservabilityReport observability;  // per free term (docs/model.md §14)
  // Per row (run): the regressor of each free term, in the fit's order (∂ modelled output / ∂ term), and the
  // modelled output Σ H K̂ of the free and fixed terms (the known columns left out), in the residuals' unit.
  Eigen::MatrixXd design;
  Eigen::VectorXd modelled;
};

// Unit of a term's coefficient.
std::string term_unit(const TableTerm& term, const ColumnUnits& units);

// The hint appended to an ill-posed fit's message for the terms involved (IllPosedFit::terms): another
// mounting for terms in a_p or a_o, more g-levels for powers of a_i; "" for neither.
std::string ill_posed_hint(const std::vector<std::string>& terms);

// Fits the table and assesses the observability of each free term (with what is known of the runs, if given;
// else from the fit's scatter). An ill-posed fit is an InputError "<source>: <the fit's message><hint>", an
// unobservable term an InputError "<source>: the test plan cannot observe <term>: <reason>; <fix>".
Identification identify_table(const CsvTable& table, const TableFitSpec& spec, const ColumnUnits& units,
                              std::string_view source, const DataResolution* resolution = nullptr);

// Observations of a test plan as an observations file (`ccal simulate`, `ccal reduce`) and their
// identification, from the same numbers the file holds: the result is bit for bit what `ccal identify` gives
// for the file.
struct FileIdentification {
  std::string csv;    // the observations file
  TableFitSpec spec;  // what its header line says to fit
  Identification id;
};
FileIdentification identify_observations(const Observations<double>& obs, const IdentificationSpec& spec,
                                         const InstrumentModel& instrument, std::string_view source,
                                         const DataResolution* resolution = nullptr,
                                         std::string_view config_sha256 = {},
                                         const std::vector<ObservationsHeader::Log>& logs = {},
                                         const std::vector<MeasuredInput>& measured = {});

}  // namespace ccal::verbs

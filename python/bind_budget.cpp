// `ccal budget` from Python: the budget in detail (every source's line, the matrices, the compensation
// choices), the Budget result and budget().
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/verbs/budget.hpp"

namespace ccal::python {

namespace {

// Rows of one per-source vector field of the budget: sources × coefficients.
Eigen::MatrixXd stacked(const BudgetDetail& b, Eigen::VectorXd SourceBudget::*field) {
  Eigen::MatrixXd out(Eigen::Index(b.sources.size()), Eigen::Index(b.coefficients.size()));
  for (std::size_t s = 0; s < b.sources.size(); ++s) {
    const Eigen::VectorXd& v = b.sources[s].*field;
    if (v.size() != out.cols()) return {};
    out.row(Eigen::Index(s)) = v.transpose();
  }
  return out;
}

// The budget in detail: every source's line (SourceBudget), the compensation choices and BudgetDetail.
void bind_budget_results(py::module_& m) {
  py::class_<SourceBudget>(m, "SourceBudget", "One error source's line of the budget (SI).")
      .def_readonly("id", &SourceBudget::id, "the error parameter's id [—]")
      .def_readonly("parameter", &SourceBudget::parameter, "its index in Config.error_ids [—]")
      .def_readonly("group", &SourceBudget::group, "its correlation group ('' for none) [—]")
      .def_property_readonly(
          "distribution",
          [](const SourceBudget& s) { return std::string(distribution_name(s.distribution)); },
          "'normal', 'uniform', 'triangular' or 'arcsine' [—]")
      .def_readonly("bound", &SourceBudget::bound, "the tolerance's bound [SI unit of the parameter]")
      .def_readonly("standard_uncertainty", &SourceBudget::standard_uncertainty,
                    "u of the parameter [SI unit of the parameter]")
      .def_readonly("sensitivity", &SourceBudget::sensitivity,
                    "∂K/∂e per coefficient [coefficient SI per SI unit of the parameter]")
      .def_readonly("effect", &SourceBudget::effect,
                    "sensitivity × u, signed, per coefficient [coefficient SI]")
      .def_readonly("effect_force", &SourceBudget::effect_force,
                    "the part of effect through the specific force [coefficient SI]")
      .def_readonly("effect_rate", &SourceBudget::effect_rate,
                    "the part of effect through the angular rate [coefficient SI]")
      .def_readonly("share", &SourceBudget::share, "share of each coefficient's variance, 0…1 [—]")
      .def_readonly("paper_effect", &SourceBudget::paper_effect,
                    "the paper-mode effect, empty if not computed [coefficient SI]")
      .def_readonly("disagrees", &SourceBudget::disagrees,
                    "exact and paper effects differ beyond the factor, per coefficient [—]")
      .def_readonly("rank", &SourceBudget::rank, "1 = the largest contributor [—]")
      .def("__repr__", [](const SourceBudget& s) { return "<ccal.SourceBudget " + s.id + ">"; });

  py::class_<CompensationChoice>(m, "CompensationChoice")
      .def_readonly("id", &CompensationChoice::id, "the modelling choice's id, e.g. 'earth_rate' [—]")
      .def_readonly("description", &CompensationChoice::description, "what is left out of the model [—]")
      .def_readonly("bias", &CompensationChoice::bias,
                    "K̂(effect not modelled) − K̂(modelled), per coefficient [coefficient SI]")
      .def_readonly("paper_bias", &CompensationChoice::paper_bias, "the same in paper mode [coefficient SI]");

  py::class_<BudgetDetail>(m, "BudgetDetail",
                           "The error budget of a configuration (SI; display units alongside).")
      .def_property_readonly(
          "mode", [](const BudgetDetail& b) { return std::string(mode_name(b.mode)); },
          "'exact' or 'paper' [—]")
      .def_property_readonly(
          "derivatives",
          [](const BudgetDetail& b) {
            return b.derivatives == DerivativeMethod::automatic ? "automatic" : "linearised";
          },
          "'linearised' or 'automatic' [—]")
      .def_readonly("coefficients", &BudgetDetail::coefficients, "the identified coefficients' ids [—]")
      .def_readonly("units", &BudgetDetail::units,
                    "the display unit of each coefficient, e.g. 'deg/s/g^3' [—]")
      .def_readonly("display_scale", &BudgetDetail::display_scale,
                    "SI → display unit factor per coefficient [display unit per SI]")
      .def_readonly("sources", &BudgetDetail::sources, "one SourceBudget per tolerance [—]")
      .def_property_readonly(
          "source_ids",
          [](const BudgetDetail& b) {
            std::vector<std::string> ids;
            for (const auto& s : b.sources) ids.push_back(s.id);
            return ids;
          },
          "the sources' ids, the rows of the matrices [—]")
      .def_property_readonly(
          "sensitivity", [](const BudgetDetail& b) { return stacked(b, &SourceBudget::sensitivity); },
          "∂K/∂e, sources × coefficients [coefficient SI per SI unit of the source]")
      .def_property_readonly(
          "effect", [](const BudgetDetail& b) { return stacked(b, &SourceBudget::effect); },
          "sensitivity × u, sources × coefficients [coefficient SI]")
      .def_property_readonly(
          "effect_force", [](const BudgetDetail& b) { return stacked(b, &SourceBudget::effect_force); },
          "the part of effect through the specific force, sources × coefficients [coefficient SI]")
      .def_property_readonly(
          "effect_rate", [](const BudgetDetail& b) { return stacked(b, &SourceBudget::effect_rate); },
          "the part of effect through the angular rate, sources × coefficients [coefficient SI]")
      .def_property_readonly(
          "share", [](const BudgetDetail& b) { return stacked(b, &SourceBudget::share); },
          "share of each coefficient's variance, sources × coefficients, 0…1 [—]")
      .def_readonly("standard_uncertainty", &BudgetDetail::standard_uncertainty,
                    "u_c per coefficient (LPU with correlation groups) [coefficient SI]")
      .def_readonly("expanded_uncertainty", &BudgetDetail::expanded_uncertainty,
                    "U = k u_c per coefficient [coefficient SI]")
      .def_property_readonly(
          "coverage_factor", [](const BudgetDetail& r) { return r.coverage.factor; }, "k of U = k u [—]")
      .def_property_readonly(
          "coverage_probability", [](const BudgetDetail& r) { return r.coverage.probability; },
          "p of U: the option's, or the normal p of a stated k [—]")
      .def_property_readonly(
          "coverage_method", [](const BudgetDetail& r) { return std::string(coverage_method_name(r.coverage.method)); },
          "how k was obtained: 'normal' (from p) or 'stated k' [—]")
      .def_readonly("covariance", &BudgetDetail::covariance,
                    "covariance of the coefficients [coefficient SI × coefficient SI]")
      .def_readonly("correlation", &BudgetDetail::correlation, "correlation of the coefficients [—]")
      .def_readonly("input_correlation", &BudgetDetail::input_correlation,
                    "with [[correlations]]: the inputs' correlation matrix R, sources × sources in the order of "
                    "`sources` (groups' r = 1 in it); else empty [—]")
      .def_property_readonly(
          "correlation_variance", [](const BudgetDetail& r) { return correlation_variance(r); },
          "per coefficient: the part of u² the sources' correlations make (negative where they cancel) "
          "[coefficient SI²]")
      .def_readonly("compensation", &BudgetDetail::compensation,
                    "the modelling choices and their biases, list of CompensationChoice [—]");
}

// The SI → display factor of each row of a test's instruments' covariance.
std::vector<double> row_scales(const verbs::InstrumentCovariance& c) {
  std::vector<double> scale;
  for (const std::string& unit : c.units) scale.push_back(display_scale_of(unit));
  return scale;
}

// A covariance in display units (the library's, as the JSON writes it) in SI: C_ij / (s_i s_j).
Eigen::MatrixXd rows_in_si(const verbs::InstrumentCovariance& c, const Eigen::MatrixXd& display) {
  const std::vector<double> scale = row_scales(c);
  Eigen::MatrixXd out = display;
  for (Eigen::Index i = 0; i < out.rows(); ++i)
    for (Eigen::Index j = 0; j < out.cols(); ++j) out(i, j) /= scale[std::size_t(i)] * scale[std::size_t(j)];
  return out;
}

// The covariance of a test's instruments' coefficients (verbs/instrument_covariance.hpp).
void bind_instrument_covariance(py::module_& m) {
  py::class_<verbs::InstrumentCovariance>(
      m, "InstrumentCovariance",
      "The tolerances' covariance of the coefficients of every instrument of a test of several (the machine's "
      "errors, g, the clock and the encoders are one for all; each instrument's own inputs and Type A parts are "
      "not in it), in SI with the rows' units and display_scale beside it: Budget.instrument_covariance, "
      "Reduction.covariance.")
      .def_readonly("instruments", &verbs::InstrumentCovariance::instruments, "the instruments' ids, in order [—]")
      .def_readonly("first_row", &verbs::InstrumentCovariance::first_row,
                    "per instrument, the row of its first coefficient [—]")
      .def_readonly("names", &verbs::InstrumentCovariance::names, "per row: '<id> <term>', e.g. 'B K2' [—]")
      .def_readonly("units", &verbs::InstrumentCovariance::units, "per row: the coefficient's display unit [—]")
      .def_property_readonly("display_scale", &row_scales,
                             "per row: the SI → display unit factor [display unit per SI]")
      .def_property_readonly(
          "lpu", [](const verbs::InstrumentCovariance& c) { return rows_in_si(c, c.lpu); },
          "the LPU covariance, rows × rows [coefficient SI_i × coefficient SI_j]")
      .def_property_readonly(
          "lpu_correlation",
          [](const verbs::InstrumentCovariance& c) {
            Eigen::MatrixXd r = c.lpu;
            for (Eigen::Index i = 0; i < r.rows(); ++i)
              for (Eigen::Index j = 0; j < r.cols(); ++j) {
                const double scale = std::sqrt(c.lpu(i, i) * c.lpu(j, j));
                r(i, j) = scale > 0 ? c.lpu(i, j) / scale : 0.0;
              }
            return r;
          },
          "the LPU's correlation, rows × rows (0 where a coefficient does not vary) [—]")
      .def_property_readonly(
          "monte_carlo", [](const verbs::InstrumentCovariance& c) { return rows_in_si(c, c.monte_carlo); },
          "the same by a Monte Carlo of shared draws; empty when none ran [coefficient SI_i × coefficient SI_j]")
      .def_readonly("trials", &verbs::InstrumentCovariance::trials, "the Monte Carlo's trials, 0 for none [—]")
      .def_readonly("seed", &verbs::InstrumentCovariance::seed, "the Monte Carlo's seed [—]")
      .def("__repr__", [](const verbs::InstrumentCovariance& c) {
        return "<ccal.InstrumentCovariance of " + std::to_string(c.instruments.size()) + " instruments>";
      });
}

}  // namespace

// The budget's results, the Budget result of `ccal budget` and budget().
void bind_budget(py::module_& m) {
  bind_budget_results(m);
  bind_instrument_covariance(m);

  bind_verb_result<verbs::BudgetResult>(m, "Budget",
                                        "`ccal budget` of a configuration: its BudgetDetail's fields are "
                                        "readable on it; str() is the CLI's text, to_json() its JSON.",
                                        "budget")
      .def_readonly("config", &verbs::BudgetResult::config)
      .def_readonly("budget", &verbs::BudgetResult::budget,
                    "the budget itself (its fields are readable on the result) [BudgetDetail]")
      .def_readonly("instruments", &verbs::BudgetResult::instruments,
                    "a test of several instruments: each one's Budget, as budget() of that instrument alone, in "
                    "the file's order (the result's own budget is then empty); [] for one instrument [list of Budget]")
      .def_readonly("instrument_covariance", &verbs::BudgetResult::covariance,
                    "a test of several instruments: the LPU covariance of all their coefficients; None for one "
                    "instrument [InstrumentCovariance]");

  const BudgetOptions defaults;  // the CLI's defaults
  m.def(
      "budget",
      [](const Config& cfg, bool compare_with_paper, const py::kwargs& keywords) {
        auto o = options_from_keywords<BudgetOptions>(keywords, "budget");
        o.compare_with_paper = compare_with_paper;
        py::gil_scoped_release release;
        return verbs::budget(cfg, o);
      },
      py::arg("config"), py::kw_only(), py::arg("compare_with_paper") = defaults.compare_with_paper,
      "Error budget (`ccal budget`): sensitivity of every identified coefficient to every tolerance, the "
      "effects, totals and compensation choices. compare_with_paper: in exact mode, also the paper's "
      "first-order effect of each source.");
  record_keywords<BudgetOptions>(m, "budget");
}

}  // namespace ccal::python

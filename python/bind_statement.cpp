// ccal.Statement: the calibration statement of `reduce(statement=True)` and `identify_file(statement=True)`
// (verbs/statement.hpp, docs/model.md §10.5): str() the command line's text, to_json() and to_csv() the files of
// `--statement-out`, the covariance as arrays; display(), to_frame() and to_uncertainties() are added in Python
// (ccal/_results.py).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "ccal/render/statement.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::python {
namespace {

using Statement = verbs::CalibrationStatement;

// One number of each coefficient, in the statement's order.
template <typename F>
std::vector<double> per_coefficient(const Statement& s, F f) {
  std::vector<double> v;
  for (const CoefficientStatement& c : s.coefficients) v.push_back(f(c));
  return v;
}

// The per-coefficient lists, in the order of `names`.
void bind_coefficient_lists(py::class_<Statement>& cls) {
  cls.def_property_readonly(
          "names",
          [](const Statement& s) {
            std::vector<std::string> v;
            for (const CoefficientStatement& c : s.coefficients) v.push_back(c.input.coefficient);
            return v;
          },
          "the coefficients, in the order of every list and matrix here [—]")
      .def_property_readonly(
          "units",
          [](const Statement& s) {
            std::vector<std::string> v;
            for (const CoefficientStatement& c : s.coefficients) v.push_back(c.input.unit);
            return v;
          },
          "each coefficient's unit, the unit of its values here [—]")
      .def_property_readonly(
          "values", [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.corrected; }); },
          "the corrected estimates K̂ + b [units]")
      .def_property_readonly(
          "standard_uncertainties",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.combined; }); },
          "u_c of each coefficient [units]")
      .def_property_readonly(
          "effective_dof",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.effective_dof; }); },
          "nu_eff of each coefficient (inf: known exactly) [—]")
      .def_property_readonly(
          "coverage_factors",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.coverage_factor; }); },
          "k of each coefficient [—]")
      .def_property_readonly(
          "expanded_uncertainties",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.expanded; }); },
          "U = k u_c of each coefficient; with the Monte Carlo's interval half its width [units]")
      .def_property_readonly(
          "intervals",
          [](const Statement& s) {
            std::vector<std::pair<double, double>> v;
            for (const CoefficientStatement& c : s.coefficients) v.emplace_back(c.low, c.high);
            return v;
          },
          "the stated coverage interval (low, high) of each coefficient [units]")
      .def_property_readonly(
          "interval_methods",
          [](const Statement& s) {
            std::vector<std::string> v;
            for (const CoefficientStatement& c : s.coefficients)
              v.emplace_back(kIntervalMethodNames[std::size_t(c.method)]);
            return v;
          },
          "per coefficient 'student_t' (y ∓ k u_c), 'monte_carlo' (the Monte Carlo's interval, stated where "
          "the JCGM 101 §8 check refused the Student-t one) or 'coverage_factor' (y ∓ k u_c with the stated k) [—]")
      .def_readonly("coverage_factor", &Statement::coverage_factor,
                    "the k the user stated (coverage_factor=), else None [—]")
      .def_readonly("setup_sha256", &Statement::setup_sha256,
                    "fingerprint of the configuration's machine and lab tables (Config.setup_sha256) [—]")
      .def_readonly("monte_carlo_trials", &Statement::monte_carlo_trials,
                    "M of the Monte Carlo check (0: none was run); more than requested while a verdict was "
                    "within the sampling error [—]")
      .def_readonly("monte_carlo_requested_trials", &Statement::monte_carlo_requested_trials,
                    "the M requested (statement_trials) [—]")
      .def_property_readonly(
          "significant",
          [](const Statement& s) {
            std::vector<bool> v;
            for (const CoefficientStatement& c : s.coefficients) v.push_back(c.significant);
            return v;
          },
          "per coefficient: its interval excludes 0 [—]");
}

// The Type B part's inputs (the GUM table), one dict per input.
py::list inputs_list(const Statement& s) {
  py::list out;
  for (const verbs::StatementSource& in : s.inputs) {
    py::dict d;
    d["id"] = in.id;
    d["standard_uncertainty"] = in.standard_uncertainty;
    d["u"] = in.standard_uncertainty / in.unit_si;
    d["unit"] = in.unit;
    d["measured"] = in.measured;
    d["basis"] = in.basis;
    py::dict effect;
    for (std::size_t k = 0; k < in.effect.size() && k < s.coefficients.size(); ++k)
      effect[py::str(s.coefficients[k].input.coefficient)] = in.effect[k];
    d["effect"] = effect;
    d["group"] = in.group;
    out.append(d);
  }
  return out;
}

constexpr const char* kInputsHelp =
    "the Type B part's inputs (the GUM table): per input a dict of id, standard_uncertainty [SI], u and unit "
    "(u in "
    "the unit it is shown in: as its tolerance was written, else its own), measured (in this test, charged "
    "at the "
    "measurement's u; else its tolerance), basis (in words), effect (per coefficient, c u signed), group "
    "(its "
    "tolerance's correlation group, '' for none) [the coefficients' units]";

}  // namespace

void bind_statement(py::module_& m) {
  py::class_<Statement> c(m, "Statement",
                        "The calibration statement (JCGM 100 §7): per coefficient the corrected estimate, u_c, "
                        "nu_eff, k, U and the interval, in the fit's units (the coefficients' output unit per "
                        "g^n); the combined covariance. str() is the command line's text; to_json() and to_csv() "
                        "are the files of `--statement-out`.");
  c.def("__str__", [](const Statement& s) { return render::text(s); })
      .def(
          "to_json", [](const Statement& s) { return render::json(s); },
          "The statement as `--statement-out FILE.json` writes it (text).")
      .def(
          "to_csv", [](const Statement& s) { return render::csv(s); },
          "The statement as `--statement-out FILE.csv` writes it: one row per coefficient, with its row of "
          "the "
          "covariance (text).")
      .def_readonly("budget_config", &Statement::budget_config,
                    "the configuration whose tolerances give the Type B part [path]")
      .def_readonly("setup_sha256", &Statement::setup_sha256,
                    "the machine set-up's fingerprint: calibrations with the same one share its errors [—]")
      .def_property_readonly(
          "input_correlations",
          [](const Statement& s) {
            py::list out;
            for (const Correlation& c : s.input_correlations)
              out.append(py::make_tuple(c.first, c.second, c.r));
            return out;
          },
          "the [[correlations]] among the inputs charged at their tolerance: (id_a, id_b, rho) tuples [—]")
      .def_property_readonly(
          "mode", [](const Statement& s) { return std::string(mode_name(s.mode)); },
          "kinematics of the Type B budget: exact or paper [—]")
      .def_readonly("coverage_probability", &Statement::coverage_probability, "p of the intervals [—]");
  bind_coefficient_lists(c);
  c.def_readonly("covariance", &Statement::covariance,
                 "combined covariance of the corrected estimates, Type A + Type B [units_i × units_j]")
      .def_readonly("covariance_a", &Statement::covariance_a,
                    "the fit's covariance (Type A) [units_i × units_j]")
      .def_readonly("covariance_b", &Statement::covariance_b,
                    "the tolerances' covariance (Type B) [units_i × units_j]")
      .def_readonly("correlation", &Statement::correlation, "correlation of the corrected estimates [—]")
      .def_property_readonly(
          "outputs",
          [](const Statement& s) {
            py::list out;
            for (std::size_t r = 0; r < s.outputs.size(); ++r) {
              const CoefficientStatement& o = s.outputs[r];
              py::dict d;
              d["run"] = o.input.coefficient;
              d["g_level"] = s.g_levels[r];
              d["unit"] = o.input.unit;
              d["value"] = o.corrected;
              d["standard_uncertainty"] = o.combined;
              d["effective_dof"] = o.effective_dof;
              d["coverage_factor"] = o.coverage_factor;
              d["expanded_uncertainty"] = o.expanded;
              d["interval"] = py::make_tuple(o.low, o.high);
              d["interval_method"] = std::string(kIntervalMethodNames[std::size_t(o.method)]);
              out.append(d);
            }
            return out;
          },
          "the modelled output of each run, ŷ = hᵀ(K̂ + b) with u from the covariance: per run a dict of run, "
          "g_level [g] (nan: no run of the plan), unit, value, standard_uncertainty, effective_dof, "
          "coverage_factor, expanded_uncertainty, interval (low, high), interval_method [the output's unit]")
      .def_property_readonly("inputs", &inputs_list, kInputsHelp)
      .def_property_readonly(
          "type_a_from_noise_model", [](const Statement& s) { return s.type_a.from_noise_model; },
          "whether the Type A part is the stated noise's (else the fit's scatter) [—]")
      .def_property_readonly(
          "residual_check",
          [](const Statement& s) {
            py::dict d;
            d["statistic"] = s.type_a.statistic;
            d["expected"] = s.type_a.expected;
            d["p_value"] = s.type_a.p_value;
            d["dof"] = s.type_a.dof;
            d["excess"] = s.type_a.excess;
            d["excess_variance"] = s.type_a.excess_variance;
            return d;
          },
          "the residuals tested against the noise and the inputs' run-to-run effects: statistic S, expected, "
          "p_value, dof, excess (charged), excess_variance [output unit²] (meaningful with a noise model)");
}

}  // namespace ccal::python

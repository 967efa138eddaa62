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

// The statement is computed in the fit's units (as the command line states it); Python gives it in SI, as every
// result (docs/python.md): a value in the fit's unit divided by that unit's display scale.
std::vector<double> display_scales(const std::vector<CoefficientStatement>& rows) {
  std::vector<double> v;
  for (const CoefficientStatement& c : rows) v.push_back(display_scale_of(c.input.unit));
  return v;
}

// One number of each coefficient, in the statement's order, in SI (`in_si`: false for a number without unit).
template <typename F>
std::vector<double> per_coefficient(const Statement& s, F f, bool in_si = true) {
  const std::vector<double> scale = display_scales(s.coefficients);
  std::vector<double> v;
  for (std::size_t k = 0; k < s.coefficients.size(); ++k)
    v.push_back(f(s.coefficients[k]) / (in_si ? scale[k] : 1.0));
  return v;
}

// A covariance in the fit's units, in SI: C_ij / (s_i s_j).
Eigen::MatrixXd covariance_in_si(const Statement& s, const Eigen::MatrixXd& c) {
  const std::vector<double> scale = display_scales(s.coefficients);
  Eigen::MatrixXd out = c;
  for (Eigen::Index i = 0; i < out.rows(); ++i)
    for (Eigen::Index j = 0; j < out.cols(); ++j) out(i, j) /= scale[std::size_t(i)] * scale[std::size_t(j)];
  return out;
}

// The SI → display factor of the output (the unit of the modelled outputs and of the residuals): every
// coefficient is in the output unit per gⁿ, and a g-level is 1 in SI, so the first coefficient's scale is it.
double output_scale(const Statement& s) {
  return s.coefficients.empty() ? 1.0 : display_scale_of(s.coefficients.front().input.unit);
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
          "each coefficient's display unit, the unit the statement is written in (to_json(), str()) [—]")
      .def_property_readonly(
          "display_scale", [](const Statement& s) { return display_scales(s.coefficients); },
          "SI → display unit factor per coefficient: value × display_scale is the figure in `units` [display "
          "unit per SI]")
      .def_property_readonly(
          "values", [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.corrected; }); },
          "the corrected estimates K̂ + b [coefficient SI]")
      .def_property_readonly(
          "standard_uncertainties",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.combined; }); },
          "u_c of each coefficient [coefficient SI]")
      .def_property_readonly(
          "effective_dof",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.effective_dof; }, false); },
          "nu_eff of each coefficient (inf: known exactly) [—]")
      .def_property_readonly(
          "coverage_factors",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.coverage_factor; }, false); },
          "k of each coefficient [—]")
      .def_property_readonly(
          "expanded_uncertainties",
          [](const Statement& s) { return per_coefficient(s, [](auto& c) { return c.expanded; }); },
          "U = k u_c of each coefficient; with the Monte Carlo's interval half its width [coefficient SI]")
      .def_property_readonly(
          "intervals",
          [](const Statement& s) {
            const std::vector<double> scale = display_scales(s.coefficients);
            std::vector<std::pair<double, double>> v;
            for (std::size_t k = 0; k < s.coefficients.size(); ++k)
              v.emplace_back(s.coefficients[k].low / scale[k], s.coefficients[k].high / scale[k]);
            return v;
          },
          "the stated coverage interval (low, high) of each coefficient [coefficient SI]")
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
  const std::vector<double> scale = display_scales(s.coefficients);
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
      effect[py::str(s.coefficients[k].input.coefficient)] = in.effect[k] / scale[k];
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
    "measurement's u; else its tolerance), basis (in words), effect (per coefficient, c u signed, in SI), group "
    "(its "
    "tolerance's correlation group, '' for none) [coefficient SI]";

}  // namespace

void bind_statement(py::module_& m) {
  py::class_<Statement> c(m, "Statement",
                        "The calibration statement (JCGM 100 §7): per coefficient the corrected estimate, u_c, "
                        "nu_eff, k, U and the interval, in SI (output SI per g^n) as every result, with `units` "
                        "(the fit's: the coefficients' output unit per g^n, in which the statement is written) "
                        "and `display_scale` beside them; the combined covariance. str() is the command line's "
                        "text; to_json() and to_csv() are the files of `--statement-out`, in `units`.");
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
  c.def_property_readonly(
       "covariance", [](const Statement& s) { return covariance_in_si(s, s.covariance); },
       "combined covariance of the corrected estimates, Type A + Type B [coefficient SI_i × coefficient SI_j]")
      .def_property_readonly(
          "covariance_a", [](const Statement& s) { return covariance_in_si(s, s.covariance_a); },
          "the fit's covariance (Type A) [coefficient SI_i × coefficient SI_j]")
      .def_property_readonly(
          "covariance_b", [](const Statement& s) { return covariance_in_si(s, s.covariance_b); },
          "the tolerances' covariance (Type B) [coefficient SI_i × coefficient SI_j]")
      .def_readonly("correlation", &Statement::correlation, "correlation of the corrected estimates [—]")
      .def_property_readonly(
          "outputs",
          [](const Statement& s) {
            const std::vector<double> scale = display_scales(s.outputs);
            py::list out;
            for (std::size_t r = 0; r < s.outputs.size(); ++r) {
              const CoefficientStatement& o = s.outputs[r];
              py::dict d;
              d["run"] = o.input.coefficient;
              d["g_level"] = s.g_levels[r];
              d["unit"] = o.input.unit;
              d["display_scale"] = scale[r];
              d["value"] = o.corrected / scale[r];
              d["standard_uncertainty"] = o.combined / scale[r];
              d["effective_dof"] = o.effective_dof;
              d["coverage_factor"] = o.coverage_factor;
              d["expanded_uncertainty"] = o.expanded / scale[r];
              d["interval"] = py::make_tuple(o.low / scale[r], o.high / scale[r]);
              d["interval_method"] = std::string(kIntervalMethodNames[std::size_t(o.method)]);
              out.append(d);
            }
            return out;
          },
          "the modelled output of each run, ŷ = hᵀ(K̂ + b) with u from the covariance: per run a dict of run, "
          "g_level [g] (nan: no run of the plan), unit (display), display_scale, value, standard_uncertainty, "
          "effective_dof, coverage_factor, expanded_uncertainty, interval (low, high), interval_method [output "
          "SI]")
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
            d["excess_variance"] = s.type_a.excess_variance / (output_scale(s) * output_scale(s));
            return d;
          },
          "the residuals tested against the noise and the inputs' run-to-run effects: statistic S, expected, "
          "p_value, dof, excess (charged), excess_variance [output SI²] (meaningful with a noise model)");
}

}  // namespace ccal::python

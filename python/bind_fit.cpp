// The identification of observations from Python: the Fit and Observability results, observability(),
// identify() and the general least-squares fit().
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/observability.hpp"
#include "ccal/reduction/observe.hpp"

namespace ccal::python {

namespace {

// The results of an identification: Fit, TermObservability and Observability.
void bind_fit_and_observability_results(py::module_& m) {
  py::class_<FitResult>(m, "Fit", "A least-squares identification with its diagnostics.")
      .def_readonly("names", &FitResult::names, "the fitted terms' ids [—]")
      .def_readonly("value", &FitResult::value, "the estimates [unit of y per unit of the column]")
      .def_readonly("std_error", &FitResult::std_error,
                    "their standard errors [unit of y per unit of the column]")
      .def_readonly("covariance", &FitResult::covariance,
                    "covariance of the estimates [products of their units]")
      .def_readonly("correlation", &FitResult::correlation, "correlation of the estimates [—]")
      .def_readonly("residuals", &FitResult::residuals, "y − fit per row [unit of y]")
      .def_readonly("residual_std", &FitResult::residual_std,
                    "√(RSS/dof) (weighted: √(χ²/dof)) [unit of y; weighted: —]")
      .def_readonly("dof", &FitResult::dof, "rows − free terms [—]")
      .def_readonly("chi2", &FitResult::chi2, "Σ r² (weighted: Σ r²/σ²) [unit of y squared; weighted: —]")
      .def_readonly("chi2_per_dof", &FitResult::chi2_per_dof, "chi2 / dof [unit of y squared; weighted: —]")
      .def_readonly("condition_number", &FitResult::condition_number, "of the column-scaled design [—]")
      .def_readonly("rank", &FitResult::rank, "numerical rank of the design [—]")
      .def_readonly("warnings", &FitResult::warnings, "e.g. no degrees of freedom, nearly aliased terms [—]");

  py::class_<TermObservability>(m, "TermObservability",
                                "How well the plan sees one free term (docs/model.md §14; SI).")
      .def_readonly("term", &TermObservability::term, "the free term's id [—]")
      .def_property_readonly(
          "status", [](const TermObservability& t) { return std::string(term_status_name(t.status)); },
          "'ok', 'weak' or 'unobservable' [—]")
      .def_readonly("sensitivity", &TermObservability::sensitivity,
                    "change of the run means (RSS over runs) per unit of the coefficient [output SI per "
                    "coefficient SI]")
      .def_readonly("natural_norm", &TermObservability::natural_norm,
                    "RSS size of its regressor before averaging [gⁿ]")
      .def_readonly("fraction", &TermObservability::fraction,
                    "the part of the regressor only this term explains, 0…1 [—]")
      .def_readonly("standard_error", &TermObservability::standard_error,
                    "predicted standard error from the run resolution [coefficient SI]")
      .def_readonly("min_detectable", &TermObservability::min_detectable,
                    "detection_factor × standard_error [coefficient SI]")
      .def_readonly("aliased_with", &TermObservability::aliased_with, "the terms it cannot be told from [—]")
      .def_readonly("reason", &TermObservability::reason, "why it is weak or unobservable ('' if ok) [—]")
      .def_readonly("fix", &TermObservability::fix, "what would make it observable [—]")
      .def("__repr__", [](const TermObservability& t) {
        return "<ccal.TermObservability " + t.term + " " + std::string(term_status_name(t.status)) + ">";
      });

  py::class_<ObservabilityResult>(m, "Observability", "The observability of every free term (SI).")
      .def_readonly("terms", &ObservabilityResult::terms, "per free term, list of TermObservability [—]")
      .def_readonly("resolution", &ObservabilityResult::resolution, "σ of each run mean [output SI]")
      .def_readonly("detection_factor", &ObservabilityResult::detection_factor,
                    "minimum detectable change / standard error [—]")
      .def_readonly("whole_revolutions", &ObservabilityResult::whole_revolutions,
                    "every run counter-rotating over whole revolutions [—]");
}

// The observability of the configuration's free terms in its planned runs, `reference` (SI per free term)
// compared with the detection limits if given.
ObservabilityResult plan_observability(const Observations<double>& obs, const Config& cfg,
                                       const std::optional<Eigen::VectorXd>& reference) {
  const Experiment ex = cfg.experiment();
  if (std::size_t(obs.output.size()) != ex.plan.runs.size())
    throw InputError("observations: " + std::to_string(obs.output.size()) +
                     " runs, the configuration plans " + std::to_string(ex.plan.runs.size()));
  std::vector<double> rates;
  for (const Run& run : ex.plan.runs) rates.push_back(nominal_rate(run, ex.geometry, ex.site));
  ObservabilityProblem p = observability_problem(obs, cfg.identification, ex.instrument, ex.plan.runs, rates);
  if (reference) p.reference = *reference;
  return assess_observability(p);
}

// The identification functions: observability(), identify() and the general least-squares fit().
void bind_identification(py::module_& m) {
  m.def(
      "observability",
      [](const Observations<double>& obs, const Config& cfg, std::optional<Eigen::VectorXd> reference) {
        return plan_observability(obs, cfg, reference);
      },
      py::arg("observations"), py::arg("config"), py::arg("reference") = py::none(),
      "Per free term: sensitivity, resolution, minimum detectable change and status (docs/model.md §14) of "
      "observations of the configuration's planned runs; reference: SI values to compare the limits with.");

  m.def(
      "identify",
      [](const Observations<double>& obs, const Config& cfg) {
        const FitResult r = fit(fit_problem(obs, cfg.identification));
        // A term the plan cannot see is refused rather than fitted from round-off (as `ccal simulate`).
        if (obs.output.size() == Eigen::Index(cfg.plan.runs.size())) {
          const ObservabilityResult o = plan_observability(obs, cfg, r.value);
          if (const TermObservability* t = o.first(TermStatus::unobservable))
            throw IllPosedFit(unobservable_message(*t));
        }
        return r;
      },
      py::arg("observations"), py::arg("config"),
      "Identifies the configuration's free terms from observations (its fixed terms held); raises "
      "IllPosedFit "
      "for a term the plan cannot observe.");

  m.def(
      "fit",
      [](const Eigen::MatrixXd& H, const Eigen::VectorXd& y, const std::vector<std::string>& names,
         std::optional<Eigen::VectorXd> weights, const std::map<std::string, double>& fixed,
         const std::string& method) {
        FitProblem p;
        p.term_names = names;
        p.H = H;
        p.y = y;
        if (weights) p.weights = *weights;
        p.fixed = fixed;
        FitOptions o;
        if (method == "svd")
          o.method = FitMethod::svd;
        else if (method != "qr")
          throw InputError("method: '" + method + "'; accepted: 'qr', 'svd'");
        return fit(p, o);
      },
      py::arg("H"), py::arg("y"), py::arg("names"), py::arg("weights") = py::none(),
      py::arg("fixed") = std::map<std::string, double>{}, py::arg("method") = "qr",
      "Least squares y ≈ H x with named columns: weights 1/σ² per row, fixed columns held at given values.");
}

}  // namespace

// Fit, TermObservability, Observability; observability(), identify() and fit().
void bind_fit(py::module_& m) {
  bind_fit_and_observability_results(m);
  bind_identification(m);
}

}  // namespace ccal::python

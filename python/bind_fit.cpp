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
#include "ccal/model/instrument.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/observability.hpp"
#include "ccal/reduction/observe.hpp"

namespace ccal::python {

namespace {

// An observability as Python gives it (ccal.Observability): SI, with each free term's display unit and SI →
// display factor beside it (the configuration's output unit per gⁿ), as every result (docs/python.md).
struct UnitObservability {
  ObservabilityResult result;
  std::vector<std::string> units;
  std::vector<double> display_scale;
};

// A field of the fit, read on the Fit.
template <class T>
auto fit_field(T FitResult::*field) {
  return [field](const UnitFit& f) { return f.fit.*field; };
}

// The results of an identification: Fit, TermObservability and Observability.
void bind_fit_and_observability_results(py::module_& m) {
  py::class_<UnitFit>(m, "Fit",
                      "A least-squares identification with its diagnostics: in SI where its data's units are "
                      "known (identify(), identify_file() of a table with its output unit), with `units` and "
                      "`display_scale` beside it; a fit() of plain arrays in its data's units (units '', "
                      "display_scale 1).")
      .def_property_readonly("names", fit_field(&FitResult::names), "the fitted terms' ids [—]")
      .def_readonly("units", &UnitFit::units, "each term's display unit ('' for a fit of plain arrays) [—]")
      .def_readonly("display_scale", &UnitFit::display_scale,
                    "SI → display unit factor per term (1 for a fit of plain arrays) [display unit per SI]")
      .def_property_readonly("value", fit_field(&FitResult::value),
                             "the estimates [coefficient SI; plain arrays: unit of y per unit of the column]")
      .def_property_readonly("std_error", fit_field(&FitResult::std_error),
                             "their standard errors [as value]")
      .def_property_readonly("covariance", fit_field(&FitResult::covariance),
                             "covariance of the estimates [products of their units]")
      .def_property_readonly("correlation", fit_field(&FitResult::correlation), "correlation of the estimates [—]")
      .def_property_readonly("residuals", fit_field(&FitResult::residuals), "y − fit per row [output SI; unit of y]")
      .def_property_readonly("residual_std", fit_field(&FitResult::residual_std),
                             "√(RSS/dof) (weighted: √(χ²/dof)) [as residuals; weighted: —]")
      .def_property_readonly("dof", fit_field(&FitResult::dof), "rows − free terms [—]")
      .def_property_readonly("chi2", fit_field(&FitResult::chi2),
                             "Σ r² (weighted: Σ r²/σ²) [residuals' unit squared; weighted: —]")
      .def_property_readonly("chi2_per_dof", fit_field(&FitResult::chi2_per_dof),
                             "chi2 / dof [residuals' unit squared; weighted: —]")
      .def_property_readonly("condition_number", fit_field(&FitResult::condition_number),
                             "of the column-scaled design [—]")
      .def_property_readonly("rank", fit_field(&FitResult::rank), "numerical rank of the design [—]")
      .def_property_readonly("warnings", fit_field(&FitResult::warnings),
                             "e.g. no degrees of freedom, nearly aliased terms [—]");

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

  py::class_<UnitObservability>(m, "Observability",
                                "The observability of every free term (SI; units and display_scale beside it).")
      .def_property_readonly(
          "terms", [](const UnitObservability& o) { return o.result.terms; },
          "per free term, list of TermObservability [—]")
      .def_readonly("units", &UnitObservability::units, "the display unit of each free term, in the order of terms [—]")
      .def_readonly("display_scale", &UnitObservability::display_scale,
                    "SI → display unit factor per free term [display unit per SI]")
      .def_property_readonly(
          "resolution", [](const UnitObservability& o) { return o.result.resolution; },
          "σ of each run mean [output SI]")
      .def_property_readonly(
          "detection_factor", [](const UnitObservability& o) { return o.result.detection_factor; },
          "minimum detectable change / standard error [—]")
      .def_property_readonly(
          "whole_revolutions", [](const UnitObservability& o) { return o.result.whole_revolutions; },
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
        UnitObservability out{plan_observability(obs, cfg, reference), {}, {}};
        for (const TermObservability& t : out.result.terms) {
          out.units.push_back(coefficient_unit(cfg.instrument.output_unit, t.term, cfg.instrument.g_symbol));
          out.display_scale.push_back(display_scale_of(out.units.back()));
        }
        return out;
      },
      py::arg("observations"), py::arg("config"), py::arg("reference") = py::none(),
      "Per free term: sensitivity, resolution, minimum detectable change and status (docs/model.md §14) of "
      "observations of the configuration's planned runs; reference: SI values to compare the limits with.");

  m.def(
      "identify",
      [](const Observations<double>& obs, const Config& cfg) {
        const FitResult r = fit(fit_problem(obs, cfg.identification));
        UnitFit out{r, {}, {}};  // the observations are SI: so is the fit
        for (const std::string& id : r.names) {
          out.units.push_back(coefficient_unit(cfg.instrument.output_unit, id, cfg.instrument.g_symbol));
          out.display_scale.push_back(display_scale_of(out.units.back()));
        }
        // A term the plan cannot see is refused rather than fitted from round-off (as `ccal simulate`).
        if (obs.output.size() == Eigen::Index(cfg.plan.runs.size())) {
          const ObservabilityResult o = plan_observability(obs, cfg, r.value);
          if (const TermObservability* t = o.first(TermStatus::unobservable))
            throw IllPosedFit(unobservable_message(*t));
        }
        return out;
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
        const FitResult r = fit(p, o);
        return UnitFit{r, std::vector<std::string>(r.names.size()), std::vector<double>(r.names.size(), 1.0)};
      },
      py::arg("H"), py::arg("y"), py::arg("names"), py::arg("weights") = py::none(),
      py::arg("fixed") = std::map<std::string, double>{}, py::arg("method") = "qr",
      "Least squares y ≈ H x with named columns: weights 1/σ² per row, fixed columns held at given values.");
}

}  // namespace

UnitFit fit_in_si(const FitResult& fit, const std::vector<std::string>& units, double output_scale, bool weighted) {
  UnitFit out{fit, units, std::vector<double>(units.size(), output_scale)};
  const double s = output_scale, y_squared = weighted ? 1.0 : s * s;  // weighted: chi2 has no unit
  FitResult& f = out.fit;
  f.value /= s;
  f.std_error /= s;
  f.covariance /= s * s;
  f.residuals /= s;
  f.residual_std /= weighted ? 1.0 : s;
  f.chi2 /= y_squared;
  f.chi2_per_dof /= y_squared;
  return out;
}

// Fit, TermObservability, Observability; observability(), identify() and fit().
void bind_fit(py::module_& m) {
  bind_fit_and_observability_results(m);
  bind_identification(m);
}

}  // namespace ccal::python

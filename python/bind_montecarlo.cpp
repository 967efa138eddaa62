// `ccal montecarlo` from Python: the Monte Carlo propagation (JCGM 101) of the tolerances, its results
// (OutputSummary, MonteCarloDetail, MonteCarlo) and monte_carlo().
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "interruptible.hpp"
#include "option_keywords.hpp"

namespace ccal::python {

namespace {

// The results of a Monte Carlo propagation: OutputSummary, MonteCarloDetail and MonteCarlo.
void bind_monte_carlo_results(py::module_& m) {
  py::class_<OutputSummary>(m, "OutputSummary", "One output of a Monte Carlo run (SI).")
      .def_readonly("name", &OutputSummary::name, "the coefficient's id [—]")
      .def_readonly("mean", &OutputSummary::mean, "y, the average of the M trial values [coefficient SI]")
      .def_readonly("std_dev", &OutputSummary::std_dev, "u(y) [coefficient SI]")
      .def_readonly("low_symmetric", &OutputSummary::low_symmetric,
                    "low end of the probabilistically symmetric 100p % interval [coefficient SI]")
      .def_readonly("high_symmetric", &OutputSummary::high_symmetric,
                    "high end of the probabilistically symmetric interval [coefficient SI]")
      .def_readonly("low_shortest", &OutputSummary::low_shortest,
                    "low end of the shortest 100p % interval [coefficient SI]")
      .def_readonly("high_shortest", &OutputSummary::high_shortest,
                    "high end of the shortest interval [coefficient SI]")
      .def_readonly("estimate", &OutputSummary::estimate,
                    "the model at zero draws (the LPU estimate) [coefficient SI]")
      .def_readonly("lpu_std", &OutputSummary::lpu_std, "the budget's u_c [coefficient SI]")
      .def_readonly("lpu_expanded", &OutputSummary::lpu_expanded, "the budget's U_p [coefficient SI]")
      .def_readonly("d_low", &OutputSummary::d_low, "|y − U_p − y_low| (JCGM 101 §8) [coefficient SI]")
      .def_readonly("d_high", &OutputSummary::d_high, "|y + U_p − y_high| (JCGM 101 §8) [coefficient SI]")
      .def_readonly("validation_delta", &OutputSummary::validation_delta,
                    "δ, the numerical tolerance of the validation [coefficient SI]")
      .def_readonly("validated", &OutputSummary::validated,
                    "JCGM 101 §8: the LPU interval agrees (d_low, d_high ≤ δ) [—]")
      .def("__repr__", [](const OutputSummary& s) { return "<ccal.OutputSummary " + s.name + ">"; });

  py::class_<MonteCarloDetail>(m, "MonteCarloDetail", "A Monte Carlo propagation of the tolerances (SI).")
      .def_readonly("trials", &MonteCarloDetail::trials, "M, trials over all stages [—]")
      .def_readonly("stages", &MonteCarloDetail::stages, "number of stages (1 for a fixed M) [—]")
      .def_readonly("converged", &MonteCarloDetail::converged,
                    "the adaptive procedure's criterion was met (always true for a fixed M) [—]")
      .def_readonly("seed", &MonteCarloDetail::seed, "the seed used [—]")
      .def_readonly("threads", &MonteCarloDetail::threads, "the threads used [—]")
      .def_readonly("coverage_probability", &MonteCarloDetail::coverage_probability, "p, the coverage probability [—]")
      .def_readonly("seconds", &MonteCarloDetail::seconds, "wall time [s]")
      .def_readonly("outputs", &MonteCarloDetail::outputs, "per coefficient, list of OutputSummary [—]")
      .def_property_readonly(
          "names",
          [](const MonteCarloDetail& r) {
            std::vector<std::string> names;
            for (const auto& o : r.outputs) names.push_back(o.name);
            return names;
          },
          "the coefficients' ids [—]")
      .def_property_readonly(
          "mean",
          [](const MonteCarloDetail& r) {
            Eigen::VectorXd v(Eigen::Index(r.outputs.size()));
            for (std::size_t k = 0; k < r.outputs.size(); ++k) v[Eigen::Index(k)] = r.outputs[k].mean;
            return v;
          },
          "y per coefficient [coefficient SI]")
      .def_property_readonly(
          "std_dev",
          [](const MonteCarloDetail& r) {
            Eigen::VectorXd v(Eigen::Index(r.outputs.size()));
            for (std::size_t k = 0; k < r.outputs.size(); ++k) v[Eigen::Index(k)] = r.outputs[k].std_dev;
            return v;
          },
          "u(y) per coefficient [coefficient SI]")
      .def_readonly("covariance", &MonteCarloDetail::covariance,
                    "sample covariance of the coefficients [coefficient SI × coefficient SI]")
      .def_readonly("correlation", &MonteCarloDetail::correlation,
                    "sample correlation of the coefficients [—]")
      .def_property_readonly(
          "samples",
          [](const MonteCarloDetail& r) -> const Eigen::MatrixXd& {
            if (r.samples.rows() == 0)
              throw InputError("samples: not kept; accepted: monte_carlo(..., keep_samples=True)");
            return r.samples;
          },
          py::return_value_policy::reference_internal,
          "every trial's outputs, M × n_outputs in trial order; needs keep_samples=True [coefficient SI: "
          "output SI per gⁿ]")
      .def_readonly("notes", &MonteCarloDetail::notes,
                    "what the run did and found, as the CLI prints it [—]");

  bind_verb_result<verbs::MonteCarloResult>(
      m, "MonteCarlo",
      "`ccal montecarlo`: its MonteCarloDetail's fields are readable on "
      "it; str() is the CLI's text, to_json() its JSON.",
      "monte_carlo")
      .def_readonly("config", &verbs::MonteCarloResult::config)
      .def_readonly("budget", &verbs::MonteCarloResult::budget,
                    "the LPU budget that the Monte Carlo validates [BudgetDetail]")
      .def_readonly("monte_carlo", &verbs::MonteCarloResult::monte_carlo,
                    "the Monte Carlo itself (its fields are readable on the result) [MonteCarloDetail]")
      .def_property_readonly(
          "units", [](const verbs::MonteCarloResult& r) { return r.budget.units; },
          "the display unit of each coefficient, in the order of names [—]")
      .def_property_readonly(
          "display_scale", [](const verbs::MonteCarloResult& r) { return r.budget.display_scale; },
          "SI → display unit factor per coefficient [display unit per SI]");
}

// The Monte Carlo propagation function monte_carlo().
void bind_monte_carlo_function(py::module_& m) {
  m.def(
      "monte_carlo",
      [](const Config& cfg, bool keep_samples, const py::object& progress, const py::kwargs& keywords) {
        auto o = options_from_keywords<verbs::MonteCarloOptions>(keywords, "monte_carlo");
        o.propagation.keep_samples = keep_samples;
        return run_interruptible(progress, [&](ProgressCallback on_progress) {
          o.propagation.on_progress = std::move(on_progress);
          return verbs::monte_carlo(cfg, o);
        });
      },
      py::arg("config"), py::kw_only(), py::arg("keep_samples") = PropagationOptions{}.keep_samples,
      py::arg("progress") = py::none(),
      "Monte Carlo propagation (JCGM 101, `ccal montecarlo`) of the tolerances to the deviations of the "
      "identified coefficients; trials = None: 10⁶, or stages of 10⁴ with digits > 0 (the adaptive procedure); "
      "the same seed gives the same bits for any thread count; keep_samples: every trial's values in "
      "`samples`. The options are the CLI's, with its defaults. progress: None or progress(done, total) called "
      "with the trials done about every 0.1 s; Ctrl-C (or an exception from progress) stops the run within a "
      "fraction of a second and raises KeyboardInterrupt (or that exception).");
  record_keywords<verbs::MonteCarloOptions>(m, "monte_carlo");
}

}  // namespace

// OutputSummary, MonteCarloDetail and MonteCarlo; monte_carlo().
void bind_montecarlo(py::module_& m) {
  bind_monte_carlo_results(m);
  bind_monte_carlo_function(m);
}

}  // namespace ccal::python

// Monte Carlo propagation (JCGM 101) of the tolerances, and the tolerance allocation.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/verbs/allocate.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "interruptible.hpp"

namespace ccal::python {

namespace {

// The results of a Monte Carlo propagation: OutputSummary, MonteCarloDetail and MonteCarlo.
void bind_monte_carlo_results(py::module_& m) {
  py::class_<OutputSummary>(m, "OutputSummary", "One output of a Monte Carlo run (SI).")
      .def_readonly("name", &OutputSummary::name)
      .def_readonly("mean", &OutputSummary::mean)
      .def_readonly("std_dev", &OutputSummary::std_dev)
      .def_readonly("low_symmetric", &OutputSummary::low_symmetric)
      .def_readonly("high_symmetric", &OutputSummary::high_symmetric)
      .def_readonly("low_shortest", &OutputSummary::low_shortest)
      .def_readonly("high_shortest", &OutputSummary::high_shortest)
      .def_readonly("estimate", &OutputSummary::estimate, "the model at zero draws")
      .def_readonly("lpu_std", &OutputSummary::lpu_std)
      .def_readonly("lpu_expanded", &OutputSummary::lpu_expanded)
      .def_readonly("d_low", &OutputSummary::d_low)
      .def_readonly("d_high", &OutputSummary::d_high)
      .def_readonly("validation_delta", &OutputSummary::validation_delta)
      .def_readonly("validated", &OutputSummary::validated, "JCGM 101 §8: the LPU interval agrees")
      .def("__repr__", [](const OutputSummary& s) { return "<ccal.OutputSummary " + s.name + ">"; });

  py::class_<MonteCarloResult>(m, "MonteCarloDetail", "A Monte Carlo propagation of the tolerances (SI).")
      .def_readonly("trials", &MonteCarloResult::trials)
      .def_readonly("stages", &MonteCarloResult::stages)
      .def_readonly("converged", &MonteCarloResult::converged)
      .def_readonly("seed", &MonteCarloResult::seed)
      .def_readonly("threads", &MonteCarloResult::threads)
      .def_readonly("coverage", &MonteCarloResult::coverage)
      .def_readonly("seconds", &MonteCarloResult::seconds)
      .def_readonly("outputs", &MonteCarloResult::outputs)
      .def_property_readonly("names",
                             [](const MonteCarloResult& r) {
                               std::vector<std::string> names;
                               for (const auto& o : r.outputs) names.push_back(o.name);
                               return names;
                             })
      .def_property_readonly("mean",
                             [](const MonteCarloResult& r) {
                               Eigen::VectorXd v(Eigen::Index(r.outputs.size()));
                               for (std::size_t k = 0; k < r.outputs.size(); ++k)
                                 v[Eigen::Index(k)] = r.outputs[k].mean;
                               return v;
                             })
      .def_property_readonly("std_dev",
                             [](const MonteCarloResult& r) {
                               Eigen::VectorXd v(Eigen::Index(r.outputs.size()));
                               for (std::size_t k = 0; k < r.outputs.size(); ++k)
                                 v[Eigen::Index(k)] = r.outputs[k].std_dev;
                               return v;
                             })
      .def_readonly("covariance", &MonteCarloResult::covariance)
      .def_readonly("correlation", &MonteCarloResult::correlation)
      .def_property_readonly(
          "samples",
          [](const MonteCarloResult& r) -> const Eigen::MatrixXd& {
            if (r.samples.rows() == 0)
              throw InputError("samples: not kept; accepted: monte_carlo(..., keep_samples=True)");
            return r.samples;
          },
          py::return_value_policy::reference_internal,
          "every trial's outputs, M × n_outputs in trial order (SI); needs keep_samples=True")
      .def_readonly("notes", &MonteCarloResult::notes);

  bind_verb_result<verbs::MonteCarloResult>(
      m, "MonteCarlo",
      "`ccal montecarlo`: its MonteCarloDetail's fields are readable on "
      "it; str() is the CLI's text, to_json() its JSON.",
      "monte_carlo")
      .def_readonly("config", &verbs::MonteCarloResult::config)
      .def_readonly("budget", &verbs::MonteCarloResult::budget)
      .def_readonly("monte_carlo", &verbs::MonteCarloResult::monte_carlo);
}

// The Monte Carlo propagation function monte_carlo().
void bind_monte_carlo_function(py::module_& m) {
  m.def(
      "monte_carlo",
      [](const Config& cfg, std::optional<std::int64_t> trials, std::uint64_t seed, int threads, int digits,
         double coverage_probability, std::optional<std::string> mode, bool keep_samples,
         const py::object& progress) {
        verbs::MonteCarloOptions o;
        if (mode) o.mode = mode_argument(*mode);
        o.trials = trials;
        o.seed = seed;
        o.threads = threads;
        o.digits = digits;
        o.coverage_probability = coverage_probability;
        o.keep_samples = keep_samples;
        return run_interruptible(progress, [&](ProgressCallback on_progress) {
          o.on_progress = std::move(on_progress);
          return verbs::monte_carlo(cfg, o);
        });
      },
      py::arg("config"), py::arg("trials") = verbs::MonteCarloOptions{}.trials,
      py::arg("seed") = verbs::MonteCarloOptions{}.seed,
      py::arg("threads") = verbs::MonteCarloOptions{}.threads,
      py::arg("digits") = verbs::MonteCarloOptions{}.digits,
      py::arg("coverage_probability") = verbs::MonteCarloOptions{}.coverage_probability,
      py::arg("mode") = py::none(), py::arg("keep_samples") = verbs::MonteCarloOptions{}.keep_samples,
      py::arg("progress") = py::none(),
      "Monte Carlo propagation (JCGM 101, `ccal montecarlo`) of the tolerances to the deviations of the "
      "identified coefficients; trials = None: 10⁶, or stages of 10⁴ with digits > 0 (the adaptive procedure); "
      "the same seed gives the same bits for any thread count; keep_samples: every trial's values in "
      "`samples`. The defaults are the CLI's. progress: None or progress(done, total) called with the "
      "trials done about every 0.1 s; Ctrl-C (or an exception from progress) stops the run within a "
      "fraction of a second and raises KeyboardInterrupt (or that exception).");
}

// The results of a tolerance allocation: AllocatedSource, AllocatedCoefficient, AllocationDetail, Allocation.
void bind_allocation_results(py::module_& m) {
  py::class_<AllocatedSource>(m, "AllocatedSource")
      .def_readonly("id", &AllocatedSource::id)
      .def_readonly("bound", &AllocatedSource::bound, "configured, SI")
      .def_readonly("scale", &AllocatedSource::scale, "λ: allocated / configured")
      .def_readonly("allocated_bound", &AllocatedSource::allocated_bound, "SI")
      .def_readonly("cost", &AllocatedSource::cost)
      .def_readonly("share", &AllocatedSource::share, "per target, at the allocated tolerances")
      .def("__repr__", [](const AllocatedSource& s) { return "<ccal.AllocatedSource " + s.id + ">"; });

  py::class_<AllocatedCoefficient>(m, "AllocatedCoefficient")
      .def_readonly("id", &AllocatedCoefficient::id)
      .def_readonly("unit", &AllocatedCoefficient::unit, "display unit")
      .def_readonly("display_scale", &AllocatedCoefficient::display_scale)
      .def_readonly("has_target", &AllocatedCoefficient::has_target)
      .def_readonly("target", &AllocatedCoefficient::target, "SI")
      .def_readonly("configured_expanded", &AllocatedCoefficient::configured_expanded)
      .def_readonly("allocated_expanded", &AllocatedCoefficient::allocated_expanded)
      .def_readonly("active", &AllocatedCoefficient::active)
      .def_readonly("mc_half_width", &AllocatedCoefficient::mc_half_width)
      .def_property_readonly(
          "verdict", [](const AllocatedCoefficient& c) { return std::string(verdict_name(c.verdict)); });

  py::class_<AllocationResult>(m, "AllocationDetail", "Tolerances allocated to meet the targets (SI).")
      .def_readonly("sources", &AllocationResult::sources, "tightened most first")
      .def_readonly("coefficients", &AllocationResult::coefficients)
      .def_readonly("coverage", &AllocationResult::coverage)
      .def_readonly("coverage_factor", &AllocationResult::coverage_factor)
      .def_readonly("objective", &AllocationResult::objective)
      .def_readonly("converged", &AllocationResult::converged)
      .def_property_readonly("verified", [](const AllocationResult& r) { return r.verification.passed; });

  bind_verb_result<verbs::AllocateResult>(
      m, "Allocation",
      "`ccal allocate`: its AllocationDetail's fields are readable on it; "
      "str() is the CLI's text, to_json() its JSON.",
      "allocation")
      .def_readonly("config", &verbs::AllocateResult::config)
      .def_readonly("allocation", &verbs::AllocateResult::allocation);
}

// The tolerance allocation function allocate().
void bind_allocate_function(py::module_& m) {
  m.def(
      "allocate",
      [](const Config& cfg, const std::map<std::string, std::variant<double, std::string>>& targets,
         double coverage_probability, double max_scale, std::int64_t verify_trials, std::uint64_t seed,
         int threads, std::optional<std::string> mode, const py::object& progress) {
        verbs::AllocateOptions o;
        if (mode) o.mode = mode_argument(*mode);
        for (const auto& [id, value] : targets)
          // A number is in the coefficient's display unit, as on the command line; a string may carry a unit.
          o.targets.push_back(std::holds_alternative<double>(value)
                                  ? fmt::format("{}={:.17g}", id, std::get<double>(value))
                                  : id + "=" + std::get<std::string>(value));
        o.coverage_probability = coverage_probability;
        o.max_scale = max_scale;
        o.verify_trials = verify_trials;
        o.seed = seed;
        o.threads = threads;
        return run_interruptible(progress, [&](ProgressCallback on_progress) {
          o.on_progress = std::move(on_progress);
          return verbs::allocate(cfg, o);
        });
      },
      py::arg("config"), py::arg("targets"), py::arg("coverage_probability") = 0.95,
      py::arg("max_scale") = 10.0, py::arg("verify_trials") = 2000, py::arg("seed") = 1,
      py::arg("threads") = 0, py::arg("mode") = py::none(), py::arg("progress") = py::none(),
      "Largest tolerances for which every target (coefficient id → allowed expanded uncertainty, a number in "
      "the display unit or a string with a unit) holds (`ccal allocate`), verified by Monte Carlo. mode: "
      "'exact' or 'paper' (default: the configuration's). progress: None or progress(done, total) of the "
      "verification's trials; Ctrl-C stops the call and raises KeyboardInterrupt.");
}

}  // namespace

void bind_uncertainty(py::module_& m) {
  bind_monte_carlo_results(m);
  bind_monte_carlo_function(m);
  bind_allocation_results(m);
  bind_allocate_function(m);
}

}  // namespace ccal::python

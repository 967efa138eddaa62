// Monte Carlo propagation (JCGM 101) of the tolerances, and the tolerance allocation.
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "ccal/allocate.hpp"
#include "ccal/budget.hpp"
#include "ccal/errors.hpp"
#include "ccal/montecarlo.hpp"

namespace ccal::python {

namespace {

// The budget (for the LPU validation and the display units) and the calibration model of a configuration,
// an ill-posed identification reported as bad input, as the CLI does.
std::pair<BudgetResult, CalibrationModel> model_of(const Config& cfg, ModelMode mode) {
  if (cfg.tolerances.empty())
    throw InputError(cfg.source + ": [tolerances] is empty; the Monte Carlo needs at least one source");
  BudgetOptions bo;
  bo.mode = mode;
  bo.compare_with_paper = false;
  try {
    return {compute_budget(cfg, bo), calibration_model(cfg, mode)};
  } catch (const IllPosedFit& e) {
    throw InputError(std::string("the test plan cannot identify the configured terms: ") + e.what());
  }
}

}  // namespace

void bind_uncertainty(py::module_& m) {
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

  py::class_<MonteCarloResult>(m, "MonteCarlo", "A Monte Carlo propagation of the tolerances (SI).")
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
      .def_readonly("notes", &MonteCarloResult::notes);

  m.def(
      "monte_carlo",
      [](const Config& cfg, std::uint64_t trials, std::uint64_t seed, int threads, int digits,
         double coverage, std::optional<std::string> mode) {
        const auto [budget, model] = model_of(cfg, mode ? parse_mode(*mode) : cfg.mode);
        MonteCarloOptions o;
        o.trials = trials;
        o.seed = seed;
        o.threads = threads;
        o.significant_digits = digits;
        o.coverage = coverage;
        py::gil_scoped_release release;
        return run_monte_carlo(monte_carlo_sources(cfg), model.n_outputs(), model.output_names(),
                               calibration_trial(model), o, &budget.standard_uncertainty);
      },
      py::arg("config"), py::arg("trials") = 100000, py::arg("seed") = 1, py::arg("threads") = 0,
      py::arg("digits") = 0, py::arg("coverage") = 0.95, py::arg("mode") = py::none(),
      "Monte Carlo propagation (JCGM 101, `ccal montecarlo`) of the tolerances to the deviations of the "
      "identified coefficients; digits > 0: the adaptive procedure; the same seed gives the same bits for "
      "any "
      "thread count.");

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

  py::class_<AllocationResult>(m, "Allocation", "Tolerances allocated to meet the targets (SI).")
      .def_readonly("sources", &AllocationResult::sources, "tightened most first")
      .def_readonly("coefficients", &AllocationResult::coefficients)
      .def_readonly("coverage", &AllocationResult::coverage)
      .def_readonly("coverage_factor", &AllocationResult::coverage_factor)
      .def_readonly("objective", &AllocationResult::objective)
      .def_readonly("converged", &AllocationResult::converged)
      .def_property_readonly("verified", [](const AllocationResult& r) { return r.verification.passed; });

  m.def(
      "allocate",
      [](const Config& cfg, const std::map<std::string, std::variant<double, std::string>>& targets,
         double coverage, double max_scale, std::uint64_t verify_trials, std::uint64_t seed, int threads) {
        BudgetOptions bo;
        bo.compare_with_paper = false;
        const BudgetResult b = compute_budget(cfg, bo);
        std::vector<AllocationTarget> parsed;
        for (const auto& [id, value] : targets) {
          // A number is in the coefficient's display unit, as on the command line; a string may carry a unit.
          const std::string text = std::holds_alternative<double>(value)
                                       ? fmt::format("{}={:.17g}", id, std::get<double>(value))
                                       : id + "=" + std::get<std::string>(value);
          parsed.push_back(parse_allocation_target(text, b.coefficients, b.units, "targets"));
        }
        AllocateOptions o;
        o.coverage = coverage;
        o.max_scale = max_scale;
        o.verify_trials = verify_trials;
        o.seed = seed;
        o.threads = threads;
        py::gil_scoped_release release;
        return allocate_tolerances(cfg, parsed, o);
      },
      py::arg("config"), py::arg("targets"), py::arg("coverage") = 0.95, py::arg("max_scale") = 10.0,
      py::arg("verify_trials") = 2000, py::arg("seed") = 1, py::arg("threads") = 0,
      "Largest tolerances for which every target (coefficient id → allowed expanded uncertainty, a number in "
      "the display unit or a string with a unit) holds (`ccal allocate`), verified by Monte Carlo.");
}

}  // namespace ccal::python

// `ccal allocate` from Python: the tolerance allocation, its results (AllocatedSource,
// AllocatedCoefficient, AllocationDetail, Allocation) and allocate().
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/verbs/allocate.hpp"
#include "interruptible.hpp"

namespace ccal::python {

namespace {

// The results of a tolerance allocation: AllocatedSource, AllocatedCoefficient, AllocationDetail, Allocation.
void bind_allocation_results(py::module_& m) {
  py::class_<AllocatedSource>(m, "AllocatedSource")
      .def_readonly("id", &AllocatedSource::id, "the error parameter's id [—]")
      .def_readonly("bound", &AllocatedSource::bound, "the configured bound [SI unit of the parameter]")
      .def_readonly("scale", &AllocatedSource::scale, "λ = allocated / configured [—]")
      .def_readonly("allocated_bound", &AllocatedSource::allocated_bound,
                    "the allocated bound [SI unit of the parameter]")
      .def_readonly("cost", &AllocatedSource::cost, "relative cost weight [—]")
      .def_readonly("floor", &AllocatedSource::floor,
                    "the machine's best achievable bound, 0: none [SI unit of the parameter]")
      .def_readonly("at_floor", &AllocatedSource::at_floor, "the allocation tightened it to its floor [—]")
      .def_readonly("share", &AllocatedSource::share,
                    "share of each target coefficient's variance at the allocated tolerances [—]")
      .def("__repr__", [](const AllocatedSource& s) { return "<ccal.AllocatedSource " + s.id + ">"; });

  py::class_<AllocatedCoefficient>(m, "AllocatedCoefficient")
      .def_readonly("id", &AllocatedCoefficient::id, "the coefficient's id [—]")
      .def_readonly("unit", &AllocatedCoefficient::unit, "its display unit [—]")
      .def_readonly("display_scale", &AllocatedCoefficient::display_scale,
                    "SI → display unit factor [display unit per SI]")
      .def_readonly("has_target", &AllocatedCoefficient::has_target, "a target was given for it [—]")
      .def_readonly("target", &AllocatedCoefficient::target,
                    "the target expanded uncertainty [coefficient SI]")
      .def_readonly("configured_expanded", &AllocatedCoefficient::configured_expanded,
                    "U at the configured tolerances [coefficient SI]")
      .def_readonly("allocated_expanded", &AllocatedCoefficient::allocated_expanded,
                    "U at the allocated tolerances [coefficient SI]")
      .def_readonly("active", &AllocatedCoefficient::active, "its target limits the allocation [—]")
      .def_readonly("held", &AllocatedCoefficient::held,
                    "no target, held at its configured expanded uncertainty [—]")
      .def_readonly("grew", &AllocatedCoefficient::grew,
                    "no target, and the allocation raised its expanded uncertainty [—]")
      .def_readonly("mc_half_width", &AllocatedCoefficient::mc_half_width,
                    "the Monte Carlo check's half-width of the interval [coefficient SI]")
      .def_property_readonly(
          "verdict", [](const AllocatedCoefficient& c) { return std::string(verdict_name(c.verdict)); },
          "the Monte Carlo check's verdict, e.g. 'pass within sampling' [—]");

  py::class_<AllocationDetail>(m, "AllocationDetail", "Tolerances allocated to meet the targets (SI).")
      .def_readonly("sources", &AllocationDetail::sources,
                    "the sources, tightened most first, list of AllocatedSource [—]")
      .def_readonly("coefficients", &AllocationDetail::coefficients,
                    "per coefficient, list of AllocatedCoefficient [—]")
      .def_readonly("coverage_probability", &AllocationDetail::coverage_probability, "p [—]")
      .def_readonly("coverage_factor", &AllocationDetail::coverage_factor, "k_p [—]")
      .def_readonly("objective", &AllocationDetail::objective, "Σ cost/λ of the allocation [cost units]")
      .def_readonly("converged", &AllocationDetail::converged, "the solver converged [—]")
      .def_property_readonly(
          "verified", [](const AllocationDetail& r) { return r.verification.passed; },
          "the Monte Carlo check passed [—]");

  bind_verb_result<verbs::AllocateResult>(
      m, "Allocation",
      "`ccal allocate`: its AllocationDetail's fields are readable on it; "
      "str() is the CLI's text, to_json() its JSON.",
      "allocation")
      .def_readonly("config", &verbs::AllocateResult::config)
      .def_readonly("allocation", &verbs::AllocateResult::allocation,
                    "the allocation itself (its fields are readable on the result) [AllocationDetail]")
      .def_property_readonly(
          "units",
          [](const verbs::AllocateResult& r) {
            std::vector<std::string> v;
            for (const AllocatedCoefficient& c : r.allocation.coefficients) v.push_back(c.unit);
            return v;
          },
          "the display unit of each coefficient, in the order of coefficients [—]")
      .def_property_readonly(
          "display_scale",
          [](const verbs::AllocateResult& r) {
            std::vector<double> v;
            for (const AllocatedCoefficient& c : r.allocation.coefficients) v.push_back(c.display_scale);
            return v;
          },
          "SI → display unit factor per coefficient [display unit per SI]");
}

// The tolerance allocation function allocate().
void bind_allocate_function(py::module_& m) {
  m.def(
      "allocate",
      [](const Config& cfg, const TargetMap& targets, const py::object& progress, const py::kwargs& keywords) {
        auto o = options_from_keywords<AllocateOptions>(keywords, "allocate", {}, {"targets"});
        o.targets = target_texts(targets);
        return run_interruptible(progress, [&](ProgressCallback on_progress) {
          o.on_progress = std::move(on_progress);
          return verbs::allocate(cfg, o);
        });
      },
      py::arg("config"), py::arg("targets"), py::kw_only(), py::arg("progress") = py::none(),
      "Largest tolerances for which every target (coefficient id → allowed expanded uncertainty, a number in "
      "the display unit or a string with a unit) holds (`ccal allocate`), verified by Monte Carlo. progress: "
      "None or progress(done, total) of the verification's trials; Ctrl-C stops the call and raises "
      "KeyboardInterrupt.");
  record_keywords<AllocateOptions>(m, "allocate", {"targets"});
}

}  // namespace

// AllocatedSource, AllocatedCoefficient, AllocationDetail and Allocation; allocate().
void bind_allocate(py::module_& m) {
  bind_allocation_results(m);
  bind_allocate_function(m);
}

}  // namespace ccal::python

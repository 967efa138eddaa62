// Configurations: read from TOML (docs/config.md) or the bundled paper example, inspected from Python.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "ccal/core/options.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/setup/config.hpp"

namespace ccal::python {

namespace {

// A configuration's parts: the runs of its plan and its tolerances.
void bind_runs_and_tolerances(py::module_& m) {
  py::class_<Run>(m, "Run", "One run of the test plan.")
      .def_readonly("name", &Run::name, "the run's name [—]")
      .def_readonly("g_level", &Run::g_level, "A = Ω² R0 / g, the centripetal level [g]")
      .def_readonly("duration", &Run::duration, "T, the run's duration [s]")
      .def_property_readonly(
          "mode", [](const Run& r) { return std::string(platform_mode_name(r.mode)); },
          "the platform: 'counter_rotating' or 'fixed' [—]")
      .def_readonly("initial_phase", &Run::initial_phase, "φ0 = γ(0) if given, else None [rad]")
      .def_readonly("terminal_phase", &Run::terminal_phase, "ψ = γ(T) if given, else None [rad]")
      .def_readonly("arm_azimuth", &Run::arm_azimuth,
                    "θ1(0), the arm's azimuth from East, counter-clockwise [rad]")
      .def_property_readonly(
          "mounting", [](const Run& r) { return std::string(mounting_name(r.mounting)); },
          "'ia_horizontal', 'ia_reversed', 'pa_vertical' or 'ia_vertical' [—]")
      .def("__repr__", [](const Run& r) { return "<ccal.Run " + r.name + ">"; });

  py::class_<Tolerance>(m, "Tolerance", "The tolerance of one error source (SI).")
      .def_readonly("id", &Tolerance::id, "the error parameter's id, e.g. 'dthz5' [—]")
      .def_readonly("parameter", &Tolerance::parameter, "its index in Config.error_ids [—]")
      .def_readonly("bound", &Tolerance::bound,
                    "σ (normal) or half-width/amplitude, in the parameter's SI unit (Config.error_units) "
                    "[rad, m, rad/s, m/(rad/s)² or 1]")
      .def_property_readonly(
          "distribution", [](const Tolerance& t) { return std::string(distribution_name(t.distribution)); },
          "'normal', 'uniform', 'triangular' or 'arcsine' [—]")
      .def_property_readonly(
          "standard_uncertainty",
          [](const Tolerance& t) { return standard_uncertainty(t.bound, t.distribution); },
          "u = bound / (1, √3, √6, √2 by distribution), the parameter's SI unit [rad, m, rad/s, m/(rad/s)² "
          "or 1]")
      .def_readonly("group", &Tolerance::group, "sources of one non-empty group are fully correlated [—]")
      .def_readonly("cost", &Tolerance::cost, "relative cost weight of tightening it, for allocate [—]")
      .def("__repr__", [](const Tolerance& t) { return "<ccal.Tolerance " + t.id + ">"; });
}

}  // namespace

void bind_config(py::module_& m) {
  bind_runs_and_tolerances(m);

  py::class_<Config>(m, "Config", py::dynamic_attr(),
                     "A centrifuge, site, instrument, test plan, tolerances and identification.")
      .def_readonly("source", &Config::source, "the file name, or the name given to parse_config [—]")
      .def_readonly("text_sha256", &Config::text_sha256,
                    "SHA-256 of the text it was read from (a job's own file); empty once changed by a with_… "
                    "method [—]")
      .def_readonly("numbers_sha256", &Config::numbers_sha256,
                    "SHA-256 of every table but [certificate] and [design], job and set-up merged, in canonical "
                    "form: the fingerprint observations files are bound to; empty once changed [—]")
      .def_readonly("setup_sha256", &Config::setup_sha256,
                    "SHA-256 of the machine's and lab's tables alone ([site], [centrifuge], [errors], "
                    "[tolerances], [[correlations]], [[inputs]]); empty once changed [—]")
      .def_readonly("setup_source", &Config::setup_source,
                    "the set-up file a job names (setup = \"…\"), as read; \"\" for a file naming none [—]")
      .def_property_readonly(
          "runs", [](const Config& c) { return c.plan.runs; }, "the test plan's runs, list of Run [—]")
      .def_readonly("tolerances", &Config::tolerances,
                    "the tolerances, list of Tolerance in catalogue order [—]")
      .def_property_readonly(
          "error_ids", [](const Config& c) { return c.centrifuge.layout.parameter_ids(); },
          "ids of the error parameters, in the order of `errors` [—]")
      .def_property_readonly(
          "errors", [](const Config& c) { return Eigen::VectorXd(c.centrifuge.errors); },
          "the configured (actual) error values, per error_ids [SI: error_units]")
      .def_property_readonly(
          "error_units",
          [](const Config& c) {
            std::vector<std::string> units;
            for (int i = 0; i < c.centrifuge.layout.size(); ++i)
              units.emplace_back(unit_symbol(c.centrifuge.layout.parameter_unit(i)));
            return units;
          },
          "the SI unit of each error parameter [—]")
      .def_property_readonly(
          "free_terms", [](const Config& c) { return c.identification.free_terms; },
          "the identified terms, e.g. ['K0', 'K2', 'K3'] [—]")
      .def_property_readonly(
          "fixed_terms", [](const Config& c) { return c.identification.fixed_terms; },
          "term id → value held fixed [coefficient SI: output SI per gⁿ]")
      .def_property_readonly(
          "instrument_terms", [](const Config& c) { return c.instrument.term_ids; },
          "the instrument's term ids [—]")
      .def_property_readonly(
          "instrument_coefficients",
          [](const Config& c) { return Eigen::VectorXd(c.instrument.coefficients); },
          "the simulated instrument's true coefficients, per instrument_terms [coefficient SI: output SI per "
          "gⁿ]")
      .def_property_readonly(
          "output_unit", [](const Config& c) { return c.instrument.output_unit; },
          "the instrument's output unit as written, e.g. 'deg/s' [—]")
      .def_property_readonly(
          "mode", [](const Config& c) { return std::string(mode_name(c.mode)); },
          "reduction of a run: 'exact' or 'paper' [—]")
      .def_property_readonly(
          "g", [](const Config& c) { return c.site.g; }, "local gravity [m/s²]")
      .def_property_readonly(
          "latitude", [](const Config& c) { return c.site.latitude; }, "the site's latitude [rad]")
      .def_readonly("instrument_id", &Config::instrument_id,
                    "the instrument's id in a test of several ([[instruments]] id); '' for one [instrument] [—]")
      .def_readonly("instruments", &Config::instruments,
                    "a test of several instruments ([[instruments]]): each one's configuration, in the file's "
                    "order (this one is then the first's); [] for one [instrument] [list of Config]")
      .def(
          "instrument",
          [](const Config& c, const std::string& id) {
            if (id.empty()) throw OptionError("instrument", "", std::string(kEmptyInstrumentId));
            return select_instrument(c, id);
          },
          py::arg("id"),
          "One instrument of a test of several, by its id: its configuration as a test of that one instrument "
          "(`--instrument ID` of the command line); InputError naming the ids for another id.")
      .def("__repr__", [](const Config& c) {
        return "<ccal.Config " + c.source + (c.instrument_id.empty() ? "" : " instrument " + c.instrument_id) + ">";
      });

  m.def(
      "bundled_example_text", [] { return std::string(bundled_example_text()); },
      "The TOML text of the bundled example, a documented starting point for a configuration.");
  m.def("bundled_example", &bundled_example,
        "The bundled configuration of the paper's experiment (examples/wang_ren_2014.toml).");
  m.def(
      "load_config",
      [](const py::object& path) {
        return load_config(path_argument(path, "load_config", "path", "the path of a TOML file (str or os.PathLike)"));
      },
      py::arg("path"),
      "Reads and checks a TOML configuration; InputError with file:line:column on bad input.");
  m.def(
      "parse_config",
      [](const std::string& text, const std::string& source) { return parse_config(text, source); },
      py::arg("text"), py::arg("source") = "<string>", "Parses configuration text.");
}

}  // namespace ccal::python

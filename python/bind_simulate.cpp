// `ccal simulate` from Python: simulated observations (the Observations and Simulation results),
// simulate() and observe().
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/core/units.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/verbs/simulate.hpp"

namespace ccal::python {

namespace {

// The log_layout argument of run_logs and logs_manifest: None (ccal's own) or a layout file's path.
LogLayout layout_argument(const py::object& log_layout, std::string_view function) {
  if (log_layout.is_none()) return {};
  return read_log_layout(path_argument(log_layout, function, "log_layout", kLayoutArgument));
}

}  // namespace


namespace {

// The truth file of a truth= keyword (a path: str or os.PathLike), read against the configuration; None: none.
std::optional<SimulationTruth> truth_of(const Config& cfg, const py::object& truth) {
  if (truth.is_none()) return std::nullopt;
  return load_truth(path_argument(truth, "simulate", "truth", "the path of a truth file (str or os.PathLike), or None"),
                    cfg);
}

// The run means: Observations.
void bind_observations(py::module_& m) {
  py::class_<Observations<double>>(m, "Observations", "Run means: one row per run (SI, inputs in g).")
      .def_readonly("runs", &Observations<double>::runs, "the runs' names [—]")
      .def_readonly("columns", &Observations<double>::columns, "term ids of the regressor columns [—]")
      .def_readonly("regressors", &Observations<double>::regressors,
                    "runs × columns, the model's run means of each term [gⁿ, or rad/s for K_w]")
      .def_readonly("output", &Observations<double>::output,
                    "the instrument's mean output per run [output SI]")
      .def_readonly("known_rate", &Observations<double>::known_rate,
                    "the model's ⟨s_ω ω_IA⟩ per run [output SI]")
      .def_readonly("input", &Observations<double>::input, "the model's ⟨a_i⟩ per run [g]");
}

}  // namespace

// Simulated observations: the Observations and Simulation results, simulate() and observe().
namespace {

// A duration as every duration is taken: a number in s, or text with its unit ("50 ms"), read by the library's
// parser.
std::optional<double> log_step(const std::optional<std::variant<double, std::string>>& step) {
  if (!step) return std::nullopt;
  if (const double* seconds = std::get_if<double>(&*step)) return *seconds;
  return parse_as(std::get<std::string>(*step), kind::time, "run logs: step", true);
}

}  // namespace

void bind_simulate(py::module_& m) {
  bind_observations(m);

  bind_verb_result<verbs::SimulateResult>(m, "Simulation",
                                          "`ccal simulate`: run means of the plan and their identification; "
                                          "str() is the CLI's text, to_json() its JSON, to_csv() the "
                                          "observations file.",
                                          "observations")
      .def_readonly("config", &verbs::SimulateResult::config)
      .def_readonly("observations", &verbs::SimulateResult::observations,
                    "the simulated run means (their fields are readable on the result) [Observations]")
      .def_property_readonly(
          "coefficients",
          // the fit is of the observations file, in the output unit: × its SI size gives output SI per gⁿ
          [](const verbs::SimulateResult& r) {
            return Eigen::VectorXd(r.identification.fit.value * r.output_unit_si);
          },
          "the identified free terms, in the order of names [coefficient SI]")
      .def_property_readonly(
          "names", [](const verbs::SimulateResult& r) { return r.identification.fit.names; },
          "the identified terms' ids [—]")
      .def_property_readonly(
          "units", [](const verbs::SimulateResult& r) { return r.identification.units; },
          "the display unit of each identified term, in the order of names [—]")
      .def_property_readonly(
          "display_scale",
          [](const verbs::SimulateResult& r) {
            return std::vector<double>(r.identification.units.size(), 1.0 / r.output_unit_si);
          },
          "SI → display unit factor per identified term [display unit per SI]")
      .def(
          "to_csv", [](const verbs::SimulateResult& r) { return render::csv(r); },
          "The observations file (the CLI's --format csv, the input of `ccal identify`).")
      .def(
          "run_logs",
          [](const verbs::SimulateResult& r, const std::optional<std::variant<double, std::string>>& step,
             const py::object& log_layout) {
            std::vector<RunLogFile> files =
                verbs::simulation_logs(r, layout_argument(log_layout, "run_logs"), log_step(step));
            files.pop_back();  // the manifest: logs_manifest()
            std::vector<std::pair<std::string, std::string>> out;
            for (RunLogFile& log : files) out.emplace_back(std::move(log.name), std::move(log.text));
            return out;
          },
          py::arg("step") = py::none(), py::arg("log_layout") = py::none(),
          "The runs' logs as `ccal simulate --logs-out` writes them: (file name, CSV text) per run, in plan "
          "order; step: sampling interval, a number in s or text with its unit (\"50 ms\") (default 0.1 s, or an eighth of a revolution if shorter); "
          "log_layout: the path of a layout file (a manifest's [format], [columns] and [instruments] tables, as "
          "`--log-layout`); for a test of several instruments each file holds every instrument's output column.")
      .def(
          "logs_manifest",
          [](const verbs::SimulateResult& r, const py::object& log_layout) {
            return verbs::simulation_logs(r, layout_argument(log_layout, "logs_manifest")).back().text;
          },
          py::arg("log_layout") = py::none(),
          "The manifest.toml of the logs of run_logs() (in that layout), as `ccal simulate --logs-out` writes it "
          "beside them.")
      .def_readonly("instruments", &verbs::SimulateResult::instruments,
                    "a test of several instruments: each one's Simulation, in the configuration's order (the "
                    "fields above are the first's); [] for one instrument [list of Simulation]");

  m.def(
      "simulate",
      [](const Config& cfg, const py::object& truth, const py::kwargs& keywords) {
        auto o = options_from_keywords<verbs::SimulateOptions>(keywords, "simulate", {}, {}, {"config", "truth"});
        o.truth = truth_of(cfg, truth);
        py::gil_scoped_release release;
        return verbs::simulate(cfg, o);
      },
      py::arg("config"), py::kw_only(), py::arg("truth") = py::none(),
      "`ccal simulate`: run means of the test plan with the machine's errors (truth: a truth file's path, "
      "whose [errors] the machine has; else the configured [errors]) and instrument noise, and the "
      "identification of the configured terms from them, as the CLI gives them.");
  record_keywords<verbs::SimulateOptions>(m, "simulate");

  m.def(
      "observe",
      [](const Config& cfg, const py::object& truth, const py::kwargs& keywords) {
        const auto o = options_from_keywords<verbs::SimulateOptions>(keywords, "observe", {}, {}, {"config", "truth"});
        const ModelMode model_mode = o.mode ? *o.mode : cfg.mode;
        const Experiment ex = cfg.experiment();
        const std::optional<SimulationTruth> machine = truth_of(cfg, truth);
        const Eigen::VectorXd& known = cfg.centrifuge.errors;
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
        Observations<double> obs = observe<double>(ex, machine ? machine->errors : known,
                                                   cfg.identification.compensate ? known : zero,
                                                   cfg.identification, model_mode);
        add_output_noise(obs, ex, o.seed);
        return obs;
      },
      py::arg("config"), py::kw_only(), py::arg("truth") = py::none(),
      "Simulated run means of the test plan with the machine's errors (truth as in simulate()) and instrument "
      "noise (`ccal simulate`), the options of simulate().");
  record_keywords<verbs::SimulateOptions>(m, "observe");
}

}  // namespace ccal::python

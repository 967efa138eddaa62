// `ccal reduce` from Python: recorded run logs reduced to observations of the runs as measured (the
// LogReduction and Reduction results), reduce() and reduce_logs().
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "ccal/verbs/reduce.hpp"

namespace ccal::python {

std::string path_argument(const py::object& value, std::string_view function, std::string_view name,
                          std::string_view accepted) {
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || py::hasattr(value, "__fspath__")) {
    std::string path = py::module_::import("os").attr("fspath")(value).cast<std::string>();
    if (path.empty())  // the message would start with the file's name: none
      throw InputError(fmt::format("{}(): {}: the path is empty; accepted: {}", function, name, accepted));
    return path;
  }
  throw py::type_error(fmt::format("{}(): {}: expected {}, got {}", function, name, accepted,
                                   py::str(value.get_type().attr("__name__")).cast<std::string>()));
}


namespace {



using LogMap = std::map<std::variant<int, std::string>, std::string>;

// The logs as the verb takes them: each run by its name (a 0-based index or a name, as run= elsewhere).
std::vector<verbs::LogFile> log_files(const Config& cfg, const LogMap& logs) {
  std::vector<verbs::LogFile> files;
  for (const auto& [run, path] : logs) files.push_back({cfg.plan.runs[run_index(cfg, run, "logs")].name, path});
  return files;
}

// A path argument (str or os.PathLike) as text; a TypeError naming the function's argument for anything else
// (os.fspath's own words name neither).

// The logs argument: a dict of run → file, or a folder with its manifest (str or os.PathLike).
constexpr std::string_view kLogsAccepted =
    "a dict of run (a name or a 0-based index) → log file, or a folder with its manifest.toml (str or "
    "os.PathLike)";

// A dict of logs, each run a name or an index and each file a path (str or os.PathLike): a TypeError naming the
// argument for anything else (pybind11's own cast names neither it nor the entry).
LogMap log_map(const py::object& logs, std::string_view function) {
  if (!py::isinstance<py::dict>(logs))
    throw py::type_error(fmt::format("{}(): logs: expected a dict of run (a name or a 0-based index) → log file, "
                                     "got {}",
                                     function, py::str(logs.get_type().attr("__name__")).cast<std::string>()));
  LogMap map;
  for (const auto& [key, value] : logs.cast<py::dict>()) {
    std::variant<int, std::string> run;
    if (py::isinstance<py::int_>(key) && !py::isinstance<py::bool_>(key))
      run = key.cast<int>();
    else if (py::isinstance<py::str>(key))
      run = key.cast<std::string>();
    else
      throw py::type_error(fmt::format("{}(): logs: a key {} is no run; accepted: a run's name (str) or its "
                                       "0-based index (int)",
                                       function, py::repr(key).cast<std::string>()));
    map[run] = path_argument(py::reinterpret_borrow<py::object>(value), function,
                             fmt::format("logs[{}]", py::repr(key).cast<std::string>()),
                             "the path of a log file (str or os.PathLike)");
  }
  return map;
}

// pulse_weight as --pulse-weight takes it: a number (in the output unit × s) stays a keyword; text, a bare
// number or a quantity with its unit ("2.5e-5 deg"), is converted with the configuration's output unit
// (verbs::pulse_weight_from_text) and set after the other keywords.
constexpr std::pair<std::string_view, std::string_view> kPulseWeightType{"pulse_weight",
                                                                          "Union[float, str, None]"};
template <class Read>
verbs::ReduceOptions with_pulse_weight(const Config& cfg, const py::kwargs& keywords, Read read) {
  py::kwargs rest;
  std::optional<double> weight;
  for (const auto& [key, value] : keywords) {
    if (py::isinstance<py::str>(value) && py::cast<std::string>(py::str(key)) == "pulse_weight")
      weight = verbs::pulse_weight_from_text(cfg, py::cast<std::string>(value));
    else
      rest[key] = value;
  }
  verbs::ReduceOptions o = read(rest);
  if (weight) o.pulse_weight = weight;
  return o;
}

// The results of reducing recorded run logs: ReducedLog, ControlEvidence, LoggedRun and LogReduction.
void bind_log_reduction_results(py::module_& m) {
  py::class_<ReducedLog>(m, "ReducedLog", "One recorded run log, reduced (SI).")
      .def_readonly("source", &ReducedLog::source, "the log's file name [—]")
      .def_readonly("samples", &ReducedLog::samples, "number of rows [—]")
      .def_readonly("gaps", &ReducedLog::gaps,
                    "steps between samples of more than 1.5 times the shortest before them [—]")
      .def_readonly("longest_gap", &ReducedLog::longest_gap, "the longest gap, between the samples either side [s]")
      .def_readonly("missing", &ReducedLog::missing, "the time the gaps miss: each less one shortest step [s]")
      .def_readonly("pulses", &ReducedLog::pulses, "the output came as a pulse count [—]")
      .def_readonly("duration", &ReducedLog::duration, "T = t_last − t_first [s]")
      .def_readonly("mean_output", &ReducedLog::mean_output, "the mean output over the span [output SI]")
      .def_readonly("has_theta1", &ReducedLog::has_theta1, "the main-axis encoder was logged [—]")
      .def_readonly("theta1_rate", &ReducedLog::theta1_rate, "θ̇1 = Ω + Δω from the encoder [rad/s]")
      .def_readonly("theta1_start", &ReducedLog::theta1_start, "θ1(t_first), in [0, 2π) [rad]")
      .def_readonly("theta1_rms", &ReducedLog::theta1_rms, "RMS residual of the encoder fit [rad]")
      .def_readonly("has_gamma", &ReducedLog::has_gamma, "the platform encoder was logged [—]")
      .def_readonly("gamma_rate", &ReducedLog::gamma_rate, "γ̇ from the encoder [rad/s]")
      .def_readonly("gamma_start", &ReducedLog::gamma_start, "φ0 of the logged span, in [0, 2π) [rad]")
      .def_readonly("gamma_end", &ReducedLog::gamma_end, "ψ, the terminal phase, in [0, 2π) [rad]")
      .def_readonly("gamma_rms", &ReducedLog::gamma_rms, "RMS residual of the encoder fit [rad]")
      .def_readonly("theta1_harmonics", &ReducedLog::theta1_harmonics,
                    "angle harmonics Ĉ1, Ŝ1, … of θ1 (empty: not fitted) [rad]")
      .def_readonly("theta1_harmonic_sigma", &ReducedLog::theta1_harmonic_sigma,
                    "standard error of one of them [rad]")
      .def_readonly("gamma_harmonics", &ReducedLog::gamma_harmonics,
                    "angle harmonics Ĉ1, Ŝ1, … of γ (empty: not fitted) [rad]")
      .def_readonly("gamma_harmonic_sigma", &ReducedLog::gamma_harmonic_sigma,
                    "standard error of one of them [rad]");

  py::class_<ControlEvidence>(m, "ControlEvidence", "The platform's control as both encoders show it.")
      .def_property_readonly(
          "look", [](const ControlEvidence& e) { return std::string(control_look_name(e.look)); },
          "'speed', 'phase_locked', 'undetermined' or 'not tested' [—]")
      .def_readonly("following", &ControlEvidence::following, "λ: 1 phase-locked, 0 speed [—]")
      .def_readonly("main_in_gamma", &ControlEvidence::main_in_gamma,
                    "|p|, the main axis's angle ripple as a phase-locked γ would carry it [rad]")
      .def_readonly("threshold", &ControlEvidence::threshold,
                    "|p| below this leaves the control undetermined [rad]");

  py::class_<LoggedRun>(m, "LoggedRun")
      .def_readonly("index", &LoggedRun::index, "0-based index in the plan [—]")
      .def_readonly("log", &LoggedRun::log, "the reduced log [ReducedLog]")
      .def_readonly("measured", &LoggedRun::measured, "the planned run as the log measured it [Run]")
      .def_readonly("planned_rate", &LoggedRun::planned_rate, "Ω of the plan [rad/s]")
      .def_readonly("rate", &LoggedRun::rate, "Ω of the run as measured [rad/s]")
      .def_readonly("mismatch", &LoggedRun::mismatch, "ΔΩ of the model [rad/s]")
      .def_readonly("main_ripple", &LoggedRun::main_ripple,
                    "measured main-axis ripple c1, s1, … (empty: the configured one) [relative rate, 1]")
      .def_readonly("platform_ripple", &LoggedRun::platform_ripple,
                    "measured platform ripple c1, s1, … (empty: the configured one) [relative rate, 1]")
      .def_readonly("control", &LoggedRun::control,
                    "the platform's control as the encoders show it [ControlEvidence]");

  py::class_<LogReduction>(m, "LogReduction")
      .def_readonly("runs", &LogReduction::runs, "the logged runs in plan order, list of LoggedRun [—]")
      .def_readonly("observations", &LogReduction::observations,
                    "per logged run: the model's regressors and the log's mean [Observations]");
}

// Run logs reduced to observations of the runs as measured: the Reduction result, reduce(), reduce_logs().
void bind_log_reduction(py::module_& m) {
  bind_verb_result<verbs::ReduceResult>(m, "Reduction",
                                        "`ccal reduce`: logged runs, their observations and identification; "
                                        "str() is the CLI's text, to_json() its JSON.",
                                        "logs")
      .def_readonly("config", &verbs::ReduceResult::config)
      .def_readonly("logs", &verbs::ReduceResult::logs,
                    "the reduced logs (their fields are readable on the result) [LogReduction]")
      .def_readonly("warnings", &verbs::ReduceResult::warnings, "what the reduction noticed in the logs [—]")
      .def_property_readonly(
          "has_statement", [](const verbs::ReduceResult& r) { return r.statement.has_value(); },
          "True when statement=True gave the calibration statement (in str() and to_json()) [—]")
      .def_readonly("statement", &verbs::ReduceResult::statement,
                    "the calibration statement with statement=True, else None [Statement]")
      .def_property_readonly(
          "coefficients",
          [](const verbs::ReduceResult& r) {
            return Eigen::VectorXd(r.identification.id.fit.value * r.output_unit_si);
          },
          "the identified free terms, in the order of names [coefficient SI]")
      .def_property_readonly(
          "names", [](const verbs::ReduceResult& r) { return r.identification.id.fit.names; },
          "the identified terms' ids [—]")
      .def_property_readonly(
          "units", [](const verbs::ReduceResult& r) { return r.identification.id.units; },
          "the display unit of each identified term, in the order of names [—]")
      .def_property_readonly(
          "display_scale",
          [](const verbs::ReduceResult& r) {
            return std::vector<double>(r.identification.id.units.size(), 1.0 / r.output_unit_si);
          },
          "SI → display unit factor per identified term [display unit per SI]")
      .def_readonly("instruments", &verbs::ReduceResult::instruments,
                    "a test of several instruments: each one's Reduction, in the configuration's order (the fields "
                    "above are the first's); [] for one instrument [list of Reduction]")
      .def_readonly("covariance", &verbs::ReduceResult::covariance,
                    "a test of several instruments with statement=True: the covariance of their coefficients "
                    "through the shared inputs, else None [InstrumentCovariance]");

  m.def(
      "reduce",
      [](const Config& cfg, const py::object& logs, const py::object& log_layout, const py::kwargs& keywords) {
        auto o = with_pulse_weight(cfg, keywords, [](const py::kwargs& k) {
          return options_from_keywords<verbs::ReduceOptions>(k, "reduce", {}, {}, {"config", "logs", "log_layout"});
        });
        const bool dict = py::isinstance<py::dict>(logs);
        const std::string folder = dict ? std::string() : path_argument(logs, "reduce", "logs", kLogsAccepted);
        if (!log_layout.is_none() && !dict)
          throw InputError("reduce: log_layout is for a dict of logs; a folder's manifest has the layout "
                           "([format] and [columns] tables)");
        if (!log_layout.is_none())
          o.layout = read_log_layout(path_argument(log_layout, "reduce", "log_layout", kLayoutArgument));
        if (dict) {
          o.logs = log_files(cfg, log_map(logs, "reduce"));
        } else {  // a folder with its manifest, as `ccal reduce --logs DIR`
          const LogManifest manifest = read_log_manifest(folder);
          o.layout = manifest.layout;
          o.logs = verbs::manifest_logs(manifest);
        }
        py::gil_scoped_release release;
        return verbs::reduce(cfg, o);
      },
      py::arg("config"), py::arg("logs"), py::arg("log_layout") = py::none(),
      "`ccal reduce`: recorded run logs (a dict of run name or 0-based index → CSV file, or a folder with its "
      "manifest.toml, as `--logs DIR`; log_layout: with a dict, a file with a manifest's [format] and [columns] "
      "tables, as `--log-layout FILE`) to run means, the model of "
      "the runs as measured and the identification, as the CLI gives them; with statement=True also the "
      "calibration statement with the configuration's tolerances as its Type B part.");
  record_keywords<verbs::ReduceOptions>(m, "reduce", {}, {kPulseWeightType});

  // The logs alone, without the identification (so without the statement's options).
  m.def(
      "reduce_logs",
      [](const Config& cfg, const py::object& logs, const py::object& log_layout, const py::kwargs& keywords) {
        auto o = with_pulse_weight(cfg, keywords, [](const py::kwargs& k) {
          return options_from_keywords<verbs::ReduceOptions>(
              k, "reduce_logs", {}, {"statement", "coverage_probability", "coverage_factor", "statement_trials", "seed", "threads", "strict_runs"},
              {"config", "logs", "log_layout"});
        });
        if (!log_layout.is_none())
          o.layout = read_log_layout(path_argument(log_layout, "reduce_logs", "log_layout", kLayoutArgument));
        const RunLogOptions lo = verbs::run_log_options(cfg, o);
        std::vector<std::pair<std::size_t, std::filesystem::path>> files;
        for (const auto& [run, path] : log_map(logs, "reduce_logs"))
          files.emplace_back(run_index(cfg, run, "logs"), path);
        py::gil_scoped_release release;
        return reduce_log_files(cfg, files, lo, o.mode.value_or(cfg.mode));
      },
      py::arg("config"), py::arg("logs"), py::arg("log_layout") = py::none(),
      "Recorded run logs (run name or 0-based index → CSV file; log_layout: a file with a manifest's [format] "
      "and [columns] tables, as `--log-layout FILE`) to observations of the runs as measured (`ccal reduce` "
      "without the identification). Identify them with identify(reduction.observations, config).");
  record_keywords<verbs::ReduceOptions>(
      m, "reduce_logs", {"statement", "coverage_probability", "coverage_factor", "statement_trials", "seed", "threads", "strict_runs"},
      {kPulseWeightType});
}

}  // namespace

// ReducedLog, ControlEvidence, LoggedRun, LogReduction and Reduction; reduce() and reduce_logs().
void bind_reduce(py::module_& m) {
  bind_log_reduction_results(m);
  bind_log_reduction(m);
}

}  // namespace ccal::python

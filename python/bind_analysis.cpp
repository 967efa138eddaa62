// The deterministic analyses: the error budget, the sensed input at an instant, simulated observations and
// their identification, and a general least-squares fit.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/io/run_log.hpp"
#include "ccal/io/run_log_writer.hpp"
#include "ccal/model/sensed_input.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/observability.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/force.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"

namespace ccal::python {

namespace {

// Rows of one per-source vector field of the budget: sources × coefficients.
Eigen::MatrixXd stacked(const BudgetResult& b, Eigen::VectorXd SourceBudget::*field) {
  Eigen::MatrixXd out(Eigen::Index(b.sources.size()), Eigen::Index(b.coefficients.size()));
  for (std::size_t s = 0; s < b.sources.size(); ++s) {
    const Eigen::VectorXd& v = b.sources[s].*field;
    if (v.size() != out.cols()) return {};
    out.row(Eigen::Index(s)) = v.transpose();
  }
  return out;
}

std::size_t run_index(const Config& cfg, const std::variant<int, std::string>& run) {
  if (const int* i = std::get_if<int>(&run)) {
    const int n = int(cfg.plan.runs.size());
    if (*i < -n || *i >= n)
      throw InputError("run: index " + std::to_string(*i) + " is out of range for " + std::to_string(n) +
                       " runs");
    return std::size_t(*i < 0 ? *i + n : *i);
  }
  // A string of digits that names no run is the same 0-based index as the int (run="1" is run=1, the
  // second run), not the command line's 1-based index.
  const std::string& text = std::get<std::string>(run);
  for (const auto& r : cfg.plan.runs)
    if (r.name == text) return select_run(cfg.plan, text, "run");
  if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos && text.size() < 9)
    return run_index(cfg, std::stoi(text));
  return select_run(cfg.plan, text, "run");
}

// The budget in detail: every source's line, the matrices and the compensation choices.
void bind_budget(py::module_& m) {
  py::class_<SourceBudget>(m, "SourceBudget", "One error source's line of the budget (SI).")
      .def_readonly("id", &SourceBudget::id)
      .def_readonly("parameter", &SourceBudget::parameter)
      .def_readonly("group", &SourceBudget::group)
      .def_property_readonly(
          "distribution",
          [](const SourceBudget& s) { return std::string(distribution_name(s.distribution)); })
      .def_readonly("bound", &SourceBudget::bound)
      .def_readonly("standard_uncertainty", &SourceBudget::standard_uncertainty)
      .def_readonly("sensitivity", &SourceBudget::sensitivity, "∂K/∂e per coefficient")
      .def_readonly("effect", &SourceBudget::effect, "sensitivity × standard uncertainty, signed")
      .def_readonly("effect_force", &SourceBudget::effect_force, "of which through the specific force")
      .def_readonly("effect_rate", &SourceBudget::effect_rate, "and through the angular rate")
      .def_readonly("share", &SourceBudget::share, "share of each coefficient's variance (0…1)")
      .def_readonly("paper_effect", &SourceBudget::paper_effect, "paper-mode effect (empty if not computed)")
      .def_readonly("disagrees", &SourceBudget::disagrees, "exact and paper effects differ beyond the factor")
      .def_readonly("rank", &SourceBudget::rank, "1 = largest contributor")
      .def("__repr__", [](const SourceBudget& s) { return "<ccal.SourceBudget " + s.id + ">"; });

  py::class_<CompensationChoice>(m, "CompensationChoice")
      .def_readonly("id", &CompensationChoice::id)
      .def_readonly("description", &CompensationChoice::description)
      .def_readonly("bias", &CompensationChoice::bias, "K̂(effect not modelled) − K̂(modelled), SI")
      .def_readonly("paper_bias", &CompensationChoice::paper_bias);

  py::class_<BudgetResult>(m, "BudgetDetail",
                           "The error budget of a configuration (SI; display units alongside).")
      .def_property_readonly("mode", [](const BudgetResult& b) { return std::string(mode_name(b.mode)); })
      .def_property_readonly("derivatives",
                             [](const BudgetResult& b) {
                               return b.derivatives == DerivativeMethod::automatic ? "automatic"
                                                                                   : "linearised";
                             })
      .def_readonly("coefficients", &BudgetResult::coefficients)
      .def_readonly("units", &BudgetResult::units, "display units of the coefficients")
      .def_readonly("display_scale", &BudgetResult::display_scale, "SI → display unit factor per coefficient")
      .def_readonly("sources", &BudgetResult::sources)
      .def_property_readonly("source_ids",
                             [](const BudgetResult& b) {
                               std::vector<std::string> ids;
                               for (const auto& s : b.sources) ids.push_back(s.id);
                               return ids;
                             })
      .def_property_readonly(
          "sensitivity", [](const BudgetResult& b) { return stacked(b, &SourceBudget::sensitivity); },
          "sources × coefficients")
      .def_property_readonly(
          "effect", [](const BudgetResult& b) { return stacked(b, &SourceBudget::effect); },
          "sources × coefficients")
      .def_property_readonly("effect_force",
                             [](const BudgetResult& b) { return stacked(b, &SourceBudget::effect_force); })
      .def_property_readonly("effect_rate",
                             [](const BudgetResult& b) { return stacked(b, &SourceBudget::effect_rate); })
      .def_property_readonly("share", [](const BudgetResult& b) { return stacked(b, &SourceBudget::share); })
      .def_readonly("standard_uncertainty", &BudgetResult::standard_uncertainty)
      .def_readonly("expanded_uncertainty", &BudgetResult::expanded_uncertainty)
      .def_readonly("coverage_factor", &BudgetResult::coverage_factor)
      .def_readonly("covariance", &BudgetResult::covariance)
      .def_readonly("correlation", &BudgetResult::correlation)
      .def_readonly("compensation", &BudgetResult::compensation);

  bind_verb_result<verbs::BudgetResult>(m, "Budget",
                                        "`ccal budget` of a configuration: its BudgetDetail's fields are "
                                        "readable on it; str() is the CLI's text, to_json() its JSON.",
                                        "budget")
      .def_readonly("config", &verbs::BudgetResult::config)
      .def_readonly("budget", &verbs::BudgetResult::budget);

  m.def(
      "budget",
      [](const Config& cfg, std::optional<std::string> mode, const std::string& derivatives,
         double coverage_factor, bool compare_with_paper) {
        verbs::BudgetOptions o;
        if (mode) o.mode = mode_argument(*mode);
        if (derivatives == "linearised")
          o.derivatives = DerivativeMethod::linearised;
        else if (derivatives == "automatic")
          o.derivatives = DerivativeMethod::automatic;
        else
          throw InputError("derivatives: '" + derivatives + "'; accepted: 'linearised', 'automatic'");
        if (!(coverage_factor > 0)) throw InputError("coverage_factor: must be > 0");
        o.coverage_factor = coverage_factor;
        o.compare_with_paper = compare_with_paper;
        py::gil_scoped_release release;
        return verbs::budget(cfg, o);
      },
      py::arg("config"), py::arg("mode") = py::none(), py::arg("derivatives") = "linearised",
      py::arg("coverage_factor") = 2.0, py::arg("compare_with_paper") = true,
      "Error budget (`ccal budget`): sensitivity of every identified coefficient to every tolerance, the "
      "effects, totals and compensation choices. mode: 'exact' or 'paper' (default: the configuration's).");
}

// The sensed input at one instant, with the first-order contributions.
void bind_sensed_input(py::module_& m) {
  py::class_<ForceContribution>(m, "ForceContribution")
      .def_readonly("id", &ForceContribution::id)
      .def_readonly("value", &ForceContribution::value_si, "the parameter's value, SI")
      .def_readonly("unit", &ForceContribution::unit)
      .def_readonly("f_ia", &ForceContribution::f_ia, "first-order change of the IA specific force [g]")
      .def_readonly("w_ia", &ForceContribution::w_ia, "first-order change of the IA rate [rad/s]");

  py::class_<SensedInputBreakdown>(m, "SensedInputDetail",
                                   "What the instrument senses at one instant of a run.")
      .def_readonly("specific_force", &SensedInputBreakdown::specific_force, "along IA, PA, OA [g]")
      .def_readonly("angular_rate", &SensedInputBreakdown::angular_rate, "inertial, about IA, PA, OA [rad/s]")
      .def_readonly("rate", &SensedInputBreakdown::rate, "nominal main-axis rate Ω [rad/s]")
      .def_readonly("initial_phase", &SensedInputBreakdown::initial_phase, "φ0 [rad]")
      .def_readonly("time", &SensedInputBreakdown::time, "[s]")
      .def_readonly("nominal_f_ia", &SensedInputBreakdown::nominal_f_ia, "error-free IA specific force [g]")
      .def_readonly("nominal_w_ia", &SensedInputBreakdown::nominal_w_ia, "error-free IA rate [rad/s]")
      .def_readonly("contributions", &SensedInputBreakdown::contributions, "first order, per non-zero error")
      .def_readonly("first_order_f_ia", &SensedInputBreakdown::first_order_f_ia)
      .def_readonly("first_order_w_ia", &SensedInputBreakdown::first_order_w_ia)
      .def_property_readonly("remainder_f_ia", &SensedInputBreakdown::remainder_f_ia,
                             "exact − first order [g]")
      .def_property_readonly("remainder_w_ia", &SensedInputBreakdown::remainder_w_ia,
                             "exact − first order [rad/s]");

  bind_verb_result<verbs::ForceResult>(m, "SensedInput",
                                       "`ccal force` at one instant: its SensedInputDetail's fields are "
                                       "readable on it; str() is the CLI's text, to_json() its JSON.",
                                       "input")
      .def_readonly("config", &verbs::ForceResult::config)
      .def_readonly("input", &verbs::ForceResult::input);

  m.def(
      "sensed_input",
      [](const Config& cfg, const std::variant<int, std::string>& run, double time, const std::string& mode) {
        verbs::ForceOptions o;
        o.run = cfg.plan.runs[run_index(cfg, run)].name;
        o.time = time;
        o.mode = mode_argument(mode);
        return verbs::force(cfg, o);
      },
      py::arg("config"), py::arg("run") = 0, py::arg("time") = 0.0, py::arg("mode") = "exact",
      "Specific force and angular rate at time t [s] of a run (a name, or a 0-based index) with the "
      "configured "
      "errors (`ccal force`).");
}

// Simulated observations: the Observations and Simulation results, simulate() and observe().
void bind_simulated_observations(py::module_& m) {
  py::class_<Observations<double>>(m, "Observations", "Run means: one row per run (SI, inputs in g).")
      .def_readonly("runs", &Observations<double>::runs)
      .def_readonly("columns", &Observations<double>::columns, "term ids of the regressor columns")
      .def_readonly("regressors", &Observations<double>::regressors, "runs × columns, the model's means")
      .def_readonly("output", &Observations<double>::output, "the instrument's mean output [output SI]")
      .def_readonly("known_rate", &Observations<double>::known_rate, "the model's ⟨s_ω ω_IA⟩ [output SI]")
      .def_readonly("input", &Observations<double>::input, "the model's ⟨a_i⟩ [g]");

  bind_verb_result<verbs::SimulateResult>(m, "Simulation",
                                          "`ccal simulate`: run means of the plan and their identification; "
                                          "str() is the CLI's text, to_json() its JSON, to_csv() the "
                                          "observations file.",
                                          "observations")
      .def_readonly("config", &verbs::SimulateResult::config)
      .def_readonly("observations", &verbs::SimulateResult::observations)
      .def_property_readonly(
          "coefficients",
          // the fit is of the observations file, in the output unit: × its SI size gives output SI per gⁿ
          [](const verbs::SimulateResult& r) {
            return Eigen::VectorXd(r.identification.fit.value * r.output_unit_si);
          },
          "identified free terms (SI)")
      .def_property_readonly("names",
                             [](const verbs::SimulateResult& r) { return r.identification.fit.names; })
      .def(
          "to_csv", [](const verbs::SimulateResult& r) { return render::csv(r); },
          "The observations file (the CLI's --format csv, the input of `ccal identify`).")
      .def(
          "run_logs",
          [](const verbs::SimulateResult& r, std::optional<double> step) {
            const Eigen::VectorXd& means = r.observations.output;
            std::vector<std::pair<std::string, std::string>> out;
            for (auto& log : write_run_logs(r.config, {means.data(), means.data() + means.size()},
                                            step ? *step : default_log_step(r.config)))
              out.emplace_back(std::move(log.name), std::move(log.text));
            return out;
          },
          py::arg("step") = py::none(),
          "The runs' logs as `ccal simulate --logs-out` writes them: (file name, CSV text) per run, in plan "
          "order; step: sampling interval [s] (default 0.1 s, or an eighth of a revolution if shorter).");

  m.def(
      "simulate",
      [](const Config& cfg, std::optional<std::string> mode, std::uint64_t seed) {
        verbs::SimulateOptions o;
        if (mode) o.mode = mode_argument(*mode);
        o.seed = seed;
        py::gil_scoped_release release;
        return verbs::simulate(cfg, o);
      },
      py::arg("config"), py::arg("mode") = py::none(), py::arg("seed") = 1,
      "`ccal simulate`: run means of the test plan with the configured errors and instrument noise, and the "
      "identification of the configured terms from them, as the CLI gives them.");

  m.def(
      "observe",
      [](const Config& cfg, std::optional<std::string> mode, std::uint64_t seed) {
        const ModelMode model_mode = mode ? mode_argument(*mode) : cfg.mode;
        const Experiment ex = cfg.experiment();
        const Eigen::VectorXd& truth = cfg.centrifuge.errors;
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
        Observations<double> obs = observe<double>(ex, truth, cfg.identification.compensate ? truth : zero,
                                                   cfg.identification, model_mode);
        add_output_noise(obs, ex, seed);
        return obs;
      },
      py::arg("config"), py::arg("mode") = py::none(), py::arg("seed") = 1,
      "Simulated run means of the test plan with the configured errors and instrument noise (`ccal "
      "simulate`).");
}

// The results of an identification: Fit, TermObservability and Observability.
void bind_fit_and_observability_results(py::module_& m) {
  py::class_<FitResult>(m, "Fit", "A least-squares identification with its diagnostics.")
      .def_readonly("names", &FitResult::names)
      .def_readonly("value", &FitResult::value)
      .def_readonly("std_error", &FitResult::std_error)
      .def_readonly("covariance", &FitResult::covariance)
      .def_readonly("correlation", &FitResult::correlation)
      .def_readonly("residuals", &FitResult::residuals)
      .def_readonly("residual_std", &FitResult::residual_std)
      .def_readonly("dof", &FitResult::dof)
      .def_readonly("chi2", &FitResult::chi2)
      .def_readonly("chi2_per_dof", &FitResult::chi2_per_dof)
      .def_readonly("condition_number", &FitResult::condition_number)
      .def_readonly("rank", &FitResult::rank)
      .def_readonly("warnings", &FitResult::warnings);

  py::class_<TermObservability>(m, "TermObservability",
                                "How well the plan sees one free term (docs/model.md §14; SI).")
      .def_readonly("term", &TermObservability::term)
      .def_property_readonly(
          "status", [](const TermObservability& t) { return std::string(term_status_name(t.status)); },
          "'ok', 'weak' or 'unobservable'")
      .def_readonly("sensitivity", &TermObservability::sensitivity,
                    "‖P⊥h‖: run-mean change per unit coefficient, root-sum-square over runs")
      .def_readonly("natural_norm", &TermObservability::natural_norm, "the regressor's size before averaging")
      .def_readonly("fraction", &TermObservability::fraction, "sensitivity / natural_norm")
      .def_readonly("standard_error", &TermObservability::standard_error, "from the run resolution alone")
      .def_readonly("min_detectable", &TermObservability::min_detectable, "detection_factor × standard_error")
      .def_readonly("aliased_with", &TermObservability::aliased_with)
      .def_readonly("reason", &TermObservability::reason)
      .def_readonly("fix", &TermObservability::fix)
      .def("__repr__", [](const TermObservability& t) {
        return "<ccal.TermObservability " + t.term + " " + std::string(term_status_name(t.status)) + ">";
      });

  py::class_<ObservabilityResult>(m, "Observability", "The observability of every free term (SI).")
      .def_readonly("terms", &ObservabilityResult::terms)
      .def_readonly("resolution", &ObservabilityResult::resolution, "σ of each run mean [output SI]")
      .def_readonly("detection_factor", &ObservabilityResult::detection_factor)
      .def_readonly("whole_revolutions", &ObservabilityResult::whole_revolutions);
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

// The results of reducing recorded run logs: ReducedLog, ControlEvidence, LoggedRun and LogReduction.
void bind_log_reduction_results(py::module_& m) {
  py::class_<ReducedLog>(m, "ReducedLog", "One recorded run log, reduced (SI).")
      .def_readonly("source", &ReducedLog::source)
      .def_readonly("samples", &ReducedLog::samples)
      .def_readonly("pulses", &ReducedLog::pulses, "the output came as a pulse count")
      .def_readonly("duration", &ReducedLog::duration, "T [s]")
      .def_readonly("mean_output", &ReducedLog::mean_output, "[output SI]")
      .def_readonly("has_theta1", &ReducedLog::has_theta1)
      .def_readonly("theta1_rate", &ReducedLog::theta1_rate, "[rad/s]")
      .def_readonly("theta1_start", &ReducedLog::theta1_start, "[rad]")
      .def_readonly("theta1_rms", &ReducedLog::theta1_rms, "[rad]")
      .def_readonly("has_gamma", &ReducedLog::has_gamma)
      .def_readonly("gamma_rate", &ReducedLog::gamma_rate, "[rad/s]")
      .def_readonly("gamma_start", &ReducedLog::gamma_start, "φ0 [rad]")
      .def_readonly("gamma_end", &ReducedLog::gamma_end, "ψ [rad]")
      .def_readonly("gamma_rms", &ReducedLog::gamma_rms, "[rad]")
      .def_readonly("theta1_harmonics", &ReducedLog::theta1_harmonics,
                    "angle harmonics Ĉ1, Ŝ1, … of θ1 [rad] (empty: not fitted)")
      .def_readonly("theta1_harmonic_sigma", &ReducedLog::theta1_harmonic_sigma, "[rad]")
      .def_readonly("gamma_harmonics", &ReducedLog::gamma_harmonics, "angle harmonics of γ [rad]")
      .def_readonly("gamma_harmonic_sigma", &ReducedLog::gamma_harmonic_sigma, "[rad]");

  py::class_<ControlEvidence>(m, "ControlEvidence", "The platform's control as both encoders show it.")
      .def_property_readonly(
          "look", [](const ControlEvidence& e) { return std::string(control_look_name(e.look)); },
          "'speed', 'phase_locked', 'undetermined' or 'not tested'")
      .def_readonly("following", &ControlEvidence::following, "λ: 1 phase-locked, 0 speed")
      .def_readonly("main_in_gamma", &ControlEvidence::main_in_gamma, "|p| [rad]")
      .def_readonly("threshold", &ControlEvidence::threshold, "[rad]");

  py::class_<LoggedRun>(m, "LoggedRun")
      .def_readonly("index", &LoggedRun::index, "0-based index in the plan")
      .def_readonly("log", &LoggedRun::log)
      .def_readonly("measured", &LoggedRun::measured, "the planned run as the log measured it")
      .def_readonly("planned_rate", &LoggedRun::planned_rate, "[rad/s]")
      .def_readonly("rate", &LoggedRun::rate, "[rad/s]")
      .def_readonly("mismatch", &LoggedRun::mismatch, "ΔΩ of the model [rad/s]")
      .def_readonly("main_ripple", &LoggedRun::main_ripple,
                    "measured main-axis ripple c1, s1, … (relative; empty: the configured one)")
      .def_readonly("platform_ripple", &LoggedRun::platform_ripple, "measured platform ripple c1, s1, …")
      .def_readonly("control", &LoggedRun::control);

  py::class_<LogReduction>(m, "LogReduction")
      .def_readonly("runs", &LogReduction::runs)
      .def_readonly("observations", &LogReduction::observations);
}

// Run logs reduced to observations of the runs as measured: the Reduction result, reduce(), reduce_logs().
void bind_log_reduction(py::module_& m) {
  bind_verb_result<verbs::ReduceResult>(m, "Reduction",
                                        "`ccal reduce`: logged runs, their observations and identification; "
                                        "str() is the CLI's text, to_json() its JSON.",
                                        "logs")
      .def_readonly("config", &verbs::ReduceResult::config)
      .def_readonly("logs", &verbs::ReduceResult::logs)
      .def_readonly("warnings", &verbs::ReduceResult::warnings)
      .def_property_readonly(
          "coefficients",
          [](const verbs::ReduceResult& r) {
            return Eigen::VectorXd(r.identification.id.fit.value * r.output_unit_si);
          },
          "identified free terms (SI)")
      .def_property_readonly("names",
                             [](const verbs::ReduceResult& r) { return r.identification.id.fit.names; });

  m.def(
      "reduce",
      [](const Config& cfg, const std::map<std::variant<int, std::string>, std::string>& logs,
         std::optional<double> pulse_weight, const std::string& angle_unit, std::optional<std::string> mode) {
        verbs::ReduceOptions o;
        for (const auto& [run, path] : logs)
          o.logs.push_back({cfg.plan.runs[run_index(cfg, run)].name, path});
        o.pulse_weight = pulse_weight;
        if (angle_unit == "deg")
          o.angles_in_degrees = true;
        else if (angle_unit != "rad")
          throw InputError("angle_unit: '" + angle_unit + "'; accepted: 'rad', 'deg'");
        if (mode) o.mode = mode_argument(*mode);
        py::gil_scoped_release release;
        return verbs::reduce(cfg, o);
      },
      py::arg("config"), py::arg("logs"), py::arg("pulse_weight") = py::none(), py::arg("angle_unit") = "rad",
      py::arg("mode") = py::none(),
      "`ccal reduce`: recorded run logs (run name or 0-based index → CSV file) to run means, the model of "
      "the "
      "runs as measured and the identification, as the CLI gives them; pulse_weight in the output unit × s "
      "(default: the instrument's quantum).");

  m.def(
      "reduce_logs",
      [](const Config& cfg, const std::map<std::variant<int, std::string>, std::string>& logs,
         std::optional<double> pulse_weight, const std::string& angle_unit, std::optional<std::string> mode) {
        RunLogOptions o;
        o.output_scale = output_unit_si(cfg.instrument.output_unit);
        o.pulse_weight = pulse_weight ? *pulse_weight : cfg.instrument.quantum;
        if (angle_unit == "deg")
          o.angle_scale = std::numbers::pi / 180;
        else if (angle_unit != "rad")
          throw InputError("angle_unit: '" + angle_unit + "'; accepted: 'rad', 'deg'");
        std::vector<std::pair<std::size_t, CsvTable>> tables;
        for (const auto& [run, path] : logs) tables.emplace_back(run_index(cfg, run), read_csv_file(path));
        return reduce_logs(cfg, tables, o, mode ? mode_argument(*mode) : cfg.mode);
      },
      py::arg("config"), py::arg("logs"), py::arg("pulse_weight") = py::none(), py::arg("angle_unit") = "rad",
      py::arg("mode") = py::none(),
      "Recorded run logs (run name or 0-based index → CSV file) to observations of the runs as measured "
      "(`ccal reduce`); pulse_weight: integrated output per pulse in SI (default: the instrument's quantum). "
      "Identify them with identify(reduction.observations, config).");
}

}  // namespace

void bind_analysis(py::module_& m) {
  bind_budget(m);
  bind_sensed_input(m);
  bind_simulated_observations(m);
  bind_fit_and_observability_results(m);
  bind_identification(m);
  bind_log_reduction_results(m);
  bind_log_reduction(m);
}

}  // namespace ccal::python

#include "ccal/render/montecarlo.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "budget_parts.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"
#include "text_lines.hpp"

namespace ccal::render {
namespace {

std::string interval(double low, double high) {
  return fmt::format("[{}, {}]", number(low, 5), number(high, 5));
}

double per_second(const MonteCarloDetail& r) { return r.seconds > 0 ? double(r.trials) / r.seconds : 0.0; }

std::string fixed_terms(const Config& cfg) {
  std::string s;
  for (const auto& [id, v] : cfg.identification.fixed_terms) s += (s.empty() ? "" : ", ") + id;
  return s.empty() ? "nothing" : s;
}

// Per coefficient, for one that failed the validation: does the sampling error of the interval ends explain
// it, and what to run; empty for a validated one.
std::vector<std::string> advice_of(const BudgetDetail& b, const MonteCarloDetail& r) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < r.outputs.size(); ++k) {
    const OutputSummary& s = r.outputs[k];
    if (!s.has_lpu || s.validated) {
      out.emplace_back();
      continue;
    }
    const ValidationDiagnosis d = validation_diagnosis(s, r.trials);
    const double f = b.display_scale[k];
    const std::string measured = fmt::format(
        "{}: not validated: max(d_low, d_high) exceeds delta by {} {}, {:.2g} standard errors of the "
        "interval "
        "ends ({} at M = {})",
        s.name, number(d.excess * f, 2), b.units[k], d.excess_in_std_errors,
        number(s.interval_end_std_error * f, 2), r.trials);
    if (d.explained_by_sampling)
      out.push_back(fmt::format(
          "{}: sampling error explains it; run `ccal montecarlo --digits {}` (the adaptive procedure) or "
          "`--trials {}` (ends to delta/3).",
          measured, r.adaptive ? r.digits + 1 : 2, d.trials_needed));
    else
      out.push_back(fmt::format(
          "{}: beyond 3 standard errors, so sampling error does not explain it: the LPU interval (first "
          "order, normal) misses the distribution; report the Monte Carlo interval.",
          measured));
  }
  return out;
}

std::string validation_advice(const BudgetDetail& b, const MonteCarloDetail& r) {
  std::string out;
  for (const std::string& line : advice_of(b, r))
    if (!line.empty()) out += line + "\n";
  return out;
}

// Per coefficient: mean, u(y) and the two 100p % intervals (JCGM 101 §7.7.2), in its display unit.
std::string mc_statistics_table(const BudgetDetail& b, const MonteCarloDetail& r) {
  const std::string pct = fmt::format("{:g} %", 100 * r.coverage_probability);
  Table stats({"coefficient", "unit", "mean y", "std u(y)", "symmetric " + pct + " interval",
               "shortest " + pct + " interval"});
  for (std::size_t k = 0; k < r.outputs.size(); ++k) {
    const OutputSummary& s = r.outputs[k];
    const double f = b.display_scale[k];
    stats.add_row({s.name, b.units[k], number(s.mean * f, 5), number(s.std_dev * f, 5),
                   interval(s.low_symmetric * f, s.high_symmetric * f),
                   interval(s.low_shortest * f, s.high_shortest * f)});
  }
  return stats.render();
}

// The validation of the LPU (JCGM 101 §8): d_low, d_high against delta per coefficient, and the advice for
// each that fails it.
std::string mc_validation_text(const BudgetDetail& b, const MonteCarloDetail& r) {
  std::string out = fmt::format(
      "\nValidation of the LPU (JCGM 101 §8; u_c from `ccal budget --mode {}`, U_p = {:.4f} u_c about the "
      "model at zero draws):\n",
      mode_name(b.mode), r.coverage_factor);
  Table lpu({"coefficient", "unit", "LPU u_c", "U_p = k u_c", "d_low", "d_high", "delta", "validated"});
  for (std::size_t k = 0; k < r.outputs.size(); ++k) {
    const OutputSummary& s = r.outputs[k];
    const double f = b.display_scale[k];
    lpu.add_row({s.name, b.units[k], number(s.lpu_std * f, 5), number(s.lpu_expanded * f, 5),
                 number(s.d_low * f, 3), number(s.d_high * f, 3), number(s.validation_delta * f, 3),
                 s.validated ? "yes" : "no"});
  }
  return out + lpu.render() + validation_advice(b, r);
}

// The adaptive procedure's stability per coefficient (JCGM 101 §7.9.4): 2s of each stage average against
// delta.
std::string mc_adaptive_text(const BudgetDetail& b, const MonteCarloDetail& r) {
  std::string out = fmt::format(
      "\nAdaptive procedure (JCGM 101 §7.9.4, n_dig = {}): standard deviations s of the stage averages "
      "against the numerical tolerance delta of u(y); stable when 2s <= delta.\n",
      r.digits);
  Table a({"coefficient", "unit", "delta", "2 s(y)", "2 s(u)", "2 s(y_low)", "2 s(y_high)"});
  for (std::size_t k = 0; k < r.outputs.size(); ++k) {
    const OutputSummary& s = r.outputs[k];
    const double f = b.display_scale[k];
    a.add_row({s.name, b.units[k], number(s.delta * f, 3), number(2 * s.s_mean * f, 3),
               number(2 * s.s_std_dev * f, 3), number(2 * s.s_low * f, 3), number(2 * s.s_high * f, 3)});
  }
  return out + a.render();
}

// The outputs' correlation matrix from the trials, 4 decimals with their sign.
std::string mc_correlation_text(const MonteCarloDetail& r) {
  std::vector<std::string> header = {"correlation (Monte Carlo)"};
  for (const auto& s : r.outputs) header.push_back(s.name);
  Table corr(header);
  for (std::size_t a = 0; a < r.outputs.size(); ++a) {
    std::vector<std::string> row = {r.outputs[a].name};
    for (std::size_t c = 0; c < r.outputs.size(); ++c)
      row.push_back(fmt::format("{:+.4f}", r.correlation(Eigen::Index(a), Eigen::Index(c))));
    corr.add_row(row);
  }
  return fmt::format("\n{}", corr.render());
}

// How the trials ran (M, stages, seed, threads, time, the adaptive verdict), then the notes.
std::string mc_run_text(const MonteCarloDetail& r) {
  std::string out = fmt::format(
      "\nM = {} trials ({} stage{} of {}), seed {}, {} thread{}, {:.3g} s, {:.4g} trials/s; p = {:g}, "
      "interval over q = {} sorted values{}.\n",
      r.trials, r.stages, r.stages == 1 ? "" : "s", r.stage_trials, r.seed, r.threads,
      r.threads == 1 ? "" : "s", r.seconds, per_second(r), r.coverage_probability, r.interval_points,
      r.adaptive ? (r.converged ? "; adaptive procedure converged" : "; adaptive procedure NOT converged")
                 : "");
  out += "\nNotes:\n";
  for (const auto& l : detail::lines_of(r.notes)) out += "  " + l + "\n";
  return out;
}

std::string text_of(const Config& cfg, const BudgetDetail& b, const MonteCarloDetail& r) {
  std::string out = fmt::format(
      "ccal montecarlo: {}, {} mode, {} sources; identified {} with {} fixed\n"
      "Outputs: deviations of the identified coefficients from those identified with no centrifuge "
      "error.\n\n",
      cfg.source, mode_name(b.mode), cfg.tolerances.size(), fmt::join(b.coefficients, ", "),
      fixed_terms(cfg));
  out += mc_statistics_table(b, r);
  out += mc_validation_text(b, r);
  if (r.adaptive) out += mc_adaptive_text(b, r);
  out += mc_correlation_text(r);
  return out + mc_run_text(r);
}

// Coefficient k in its display unit: the statistics, the adaptive procedure's (when it ran), the LPU's
// validation with its diagnosis, and the histogram.
nlohmann::ordered_json mc_coefficient_json(const BudgetDetail& b, const MonteCarloDetail& r, std::size_t k) {
  const OutputSummary& s = r.outputs[k];
  const double f = b.display_scale[k];
  nlohmann::ordered_json c;
  c["unit"] = b.units[k];
  c["mean"] = s.mean * f;
  c["std_dev"] = s.std_dev * f;
  c["symmetric_interval"] = {s.low_symmetric * f, s.high_symmetric * f};
  c["shortest_interval"] = {s.low_shortest * f, s.high_shortest * f};
  c["estimate"] = s.estimate * f;
  if (r.adaptive)
    c["adaptive"] = {{"delta", s.delta * f},
                     {"s_mean", s.s_mean * f},
                     {"s_std_dev", s.s_std_dev * f},
                     {"s_low", s.s_low * f},
                     {"s_high", s.s_high * f}};
  c["lpu"] = {{"std_uncertainty", s.lpu_std * f},
              {"expanded_uncertainty", s.lpu_expanded * f},
              {"d_low", s.d_low * f},
              {"d_high", s.d_high * f},
              {"delta", s.validation_delta * f},
              {"validated", s.validated}};
  const ValidationDiagnosis d = validation_diagnosis(s, r.trials);
  c["lpu"]["interval_end_std_error"] = s.interval_end_std_error * f;
  c["lpu"]["explained_by_sampling"] = d.explained_by_sampling;
  c["lpu"]["trials_needed"] = d.trials_needed;
  c["histogram"] = {{"lowest", s.histogram.lowest * f},
                    {"highest", s.histogram.highest * f},
                    {"bin_width", s.histogram.bin_width() * f},
                    {"counts", s.histogram.counts}};
  return c;
}

std::string json_of(const Config& cfg, const BudgetDetail& b, const MonteCarloDetail& r) {
  nlohmann::ordered_json j;
  j["command"] = "montecarlo";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = std::string(mode_name(b.mode));
  j["trials"] = r.trials;
  j["stage_trials"] = r.stage_trials;
  j["stages"] = r.stages;
  j["adaptive"] = r.adaptive;
  j["converged"] = r.converged;
  j["significant_digits"] = r.digits;
  j["seed"] = r.seed;
  j["threads"] = r.threads;
  j["coverage_probability"] = r.coverage_probability;
  j["coverage_factor"] = r.coverage_factor;
  j["interval_points"] = r.interval_points;
  j["sample_bytes"] = r.sample_bytes;
  j["wall_time_s"] = r.seconds;
  j["trials_per_s"] = per_second(r);
  j["terms"] = b.coefficients;
  if (nlohmann::ordered_json ic = budget_parts::input_correlation_json(b); !ic.is_null())
    j["input_correlation"] = std::move(ic);  // drawn through the Gaussian copula (docs/model.md §10.2)
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.outputs.size(); ++k)
    coefficients[r.outputs[k].name] = mc_coefficient_json(b, r, k);
  j["coefficients"] = coefficients;
  // Covariance in the display units (the scales of both coefficients), correlation as it is.
  nlohmann::ordered_json cov = nlohmann::ordered_json::array(), corr = nlohmann::ordered_json::array();
  for (Eigen::Index a = 0; a < r.covariance.rows(); ++a) {
    nlohmann::ordered_json rc = nlohmann::ordered_json::array(), rr = nlohmann::ordered_json::array();
    for (Eigen::Index c = 0; c < r.covariance.cols(); ++c) {
      rc.push_back(r.covariance(a, c) * b.display_scale[std::size_t(a)] * b.display_scale[std::size_t(c)]);
      rr.push_back(r.correlation(a, c));
    }
    cov.push_back(rc);
    corr.push_back(rr);
  }
  j["covariance"] = cov;
  j["correlation"] = corr;
  j["notes"] = detail::lines_of(r.notes);
  return j.dump(2) + "\n";
}

std::string csv_of(const BudgetDetail& b, const MonteCarloDetail& r) {
  std::string out =
      "coefficient,unit,mean,std_dev,low_symmetric,high_symmetric,low_shortest,high_shortest,estimate,"
      "lpu_std,lpu_expanded,d_low,d_high,validation_delta,validated\n";
  for (std::size_t k = 0; k < r.outputs.size(); ++k) {
    const OutputSummary& s = r.outputs[k];
    const double f = b.display_scale[k];
    out += fmt::format(
        "{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
        "{:.17g},{:.17g},{}\n",
        s.name, b.units[k], s.mean * f, s.std_dev * f, s.low_symmetric * f, s.high_symmetric * f,
        s.low_shortest * f, s.high_shortest * f, s.estimate * f, s.lpu_std * f, s.lpu_expanded * f,
        s.d_low * f, s.d_high * f, s.validation_delta * f, s.validated ? "true" : "false");
  }
  return out;
}

}  // namespace

std::string text(const verbs::MonteCarloResult& r) { return text_of(r.config, r.budget, r.monte_carlo); }
std::string json(const verbs::MonteCarloResult& r) { return json_of(r.config, r.budget, r.monte_carlo); }
std::string csv(const verbs::MonteCarloResult& r) { return csv_of(r.budget, r.monte_carlo); }
std::vector<std::string> validation_advice_lines(const verbs::MonteCarloResult& r) {
  return advice_of(r.budget, r.monte_carlo);
}

}  // namespace ccal::render

#include "ccal/reduction/observability.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "text_lists.hpp"

namespace ccal {
namespace {

using Index = Eigen::Index;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// The regressor of a term as written in messages, and its unit.
std::string regressor_text(const TermSpec& t) {
  switch (t.kind) {
    case TermKind::power:
      return t.power == 0 ? "1" : t.power == 1 ? "<a_i>" : fmt::format("<a_i^{}>", t.power);
    case TermKind::abs_square:
      return "<|a_i| a_i>";
    case TermKind::p:
      return "<a_p>";
    case TermKind::o:
      return "<a_o>";
    case TermKind::ip:
      return "<a_i a_p>";
    case TermKind::io:
      return "<a_i a_o>";
    case TermKind::pp:
      return "<a_p^2>";
    case TermKind::oo:
      return "<a_o^2>";
    case TermKind::po:
      return "<a_p a_o>";
    case TermKind::rate:
      return "<w_IA>";
  }
  return "";
}

std::string regressor_unit(const TermSpec& t) {
  if (t.kind == TermKind::rate) return "rad/s";
  const int d = term_degree(t);
  return d == 0 ? "" : d == 1 ? " g" : fmt::format(" g^{}", d);
}

void validate(const ObservabilityProblem& p) {
  const Index rows = p.H.rows();
  if (rows == 0 && p.H.cols() > 0)
    throw std::invalid_argument("assess_observability: the design has no rows");
  if (static_cast<Index>(p.terms.size()) != p.H.cols())
    throw std::invalid_argument(
        fmt::format("assess_observability: {} terms for {} columns", p.terms.size(), p.H.cols()));
  if (static_cast<Index>(p.other_terms.size()) != p.others.cols() ||
      (p.others.cols() > 0 && p.others.rows() != rows))
    throw std::invalid_argument("assess_observability: other_terms and others do not match the design");
  if (!p.runs.empty() && static_cast<Index>(p.runs.size()) != rows)
    throw std::invalid_argument(
        fmt::format("assess_observability: {} runs described for {} rows", p.runs.size(), rows));
  if (p.reference.size() != 0 && p.reference.size() != p.H.cols())
    throw std::invalid_argument("assess_observability: one reference value per term, or none");
  for (const auto& id : p.terms)
    if (!parse_term(id))
      throw std::invalid_argument(fmt::format("assess_observability: '{}' is not a term id", id));
  for (const auto& id : p.other_terms)
    if (!parse_term(id))
      throw std::invalid_argument(fmt::format("assess_observability: '{}' is not a term id", id));
  if (!p.H.allFinite() || !p.others.allFinite())
    throw std::invalid_argument("assess_observability: the design has non-finite entries");
  const auto bad = [](double v) { return !(std::isfinite(v) && v >= 0); };
  if (bad(p.noise_density) || bad(p.quantum))
    throw std::invalid_argument("assess_observability: noise density and quantum must be finite and >= 0");
  for (const auto& r : p.runs)
    if (bad(r.duration) || bad(r.input_scale) || bad(r.rate_scale) || bad(r.output_magnitude) ||
        bad(r.extra_sigma) || !std::isfinite(r.platform_turns))
      throw std::invalid_argument("assess_observability: a run has a negative or non-finite entry");
}

// Magnitude of the input in each run [g]: given, or the largest |⟨regressor⟩|^(1/degree) over the columns of
// degree ≥ 1 in the inputs (|⟨x^d⟩| ≤ max|x|^d, so this never exceeds the true magnitude); 1 g if nothing
// tells.
Eigen::VectorXd input_scales(const ObservabilityProblem& p) {
  const Index rows = p.H.rows();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(rows);
  const auto scan = [&](const std::vector<std::string>& ids, const Eigen::MatrixXd& cols, Index j) {
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const TermSpec t = parse_term(ids[k]).value();
      const int d = term_degree(t);
      if (t.kind == TermKind::rate || d == 0) continue;
      x(j) = std::max(x(j), std::pow(std::abs(cols(j, static_cast<Index>(k))), 1.0 / d));
    }
  };
  for (Index j = 0; j < rows; ++j) {
    const double given = p.runs.empty() ? 0.0 : p.runs[static_cast<std::size_t>(j)].input_scale;
    if (given > 0) {
      x(j) = given;
      continue;
    }
    scan(p.terms, p.H, j);
    scan(p.other_terms, p.others, j);
    if (!(x(j) > 0)) x(j) = 1.0;
  }
  return x;
}

// σ_j of each run mean (header): noise, quantum, floating-point resolution and any other scatter.
Eigen::VectorXd resolutions(const ObservabilityProblem& p, const ObservabilityOptions& o) {
  const Index rows = p.H.rows();
  Eigen::VectorXd sigma = Eigen::VectorXd::Zero(rows);
  for (Index j = 0; j < rows; ++j) {
    if (p.runs.empty()) continue;
    const RunResolutionInfo& r = p.runs[static_cast<std::size_t>(j)];
    double var = 0;
    if (r.duration > 0) {
      const double noise = p.noise_density / std::sqrt(r.duration);
      const double quantum = p.quantum / (r.duration * std::sqrt(12.0));
      var += noise * noise + quantum * quantum;
    }
    const double rounding = o.rounding_ulps * kEpsilon * r.output_magnitude;
    var += rounding * rounding + r.extra_sigma * r.extra_sigma;
    sigma(j) = std::sqrt(var);
  }
  return sigma;
}

// The part of column k of a that the other columns cannot explain, and the coefficients (per unit-norm other
// column) of what they do explain. Least squares on the column-scaled others, with one step of refinement.
struct Projection {
  Eigen::VectorXd residual;
  Eigen::VectorXd weights;  // per other column (unit-norm scale), in the order of the columns without k
};

Projection project_out_others(const Eigen::MatrixXd& a, Index k) {
  const Index rows = a.rows(), m = a.cols();
  Projection p;
  p.residual = a.col(k);
  p.weights = Eigen::VectorXd::Zero(m - 1);
  if (m == 1) return p;
  Eigen::MatrixXd others(rows, m - 1);
  for (Index c = 0, o = 0; c < m; ++c) {
    if (c == k) continue;
    const double norm = a.col(c).norm();
    others.col(o++) = norm > 0 ? (a.col(c) / norm).eval() : a.col(c);
  }
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(others);
  for (int step = 0; step < 2; ++step) {
    const Eigen::VectorXd c = cod.solve(p.residual);
    p.weights += c;
    p.residual -= others * c;
  }
  return p;
}

std::string vanishing_reason(const TermSpec& t, const std::string& id, double largest_mean,
                             double largest_natural, bool whole_revolutions) {
  const std::string unit = regressor_unit(t);
  std::string reason = fmt::format(
      "its regressor {} averages to round-off in every run (|{}| <= {:.2g}{} while the integrand reaches "
      "{:.2g}{})",
      regressor_text(t), regressor_text(t), largest_mean, unit, largest_natural, unit);
  (void)id;
  if (whole_revolutions) {
    const bool odd_power = t.kind == TermKind::power && t.power % 2 == 1;
    reason += odd_power ? ": every run lasts a whole number of platform revolutions on a counter-rotating "
                          "platform, over which odd powers of a_i = -A cos(gamma) average to zero"
                        : ": every run lasts a whole number of platform revolutions on a counter-rotating "
                          "platform, over which it averages to zero";
  }
  return reason;
}

// Term k's regressor at its natural size: the input to its degree (x^n), or for a rate term the run's rate
// scale (else |H|), so that `fraction` compares what only it explains with its own size.
Eigen::VectorXd natural_regressor(const ObservabilityProblem& p, Index k, const TermSpec& spec, int degree,
                                  const Eigen::VectorXd& x) {
  const Index rows = p.H.rows();
  Eigen::VectorXd natural(rows);
  for (Index j = 0; j < rows; ++j) {
    if (spec.kind == TermKind::rate) {
      const double w = p.runs.empty() ? 0.0 : p.runs[static_cast<std::size_t>(j)].rate_scale;
      natural(j) = w > 0 ? w : std::abs(p.H(j, k));
    } else {
      natural(j) = std::pow(x(j), degree);
    }
  }
  return natural;
}

// Why term k cannot be told from the data, and what would: its column vanishes (averaged out by the plan), or
// the other terms' columns explain it (named in aliased_with).
void explain_unobservable(const ObservabilityProblem& p, Index k, const TermSpec& spec,
                          const Projection& plain, double natural_max, double limit, bool whole_revolutions,
                          TermObservability& t) {
  const Index m = p.H.cols();
  t.status = TermStatus::unobservable;
  if (!(t.column_norm > limit)) {
    t.reason =
        vanishing_reason(spec, t.term, p.H.col(k).cwiseAbs().maxCoeff(), natural_max, whole_revolutions);
    t.fix = whole_revolutions
                ? fmt::format(
                      "end the runs part-way through a revolution (change the durations so that "
                      "Omega*T/2pi is not a whole number) or fix {}",
                      t.term)
                : fmt::format(
                      "change the plan (g-levels, mountings, platform mode or durations) so that {} "
                      "does not average out, or fix {}",
                      regressor_text(spec), t.term);
  } else {
    // The column is there but the others explain it: name those that carry it.
    const double largest = plain.weights.size() ? plain.weights.cwiseAbs().maxCoeff() : 0.0;
    for (Index c = 0, other = 0; c < m; ++c) {
      if (c == k) continue;
      if (std::abs(plain.weights(other++)) > 0.1 * largest)
        t.aliased_with.push_back(p.terms[static_cast<std::size_t>(c)]);
    }
    t.reason = fmt::format(
        "its column is a combination of those of {} up to round-off (what only {} explains is {:.2g} of "
        "its size)",
        detail::join_names(t.aliased_with), t.term, t.sensitivity / t.column_norm);
    t.fix = fmt::format("add runs that separate {} from {} (other g-levels or mountings), or fix {}", t.term,
                        detail::join_names(t.aliased_with), t.term);
  }
}

}  // namespace

std::string_view term_status_name(TermStatus status) noexcept {
  switch (status) {
    case TermStatus::ok:
      return "ok";
    case TermStatus::weak:
      return "weak";
    case TermStatus::unobservable:
      return "unobservable";
  }
  return "";
}

int term_degree(const TermSpec& term) {
  switch (term.kind) {
    case TermKind::power:
      return term.power;
    case TermKind::p:
    case TermKind::o:
    case TermKind::rate:
      return 1;
    default:
      return 2;
  }
}

const TermObservability* ObservabilityResult::first(TermStatus status) const {
  for (const auto& t : terms)
    if (t.status == status) return &t;
  return nullptr;
}

ObservabilityResult assess_observability(const ObservabilityProblem& p, const ObservabilityOptions& o) {
  validate(p);
  const Index rows = p.H.rows(), m = p.H.cols();
  ObservabilityResult result;
  result.detection_factor = o.detection_factor;
  result.resolution = resolutions(p, o);
  result.whole_revolutions = !p.runs.empty() && std::all_of(p.runs.begin(), p.runs.end(), [&](const auto& r) {
    return r.counter_rotating && r.platform_turns > 0 &&
           std::abs(r.platform_turns - std::round(r.platform_turns)) <= o.whole_turn_tolerance;
  });
  const Eigen::VectorXd x = input_scales(p);

  // σ-weighted design for the standard errors. A run of zero resolution counts with the smallest positive
  // one; if no run has a resolution, nothing limits the detection (u = 0).
  const bool resolved = rows > 0 && result.resolution.maxCoeff() > 0;
  Eigen::MatrixXd weighted = p.H;
  if (resolved) {
    const double floor =
        (result.resolution.array() > 0).select(result.resolution, result.resolution.maxCoeff()).minCoeff();
    for (Index j = 0; j < rows; ++j) weighted.row(j) /= std::max(result.resolution(j), floor);
  }

  for (Index k = 0; k < m; ++k) {
    TermObservability t;
    t.term = p.terms[static_cast<std::size_t>(k)];
    const TermSpec spec = parse_term(t.term).value();
    t.degree = term_degree(spec);
    const Eigen::VectorXd natural = natural_regressor(p, k, spec, t.degree, x);
    t.column_norm = p.H.col(k).norm();
    t.natural_norm = natural.norm();
    const Projection plain = project_out_others(p.H, k);
    t.sensitivity = plain.residual.norm();
    t.fraction = t.natural_norm > 0 ? t.sensitivity / t.natural_norm : 0.0;
    const double weighted_sensitivity = project_out_others(weighted, k).residual.norm();
    t.standard_error = !resolved                  ? 0.0
                       : weighted_sensitivity > 0 ? 1.0 / weighted_sensitivity
                                                  : std::numeric_limits<double>::infinity();
    t.min_detectable = o.detection_factor * t.standard_error;

    const double limit = o.roundoff_fraction * t.natural_norm;
    if (!(t.sensitivity > limit) || !std::isfinite(t.standard_error)) {
      explain_unobservable(p, k, spec, plain, natural.maxCoeff(), limit, result.whole_revolutions, t);
    } else if (p.reference.size() != 0 && p.reference(k) != 0 &&
               std::abs(p.reference(k)) < t.min_detectable) {
      t.status = TermStatus::weak;
      t.reason = fmt::format("the smallest change the plan can detect ({:.3g} sigma) exceeds the coefficient",
                             o.detection_factor);
      t.fix = "longer runs, a quieter instrument, higher g-levels or more runs";
    }
    result.terms.push_back(std::move(t));
  }
  return result;
}

ObservabilityProblem observability_problem(const Observations<double>& obs, const IdentificationSpec& spec,
                                           const InstrumentModel& instrument, const std::vector<Run>& runs,
                                           const std::vector<double>& rates) {
  if (runs.size() != std::size_t(obs.output.size()) || rates.size() != runs.size())
    throw std::invalid_argument("observability_problem: one run and one rate per observation");
  ObservabilityProblem p;
  const auto nfree = static_cast<Index>(spec.free_terms.size());
  p.terms.assign(obs.columns.begin(), obs.columns.begin() + nfree);
  p.H = obs.regressors.leftCols(nfree);
  p.other_terms.assign(obs.columns.begin() + nfree, obs.columns.end());
  p.others = obs.regressors.rightCols(obs.regressors.cols() - nfree);
  p.noise_density = instrument.noise_density;
  p.quantum = instrument.quantum;
  const std::vector<TermSpec> terms = instrument.terms();
  for (std::size_t j = 0; j < runs.size(); ++j) {
    RunResolutionInfo r;
    r.duration = runs[j].duration;
    // The specific force of a run at g-level A: the centripetal A g and gravity, √(A² + 1) g.
    r.input_scale = std::hypot(runs[j].g_level, 1.0);
    r.rate_scale = std::abs(rates[j]);
    r.counter_rotating = runs[j].mode == PlatformMode::counter_rotating;
    r.platform_turns = r.counter_rotating ? r.rate_scale * r.duration / (2 * std::numbers::pi) : 0.0;
    double bound =
        std::abs(obs.output[static_cast<Index>(j)]) + std::abs(instrument.rate_gain) * r.rate_scale;
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const double c = std::abs(instrument.coefficients[static_cast<Index>(k)]);
      bound += terms[k].kind == TermKind::rate ? c * r.rate_scale
                                               : c * std::pow(r.input_scale, term_degree(terms[k]));
    }
    r.output_magnitude = bound;
    p.runs.push_back(r);
  }
  return p;
}

std::string unobservable_message(const TermObservability& term) {
  return fmt::format("the test plan cannot observe {}: {}; {}", term.term, term.reason, term.fix);
}

}  // namespace ccal

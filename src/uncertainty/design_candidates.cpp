#include "ccal/uncertainty/design_candidates.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>

#include "ccal/core/constants.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/reduction/observability.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/setup/input_correlation.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/rate_noise.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ccal {

namespace {

constexpr double kTurn = 2 * std::numbers::pi;

std::vector<double> circle_grid(double step) {
  const int m = std::max(1, int(std::lround(kTurn / step)));
  std::vector<double> out;
  for (int k = 0; k < m; ++k) out.push_back(kTurn * k / m);
  return out;
}

template <class T>
std::vector<T> distinct(const std::vector<T>& v) {
  std::vector<T> out;
  for (const T& x : v)
    if (std::find(out.begin(), out.end(), x) == out.end()) out.push_back(x);
  return out;
}

// The platform's turn period 2π/Ω of a run at g-level A [s].
double turn_period(double g_level, const Config& config) {
  Run r;
  r.g_level = g_level;
  return kTurn / nominal_rate(r, config.centrifuge.geometry, config.site);
}

void resolve_g_levels(const Config& config, ResolvedDesignSpace& s) {
  const DesignSpace& d = config.design;
  const std::vector<Run>& plan = config.plan.runs;
  double g_lo = plan.front().g_level, g_hi = g_lo;
  for (const Run& r : plan) {
    g_lo = std::min(g_lo, r.g_level);
    g_hi = std::max(g_hi, r.g_level);
  }
  s.max_g = d.max_g.value_or(g_hi);
  auto above = [&](double g, std::string_view key) {
    throw InputError(
        fmt::format("{}: design.{}: {:g} g exceeds max_g = {:g} g (the machine's largest g-level{}); "
                    "accepted: g-levels up "
                    "to max_g, or a larger max_g",
                    config.source, key, g, s.max_g, d.max_g ? "" : ", by default the plan's largest"));
  };
  if (!d.g_levels.empty()) {
    for (double g : d.g_levels)
      if (g > s.max_g) above(g, "g_levels");
    s.g_levels = distinct(d.g_levels);
    std::sort(s.g_levels.begin(), s.g_levels.end());
    s.fixed.push_back(fmt::format("g-levels from design.g_levels ({} levels)", s.g_levels.size()));
    return;
  }
  const double lo = d.g_min.value_or(g_lo);
  const double hi = d.g_max.value_or(std::min(g_hi, s.max_g));
  if (hi > s.max_g) above(hi, "g_range");
  if (lo > hi) above(lo, "g_range");
  const double step = d.g_step.value_or(hi > lo ? (hi - lo) / 25 : 1.0);
  for (int k = 0;; ++k) {
    const double g = lo + k * step;
    if (g > hi * (1 + 1e-12)) break;
    s.g_levels.push_back(std::min(g, hi));
    if (k > 100000)
      throw InputError(
          fmt::format("{}: design.g_step: {:g} g makes more than 1e5 g-levels; accepted: a "
                      "coarser step such as 1 g",
                      config.source, step));
  }
  if (s.g_levels.back() < hi * (1 - 1e-12)) s.g_levels.push_back(hi);
  if (s.g_levels.size() > 1) {
    s.refinement.g_step = step / 2;
    s.refinement.g_low = lo;
    s.refinement.g_high = hi;
  }
  s.free.push_back(fmt::format("g-level in [{:g} g, {:g} g] (grid step {:g} g)", lo, hi, step));
}

void resolve_timing(const Config& config, ResolvedDesignSpace& s) {
  const DesignSpace& d = config.design;
  double total = 0;
  for (const Run& r : config.plan.runs) total += r.duration;
  s.total_time = d.total_time.value_or(total);
  s.durations = d.durations.empty() ? std::vector<double>{s.total_time / s.runs} : distinct(d.durations);
  s.turn_fractions = d.turn_fractions.value_or(8);
  const double longest_period = turn_period(s.g_levels.front(), config);
  const double shortest = *std::min_element(s.durations.begin(), s.durations.end());
  const double longest = *std::max_element(s.durations.begin(), s.durations.end());
  // A candidate lasts whole turns of its nominal duration less k/n of a turn: at least a turn shorter.
  const double least = s.turn_fractions > 0 ? std::max(shortest - longest_period, 0.0) : shortest;
  if (s.runs * least > s.total_time * (1 + 1e-12))
    throw InputError(fmt::format(
        "{}: design: {} runs of at least {:g} s (design.durations) cannot fit total_time = {:g} s; accepted: "
        "shorter durations, fewer runs or a longer total_time",
        config.source, s.runs, least, s.total_time));
  if (s.turn_fractions > 0 && shortest <= longest_period)
    throw InputError(fmt::format(
        "{}: design.durations: {:g} s is shorter than a turn at the lowest g-level ({:g} s); accepted: "
        "durations of at least one turn, or turn_fractions = 0",
        config.source, shortest, longest_period));
  if (s.turn_fractions > 0) {
    s.refinement.duration_step =
        turn_period(s.g_levels[s.g_levels.size() / 2], config) / (2.0 * s.turn_fractions);
    s.refinement.duration_low = least;
    s.refinement.duration_high = longest;
    s.free.push_back(
        fmt::format("durations: whole turns of {} s less k/{} of a turn, the total at most {:g} s",
                    fmt::join(s.durations, " s, "), s.turn_fractions, s.total_time));
  } else {
    s.fixed.push_back(fmt::format("durations {} s, the total at most {:g} s", fmt::join(s.durations, " s, "),
                                  s.total_time));
  }
}

// What the machine sets ([design] g_resolution, duration_resolution) must be finer than the smallest g-level
// and the shortest run the design may choose: the rounding keeps a setting at one step at least, so a coarser
// step would raise every run to it (past max_g, past the total time).
void resolve_resolutions(const Config& config, const ResolvedDesignSpace& s) {
  const SettingResolution res = setting_resolution(config.design);
  const double lowest_g = *std::min_element(s.g_levels.begin(), s.g_levels.end());
  if (res.g > lowest_g * (1 + 1e-12))
    throw InputError(
        fmt::format("{}: design.g_resolution: {:g} g is coarser than the lowest g-level the design "
                    "may choose ({:g} g); accepted: at most {:g} g, such as \"0.01 g\"",
                    config.source, res.g, lowest_g, lowest_g));
  const double shortest = s.turn_fractions > 0 ? s.refinement.duration_low
                                               : *std::min_element(s.durations.begin(), s.durations.end());
  if (res.duration > shortest * (1 + 1e-12))
    throw InputError(
        fmt::format("{}: design.duration_resolution: {:g} s is coarser than the shortest run the design may "
                    "choose ({:g} s); "
                    "accepted: at most {:g} s, such as \"1 ms\"",
                    config.source, res.duration, shortest, shortest));
}

void resolve_angles(const Config& config, ResolvedDesignSpace& s) {
  const DesignSpace& d = config.design;
  const Run& first = config.plan.runs.front();
  s.phase = d.phase.value_or(first.terminal_phase ? DesignPhase::terminal : DesignPhase::initial);
  const char* phase_name = s.phase == DesignPhase::terminal ? "terminal phase" : "initial phase";
  if (!d.phases.empty()) {
    s.phases = distinct(d.phases);
    s.fixed.push_back(fmt::format("{} from design.phases ({} values)", phase_name, s.phases.size()));
  } else {
    const double step = d.phase_step.value_or(30 * constants::deg);
    s.phases = circle_grid(step);
    s.refinement.phase_step = kTurn / double(s.phases.size()) / 2;
    s.free.push_back(fmt::format("{} (grid of {} over a turn)", phase_name, s.phases.size()));
  }
  if (!d.arm_azimuths.empty()) {
    s.arm_azimuths = distinct(d.arm_azimuths);
    s.fixed.push_back(
        fmt::format("arm azimuths from design.arm_azimuths ({} values)", s.arm_azimuths.size()));
  } else {
    s.arm_azimuths = circle_grid(d.azimuth_step.value_or(90 * constants::deg));
    s.refinement.azimuth_step = kTurn / double(s.arm_azimuths.size()) / 2;
    s.free.push_back(fmt::format("arm azimuth (grid of {} over a turn)", s.arm_azimuths.size()));
  }
  std::vector<Mounting> mountings;
  std::vector<PlatformMode> platforms;
  for (const Run& r : config.plan.runs) {
    mountings.push_back(r.mounting);
    platforms.push_back(r.mode);
  }
  s.mountings = d.mountings.empty() ? distinct(mountings) : d.mountings;
  s.platforms = d.platforms.empty() ? distinct(platforms) : d.platforms;
  std::vector<std::string> m, p;
  for (Mounting x : s.mountings) m.emplace_back(mounting_name(x));
  for (PlatformMode x : s.platforms) p.emplace_back(platform_mode_name(x));
  (d.mountings.empty() ? s.fixed : s.free).push_back(fmt::format("mounting {}", fmt::join(m, ", ")));
  (d.platforms.empty() ? s.fixed : s.free).push_back(fmt::format("platform {}", fmt::join(p, ", ")));
}

// The distinct g-levels a plan keeps: by default one more than the free terms, so that the fit's residuals
// have a degree of freedom across g-levels and can show a term of the instrument's g-dependence that the
// model lacks (an unmodelled K1 or K4 leaves a pattern no combination of the free terms' columns absorbs).
void resolve_min_g_levels(const Config& config, ResolvedDesignSpace& s) {
  const DesignSpace& d = config.design;
  const auto nfree = int(config.identification.free_terms.size());
  s.min_g_levels = d.min_g_levels.value_or(nfree + 1);
  const int most = std::min(s.runs, int(s.g_levels.size()));
  if (s.min_g_levels > most) {
    const std::string why = fmt::format("{} runs over {} allowed g-levels give at most {} distinct g-levels",
                                        s.runs, s.g_levels.size(), most);
    if (d.min_g_levels)
      throw InputError(
          fmt::format("{}: design.min_g_levels: {} but {}; accepted: at most {}, or more runs or "
                      "g-levels",
                      config.source, s.min_g_levels, why, most));
    throw InputError(
        fmt::format("{}: design: {}, but a test of the fit of {} free terms ({}) for a missing term needs {} "
                    "(the default of "
                    "design.min_g_levels: free terms + 1); accepted: design.runs and the allowed g-levels at "
                    "least {}, or "
                    "design.min_g_levels = {} to design without that test",
                    config.source, why, nfree, fmt::join(config.identification.free_terms, ", "),
                    s.min_g_levels, s.min_g_levels, most));
  }
  if (s.min_g_levels > 1)
    s.fixed.push_back(
        d.min_g_levels
            ? fmt::format("at least {} distinct g-levels (design.min_g_levels)", s.min_g_levels)
            : fmt::format(
                  "at least {} distinct g-levels ({} free terms + 1, so that the residuals can show a "
                  "term the model lacks)",
                  s.min_g_levels, nfree));
}

}  // namespace

ResolvedDesignSpace resolve_design_space(const Config& config) {
  if (config.plan.runs.empty())
    throw InputError(config.source + ": the plan has no runs to start a design from");
  ResolvedDesignSpace s;
  const auto nfree = int(config.identification.free_terms.size());
  s.runs = config.design.runs.value_or(int(config.plan.runs.size()));
  if (s.runs < nfree)
    throw InputError(
        fmt::format("{}: design.runs: {} runs cannot identify {} free terms ({}); accepted: at least {} runs",
                    config.source, s.runs, nfree, fmt::join(config.identification.free_terms, ", "), nfree));
  resolve_g_levels(config, s);
  resolve_timing(config, s);
  resolve_resolutions(config, s);
  resolve_angles(config, s);
  resolve_min_g_levels(config, s);
  // Each refinement step evaluates up to 8 trial runs per run (the cache's cost per run): a few halvings
  // (steps down to 1/32 of the grid's) and a bounded number of moves keep it to seconds.
  s.refinement.halvings = 5;
  s.refinement.max_moves = 30;
  if (!config.design.refine) s.refinement = Refinement{};
  return s;
}

std::vector<DesignRun> candidate_runs(const ResolvedDesignSpace& s, const Config& config) {
  std::vector<DesignRun> out;
  for (PlatformMode platform : s.platforms)
    for (Mounting mounting : s.mountings)
      for (double g : s.g_levels) {
        const double period = turn_period(g, config);
        std::vector<double> durations;
        for (double nominal : s.durations) {
          if (s.turn_fractions == 0) {
            durations.push_back(nominal);
            continue;
          }
          const double whole = std::floor(nominal / period) * period;
          for (int k = 0; k < s.turn_fractions; ++k)
            durations.push_back(whole - period * k / s.turn_fractions);
        }
        for (double duration : durations)
          for (double phase : s.phases)
            for (double azimuth : s.arm_azimuths)
              out.push_back({g, duration, phase, azimuth, s.phase, mounting, platform});
      }
  return out;
}

DesignRun design_run(const Run& run) {
  DesignRun d;
  d.g_level = run.g_level;
  d.duration = run.duration;
  d.phase_kind = run.terminal_phase ? DesignPhase::terminal : DesignPhase::initial;
  d.phase = run.terminal_phase ? *run.terminal_phase : run.initial_phase.value_or(0.0);
  d.arm_azimuth = run.arm_azimuth;
  d.mounting = run.mounting;
  d.platform = run.mode;
  return d;
}

Run plan_run(const DesignRun& d, std::string name) {
  Run r;
  r.name = std::move(name);
  r.g_level = d.g_level;
  r.duration = d.duration;
  r.mode = d.platform;
  // Angles in [0, 2π), so that a plan written out reads back as the same numbers.
  auto wrap = [](double a) {
    const double w = std::fmod(a, kTurn);
    return w < 0 ? w + kTurn : w;
  };
  (d.phase_kind == DesignPhase::terminal ? r.terminal_phase : r.initial_phase) = wrap(d.phase);
  r.arm_azimuth = wrap(d.arm_azimuth);
  r.mounting = d.mounting;
  return r;
}

SettingResolution setting_resolution(const DesignSpace& design) {
  SettingResolution r;
  r.g = design.g_resolution.value_or(r.g);
  r.duration = design.duration_resolution.value_or(r.duration);
  r.angle = design.angle_resolution.value_or(r.angle);
  return r;
}

namespace {

// A count of steps as its shortest decimal with the unit, read back as a configuration reads it.
double as_written(double steps, double step, const char* unit) {
  return parse_quantity(fmt::format("{:.12g} {}", steps * step, unit)).value_si;
}

// An angle in [0, 2π) to the nearest step, as written in degrees.
double rounded_angle(double radians, double step) {
  const double degrees = std::fmod(std::fmod(radians, kTurn) + kTurn, kTurn) * 180 / std::numbers::pi;
  const double step_deg = step * 180 / std::numbers::pi;
  double k = std::round(degrees / step_deg);
  if (k * step_deg >= 360 - 1e-9) k = 0;
  return as_written(k, step_deg, "deg");
}

}  // namespace

Run rounded_run(const Run& run, const SettingResolution& res, double max_g) {
  Run r = run;
  double k = std::round(run.g_level / res.g);
  if (k * res.g > max_g * (1 + 1e-12)) k -= 1;
  r.g_level = as_written(std::max(k, 1.0), res.g, "g");
  r.duration = as_written(std::max(std::floor(run.duration / res.duration + 1e-9), 1.0), res.duration, "s");
  if (r.terminal_phase) r.terminal_phase = rounded_angle(*r.terminal_phase, res.angle);
  if (r.initial_phase) r.initial_phase = rounded_angle(*r.initial_phase, res.angle);
  r.arm_azimuth = rounded_angle(run.arm_azimuth, res.angle);
  return r;
}

namespace {

// The rows of one block of runs: model means as observe() takes them, ∂ȳ/∂e as the budget takes it.
CandidateRows block_rows(const Config& config, const Experiment& base, const std::vector<DesignRun>& runs,
                         const std::vector<int>& parameters, const Eigen::MatrixXd& group_map) {
  const IdentificationSpec& spec = config.identification;
  const Eigen::VectorXd& at = config.centrifuge.errors;
  const Eigen::VectorXd known = spec.compensate ? at : Eigen::VectorXd::Zero(at.size());
  Experiment ex = base;
  ex.plan.runs.clear();
  for (std::size_t j = 0; j < runs.size(); ++j)
    ex.plan.runs.push_back(plan_run(runs[j], fmt::format("c{}", j)));
  const auto n = Eigen::Index(runs.size());
  const auto nfree = Eigen::Index(spec.free_terms.size());
  std::vector<TermSpec> terms, free_terms;
  for (const auto& id : observation_columns(spec)) terms.push_back(parse_term(id).value());
  free_terms.assign(terms.begin(), terms.begin() + nfree);

  CandidateRows rows;
  rows.regressors.resize(n, nfree);
  rows.natural.resize(n, nfree);
  rows.duration.resize(n);
  rows.noise.resize(n);
  const double N = config.instrument.noise_density, q = config.instrument.quantum;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Run& run = ex.plan.runs[std::size_t(j)];
    const RunAverage<double> model =
        config.mode == ModelMode::exact
            ? average_run<double>(ex.geometry, ex.layout, known, ex.site, run, nullptr, terms)
            : paper_average<double>(ex, known, run, nullptr, terms, spec.paper_cross_terms);
    rows.regressors.row(j) = model.regressors.head(nfree).transpose();
    const double T = run.duration;
    rows.duration[j] = T;
    rows.noise[j] = N * N / T + q * q / (12 * T * T);  // model.md §14: (N/√T)² + (q/(T√12))²
    const double x = std::sqrt(run.g_level * run.g_level + 1);
    const double rate = nominal_rate(run, ex.geometry, ex.site);
    for (Eigen::Index k = 0; k < nfree; ++k) {
      const TermSpec& t = free_terms[std::size_t(k)];
      rows.natural(j, k) = t.kind == TermKind::rate ? rate : std::pow(x, term_degree(t));
    }
  }
  // ∂ȳ/∂e at zero errors in exact mode, by the closed-form linearisation (one dual pass for the drive columns
  // only): at the known errors the budget differentiates the whole chain by AD, one pass per 8 sources and
  // ~100× the cost, for a change of relative order |e| (≲ 1e-4) that cannot reorder plans; the designed and
  // the configured plan are scored by the full budget at the known errors before they are reported.
  const Eigen::VectorXd at_jacobian = config.mode == ModelMode::exact ? Eigen::VectorXd::Zero(at.size()) : at;
  const OutputJacobian J = output_jacobian(ex, spec, parameters, at_jacobian, config.mode, {},
                                           DerivativeMethod::linearised, false);
  rows.leaks = J.total * group_map;
  rows.scatter = Eigen::VectorXd::Zero(n);
  const double main = ex.rate_noise.main, platform = ex.rate_noise.platform;
  if (main > 0 || platform > 0) {
    const RateNoiseGains gains = rate_noise_gains(ex, at, main > 0, platform > 0);
    if (main > 0) rows.scatter += (main * gains.main).array().square().matrix();
    if (platform > 0) rows.scatter += (platform * gains.platform).array().square().matrix();
  }
  return rows;
}

// The blocks' rows one after the other, copied once into storage sized for all of them.
CandidateRows stacked(const std::vector<CandidateRows>& parts) {
  Eigen::Index n = 0;
  for (const CandidateRows& p : parts) n += p.size();
  CandidateRows all;
  if (parts.empty()) return all;
  const CandidateRows& first = parts.front();
  all.regressors.resize(n, first.regressors.cols());
  all.leaks.resize(n, first.leaks.cols());
  all.natural.resize(n, first.natural.cols());
  all.scatter.resize(n), all.noise.resize(n), all.duration.resize(n);
  Eigen::Index at = 0;
  for (const CandidateRows& p : parts) {
    const Eigen::Index k = p.size();
    all.regressors.middleRows(at, k) = p.regressors;
    all.leaks.middleRows(at, k) = p.leaks;
    all.natural.middleRows(at, k) = p.natural;
    all.scatter.segment(at, k) = p.scatter;
    all.noise.segment(at, k) = p.noise;
    all.duration.segment(at, k) = p.duration;
    at += k;
  }
  return all;
}

}  // namespace

CandidateRows candidate_rows(const Config& config, const std::vector<DesignRun>& runs, int threads,
                             const std::function<void()>& on_row) {
  const Experiment base = config.experiment();
  std::vector<int> parameters;
  for (const Tolerance& t : config.tolerances) parameters.push_back(t.parameter);
  // Scaled by u_s and added as the budget's independent components (model.md §10.1): diag(u) F, R = F Fᵀ
  // (the group indicator when only groups correlate sources).
  Eigen::MatrixXd group_map = input_correlation(config.tolerances, config.correlations).factor;
  for (std::size_t s = 0; s < config.tolerances.size(); ++s)
    group_map.row(Eigen::Index(s)) *=
        standard_uncertainty(config.tolerances[s].bound, config.tolerances[s].distribution);

  constexpr std::size_t kBlock = 32;
  const std::size_t blocks = (runs.size() + kBlock - 1) / kBlock;
  std::vector<CandidateRows> parts(blocks);
  std::exception_ptr failure;
#ifdef _OPENMP
  const int team = threads > 0 ? threads : omp_get_max_threads();
#else
  const int team = 1;
#endif
  (void)team;
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (std::size_t b = 0; b < blocks; ++b) {
    try {
      const auto first = runs.begin() + std::ptrdiff_t(b * kBlock);
      const auto last = runs.begin() + std::ptrdiff_t(std::min(runs.size(), (b + 1) * kBlock));
      parts[b] = block_rows(config, base, std::vector<DesignRun>(first, last), parameters, group_map);
      if (on_row)
        for (auto run = first; run != last; ++run) on_row();
    } catch (...) {
#pragma omp critical
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  return stacked(parts);
}

}  // namespace ccal

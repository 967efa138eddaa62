#include "ccal/uncertainty/design_search.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "ccal/core/errors.hpp"
#include "design_exchange.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ccal {

CandidateRows CandidateRows::select(const std::vector<int>& runs) const {
  CandidateRows out;
  const auto n = Eigen::Index(runs.size());
  out.regressors.resize(n, regressors.cols());
  out.leaks.resize(n, leaks.cols());
  out.scatter.resize(n);
  out.noise.resize(n);
  out.natural.resize(n, natural.cols());
  out.duration.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index c = runs[std::size_t(j)];
    out.regressors.row(j) = regressors.row(c);
    out.leaks.row(j) = leaks.row(c);
    out.scatter[j] = scatter[c];
    out.noise[j] = noise[c];
    out.natural.row(j) = natural.row(c);
    out.duration[j] = duration[c];
  }
  return out;
}

void CandidateRows::append(const CandidateRows& more) {
  if (size() == 0) {
    *this = more;
    return;
  }
  auto stack = [](Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    Eigen::MatrixXd c(a.rows() + b.rows(), a.cols());
    c << a, b;
    a = std::move(c);
  };
  auto stackv = [](Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    Eigen::VectorXd c(a.size() + b.size());
    c << a, b;
    a = std::move(c);
  };
  stack(regressors, more.regressors);
  stack(leaks, more.leaks);
  stack(natural, more.natural);
  stackv(scatter, more.scatter);
  stackv(noise, more.noise);
  stackv(duration, more.duration);
}

namespace {

// Scores plans given as indices into a set of rows, with its own workspace (one per thread).
class PlanScorer {
 public:
  explicit PlanScorer(const DesignCriterion& c) : c_(c) {}

  // The objective of rows[plan] (infinity when the plan is ill-posed); the covariance too when `full`.
  double objective(const CandidateRows& rows, const std::vector<int>& plan, PlanScore* full = nullptr) {
    const auto n = Eigen::Index(plan.size());
    const Eigen::Index p = rows.regressors.cols();
    if (n < p) return fail(full);
    H_.resize(n, p);
    nat_.resize(n, p);
    v_.resize(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index r = plan[std::size_t(j)];
      H_.row(j) = rows.regressors.row(r);
      nat_.row(j) = rows.natural.row(r);
      v_[j] = rows.noise[r];
    }
    // Column scaling, as the fit does (model.md §9): the projected norms then come from a well-scaled matrix.
    scale_.resize(p);
    for (Eigen::Index k = 0; k < p; ++k) {
      const double norm = H_.col(k).norm();
      if (!(norm > 0) || !std::isfinite(norm)) return fail(full);
      scale_[k] = 1.0 / norm;
    }
    Hs_.noalias() = H_ * scale_.asDiagonal();
    N_.noalias() = Hs_.transpose() * Hs_;
    ldlt_.compute(N_);
    if (ldlt_.info() != Eigen::Success) return fail(full);
    Ninv_ = ldlt_.solve(Eigen::MatrixXd::Identity(p, p));
    // Well posed: ‖P⊥h_k‖ = ‖h_k‖/√[N⁻¹]_kk above the round-off of its natural size, correlations below the
    // limit (model.md §14, §9).
    for (Eigen::Index k = 0; k < p; ++k) {
      const double d = Ninv_(k, k);
      if (!(d > 0) || !std::isfinite(d)) return fail(full);
      const double projected = 1.0 / (scale_[k] * std::sqrt(d));
      if (!(projected > c_.roundoff_fraction * nat_.col(k).norm())) return fail(full);
      for (Eigen::Index l = 0; l < k; ++l)
        if (std::abs(Ninv_(k, l)) > c_.max_correlation * std::sqrt(d * Ninv_(l, l))) return fail(full);
    }
    if (c_.objective == DesignObjective::uncertainty) return uncertainty(rows, plan, full);
    return noise_alone(full);
  }

 private:
  double fail(PlanScore* full) const {
    if (full) *full = PlanScore{};
    return std::numeric_limits<double>::infinity();
  }

  double uncertainty(const CandidateRows& rows, const std::vector<int>& plan, PlanScore* full) {
    const auto n = Eigen::Index(plan.size());
    const Eigen::Index p = H_.cols();
    // H⁺ = S (Hsᵀ Hs)⁻¹ Hsᵀ with S the column scales.
    pinv_.noalias() = scale_.asDiagonal() * (Ninv_ * Hs_.transpose());
    L_.resize(n, rows.leaks.cols());
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index r = plan[std::size_t(j)];
      L_.row(j) = rows.leaks.row(r);
      v_[j] = rows.scatter[r] + rows.noise[r];
    }
    A_.noalias() = pinv_ * L_;
    double f = 0;
    for (Eigen::Index k = 0; k < p; ++k) {
      if (!(c_.weight[k] > 0) && !full) continue;
      const double var =
          A_.row(k).squaredNorm() + (pinv_.row(k).array().square() * v_.transpose().array()).sum();
      if (c_.weight[k] > 0)
        f += c_.weight[k] * c_.coverage_factor * c_.coverage_factor * var /
             (c_.reference[k] * c_.reference[k]);
    }
    if (full) {
      full->well_posed = true;
      full->objective = f;
      full->covariance = A_ * A_.transpose() + pinv_ * v_.asDiagonal() * pinv_.transpose();
      full->expanded = c_.coverage_factor * full->covariance.diagonal().cwiseSqrt();
    }
    return f;
  }

  // D- and A-optimality with the instrument's noise alone: information Hᵀ W H, W = diag(1/σ_j²), or I when
  // the instrument has no noise.
  double noise_alone(PlanScore* full) {
    const Eigen::Index p = H_.cols();
    const bool unit = !(v_.maxCoeff() > 0);
    if (!unit && !(v_.minCoeff() > 0)) return fail(full);
    w_ = unit ? Eigen::VectorXd::Ones(v_.size()) : Eigen::VectorXd(v_.cwiseInverse());
    N_.noalias() = Hs_.transpose() * w_.asDiagonal() * Hs_;
    ldlt_.compute(N_);
    if (ldlt_.info() != Eigen::Success || !(ldlt_.vectorD().minCoeff() > 0)) return fail(full);
    Ninv_ = scale_.asDiagonal() * ldlt_.solve(Eigen::MatrixXd::Identity(p, p)) * scale_.asDiagonal();
    double f = 0;
    if (c_.objective == DesignObjective::d_optimal) {
      // ln det(HᵀWH) = ln det(Hsᵀ W Hs) − 2 Σ ln s_k.
      f = -(ldlt_.vectorD().array().log().sum() - 2 * scale_.array().log().sum());
    } else {
      for (Eigen::Index k = 0; k < p; ++k)
        if (c_.weight[k] > 0) f += c_.weight[k] * Ninv_(k, k) / (c_.reference[k] * c_.reference[k]);
    }
    if (full) {
      full->well_posed = true;
      full->objective = f;
      full->covariance = Ninv_;
      full->expanded = c_.coverage_factor * Ninv_.diagonal().cwiseSqrt();
    }
    return f;
  }

  const DesignCriterion& c_;
  Eigen::MatrixXd H_, Hs_, nat_, N_, Ninv_, pinv_, L_, A_;
  Eigen::VectorXd v_, w_, scale_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};

// Scores a plan for every instrument of a problem and combines the objectives (joint_objective); for one
// instrument, its PlanScorer's objective itself.
class JointScorer {
 public:
  explicit JointScorer(const DesignProblem& pr) : pr_(pr), f_(1 + pr.others.size()) {
    scorers_.reserve(f_.size());
    scorers_.emplace_back(pr.criterion);
    for (const DesignInstrument& o : pr.others) scorers_.emplace_back(o.criterion);
  }
  // The plan of candidates, by every instrument's rows of them.
  double objective(const std::vector<int>& plan) {
    if (pr_.others.empty()) return scorers_[0].objective(pr_.rows, plan);
    for (std::size_t i = 0; i < f_.size(); ++i)
      if (!std::isfinite(f_[i] = scorers_[i].objective(i == 0 ? pr_.rows : pr_.others[i - 1].rows, plan)))
        return std::numeric_limits<double>::infinity();
    return joint_objective(pr_, f_);
  }
  // The plan of rows[i][plan] for instrument i.
  double objective(const std::vector<CandidateRows>& rows, const std::vector<int>& plan) {
    if (pr_.others.empty()) return scorers_[0].objective(rows[0], plan);
    for (std::size_t i = 0; i < f_.size(); ++i)
      if (!std::isfinite(f_[i] = scorers_[i].objective(rows[i], plan))) return std::numeric_limits<double>::infinity();
    return joint_objective(pr_, f_);
  }

 private:
  const DesignProblem& pr_;
  std::vector<PlanScorer> scorers_;
  std::vector<double> f_;
};

// The exchange step's rank-one scorer (design_exchange.hpp) of every instrument, combined as JointScorer does.
class JointUpdate {
 public:
  JointUpdate(const DesignProblem& pr, const std::vector<Eigen::VectorXd>& norms) : pr_(pr), f_(norms.size()) {
    updates_.reserve(f_.size());
    updates_.emplace_back(pr.rows, norms[0], pr.criterion);
    for (std::size_t i = 0; i < pr.others.size(); ++i)
      updates_.emplace_back(pr.others[i].rows, norms[i + 1], pr.others[i].criterion);
  }
  void set_others(const std::vector<int>& plan, std::size_t position) {
    for (design_detail::ExchangeScorer& u : updates_) u.set_others(plan, position);
  }
  double objective(int candidate) {
    if (updates_.size() == 1) return updates_[0].objective(candidate);
    for (std::size_t i = 0; i < f_.size(); ++i)
      if (!std::isfinite(f_[i] = updates_[i].objective(candidate))) return std::numeric_limits<double>::infinity();
    return joint_objective(pr_, f_);
  }

 private:
  const DesignProblem& pr_;
  std::vector<design_detail::ExchangeScorer> updates_;
  std::vector<double> f_;
};

// Row j of `to` set to row s of `from`.
void set_row(CandidateRows& to, Eigen::Index j, const CandidateRows& from, Eigen::Index s) {
  to.regressors.row(j) = from.regressors.row(s);
  to.leaks.row(j) = from.leaks.row(s);
  to.natural.row(j) = from.natural.row(s);
  to.scatter[j] = from.scatter[s];
  to.noise[j] = from.noise[s];
  to.duration[j] = from.duration[s];
}

// A deterministic stream per start: SplitMix64 of the seed and the start's index.
std::uint64_t start_seed(std::uint64_t seed, int start) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * std::uint64_t(start + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double plan_time(const CandidateRows& rows, const std::vector<int>& plan) {
  double t = 0;
  for (int c : plan) t += rows.duration[c];
  return t;
}

bool within(double time, double budget) { return time <= budget * (1 + 1e-12); }

// A g-level's identity: its multiple of the resolution (levels that the operator sets alike are one).
long long level_key(double g, double resolution) {
  return resolution > 0 ? std::llround(g / resolution) : std::llround(g * 1e9);
}

// The distinct g-levels of a plan, as sorted keys.
std::vector<long long> plan_levels(const std::vector<long long>& keys, const std::vector<int>& plan,
                                   std::size_t skip = std::size_t(-1)) {
  std::vector<long long> out;
  for (std::size_t j = 0; j < plan.size(); ++j)
    if (j != skip) out.push_back(keys[std::size_t(plan[j])]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Every candidate's level key.
std::vector<long long> candidate_levels(const DesignProblem& pr) {
  std::vector<long long> keys;
  for (const DesignRun& run : pr.candidates) keys.push_back(level_key(run.g_level, pr.g_resolution));
  return keys;
}

// A plan meets the time budget, keeps its distinct g-levels and is well posed.
bool acceptable(const DesignProblem& pr, const std::vector<long long>& keys, JointScorer& scorer,
                const std::vector<int>& plan) {
  return within(plan_time(pr.rows, plan), pr.total_time) &&
         int(plan_levels(keys, plan).size()) >= pr.min_g_levels && std::isfinite(scorer.objective(plan));
}

// A random acceptable plan, or an empty one after `attempts` draws.
std::vector<int> random_plan(const DesignProblem& pr, const std::vector<long long>& keys, JointScorer& scorer,
                             std::uint64_t seed, int attempts) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> pick(0, int(pr.candidates.size()) - 1);
  std::vector<int> plan(std::size_t(pr.runs));
  for (int a = 0; a < attempts; ++a) {
    for (int& c : plan) c = pick(rng);
    if (acceptable(pr, keys, scorer, plan)) return plan;
  }
  return {};
}

// The lexicographic minimum of (objective, index) over the feasible candidates for run i of the plan (within
// the total time with the others' `others` seconds, and keeping the distinct g-levels: keeps_levels): the
// same for any number of threads. (inf, -1) when none is feasible.
template <class KeepsLevels>
std::pair<double, int> best_exchange(const DesignProblem& pr, const std::vector<Eigen::VectorXd>& leak_norms,
                                     const std::vector<int>& plan, std::size_t i, double others,
                                     const KeepsLevels& keeps_levels) {
  const bool by_update = pr.criterion.objective == DesignObjective::uncertainty;
  const int count = int(pr.candidates.size());
  double best_f = std::numeric_limits<double>::infinity();
  int best_c = -1;
#pragma omp parallel
  {
    JointScorer local(pr);
    JointUpdate update(pr, leak_norms);
    if (by_update) update.set_others(plan, i);
    std::vector<int> trial = plan;
    double tf = std::numeric_limits<double>::infinity();
    int tc = -1;
#pragma omp for schedule(static) nowait
    for (int c = 0; c < count; ++c) {
      if (c == plan[i] || !within(others + pr.rows.duration[c], pr.total_time) || !keeps_levels(c)) continue;
      trial[i] = c;
      const double v = by_update ? update.objective(c) : local.objective(trial);
      if (v < tf) {
        tf = v;
        tc = c;
      }
    }
#pragma omp critical
    if (tc >= 0 && (tf < best_f || (tf == best_f && tc < best_c))) {
      best_f = tf;
      best_c = tc;
    }
  }
  return {best_f, best_c};
}

// Exchange: for each run in turn, the candidate that lowers the objective most (ties: the lowest index),
// until a sweep changes nothing. The uncertainty objective is scored by rank-one updates of the other runs'
// sums (design_exchange.hpp), the noise-alone criteria by a fit per candidate.
double exchange(const DesignProblem& pr, const std::vector<Eigen::VectorXd>& leak_norms,
                const std::vector<long long>& keys, std::vector<int>& plan, int max_sweeps,
                long long& evaluations) {
  const bool by_update = pr.criterion.objective == DesignObjective::uncertainty;
  JointScorer scorer(pr);
  double f = scorer.objective(plan);
  const int count = int(pr.candidates.size());
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool improved = false;
    for (std::size_t i = 0; i < plan.size(); ++i) {
      const double others = plan_time(pr.rows, plan) - pr.rows.duration[plan[i]];
      // A candidate keeps the plan's distinct g-levels when the others have enough, or it brings a new one.
      const std::vector<long long> levels = plan_levels(keys, plan, i);
      const bool any_level = int(levels.size()) >= pr.min_g_levels;
      auto keeps_levels = [&](int c) {
        return any_level || (int(levels.size()) + 1 >= pr.min_g_levels &&
                             !std::binary_search(levels.begin(), levels.end(), keys[std::size_t(c)]));
      };
      double current = f;  // the plan as it is, by the same scorer as the trials
      if (by_update) {
        JointUpdate update(pr, leak_norms);
        update.set_others(plan, i);
        current = update.objective(plan[i]);
      }
      const auto [best_f, best_c] = best_exchange(pr, leak_norms, plan, i, others, keeps_levels);
      evaluations += count;
      if (best_c >= 0 && best_f < current - 1e-12 * std::abs(current)) {
        plan[i] = best_c;
        f = best_f;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return f;
}

// One variable of a run moved by a signed step: 0 g-level, 1 duration, 2 phase, 3 arm azimuth. False when the
// move leaves the bounds.
bool move(DesignRun& run, int variable, double step, const Refinement& r) {
  switch (variable) {
    case 0:
      run.g_level += step;
      return run.g_level >= r.g_low && run.g_level <= r.g_high;
    case 1:
      run.duration += step;
      return run.duration >= r.duration_low && run.duration <= r.duration_high;
    case 2:
      run.phase += step;
      return true;
    default:
      run.arm_azimuth += step;
      return true;
  }
}

// Whether run j of a plan may move to g-level g and the plan still keep its distinct g-levels.
bool keeps_levels(const DesignProblem& pr, const std::vector<DesignRun>& runs, std::size_t j, double g) {
  std::vector<long long> levels;
  for (std::size_t i = 0; i < runs.size(); ++i)
    levels.push_back(level_key(i == j ? g : runs[i].g_level, pr.g_resolution));
  std::sort(levels.begin(), levels.end());
  return std::unique(levels.begin(), levels.end()) - levels.begin() >= pr.min_g_levels;
}

// Local refinement of the continuous variables: best-improvement coordinate steps, all trial runs of a step
// evaluated in one batch; a step size that improves nothing is halved.
void refine(const DesignProblem& pr, std::vector<DesignRun>& runs, std::vector<CandidateRows>& rows,
            JointScorer& scorer, DesignSearchResult& out,
            const std::function<void(std::string_view, int, int)>& report) {
  const Refinement& r = pr.refinement;
  double steps[4] = {r.g_step, r.duration_step, r.phase_step, r.azimuth_step};
  std::vector<int> identity(runs.size());
  for (std::size_t j = 0; j < runs.size(); ++j) identity[j] = int(j);
  double f = scorer.objective(rows, identity);
  for (int halving = 0, moves = 0; halving <= r.halvings && moves < r.max_moves; ++moves) {
    struct Trial {
      std::size_t run;
      DesignRun value;
    };
    std::vector<Trial> trials;
    const double time = rows[0].duration.sum();
    for (std::size_t j = 0; j < runs.size(); ++j)
      for (int v = 0; v < 4; ++v)
        for (double sign : {1.0, -1.0}) {
          if (!(steps[v] > 0)) continue;
          DesignRun t = runs[j];
          if (!move(t, v, sign * steps[v], r)) continue;
          if (v == 1 && !within(time - runs[j].duration + t.duration, pr.total_time)) continue;
          if (v == 0 && !keeps_levels(pr, runs, j, t.g_level)) continue;
          trials.push_back({j, t});
        }
    if (trials.empty()) break;
    std::vector<DesignRun> batch;
    for (const Trial& t : trials) batch.push_back(t.value);
    std::vector<CandidateRows> trial_rows{pr.evaluate(batch)};  // per instrument
    for (const DesignInstrument& o : pr.others) trial_rows.push_back(o.evaluate(batch));
    out.row_evaluations += Eigen::Index(batch.size() * rows.size());
    double best = f;
    std::size_t chosen = trials.size();
    for (std::size_t t = 0; t < trials.size(); ++t) {
      std::vector<CandidateRows> candidate = rows;
      for (std::size_t i = 0; i < rows.size(); ++i)
        set_row(candidate[i], Eigen::Index(trials[t].run), trial_rows[i], Eigen::Index(t));
      const double v = scorer.objective(candidate, identity);
      ++out.evaluations;
      if (v < best - 1e-12 * std::abs(best)) {
        best = v;
        chosen = t;
      }
    }
    if (chosen == trials.size()) {
      for (double& s : steps) s /= 2;
      ++halving;
      report("refinement", std::min(halving, r.halvings + 1), r.halvings + 1);
      continue;
    }
    const std::size_t j = trials[chosen].run;
    runs[j] = trials[chosen].value;
    for (std::size_t i = 0; i < rows.size(); ++i)
      set_row(rows[i], Eigen::Index(j), trial_rows[i], Eigen::Index(chosen));
    f = best;
  }
}

}  // namespace

double joint_objective(const DesignProblem& pr, const std::vector<double>& f) {
  if (f.size() == 1) return f.front();
  double joint = pr.criterion.objective == DesignObjective::d_optimal ? 0.0 : -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (pr.criterion.objective == DesignObjective::d_optimal) {
      joint += f[i];
      continue;
    }
    const double w = (i == 0 ? pr.criterion : pr.others[i - 1].criterion).weight.sum();
    joint = std::max(joint, w > 0 ? f[i] / w : f[i]);
  }
  return joint;
}

PlanScore score_plan(const CandidateRows& plan, const DesignCriterion& criterion) {
  PlanScorer scorer(criterion);
  std::vector<int> all(std::size_t(plan.size()));
  for (std::size_t j = 0; j < all.size(); ++j) all[j] = int(j);
  PlanScore s;
  scorer.objective(plan, all, &s);
  return s;
}

namespace {

// A problem the search can take: one run at least, one candidate at least, every instrument's rows of the
// same candidates.
void check_design_problem(const DesignProblem& pr) {
  if (pr.runs < 1) throw InputError("the design needs at least one run");
  if (pr.candidates.empty()) throw InputError("the design space has no candidate run");
  for (const DesignInstrument& o : pr.others)
    if (o.rows.size() != pr.rows.size() || bool(o.evaluate) != bool(pr.evaluate))
      throw InputError("the design's instruments have rows of other candidate runs");
}

// The found plan's score by its rows (one per instrument): each instrument's, and with several the joint
// objective over them.
void score_design(const DesignProblem& pr, const std::vector<CandidateRows>& rows, DesignSearchResult& out) {
  out.rows = rows[0];
  out.score = score_plan(out.rows, pr.criterion);
  if (!pr.others.empty()) {
    std::vector<double> f{out.score.objective};
    out.scores.push_back(out.score);
    for (std::size_t i = 0; i < pr.others.size(); ++i) {
      out.scores.push_back(score_plan(rows[i + 1], pr.others[i].criterion));
      out.other_rows.push_back(rows[i + 1]);
      f.push_back(out.scores.back().objective);
    }
    out.score.objective = joint_objective(pr, f);
  }
}

}  // namespace

DesignSearchResult search_design(const DesignProblem& pr, const DesignSearchOptions& options) {
  check_design_problem(pr);
  DesignSearchResult out;
  JointScorer scorer(pr);
  std::vector<int> best;
  double best_f = std::numeric_limits<double>::infinity();
  const int starts = int(pr.initial_plans.size()) + options.starts;
  std::vector<Eigen::VectorXd> norms{design_detail::leak_norms(pr.rows)};  // per instrument
  for (const DesignInstrument& o : pr.others) norms.push_back(design_detail::leak_norms(o.rows));
  const std::vector<long long> keys = candidate_levels(pr);
  auto report = [&options](std::string_view stage, int done, int total) {
    if (options.on_progress) options.on_progress(stage, done, total);
  };
  // The count of starts done is reported after each, skipped ones included (the increment runs on continue).
  for (int s = 0; s < starts; ++s, report("search", s, starts)) {
    std::vector<int> plan;
    if (s < int(pr.initial_plans.size())) {
      plan = pr.initial_plans[std::size_t(s)];
      if (int(plan.size()) != pr.runs || !acceptable(pr, keys, scorer, plan)) plan.clear();
    } else {
      plan = random_plan(pr, keys, scorer, start_seed(options.seed, s), 2000);
    }
    if (plan.empty()) {
      out.start_objectives.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    const double f = exchange(pr, norms, keys, plan, options.max_sweeps, out.evaluations);
    out.start_objectives.push_back(f);
    if (f < best_f) {
      best_f = f;
      best = plan;
      out.start = s;
    }
  }
  if (best.empty())
    throw InputError(
        "no plan of " + std::to_string(pr.runs) + " runs from the design space fits the total time, keeps " +
        std::to_string(pr.min_g_levels) +
        " distinct g-levels and identifies every free term; widen the design space ([design] g_range, "
        "durations, phases), raise total_time or lower min_g_levels");
  out.grid_objective = best_f;
  for (int c : best) out.runs.push_back(pr.candidates[std::size_t(c)]);
  std::vector<CandidateRows> rows{pr.rows.select(best)};  // per instrument
  for (const DesignInstrument& o : pr.others) rows.push_back(o.rows.select(best));
  if (pr.evaluate) {
    refine(pr, out.runs, rows, scorer, out, report);
    // Done, whether the steps were halved to the end or no move was left.
    report("refinement", pr.refinement.halvings + 1, pr.refinement.halvings + 1);
  }
  score_design(pr, rows, out);
  return out;
}

}  // namespace ccal

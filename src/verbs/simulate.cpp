#include "ccal/verbs/simulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "ccal/core/errors.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/uncertainty/chain_inputs.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/uncertainty/rate_noise.hpp"

namespace ccal::verbs {

std::string regressor_unit(const std::string& id) {
  const TermSpec t = parse_term(id).value();
  switch (t.kind) {
    case TermKind::power:
      return t.power == 0 ? "1" : t.power == 1 ? "g" : fmt::format("g^{}", t.power);
    case TermKind::p:
    case TermKind::o:
      return "g";
    case TermKind::rate:
      return "rad/s";
    default:
      return "g^2";
  }
}

namespace {

// A drawn machine's drives also have their stated rate noise (docs/model.md §3.2): each run mean moves by a
// normal draw of its σ_j (σ_j = N √(∫h_j²)/T, the budget's own), from a stream of its own (the seed's, mixed),
// so that the machine differs from the configured one in everything the lab states it does not know.
void add_rate_noise_draws(Observations<double>& obs, const Experiment& ex, const Eigen::VectorXd& errors,
                          std::uint64_t seed) {
  if (!ex.rate_noise.any()) return;
  const RateNoiseGains gains = rate_noise_gains(ex, errors, ex.rate_noise.main > 0, ex.rate_noise.platform > 0);
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (Eigen::Index j = 0; j < obs.output.size(); ++j) {
    if (ex.rate_noise.main > 0) obs.output[j] += ex.rate_noise.main * gains.main[j] * normal(rng);
    if (ex.rate_noise.platform > 0) obs.output[j] += ex.rate_noise.platform * gains.platform[j] * normal(rng);
  }
}

constexpr OptionSpec<SimulateOptions> kSimulateRows[] = {
    rows::mode<&SimulateOptions::mode>(
        "Model of the reduction: exact (full chain) or paper (Wang & Ren "
        "first-order rules); default: the configuration's [identification] mode"),
    rows::seed(&SimulateOptions::seed,
               "Seed of the output noise (used only if the instrument has noise) and of the drawn truth"),
    {"draw_truth", &SimulateOptions::draw_truth, "",
     "The machine's errors: the configuration's [errors] plus one draw of every [tolerances] input from its "
     "distribution (groups and [[correlations]] included), by the seed"},
};

}  // namespace

OptionTable<SimulateOptions> options_of(std::type_identity<SimulateOptions>) { return kSimulateRows; }

SimulateResult simulate(const Config& cfg, const SimulateOptions& o) {
  require_one_instrument(cfg, "simulate");
  check_options(o, option_table<SimulateOptions>());
  SimulateResult s;
  s.config = cfg;
  s.seed = o.seed;
  s.mode = o.mode.value_or(cfg.mode);
  if (s.mode == ModelMode::paper)
    for (const Run& run : cfg.plan.runs)
      if (run.mounting != Mounting::ia_horizontal)
        throw InputError(
            fmt::format("run '{}': mode paper reduces runs on the paper's mounting (ia_horizontal) "
                        "only; accepted: mode exact, or mounting ia_horizontal",
                        run.name));
  const Experiment ex = cfg.experiment();
  const IdentificationSpec& spec = cfg.identification;
  // The machine has the truth's errors (the configuration's [errors] without a truth file); the model knows the
  // configuration's [errors] only, and uses them when it compensates.
  if (o.truth && o.truth->errors.size() != ex.layout.size())
    throw InputError(fmt::format("{}: its errors are of another layout than {}'s; accepted: a truth read against "
                                 "this configuration",
                                 o.truth->source, cfg.source));
  s.truth = o.truth;
  s.machine_errors = o.truth ? o.truth->errors : cfg.centrifuge.errors;
  std::vector<std::pair<int, double>> chain_errors = o.truth ? o.truth->chain_errors : cfg.chain.errors;
  if (o.draw_truth) {
    if (o.truth)
      throw OptionError("draw_truth", "",
                        fmt::format("and the truth {} are two answers for the machine's errors; accepted: one of "
                                    "them",
                                    o.truth->source));
    s.drawn = draw_sources(cfg.tolerances, cfg.correlations, o.seed);
    for (std::size_t k = 0; k < s.drawn.size(); ++k) {
      const int p = cfg.tolerances[k].parameter;
      if (is_chain_parameter(p))
        chain_errors.emplace_back(p, s.drawn[k]);
      else
        s.machine_errors[p] += s.drawn[k];
    }
  }
  // The measuring chain's errors: the machine's gravity and terms, the reading of its output (and, in its logs,
  // the time base's clock and the encoders' readings, io/run_log_writer.hpp).
  s.config.chain.errors = chain_errors;
  const Experiment machine = with_chain_errors(ex, chain_errors);
  const Eigen::VectorXd& known = cfg.centrifuge.errors;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  s.error_count = static_cast<int>((s.machine_errors.array() != 0.0).count());
  for (const auto& [code, value] : chain_errors) s.error_count += value != 0.0 ? 1 : 0;
  s.observations = observe<double>(machine, ex, s.machine_errors, spec.compensate ? known : zero, spec, s.mode);
  read_through_chain(s.observations.output, ex.instrument, chain_errors);
  s.noisy = ex.instrument.noise_density > 0 || ex.instrument.quantum > 0;
  add_output_noise(s.observations, ex, o.seed);
  if (o.draw_truth) add_rate_noise_draws(s.observations, ex, s.machine_errors, o.seed);
  s.output_unit_si = output_unit_si(ex.instrument.output_unit);
  s.order.resize(s.observations.columns.size());
  std::iota(s.order.begin(), s.order.end(), std::size_t{0});
  std::stable_sort(s.order.begin(), s.order.end(), [&](std::size_t a, std::size_t b) {
    return term_rank(parse_term(s.observations.columns[a]).value()) <
           term_rank(parse_term(s.observations.columns[b]).value());
  });

  std::vector<double> rates;
  for (const Run& run : ex.plan.runs) rates.push_back(nominal_rate(run, ex.geometry, ex.site));
  const DataResolution resolution = run_resolution(ex.plan.runs, rates, s.observations, spec, ex.instrument);
  FileIdentification f = identify_observations(s.observations, spec, ex.instrument, cfg.source, &resolution,
                                                cfg.numbers_sha256);
  s.observations_csv = std::move(f.csv);
  s.identification = std::move(f.id);
  return s;
}

}  // namespace ccal::verbs

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
#include "ccal/verbs/instrument_covariance.hpp"

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

namespace {

// Paper mode reduces runs on the paper's mounting only.
void check_paper_mounting(const Config& cfg) {
  for (const Run& run : cfg.plan.runs)
    if (run.mounting != Mounting::ia_horizontal)
      throw InputError(
          fmt::format("run '{}': mode paper reduces runs on the paper's mounting (ia_horizontal) "
                      "only; accepted: mode exact, or mounting ia_horizontal",
                      run.name));
}

// The regressor columns in canonical term order (as in the observations file).
std::vector<std::size_t> canonical_column_order(const std::vector<std::string>& columns) {
  std::vector<std::size_t> order(columns.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return term_rank(parse_term(columns[a]).value()) < term_rank(parse_term(columns[b]).value());
  });
  return order;
}

// One instrument's test on the machine: its errors the truth's or the configuration's, plus `drawn` (a draw of
// each of its [tolerances] inputs, SI; empty: none), its output noise from noise_seed.
SimulateResult simulate_machine(const Config& cfg, const SimulateOptions& o, const std::vector<double>& drawn,
                                std::uint64_t noise_seed) {
  SimulateResult s;
  s.config = cfg;
  s.seed = o.seed;
  s.mode = o.mode.value_or(cfg.mode);
  if (s.mode == ModelMode::paper) check_paper_mounting(cfg);
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
  s.drawn = drawn;
  for (std::size_t k = 0; k < s.drawn.size(); ++k) {
    const int p = cfg.tolerances[k].parameter;
    if (is_chain_parameter(p))
      chain_errors.emplace_back(p, s.drawn[k]);
    else
      s.machine_errors[p] += s.drawn[k];
  }
  // The measuring chain's errors: the machine's gravity and terms, the reading of its output (and, in its logs,
  // the time base's clock and the encoders' readings, intake/run_log_writer.hpp).
  s.config.chain.errors = chain_errors;
  const Experiment machine = with_chain_errors(ex, chain_errors);
  const Eigen::VectorXd& known = cfg.centrifuge.errors;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  s.error_count = static_cast<int>((s.machine_errors.array() != 0.0).count());
  for (const auto& [code, value] : chain_errors) s.error_count += value != 0.0 ? 1 : 0;
  s.observations = observe<double>(machine, ex, s.machine_errors, spec.compensate ? known : zero, spec, s.mode);
  read_through_chain(s.observations.output, ex.instrument, chain_errors);
  s.noisy = ex.instrument.noise_density > 0 || ex.instrument.quantum > 0;
  add_output_noise(s.observations, ex, noise_seed);
  if (o.draw_truth) add_rate_noise_draws(s.observations, ex, s.machine_errors, o.seed);
  s.output_unit_si = output_unit_si(ex.instrument.output_unit);
  s.order = canonical_column_order(s.observations.columns);

  std::vector<double> rates;
  for (const Run& run : ex.plan.runs) rates.push_back(nominal_rate(run, ex.geometry, ex.site));
  const DataResolution resolution = run_resolution(ex.plan.runs, rates, s.observations, spec, ex.instrument);
  FileIdentification f = identify_observations(s.observations, spec, ex.instrument, cfg.source, &resolution,
                                                cfg.numbers_sha256);
  s.observations_csv = std::move(f.csv);
  s.identification = std::move(f.id);
  return s;
}

// A test of several instruments: one machine, whose shared errors are one draw for all of them (each
// instrument's own inputs drawn for it: joint_sources); the drives' rate noise is the machine's, one draw for all
// (the same stream); each instrument's output noise its own.
SimulateResult simulate_instruments(const Config& cfg, const SimulateOptions& o) {
  if (o.truth)
    throw OptionError("truth", o.truth->source,
                      fmt::format("holds one configuration's errors, and {} is a test of {} instruments; accepted: "
                                  "one instrument chosen with {}, or no truth",
                                  cfg.source, cfg.instruments.size(), OptionError::name("instrument")));
  std::vector<std::vector<double>> drawn(cfg.instruments.size());
  if (o.draw_truth) {
    const JointSources joint = joint_sources(cfg.instruments);
    const std::vector<double> all = draw_sources(joint.sources, joint.correlations, o.seed);
    for (std::size_t a = 0; a < drawn.size(); ++a)
      for (const std::size_t source : joint.of_instrument[a]) drawn[a].push_back(all[source]);
  }
  std::vector<SimulateResult> each;
  for (std::size_t a = 0; a < cfg.instruments.size(); ++a) {
    const std::uint64_t noise_seed = o.seed ^ (0xa24baed4963ee407ULL * a);  // the first's as alone
    each.push_back(simulate_machine(cfg.instruments[a], o, drawn[a], noise_seed));
  }
  SimulateResult r = each.front();
  r.config = cfg;
  r.instruments = std::move(each);
  return r;
}

}  // namespace

SimulateResult simulate(const Config& cfg, const SimulateOptions& o) {
  check_options(o, option_table<SimulateOptions>());
  if (o.draw_truth && o.truth)
    throw OptionError("draw_truth", "",
                      fmt::format("and the truth {} are two answers for the machine's errors; accepted: one of them",
                                  o.truth->source));
  if (cfg.instruments.size() > 1) return simulate_instruments(cfg, o);
  return simulate_machine(cfg, o, o.draw_truth ? draw_sources(cfg.tolerances, cfg.correlations, o.seed)
                                               : std::vector<double>{},
                          o.seed);
}

namespace {

// The column of each instrument of a test in its logs: the layout's [instruments] entry, or pulses_<id>/output_<id>.
void name_instrument_columns(const SimulateResult& s, LogLayout& layout) {
  std::vector<LogLayout::InstrumentColumn> named;
  for (const SimulateResult& one : s.instruments) {
    const std::string& id = one.config.instrument_id;
    const bool pulses = one.config.instrument.quantum > 0;
    const auto given = std::ranges::find(layout.instruments, id, &LogLayout::InstrumentColumn::id);
    if (given == layout.instruments.end() && !layout.instruments.empty())
      throw InputError(fmt::format("the log layout's [instruments] names no column for instrument '{}'; accepted: "
                                   "{} = {{ {} = \"…\" }}, or no [instruments] (columns {}_<id>)",
                                   id, id, pulses ? "pulses" : "output", pulses ? "pulses" : "output"));
    if (given != layout.instruments.end() && given->pulses != pulses)
      throw InputError(fmt::format(
          "the log layout's [instruments] (line {}): instrument '{}' {}; accepted: {} = {{ {} = \"{}\" }}",
          given->line, id,
          pulses ? "has a quantum, so its output is logged as a count of pulses"
                 : "has no quantum, so its output is logged as it is, not as pulses",
          id, pulses ? "pulses" : "output", given->column));
    named.push_back(given != layout.instruments.end()
                        ? *given
                        : LogLayout::InstrumentColumn{id, fmt::format("{}_{}", pulses ? "pulses" : "output", id),
                                                      pulses, 0});
  }
  layout.instruments = std::move(named);
}

}  // namespace

std::vector<RunLogFile> simulation_logs(const SimulateResult& s, LogLayout layout, std::optional<double> step) {
  if (layout.angle_unit.empty()) layout.angle_unit = "rad";  // ccal's own, stated: the folder reads as written
  const double dt = step ? *step : default_log_step(s.config);
  std::vector<RunLogFile> files;
  if (s.instruments.empty()) {
    const Eigen::VectorXd& means = s.observations.output;
    files = write_run_logs(s.config, s.machine_errors, {means.data(), means.data() + means.size()}, dt, layout);
  } else {
    name_instrument_columns(s, layout);
    std::vector<LoggedOutput> outputs;
    for (std::size_t a = 0; a < s.instruments.size(); ++a) {
      const Eigen::VectorXd& means = s.instruments[a].observations.output;
      outputs.push_back({layout.instruments[a].column, s.instruments[a].config.instrument,
                         {means.data(), means.data() + means.size()}});
    }
    // The machine's readings (clock, encoders) are the first instrument's configuration's, shared by all.
    const SimulateResult& first = s.instruments.front();
    files = write_instrument_logs(first.config, first.machine_errors, outputs, dt, layout);
  }
  std::vector<std::pair<std::string, std::string>> runs;
  for (std::size_t r = 0; r < files.size(); ++r) runs.emplace_back(s.config.plan.runs[r].name, files[r].name);
  files.push_back({std::string(kLogManifestName), log_manifest_text(layout, runs)});
  return files;
}

}  // namespace ccal::verbs

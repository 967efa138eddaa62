// ccal simulate: the run means a test plan produces (truth: the exact chain with the configured [errors]) and
// the regressors the analyst computes (with zero errors, or the [errors] values when compensating), written
// as an observations file and identified as `ccal identify` would (docs/cli.md).
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>

#include "ccal/config.hpp"
#include "ccal/observation_csv.hpp"
#include "ccal/simulate.hpp"
#include "ccal/version.hpp"
#include "commands.hpp"
#include "identification.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct SimulateOptions {
  std::string config;
  std::string mode;  // empty: the configuration's
  std::uint64_t seed = 1;
  std::string observations_out;
  OutputOptions output;
};

struct Simulation {
  ModelMode mode = ModelMode::exact;
  Observations<double> obs;
  double unit = 1;  // SI size of one output unit
  bool noisy = false;
  int error_count = 0;             // non-zero [errors] parameters
  std::vector<std::size_t> order;  // regressor columns in canonical term order, as in the file
  std::string csv;
  Identification id;
};

std::string_view mode_word(ModelMode m) { return m == ModelMode::exact ? "exact" : "paper"; }

// Unit of a regressor column: gⁿ, or rad/s for K_w.
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

Simulation simulate(const Config& cfg, const SimulateOptions& o) {
  Simulation s;
  s.mode = o.mode.empty() ? cfg.mode : (o.mode == "paper" ? ModelMode::paper : ModelMode::exact);
  if (s.mode == ModelMode::paper)
    for (const Run& run : cfg.plan.runs)
      if (run.mounting != Mounting::ia_horizontal)
        throw InputError(
            fmt::format("run '{}': mode paper reduces runs on the paper's mounting (ia_horizontal) "
                        "only; accepted: mode exact, or mounting ia_horizontal",
                        run.name));
  const Experiment ex = cfg.experiment();
  const IdentificationSpec& spec = cfg.identification;
  const Eigen::VectorXd& truth = cfg.centrifuge.errors;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  s.error_count = static_cast<int>((truth.array() != 0.0).count());
  s.obs = observe<double>(ex, truth, spec.compensate ? truth : zero, spec, s.mode);
  s.noisy = ex.instrument.noise_density > 0 || ex.instrument.quantum > 0;
  add_output_noise(s.obs, ex, o.seed);
  s.unit = output_unit_si(ex.instrument.output_unit);
  s.order.resize(s.obs.columns.size());
  std::iota(s.order.begin(), s.order.end(), std::size_t{0});
  std::stable_sort(s.order.begin(), s.order.end(), [&](std::size_t a, std::size_t b) {
    return term_rank(parse_term(s.obs.columns[a]).value()) < term_rank(parse_term(s.obs.columns[b]).value());
  });

  std::vector<double> rates;
  for (const Run& run : ex.plan.runs) rates.push_back(nominal_rate(run, ex.geometry, ex.site));
  const DataResolution resolution = run_resolution(ex.plan.runs, rates, s.obs, spec, ex.instrument);
  FileIdentification f = identify_observations(s.obs, spec, ex.instrument, cfg.source, &resolution);
  s.csv = std::move(f.csv);
  s.id = std::move(f.id);
  return s;
}

std::string describe_errors(const Config& cfg, const Simulation& s) {
  if (s.error_count == 0) return "[errors]: none";
  return fmt::format("[errors]: {} non-zero, {}", s.error_count,
                     cfg.identification.compensate ? "compensated (regressors computed with them)"
                                                   : "uncompensated (regressors computed without them)");
}

std::string describe_noise(const Config& cfg, const SimulateOptions& o) {
  const InstrumentModel& ins = cfg.instrument;
  if (ins.noise_density == 0 && ins.quantum == 0) return "noise: none";
  const double unit = output_unit_si(ins.output_unit);
  std::string out = "noise:";
  if (ins.noise_density > 0)
    out += fmt::format(" white {} {}/rtHz", number(ins.noise_density / unit, 6), ins.output_unit);
  if (ins.quantum > 0) out += fmt::format(" quantum {} {}*s", number(ins.quantum / unit, 6), ins.output_unit);
  return out + fmt::format(", seed {}", o.seed);
}

std::string to_text(const Config& cfg, const SimulateOptions& o, const Simulation& s) {
  const Experiment ex = cfg.experiment();
  const std::string& unit = cfg.instrument.output_unit;
  std::string out =
      fmt::format("ccal simulate: {} runs of {}; {} model; {}; {}\n\n", cfg.plan.runs.size(), cfg.source,
                  mode_word(s.mode), describe_errors(cfg, s), describe_noise(cfg, o));
  Table runs({"run", "g-level [g]", "Omega [rad/s]", "phi0 [rad]", "T [s]", "platform"});
  for (const Run& run : cfg.plan.runs)
    runs.add_row({run.name, number(run.g_level), number(nominal_rate(run, ex.geometry, ex.site)),
                  number(initial_phase(run, ex.geometry, ex.site)), number(run.duration),
                  std::string(platform_mode_name(run.mode))});
  out += runs.render() + "\n";

  std::vector<std::string> header{"run", "<a_i> [g]"};
  for (std::size_t k : s.order)
    header.push_back(fmt::format("{} [{}]", s.obs.columns[k], regressor_unit(s.obs.columns[k])));
  header.push_back(fmt::format("rate term [{}]", unit));
  header.push_back(fmt::format("output [{}]", unit));
  Table means(header);
  for (Eigen::Index j = 0; j < s.obs.output.size(); ++j) {
    std::vector<std::string> row{s.obs.runs[static_cast<std::size_t>(j)], number(s.obs.input[j], 10)};
    for (std::size_t k : s.order)
      row.push_back(number(s.obs.regressors(j, static_cast<Eigen::Index>(k)), 10));
    row.push_back(number(s.obs.known_rate[j] / s.unit, 6));
    row.push_back(number(s.obs.output[j] / s.unit, 12));
    means.add_row(row);
  }
  out += "  run means (regressors: the model's, from " +
         std::string(cfg.identification.compensate ? "the [errors] values" : "zero errors") +
         "; output: the exact chain with the [errors] values)\n";
  out += means.render() + "\n";
  out += "  identification of these observations\n";
  return out + identification_text(s.id);
}

std::string to_json(const Config& cfg, const SimulateOptions& o, const Simulation& s) {
  const Experiment ex = cfg.experiment();
  nlohmann::ordered_json j;
  j["command"] = "simulate";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = mode_word(s.mode);
  j["compensate"] = cfg.identification.compensate;
  j["errors_nonzero"] = s.error_count;
  j["noise"] = {{"density", cfg.instrument.noise_density / s.unit},
                {"quantum", cfg.instrument.quantum / s.unit},
                {"applied", s.noisy},
                {"seed", o.seed}};
  j["output_unit"] = cfg.instrument.output_unit;
  j["terms"] = cfg.identification.free_terms;
  nlohmann::ordered_json fixed = nlohmann::ordered_json::object();
  for (const auto& f : s.id.fixed) fixed[f.id] = {{"value", f.value}, {"unit", f.unit}};
  j["fixed"] = fixed;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < cfg.plan.runs.size(); ++r) {
    const Run& run = cfg.plan.runs[r];
    const auto i = static_cast<Eigen::Index>(r);
    nlohmann::ordered_json regressors = nlohmann::ordered_json::object();
    for (std::size_t k : s.order)
      regressors[s.obs.columns[k]] = s.obs.regressors(i, static_cast<Eigen::Index>(k));
    runs.push_back({{"name", run.name},
                    {"g_level_g", run.g_level},
                    {"rate_rad_per_s", nominal_rate(run, ex.geometry, ex.site)},
                    {"initial_phase_rad", initial_phase(run, ex.geometry, ex.site)},
                    {"duration_s", run.duration},
                    {"a_i_g", s.obs.input[i]},
                    {"regressors", regressors},
                    {"rate_term", s.obs.known_rate[i] / s.unit},
                    {"output", s.obs.output[i] / s.unit}});
  }
  j["runs"] = runs;
  j["identification"] = identification_json(s.id);
  return j.dump(2) + "\n";
}

}  // namespace

Command add_simulate(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* cmd =
      app.add_subcommand("simulate",
                         "Simulated run means of the test plan (exact chain with the configured [errors], "
                         "instrument noise), their "
                         "regressors, and the identification of the [identification] terms from them.");
  add_config_argument(*cmd, o->config);
  cmd->add_option("--mode", o->mode,
                  "Reduction of a run: exact (full chain) or paper (Wang & Ren's first order); default: "
                  "[identification] mode of the configuration")
      ->check(CLI::IsMember({"exact", "paper"}));
  cmd->add_option("--seed", o->seed, "Seed of the output noise (used only if the instrument has noise)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)  // a negative seed would wrap to 2^64 - 1 silently
      ->type_name("S");
  add_observations_out_option(*cmd, o->observations_out);
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal simulate\n"
      "      the bundled paper example: run means and the identified K0, K2, K3\n"
      "  ccal simulate my.toml --observations-out obs.csv && ccal identify obs.csv\n"
      "  ccal simulate my.toml --mode paper --format json -o sim.json\n"
      "  ccal simulate --format csv > obs.csv\n");

  return {cmd, [o] {
            const Config cfg = load_config_or_example(o->config);
            check_observations_out(o->observations_out, o->output);
            const Simulation s = simulate(cfg, *o);
            std::string text;
            if (o->output.format == "json")
              text = to_json(cfg, *o, s);
            else if (o->output.format == "csv")
              text = s.csv;
            else
              text = to_text(cfg, *o, s);
            std::vector<ExtraFile> extra;
            if (!o->observations_out.empty())
              extra.push_back({"--observations-out", o->observations_out, s.csv});
            write_outputs(o->output, text, extra);
          }};
}

}  // namespace ccal::cli

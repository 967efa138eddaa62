#include "ccal/render/simulate.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "ccal/core/errors.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"
#include "parts.hpp"

namespace ccal::render {
namespace {

// The machine's errors (the truth's, or the configuration's [errors]) and what the model knows of them.
std::string describe_errors(const Config& cfg, const verbs::SimulateResult& s) {
  const int known = int((cfg.centrifuge.errors.array() != 0.0).count());
  const std::string model = cfg.identification.compensate ? "compensated (regressors computed with them)"
                                                          : "uncompensated (regressors computed without them)";
  if (!s.drawn.empty())
    return fmt::format("machine: the [errors] plus one draw of the {} [tolerances] inputs (seed {}); known "
                       "[errors]: {}{}",
                       s.drawn.size(), s.seed, known == 0 ? "none" : fmt::format("{} non-zero, ", known),
                       known == 0 ? "" : model);
  if (s.truth)
    return fmt::format("machine: {} non-zero errors of the truth {}; known [errors]: {}{}", s.error_count,
                       s.truth->source, known == 0 ? "none" : fmt::format("{} non-zero, ", known),
                       known == 0 ? "" : model);
  if (s.error_count == 0) return "[errors]: none";
  return fmt::format("[errors]: {} non-zero, {}", s.error_count, model);
}

std::string describe_noise(const Config& cfg, std::uint64_t seed) {
  const InstrumentModel& ins = cfg.instrument;
  if (ins.noise_density == 0 && ins.quantum == 0) return "noise: none";
  const double unit = output_unit_si(ins.output_unit);
  std::string out = "noise:";
  if (ins.noise_density > 0)
    out += fmt::format(" white {} {}/rtHz", number(ins.noise_density / unit, 6), ins.output_unit);
  if (ins.quantum > 0) out += fmt::format(" quantum {} {}*s", number(ins.quantum / unit, 6), ins.output_unit);
  return out + fmt::format(", seed {}", seed);
}

std::string text_of(const Config& cfg, const verbs::SimulateResult& s) {
  const Experiment ex = cfg.experiment();
  const std::string& unit = cfg.instrument.output_unit;
  std::string out =
      fmt::format("ccal simulate: {} runs of {}; {} model; {}; {}\n\n", cfg.plan.runs.size(), cfg.source,
                  mode_name(s.mode), describe_errors(cfg, s), describe_noise(cfg, s.seed));
  Table runs({"run", "g-level [g]", "Omega [rad/s]", "phi0 [rad]", "T [s]", "platform"});
  for (const Run& run : cfg.plan.runs)
    runs.add_row({run.name, number(run.g_level), number(nominal_rate(run, ex.geometry, ex.site)),
                  number(initial_phase(run, ex.geometry, ex.site)), number(run.duration),
                  std::string(platform_mode_name(run.mode))});
  out += runs.render() + "\n";

  std::vector<std::string> header{"run", "<a_i> [g]"};
  for (std::size_t k : s.order)
    header.push_back(
        fmt::format("{} [{}]", s.observations.columns[k], verbs::regressor_unit(s.observations.columns[k])));
  header.push_back(fmt::format("rate term [{}]", unit));
  header.push_back(fmt::format("output [{}]", unit));
  Table means(header);
  for (Eigen::Index j = 0; j < s.observations.output.size(); ++j) {
    std::vector<std::string> row{s.observations.runs[static_cast<std::size_t>(j)],
                                 number(s.observations.input[j], 10)};
    for (std::size_t k : s.order)
      row.push_back(number(s.observations.regressors(j, static_cast<Eigen::Index>(k)), 10));
    row.push_back(number(s.observations.known_rate[j] / s.output_unit_si, 6));
    row.push_back(number(s.observations.output[j] / s.output_unit_si, 12));
    means.add_row(row);
  }
  out += "  run means (regressors: the model's, from " +
         std::string(cfg.identification.compensate ? "the [errors] values" : "zero errors") +
         "; output: the exact chain with the " + (s.truth ? "truth's errors" : std::string("[errors] values")) +
         ")\n";
  out += means.render() + "\n";
  out += "  identification of these observations\n";
  return out + identification_text(s.identification);
}

nlohmann::ordered_json json_of(const Config& cfg, const verbs::SimulateResult& s) {
  const Experiment ex = cfg.experiment();
  nlohmann::ordered_json j;
  j["command"] = "simulate";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = mode_name(s.mode);
  j["compensate"] = cfg.identification.compensate;
  j["errors_nonzero"] = s.error_count;
  j["truth"] = s.truth ? nlohmann::ordered_json{{"file", s.truth->source}, {"sha256", s.truth->text_sha256}}
                       : nlohmann::ordered_json(nullptr);
  if (!s.drawn.empty()) {  // the drawn inputs, SI, by id: what the coverage study compares against
    nlohmann::ordered_json drawn;
    for (std::size_t k = 0; k < s.drawn.size(); ++k) drawn[cfg.tolerances[k].id] = s.drawn[k];
    j["drawn_errors_si"] = std::move(drawn);
  }
  j["noise"] = {{"density", cfg.instrument.noise_density / s.output_unit_si},
                {"quantum", cfg.instrument.quantum / s.output_unit_si},
                {"applied", s.noisy},
                {"seed", s.seed}};
  j["output_unit"] = cfg.instrument.output_unit;
  j["terms"] = cfg.identification.free_terms;
  nlohmann::ordered_json fixed = nlohmann::ordered_json::object();
  for (const auto& f : s.identification.fixed) fixed[f.id] = {{"value", f.value}, {"unit", f.unit}};
  j["fixed"] = fixed;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < cfg.plan.runs.size(); ++r) {
    const Run& run = cfg.plan.runs[r];
    const auto i = static_cast<Eigen::Index>(r);
    nlohmann::ordered_json regressors = nlohmann::ordered_json::object();
    for (std::size_t k : s.order)
      regressors[s.observations.columns[k]] = s.observations.regressors(i, static_cast<Eigen::Index>(k));
    runs.push_back({{"name", run.name},
                    {"g_level_g", run.g_level},
                    {"rate_rad_per_s", nominal_rate(run, ex.geometry, ex.site)},
                    {"initial_phase_rad", initial_phase(run, ex.geometry, ex.site)},
                    {"duration_s", run.duration},
                    {"a_i_g", s.observations.input[i]},
                    {"regressors", regressors},
                    {"rate_term", s.observations.known_rate[i] / s.output_unit_si},
                    {"output", s.observations.output[i] / s.output_unit_si}});
  }
  j["runs"] = runs;
  j["identification"] = identification_json(s.identification);
  return j;
}

}  // namespace

std::string text(const verbs::SimulateResult& r) {
  if (r.instruments.empty()) return text_of(r.config, r);
  std::string out = fmt::format("ccal simulate: a test of {} instruments ({}) on one machine\n\n",
                                r.instruments.size(), r.config.source);
  for (const verbs::SimulateResult& one : r.instruments)
    out += fmt::format("=== instrument {} ===\n", one.config.instrument_id) + text_of(one.config, one) + "\n";
  return out;
}

std::string json(const verbs::SimulateResult& r) {
  if (r.instruments.empty()) return json_of(r.config, r).dump(2) + "\n";
  nlohmann::ordered_json j;
  j["command"] = "simulate";
  j["ccal_version"] = version();
  j["config"] = r.config.source;
  nlohmann::ordered_json each = nlohmann::ordered_json::array();
  for (const verbs::SimulateResult& one : r.instruments)
    each.push_back(instrument_part_json(one.config.instrument_id, json_of(one.config, one)));
  j["instruments"] = std::move(each);
  return j.dump(2) + "\n";
}

std::string csv(const verbs::SimulateResult& r) {
  if (!r.instruments.empty())
    throw OptionError("format", "csv",
                      "is one table, and a test of several instruments has one observations table per instrument; "
                      "accepted: " + OptionError::name("format") + " text or json, or " + OptionError::name("instrument") +
                      " ID for one of them");
  return r.observations_csv;
}

}  // namespace ccal::render

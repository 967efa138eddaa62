// ccal force: specific force and angular rate at the instrument at one instant of a run, exact and as a sum
// of first-order contributions of the configured centrifuge errors (docs/cli.md).
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "ccal/config.hpp"
#include "ccal/constants.hpp"
#include "ccal/force.hpp"
#include "ccal/units.hpp"
#include "ccal/version.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct ForceOptions {
  std::string config;
  std::string run = "1";
  std::string time = "0";
  std::string mode = "exact";
  OutputOptions output;
};

constexpr double kDeg = constants::deg;

// Angle in degrees wrapped to [0, 360).
double wrapped_deg(double rad) {
  const double d = std::fmod(rad / kDeg, 360.0);
  return d < 0 ? d + 360.0 : d;
}

nlohmann::ordered_json axes(const Eigen::Vector3d& v, double scale) {
  return {{"IA", v[0] * scale}, {"PA", v[1] * scale}, {"OA", v[2] * scale}};
}

nlohmann::ordered_json ia_pair(double f, double w) { return {{"f_IA_g", f}, {"w_IA_deg_per_s", w / kDeg}}; }

std::string to_json(const Config& cfg, std::size_t index, const ForceResult& r) {
  nlohmann::ordered_json j;
  j["command"] = "force";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = r.mode == ModelMode::exact ? "exact" : "paper";
  j["run"] = {{"index", index + 1},
              {"name", r.run.name},
              {"g_level_g", r.run.g_level},
              {"rate_rad_per_s", r.rate},
              {"initial_phase_rad", r.initial_phase},
              {"duration_s", r.run.duration},
              {"time_s", r.time},
              {"platform", platform_mode_name(r.run.mode)},
              {"mounting", mounting_name(r.run.mounting)},
              {"arm_azimuth_rad", r.run.arm_azimuth}};
  j["joint_state"] = {{"theta1_rad", r.joints.theta1},
                      {"theta1_rate_rad_per_s", r.joints.theta1_rate},
                      {"beta_rad", r.joints.beta},
                      {"gamma_rad", r.joints.gamma},
                      {"gamma_rate_rad_per_s", r.joints.gamma_rate}};
  j["specific_force_g"] = axes(r.specific_force, 1.0);
  j["angular_rate_deg_per_s"] = axes(r.angular_rate, 1.0 / kDeg);
  nlohmann::ordered_json contributions = nlohmann::ordered_json::array();
  for (const auto& c : r.contributions)
    contributions.push_back({{"id", c.id},
                             {"value_si", c.value_si},
                             {"unit", c.unit},
                             {"f_IA_g", c.f_ia},
                             {"w_IA_deg_per_s", c.w_ia / kDeg}});
  j["contributions"] = contributions;
  j["first_order"] = {{"nominal", ia_pair(r.nominal_f_ia, r.nominal_w_ia)},
                      {"total", ia_pair(r.first_order_f_ia, r.first_order_w_ia)},
                      {"exact", ia_pair(r.specific_force[0], r.angular_rate[0])},
                      {"remainder", ia_pair(r.remainder_f_ia(), r.remainder_w_ia())}};
  return j.dump(2) + "\n";
}

std::string to_text(const Config& cfg, std::size_t index, const ForceResult& r) {
  const std::string mode = r.mode == ModelMode::exact ? "exact" : "paper";
  std::string out = fmt::format("ccal force: run {} of {}, '{}', from {}\n\n", index + 1,
                                cfg.plan.runs.size(), r.run.name, cfg.source);
  Table run({"run", "value"});
  run.add_row({"g-level [g]", number(r.run.g_level)});
  run.add_row({"main-axis rate Omega [rad/s]", number(r.rate)});
  run.add_row({"initial phase phi0 [rad]",
               fmt::format("{} ({} deg)", number(r.initial_phase), number(r.initial_phase / kDeg, 6))});
  run.add_row({"duration T [s]", number(r.run.duration)});
  run.add_row({"time t [s]", number(r.time)});
  run.add_row({"platform", std::string(platform_mode_name(r.run.mode))});
  run.add_row({"mounting", std::string(mounting_name(r.run.mounting))});
  out += run.render() + "\n";

  Table joints({"joints at t", "angle [deg, mod 360]", "rate [rad/s]"});
  joints.add_row({"main axis theta1", number(wrapped_deg(r.joints.theta1)), number(r.joints.theta1_rate)});
  joints.add_row({"horizontal axis beta", number(wrapped_deg(r.joints.beta)), number(r.joints.beta_rate)});
  joints.add_row({"platform gamma", number(wrapped_deg(r.joints.gamma)), number(r.joints.gamma_rate)});
  out += joints.render() + "\n";

  Table sensed({"exact input at t", "IA", "PA", "OA"});
  sensed.add_row({"specific force [g]", number(r.specific_force[0]), number(r.specific_force[1]),
                  number(r.specific_force[2])});
  sensed.add_row({"angular rate [deg/s]", number(r.angular_rate[0] / kDeg), number(r.angular_rate[1] / kDeg),
                  number(r.angular_rate[2] / kDeg)});
  out += sensed.render() + "\n";

  Table first({fmt::format("first order along the IA ({} model)", mode), "value", "unit", "f_IA [g]",
               "w_IA [deg/s]"});
  first.add_row({"error-free", "", "", number(r.nominal_f_ia), number(r.nominal_w_ia / kDeg)});
  for (const auto& c : r.contributions)
    first.add_row({c.id, number(c.value_si, 6), c.unit, number(c.f_ia), number(c.w_ia / kDeg)});
  if (r.contributions.empty()) first.add_row({"(no non-zero [errors])"});
  first.add_rule();
  first.add_row({"first-order total", "", "", number(r.first_order_f_ia), number(r.first_order_w_ia / kDeg)});
  first.add_row({"exact", "", "", number(r.specific_force[0]), number(r.angular_rate[0] / kDeg)});
  first.add_row({"remainder (exact - first order)", "", "", number(r.remainder_f_ia(), 6),
                 number(r.remainder_w_ia() / kDeg, 6)});
  out += first.render();
  return out;
}

}  // namespace

Command add_force(CLI::App& app) {
  auto options = std::make_shared<ForceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "force",
      "Specific force and angular rate at the instrument at one instant of a run, exact and as "
      "first-order contributions of the configured [errors].");
  add_config_argument(*cmd, options->config);
  cmd->add_option("--run", options->run, "Run name or 1-based index")->capture_default_str()->type_name("J");
  cmd->add_option("--time", options->time, "Time into the run, e.g. \"10 s\" or 10 (seconds), within [0, T]")
      ->capture_default_str()
      ->type_name("T");
  cmd->add_option("--mode", options->mode,
                  "First-order model: exact (linearised exact chain) or paper (Wang & Ren Eq.14 form)")
      ->check(CLI::IsMember({"exact", "paper"}))
      ->capture_default_str();
  add_output_options(*cmd, options->output, {"text", "json"});
  cmd->footer(
      "Examples:\n"
      "  ccal force\n"
      "      run 1 of the bundled paper example at t = 0\n"
      "  ccal force examples/wang_ren_2014.toml --run 20g --time \"10 s\" --mode paper\n"
      "  ccal force my.toml --run 3 --time 120 --format json -o force.json\n");

  return {cmd, [options] {
            const Config cfg = load_config_or_example(options->config);
            const std::size_t index = select_run(cfg.plan, options->run, "--run");
            const Run& run = cfg.plan.runs[index];
            const double t = parse_as(options->time, kind::time, "--time", true);
            if (!(t >= 0.0 && t <= run.duration))
              throw InputError(fmt::format("--time: {} s is outside run '{}'; accepted: 0 to {} s", number(t),
                                           run.name, number(run.duration)));
            const ModelMode mode = options->mode == "paper" ? ModelMode::paper : ModelMode::exact;
            const ForceResult result = evaluate_force(cfg.site, cfg.centrifuge, run, t, mode);
            write_output(options->output, options->output.format == "json" ? to_json(cfg, index, result)
                                                                           : to_text(cfg, index, result));
          }};
}

}  // namespace ccal::cli

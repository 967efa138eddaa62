#include "ccal/render/force.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "ccal/core/constants.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"

namespace ccal::render {
namespace {

// Angle in degrees wrapped to [0, 360).
double wrapped_deg(double rad) {
  const double d = std::fmod(rad / constants::deg, 360.0);
  return d < 0 ? d + 360.0 : d;
}

nlohmann::ordered_json axes(const Eigen::Vector3d& v, double scale) {
  return {{"IA", v[0] * scale}, {"PA", v[1] * scale}, {"OA", v[2] * scale}};
}

nlohmann::ordered_json ia_pair(double f, double w) {
  return {{"f_IA_g", f}, {"w_IA_deg_per_s", w / constants::deg}};
}

std::string json_text(const Config& cfg, std::size_t index, const SensedInputBreakdown& r) {
  nlohmann::ordered_json j;
  j["command"] = "force";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = mode_name(r.mode);
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
  j["angular_rate_deg_per_s"] = axes(r.angular_rate, 1.0 / constants::deg);
  nlohmann::ordered_json contributions = nlohmann::ordered_json::array();
  for (const auto& c : r.contributions)
    contributions.push_back({{"id", c.id},
                             {"value_si", c.value_si},
                             {"unit", c.unit},
                             {"f_IA_g", c.f_ia},
                             {"w_IA_deg_per_s", c.w_ia / constants::deg}});
  j["contributions"] = contributions;
  j["first_order"] = {{"nominal", ia_pair(r.nominal_f_ia, r.nominal_w_ia)},
                      {"total", ia_pair(r.first_order_f_ia, r.first_order_w_ia)},
                      {"exact", ia_pair(r.specific_force[0], r.angular_rate[0])},
                      {"remainder", ia_pair(r.remainder_f_ia(), r.remainder_w_ia())}};
  return j.dump(2) + "\n";
}

std::string text_of(const Config& cfg, std::size_t index, const SensedInputBreakdown& r) {
  const std::string mode(mode_name(r.mode));
  std::string out = fmt::format("ccal force: run {} of {}, '{}', from {}\n\n", index + 1,
                                cfg.plan.runs.size(), r.run.name, cfg.source);
  Table run({"run", "value"});
  run.add_row({"g-level [g]", number(r.run.g_level)});
  run.add_row({"main-axis rate Omega [rad/s]", number(r.rate)});
  run.add_row({"initial phase phi0 [rad]", fmt::format("{} ({} deg)", number(r.initial_phase),
                                                       number(r.initial_phase / constants::deg, 6))});
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
  sensed.add_row({"angular rate [deg/s]", number(r.angular_rate[0] / constants::deg),
                  number(r.angular_rate[1] / constants::deg), number(r.angular_rate[2] / constants::deg)});
  out += sensed.render() + "\n";

  Table first({fmt::format("first order along the IA ({} model)", mode), "value", "unit", "f_IA [g]",
               "w_IA [deg/s]"});
  first.add_row({"error-free", "", "", number(r.nominal_f_ia), number(r.nominal_w_ia / constants::deg)});
  for (const auto& c : r.contributions)
    first.add_row({c.id, number(c.value_si, 6), c.unit, number(c.f_ia), number(c.w_ia / constants::deg)});
  if (r.contributions.empty()) first.add_row({"(no non-zero [errors])"});
  first.add_rule();
  first.add_row(
      {"first-order total", "", "", number(r.first_order_f_ia), number(r.first_order_w_ia / constants::deg)});
  first.add_row({"exact", "", "", number(r.specific_force[0]), number(r.angular_rate[0] / constants::deg)});
  first.add_row({"remainder (exact - first order)", "", "", number(r.remainder_f_ia(), 6),
                 number(r.remainder_w_ia() / constants::deg, 6)});
  out += first.render();
  return out;
}

}  // namespace

// The first-order breakdown of the IA input and the exact input on all three axes, one row each: the nominal
// part, each error's contribution (with the error's value, SI), their sum, the exact value (IA, PA, OA) and
// the remainder (exact − first order). 17 digits, so that the file reads back to the same doubles.
std::string csv_of(const SensedInputBreakdown& r) {
  std::string out =
      "row,error_value_si,error_unit,f_IA_g,f_PA_g,f_OA_g,w_IA_deg_per_s,w_PA_deg_per_s,w_OA_deg_per_s\n";
  const auto ia_row = [&](std::string_view row, std::string value, std::string_view unit, double f,
                          double w) {
    out += fmt::format("{},{},{},{:.17g},,,{:.17g},,\n", row, value, unit, f, w / constants::deg);
  };
  ia_row("nominal", "", "", r.nominal_f_ia, r.nominal_w_ia);
  for (const auto& c : r.contributions)
    ia_row(c.id, fmt::format("{:.17g}", c.value_si), c.unit, c.f_ia, c.w_ia);
  ia_row("first_order", "", "", r.first_order_f_ia, r.first_order_w_ia);
  const Eigen::Vector3d& f = r.specific_force;
  const Eigen::Vector3d w = r.angular_rate / constants::deg;
  out += fmt::format("exact,,,{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", f[0], f[1], f[2], w[0], w[1],
                     w[2]);
  ia_row("remainder", "", "", r.remainder_f_ia(), r.remainder_w_ia());
  return out;
}

std::string text(const verbs::ForceResult& r) { return text_of(r.config, r.run_index, r.input); }
std::string json(const verbs::ForceResult& r) { return json_text(r.config, r.run_index, r.input); }
std::string csv(const verbs::ForceResult& r) { return csv_of(r.input); }

}  // namespace ccal::render

#include "ccal/model/sensed_input.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/model/first_order.hpp"

namespace ccal {

namespace {

// The first-order view along the IA: the error-free value and one contribution per non-zero error
// (sensitivity × value), which add to the first-order total.
void add_first_order_along_ia(const FirstOrderResult& first, const Eigen::Vector3d& ia,
                              const CentrifugeModel& centrifuge, SensedInputBreakdown& out) {
  const ErrorLayout& layout = centrifuge.layout;
  // IA component of a frame-5 vector (rows 0..2 or 3..5 of the first-order result). The paper's form fills
  // only the x5 rows, which is all an IA along ±x5 needs.
  auto along_ia = [&](const Eigen::Matrix<double, 6, 1>& v, int first_row) {
    return ia.dot(v.segment<3>(first_row));
  };
  out.nominal_f_ia = along_ia(first.nominal, 0);
  out.nominal_w_ia = along_ia(first.nominal, 3);
  out.first_order_f_ia = out.nominal_f_ia;
  out.first_order_w_ia = out.nominal_w_ia;
  for (int i = 0; i < layout.size(); ++i) {
    const double v = centrifuge.errors[i];
    if (v == 0.0) continue;
    const Eigen::Matrix<double, 6, 1> column = first.sensitivity.col(i);
    ForceContribution c;
    c.parameter = i;
    c.id = layout.parameter_id(i);
    c.value_si = v;
    c.unit = std::string(unit_symbol(layout.parameter_unit(i)));
    c.f_ia = along_ia(column, 0) * v;
    c.w_ia = along_ia(column, 3) * v;
    out.first_order_f_ia += c.f_ia;
    out.first_order_w_ia += c.w_ia;
    out.contributions.push_back(std::move(c));
  }
}

}  // namespace

SensedInputBreakdown evaluate_force(const Site& site, const CentrifugeModel& centrifuge, const Run& run,
                                    double t, ModelMode mode) {
  if (!(t >= 0.0 && t <= run.duration))
    throw InputError(fmt::format("time {} s is outside run '{}', which lasts {} s; accepted: 0 to {} s", t,
                                 run.name, run.duration, run.duration));
  const Geometry& geo = centrifuge.geometry;
  const ErrorLayout& layout = centrifuge.layout;
  const Eigen::Matrix3d M = mounting_matrix(run.mounting);
  if (mode == ModelMode::paper && std::abs(M(0, 0)) != 1.0)
    throw InputError(
        fmt::format("run '{}': mode paper gives the input along IA = ±x5 only, and this run's "
                    "mounting puts the IA elsewhere; accepted: mode exact, or mounting "
                    "ia_horizontal, ia_reversed or pa_vertical",
                    run.name));

  SensedInputBreakdown out;
  out.run = run;
  out.rate = nominal_rate(run, geo, site);
  out.initial_phase = initial_phase(run, geo, site);
  out.time = t;
  out.mode = mode;

  const RunMotion<double> actual = run_motion<double>(out.rate, run.arm_azimuth, out.initial_phase, run.mode,
                                                      geo, layout, centrifuge.errors);
  out.joints = actual.at(t);
  const InstrumentState<double> state = exact_state<double>(geo, layout, centrifuge.errors, site, out.joints);
  out.specific_force = M.transpose() * state.specific_force;
  out.angular_rate = M.transpose() * state.angular_rate;

  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(layout.size());
  const RunMotion<double> nominal =
      run_motion<double>(out.rate, run.arm_azimuth, out.initial_phase, run.mode, geo.beta, zero);
  const FirstOrderResult first = mode == ModelMode::exact
                                     ? exact_first_order(geo, layout, site, nominal, run.mode, t)
                                     : paper_first_order(geo, layout, site, nominal.at(t));
  add_first_order_along_ia(first, M.col(0), centrifuge, out);
  return out;
}

}  // namespace ccal

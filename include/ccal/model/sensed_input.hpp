#pragma once
// The sensed input of the instrument at one instant of a run, exact and to first order in the centrifuge
// errors (the `ccal force` command). The exact value comes from the full chain with the centrifuge's actual
// errors (drive errors included in the joint motion); the first-order view splits the error effect into one
// contribution per non-zero error parameter, so that
//     exact = nominal + Σ contributions + nonlinear remainder.
// In paper mode the nominal value and the contributions follow the paper's Eq.(14) form (paper_first_order),
// so the remainder also holds everything the paper's approximations leave out.
//
// Instrument axes: IA, PA, OA of the run's mounting, i.e. mounting_matrix(m)ᵀ × (frame-5 components).

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"

namespace ccal {

struct ForceContribution {
  int parameter = 0;      // index in the centrifuge's ErrorLayout
  std::string id;         // e.g. "dthz5"
  double value_si = 0.0;  // the parameter's value [SI unit of the parameter]
  std::string unit;       // that SI unit: rad, m, rad/s, m/(rad/s)^2
  double f_ia = 0.0;      // first-order change of the specific force along the IA [g]
  double w_ia = 0.0;      // first-order change of the inertial rate about the IA [rad/s]
};

struct SensedInputBreakdown {
  Run run;
  double rate = 0.0;           // nominal main-axis rate Ω [rad/s]
  double initial_phase = 0.0;  // φ0 [rad]
  double time = 0.0;           // t [s]
  ModelMode mode = ModelMode::exact;
  JointState<double> joints;       // joint angles and rates at t, drive errors included
  Eigen::Vector3d specific_force;  // exact, along IA, PA, OA [g]
  Eigen::Vector3d angular_rate;    // exact, inertial, about IA, PA, OA [rad/s]
  // First-order view of the IA components: error-free value of the model (exact chain, or the paper's form),
  // one contribution per non-zero error parameter (catalogue order), and their sum.
  double nominal_f_ia = 0.0, nominal_w_ia = 0.0;
  std::vector<ForceContribution> contributions;
  double first_order_f_ia = 0.0, first_order_w_ia = 0.0;
  // exact − first order: the nonlinear remainder (plus, in paper mode, the paper form's own model error).
  double remainder_f_ia() const { return specific_force[0] - first_order_f_ia; }
  double remainder_w_ia() const { return angular_rate[0] - first_order_w_ia; }
};

// Evaluates run `run` at time t ∈ [0, T]. Throws InputError if t is outside the run, or if paper mode is
// asked for a mounting whose IA is not along ±x5 (the paper's form covers only that).
SensedInputBreakdown evaluate_force(const Site& site, const CentrifugeModel& centrifuge, const Run& run,
                                    double t, ModelMode mode = ModelMode::exact);

}  // namespace ccal

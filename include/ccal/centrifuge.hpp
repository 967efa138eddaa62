#pragma once
// The centrifuge as data: nominal geometry plus the values of every error parameter (docs/model.md §2–3).

#include <Eigen/Core>
#include <string_view>

#include "ccal/error_sources.hpp"

namespace ccal {

enum class PlatformMode {
  counter_rotating,  // γ̇ = −(Ω + Δω + ΔΩ): the platform holds its inertial heading
  fixed,             // γ constant: the instrument turns with the arm
};

struct Geometry {
  double R0 = 2.5;    // nominal radius: main axis to azimuth axis [m]
  double L = 0.0;     // azimuth-axis origin o3 to working base plane [m]
  double l = 0.0;     // base plane to instrument origin o5 [m]
  double beta = 0.0;  // horizontal-axis angle [rad]; 0 in the paper
};

struct CentrifugeModel {
  Geometry geometry;
  ErrorLayout layout{1};
  Eigen::VectorXd errors = Eigen::VectorXd::Zero(ErrorLayout{1}.size());  // SI, indexed by `layout`

  CentrifugeModel() = default;
  explicit CentrifugeModel(Geometry g, int harmonic_order = 1)
      : geometry(g), layout(harmonic_order), errors(Eigen::VectorXd::Zero(layout.size())) {}

  // By parameter id ("dthz5", "dx3_c1", …); throws std::out_of_range naming the id if there is none.
  double error(std::string_view id) const;
  void set_error(std::string_view id, double value_si);
  bool has_dynamic_errors() const;
};

}  // namespace ccal

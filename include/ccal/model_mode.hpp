#pragma once

namespace ccal {

// Which kinematics a computation uses (docs/model.md §4, §5.1).
enum class ModelMode {
  exact,  // the full chain (the default)
  paper,  // the paper's first-order rules: frozen-γ, constant Coriolis and Δx5 terms, K1-only error terms
};

}  // namespace ccal

#pragma once
#include <array>
#include <string_view>

namespace ccal {

// Which kinematics a computation uses (docs/model.md §4, §5.1).
enum class ModelMode {
  exact,  // the full chain (the default)
  paper,  // the paper's first-order rules: frozen-γ, constant Coriolis and Δx5 terms, K1-only error terms
};

// The name of a mode as the configuration, the options and every report write it: "exact" or "paper".
constexpr std::string_view mode_name(ModelMode m) noexcept {
  return m == ModelMode::exact ? "exact" : "paper";
}

// Every mode's name, in the enum's order: what an option or a key accepts.
inline constexpr std::array<std::string_view, 2> kModeNames = {mode_name(ModelMode::exact),
                                                               mode_name(ModelMode::paper)};

}  // namespace ccal

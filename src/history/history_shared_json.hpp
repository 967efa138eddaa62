#pragma once
// What a calibration shares (uncertainty/history_shared.hpp) as JSON: read from a calibration statement's
// keys (setup_sha256, inputs[] {id, measured, group, effect}, input_correlations [[a, b, ρ]], covariance
// {order, type_b}), and written to the store's `shared` column with the same keys, so that one reader serves
// both.
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "ccal/uncertainty/history_shared.hpp"

namespace ccal::detail {

// None when the statement states no setup_sha256 (written before it was kept); InputError naming `source` and
// the key for a malformed part.
std::optional<SharedPart> shared_part_of(const nlohmann::json& statement, const std::string& source);
std::string shared_part_text(const SharedPart& part);

// A JSON parser's message without its library's tag ("[json.exception.parse_error.101] "): where and what.
inline std::string json_problem(std::string message) {
  if (message.starts_with("[json.exception.")) message.erase(0, message.find("] ") + 2);
  return message;
}

}  // namespace ccal::detail

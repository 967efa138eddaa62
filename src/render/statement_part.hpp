#pragma once
// The calibration statement (verbs/statement.hpp) as a section of the reports of `ccal reduce` and `ccal
// identify` (private to the library). In JSON an infinite number of degrees of freedom is null.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "ccal/verbs/statement.hpp"

namespace ccal::render {

nlohmann::ordered_json statement_json(const verbs::CalibrationStatement& statement);
std::string statement_text(const verbs::CalibrationStatement& statement, std::size_t width = 100);

// How its Type A part was evaluated (and the residuals' check), and its table of Type B inputs
// (statement_inputs.cpp).
std::string type_a_text(const verbs::CalibrationStatement& statement, std::size_t width);
std::string inputs_text(const verbs::CalibrationStatement& statement, std::size_t width);
nlohmann::ordered_json type_a_json(const verbs::CalibrationStatement& statement);
nlohmann::ordered_json inputs_json(const verbs::CalibrationStatement& statement);

}  // namespace ccal::render

#pragma once
// The identification section shared by the reports of `simulate`, `identify` and `reduce`: text, and JSON
// (an object, as text).
#include <string>

#include "ccal/verbs/identification.hpp"

namespace ccal::render {

std::string text(const verbs::Identification& identification);
std::string json(const verbs::Identification& identification);

}  // namespace ccal::render

#pragma once
// Numbers as ccal writes them for people, in messages and reports.
#include <string>

namespace ccal {

// Number with `digits` significant digits (%g style); "0" for zero.
std::string number(double v, int digits = 9);

}  // namespace ccal

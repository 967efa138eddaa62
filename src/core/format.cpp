#include "ccal/core/format.hpp"

#include <fmt/format.h>

namespace ccal {

std::string number(double v, int digits) {
  if (v == 0.0) return "0";
  return fmt::format("{:.{}g}", v, digits);
}

}  // namespace ccal

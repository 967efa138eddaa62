#pragma once
// A target on the expanded uncertainty of a free coefficient, as `ccal allocate --target`, `ccal design --target`
// and the [design] table give it, read into SI.

#include <string>
#include <string_view>
#include <vector>

namespace ccal {

// A target on one free coefficient: its allowed expanded uncertainty (half-width of the 100p % interval), SI.
struct AllocationTarget {
  std::string coefficient;
  double expanded = 0;
  std::string text = "";          // as given, e.g. "K3=1e-6", for messages
  std::string field = "targets";  // the option it was given in, for messages
};

// Parses "K3=1e-6" (a number in the coefficient's display unit, e.g. deg/s/g^3) or "K3=1e-6 deg/s/g^3" (a
// quantity whose unit must have the coefficient's dimension) into SI. coefficients and units: the free terms
// and their display units (e.g. BudgetDetail::coefficients, ::units). Throws OptionError of `field` (the option
// the text was given in) for bad syntax, an unknown or non-free coefficient (listing the free terms), a wrong
// unit or a value ≤ 0.
AllocationTarget parse_allocation_target(std::string_view text, const std::vector<std::string>& coefficients,
                                         const std::vector<std::string>& units,
                                         std::string_view field = "targets");

}  // namespace ccal

#pragma once
// What an input of the budget is, for reading and printing it: a centrifuge error of the layout or an input
// of the measuring chain (setup/measuring_chain.hpp), by its parameter code. The one home of each input's
// dimension, its SI unit, the unit it is shown in by default and an example bound.

#include <string>

#include "ccal/core/units.hpp"
#include "ccal/setup/config.hpp"

namespace ccal {

struct InputDescription {
  std::string id;    // "dthz5", "g", "K1", "encoder1_c2", a declared id
  std::string name;  // what it is, in words
  Dimension dim;     // of its SI values (a declared input: dimensionless, its values are in its own unit)
  std::string si_unit;       // the SI unit's symbol ("rad", "m/s^2"; "1" for a relative input)
  std::string display_unit;  // the unit it is shown in unless written in another ("um", "ppm", "arcsec")
  std::string example;       // a bound as a user writes it, e.g. "25 um"
  double estimate_si = 0;    // the lab's estimate of its error ([errors]); 0 for the chain's inputs
  bool own_unit = false;     // a declared input: its values are in its own unit, which ccal does not parse
  double relative_to = 0;    // a fixed term: |its value| (SI), what a relative unit ("ppm") is a fraction of
  // The kind of standard its value is traceable to (a key of kTraceabilityKinds, setup/certificate.hpp): the
  // arm radius, other lengths, angles, rates and encoders, the time base, g, the output chain, the fixed
  // terms' source; a declared input its own id.
  std::string traceability;
};

// The size of one `unit` in the input's SI unit (1 for a declared input's own unit; a relative unit of a fixed
// term is that fraction of its value); pulses count as rad.
double unit_in_si(const InputDescription& d, const std::string& unit);
// A value in SI as text in `unit` with 4 significant digits, e.g. "0.5 arcsec" or "0.05 K".
std::string input_quantity_text(const InputDescription& d, double si, const std::string& unit);

// Of a layout parameter or a chain parameter code of the configuration (std::invalid_argument otherwise).
InputDescription describe_input(const Config& config, int parameter);
// The same for a layout parameter alone (no configuration needed).
InputDescription describe_layout_parameter(const ErrorLayout& layout, int parameter);

// The SI dimension of the instrument's output unit (pulses read as rad): rad/s for deg/s or pulse/s.
Dimension output_dimension(const std::string& output_unit);

}  // namespace ccal

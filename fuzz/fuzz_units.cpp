// Fuzz target: the unit parser and quantity reader (src/units.cpp). Any input must either parse or throw
// ccal::InputError; anything else (a crash, another exception, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)ccal::parse_unit(text);
  } catch (const ccal::InputError&) {
  }
  try {
    (void)ccal::parse_quantity(text);
  } catch (const ccal::InputError&) {
  }
  return 0;
}

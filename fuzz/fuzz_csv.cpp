// Fuzz target: the CSV reader and the observations header (src/observation_csv.cpp).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "ccal/core/errors.hpp"
#include "ccal/io/observation_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const ccal::CsvTable t = ccal::parse_csv(text, "fuzz.csv");
    (void)ccal::observations_header(t);
    for (const auto& name : t.header) (void)t.numbers(name, "fuzzing");
  } catch (const ccal::InputError&) {
  }
  return 0;
}

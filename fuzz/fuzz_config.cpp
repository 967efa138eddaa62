// Fuzz target: the configuration loader (src/config.cpp) on arbitrary TOML text. Seeds: examples/*.toml.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const ccal::Config cfg = ccal::parse_config(text, "fuzz.toml");
    (void)cfg.experiment();
  } catch (const ccal::InputError&) {
  }
  return 0;
}

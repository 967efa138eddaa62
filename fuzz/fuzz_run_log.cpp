// Fuzz target: a run log (src/run_log.cpp) as CSV text, reduced as the log of the bundled example's first run
// (its planned rate bounds the encoder sampling), in radians and degrees, and that run as measured.
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string_view>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/run_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ccal::Config cfg = ccal::bundled_example();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const ccal::CsvTable t = ccal::parse_csv(text, "fuzz_log.csv");
    for (double angle_scale : {1.0, std::numbers::pi / 180}) {
      ccal::RunLogOptions o;
      o.pulse_weight = 1e-6;
      o.angle_scale = angle_scale;
      try {
        const ccal::ReducedLog log = ccal::reduce_run_log(t, o, 4.4);
        (void)ccal::measured_run(cfg.plan.runs[0], log, cfg.centrifuge.geometry, cfg.site);
      } catch (const ccal::InputError&) {
      }
    }
  } catch (const ccal::InputError&) {
  }
  return 0;
}

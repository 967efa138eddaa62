// Fuzz target: a run log (src/io/run_log.cpp) as CSV text, reduced as the log of the bundled example's first
// run (its planned rate bounds the encoder sampling), in radians and degrees, and that run as measured. The
// same text streamed from a file (csv_stream.hpp: its rows of plain decimals read in place, those laid out
// alike by their layout, plain_decimal_row.hpp) must reduce to the same bits, or be refused in the same words,
// as the table read whole; a difference aborts. (corpus/fuzz_run_log/seed_logger_rows.csv: rows as loggers
// write them, one of another layout among them.)
#include <unistd.h>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <string_view>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/intake/run_log.hpp"

namespace {

// Every number of a reduction, as the bits of its doubles.
std::string bits(const ccal::ReducedLog& r) {
  std::string out = std::to_string(r.samples) + (r.pulses ? "p" : "o") + (r.has_theta1 ? "t" : "") +
                    (r.has_gamma ? "g" : "");
  auto add = [&out](double v) { out += ' ' + std::to_string(std::bit_cast<std::uint64_t>(v)); };
  for (double v :
       {r.duration, r.mean_output, r.theta1_rate, r.theta1_start, r.theta1_rms, r.theta1_harmonic_sigma,
        r.gamma_rate, r.gamma_start, r.gamma_end, r.gamma_rms, r.gamma_harmonic_sigma})
    add(v);
  for (double v : r.theta1_harmonics) add(v);
  out += ';';
  for (double v : r.gamma_harmonics) add(v);
  return out;
}

template <class Reduce>
std::string outcome(Reduce reduce) {
  try {
    return bits(reduce());
  } catch (const ccal::InputError& e) {
    return std::string("refused: ") + e.what();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ccal::Config cfg = ccal::bundled_example();
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("ccal_fuzz_run_log_" + std::to_string(::getpid()) + ".csv");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (f == nullptr || std::fwrite(text.data(), 1, text.size(), f) != text.size()) std::abort();
  std::fclose(f);
  for (double angle_scale : {1.0, std::numbers::pi / 180}) {
    ccal::RunLogOptions o;
    o.pulse_weight = 1e-6;
    o.angle_scale = angle_scale;
    auto measured = [&](const ccal::ReducedLog& log) {
      (void)ccal::measured_run(cfg.plan.runs[0], log, cfg.centrifuge.geometry, cfg.site);
      return log;
    };
    const std::string table =
        outcome([&] { return measured(ccal::reduce_run_log(ccal::parse_csv(text, file.string()), o, 4.4)); });
    const std::string streamed = outcome([&] { return measured(ccal::reduce_run_log_file(file, o, 4.4)); });
    // A text parse_csv refuses as CSV (a ragged row, …) the stream may refuse for its header first (a preamble
    // read as the header names none of a log's columns, run_log.cpp): both refuse, each in its words.
    bool csv = true;
    try {
      (void)ccal::parse_csv(text, file.string());
    } catch (const ccal::InputError&) {
      csv = false;
    }
    if (!csv && table.starts_with("refused: ") && streamed.starts_with("refused: ")) continue;
    if (table != streamed) {
      std::fprintf(stderr, "table:    %s\nstreamed: %s\n", table.c_str(), streamed.c_str());
      std::abort();
    }
  }
  return 0;
}

// The same simulated test (examples/lab.toml with the truth of examples/lab_truth.toml) written in each layout a
// data acquisition system may use — ccal's comma-separated file, semicolons with decimal commas, tabs, a units
// row, ISO 8601 timestamps, encoders in counts latched down or to the nearest, a 5 s gap in every run —
// reduces to the same coefficients within the quantisation of the logs (intake/log_manifest.hpp, docs/cli.md "A
// folder of logs").
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"
#include "test_paths.hpp"

namespace ccal::test {
namespace {

namespace fs = std::filesystem;

struct Layout {
  std::string name;
  std::string toml;  // the layout file's text (--log-layout)
  bool gap = false;  // the rows of 100 s < t < 105 s left out of every run
};

const Layout kLayouts[] = {
    {"semicolon, decimal comma, ms", R"([format]
delimiter = "semicolon"
decimal = "comma"
[columns]
time = "t_ms"
time_unit = "ms"
pulses = "piga_count"
)"},
    {"tab, counts to the nearest", R"([format]
delimiter = "tab"
[columns]
angle_unit = "counts"
counts_per_revolution = 16777216
count_rounding = "nearest"
)"},
    {"units row, preamble, counts latched down", R"([format]
header_line = 3
units_row = true
[columns]
time_unit = "ms"
angle_unit = "counts"
counts_per_revolution = 16777216
count_rounding = "floor"
)"},
    {"whitespace, ISO 8601 timestamps", R"([format]
delimiter = "whitespace"
[columns]
time_unit = "iso8601"
)"},
    {"a 5 s gap", R"([format]
max_gap = "10 s"
)",
     true},
};

class ReduceLayouts : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ccal-reduce-layouts-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    config_ = load_config(source_dir() + "/examples/lab.toml");
    verbs::SimulateOptions so;
    so.truth = load_truth(source_dir() + "/examples/lab_truth.toml", config_);
    sim_ = verbs::simulate(config_, so);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The simulation's logs written in `layout` to a folder, reduced as `ccal reduce --log … --log-layout`.
  verbs::ReduceResult reduce_in(const std::string& name, const LogLayout& layout, bool gap) {
    const fs::path folder = dir_ / std::to_string(folders_++);
    fs::create_directories(folder);
    const Eigen::VectorXd& means = sim_.observations.output;
    const auto logs = write_run_logs(sim_.config, sim_.machine_errors, {means.data(), means.data() + means.size()},
                                     default_log_step(config_), layout);
    verbs::ReduceOptions o;
    o.layout = layout;
    for (std::size_t r = 0; r < logs.size(); ++r) {
      std::string text = logs[r].text;
      if (gap) {  // ccal's own layout: t in s is the first cell
        std::istringstream in(text);
        std::string line, kept;
        std::getline(in, line);
        kept = line + "\n";
        while (std::getline(in, line)) {
          const double t = std::stod(line.substr(0, line.find(',')));
          if (!(t > 100 && t < 105)) kept += line + "\n";
        }
        text = kept;
      }
      std::ofstream(folder / logs[r].name) << text;
      o.logs.push_back({config_.plan.runs[r].name, (folder / logs[r].name).string()});
    }
    SCOPED_TRACE(name);
    return verbs::reduce(config_, o);
  }

  fs::path dir_;
  int folders_ = 0;
  Config config_;
  verbs::SimulateResult sim_;
};

// Tolerances, from the quantisation of the logs (the reference, ccal's own file, has 17 digits):
// - the run means: the pulse counts are the same integers in every layout, and T = t_last − t_first the same
//   but for timestamps to the microsecond (±0.5 µs at each end of 30 … 450 s: 2.2e-9 of T at most);
// - the encoders' phases: a count of 2^24 a revolution is q = 3.7e-7 rad; read by its own rounding the line
//   fit's phase is within 0.1 q (the quantisation's error, uniform over ±q/2, averages over the 6215 samples of
//   a run to q/√(12·6215) ≈ 0.004 q, and the line's end to some 0.01 q); read by the other rounding, half a
//   count off, it would fail;
// - the coefficients: 1e-4 of their standard errors, which those changes of the run means (≤ 2.2e-9 of 6.3
//   deg/s) and of the phases stay within (the largest seen: 1.5e-5, for the timestamps).
constexpr double kMeanTolerance = 2.5e-9;  // relative
constexpr double kPhaseTolerance = 0.1 * 2 * 3.141592653589793 / 16777216;  // rad
constexpr double kCoefficientTolerance = 1e-4;  // standard errors

TEST_F(ReduceLayouts, EveryLayoutGivesTheSameCoefficientsWithinTheLogsQuantisation) {
  LogLayout own;
  own.angle_unit = "rad";
  const verbs::ReduceResult reference = reduce_in("comma", own, false);
  const FitResult& a = reference.identification.id.fit;
  for (const Layout& l : kLayouts) {
    SCOPED_TRACE(l.name);
    const LogLayout layout = parse_log_layout(l.toml, l.name);
    const verbs::ReduceResult r = reduce_in(l.name, layout, l.gap);
    ASSERT_EQ(r.logs.runs.size(), reference.logs.runs.size());
    for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
      const ReducedLog &x = r.logs.runs[k].log, &y = reference.logs.runs[k].log;
      EXPECT_NEAR(x.mean_output, y.mean_output, kMeanTolerance * std::abs(y.mean_output));
      // Phases in [0, 2π): compared across the wrap.
      EXPECT_NEAR(std::remainder(x.theta1_start - y.theta1_start, 2 * 3.141592653589793), 0.0, kPhaseTolerance);
      EXPECT_NEAR(std::remainder(x.gamma_start - y.gamma_start, 2 * 3.141592653589793), 0.0, kPhaseTolerance);
      if (l.gap) {
        // The samples missing, each a step of 450 s / (samples − 1) (0.072 s at 30 g): their time is 5 s
        // to a step, the gap less one step.
        const double step = 450.0 / double(y.samples - 1);
        EXPECT_EQ(x.gaps, 1u);
        EXPECT_NEAR(x.missing, 5.0, step);
        EXPECT_NEAR(x.longest_gap, x.missing + step, 1e-9);
        EXPECT_EQ(x.samples + std::size_t(std::lround(x.missing / step)), y.samples);
      } else {
        EXPECT_EQ(x.gaps, 0u);
      }
    }
    const FitResult& b = r.identification.id.fit;
    ASSERT_EQ(b.names, a.names);
    for (Eigen::Index k = 0; k < a.value.size(); ++k)
      EXPECT_NEAR(b.value[k], a.value[k], kCoefficientTolerance * a.std_error[k]) << a.names[std::size_t(k)];
  }
}

}  // namespace
}  // namespace ccal::test

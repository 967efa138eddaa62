// `ccal reduce` as read (render/reduce.hpp), on results of verbs::reduce over run logs simulated from the
// bundled example with known errors (tests/support/simulated_logs.hpp): one row per logged run with its file,
// samples and mean output (12 digits), the encoders' fits or '-' where a log has no encoder, the ripple table
// only when the encoders measured one, a gap named with its length, and JSON entries that carry each encoder
// only when it was logged.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "ccal/core/format.hpp"
#include "ccal/render/reduce.hpp"
#include "ccal/verbs/reduce.hpp"
#include "render_support.hpp"
#include "simulated_logs.hpp"

namespace ccal {
namespace reduce_render_test {

using test::line_starting;
using test::table_cells;

class ReduceRender : public test::SimulatedLogs {
 protected:
  ReduceRender() : SimulatedLogs("ccal-reduce-render") {}
};

class ReduceRenderNoEncoders : public test::SimulatedLogs {
 protected:
  ReduceRenderNoEncoders() : SimulatedLogs("ccal-reduce-render-bare", 2) {}  // time and pulses only
};

TEST_F(ReduceRender, EachLoggedRunHasItsRowAndTheEncodersTheirFits) {
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  const std::string text = render::text(r);
  EXPECT_EQ(text.rfind(fmt::format("ccal reduce: {} logged runs of compensated.toml ({} planned); exact model\n\n",
                                   r.logs.runs.size(), config_.plan.runs.size()),
                       0),
            0u)
      << text;
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
    const LoggedRun& lr = r.logs.runs[k];
    const auto row = line_starting(text, lr.measured.name + " ");
    ASSERT_TRUE(row) << lr.measured.name;
    const auto cells = table_cells(*row);
    ASSERT_EQ(cells.size(), 10u) << *row;
    EXPECT_EQ(cells[1], r.files[k]);
    EXPECT_EQ(cells[2], std::to_string(lr.log.samples));
    EXPECT_EQ(cells[5], number(lr.log.theta1_rate, 12));  // Omega log, from the main-axis encoder
    EXPECT_EQ(cells[9], number(lr.log.mean_output / r.output_unit_si, 12));
  }
  EXPECT_EQ(text.find("gap(s) in the log"), std::string::npos);
  // Both encoders logged: the drives' ripple they measured, per run.
  EXPECT_TRUE(line_starting(text, "drive rate ripple measured by the encoders (model.md §13.1;")) << text;
  const auto j = nlohmann::json::parse(render::json(r));
  ASSERT_EQ(j["runs"].size(), r.logs.runs.size());
  EXPECT_TRUE(j["runs"][0].contains("main_encoder"));
  EXPECT_TRUE(j["runs"][0].contains("platform_encoder"));
  EXPECT_EQ(j["runs"][0]["output_from"], r.logs.runs[0].log.pulses ? "pulses" : "output");
  EXPECT_EQ(j["runs"][0]["output"].get<double>(), r.logs.runs[0].log.mean_output / r.output_unit_si);
  // The CSV is the observations file of these runs.
  EXPECT_EQ(render::csv(r), r.identification.csv);
}

TEST_F(ReduceRenderNoEncoders, WithoutEncodersTheirCellsAreDashesAndNoRippleTable) {
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  const std::string text = render::text(r);
  const auto cells = table_cells(*line_starting(text, r.logs.runs[0].measured.name + " "));
  ASSERT_EQ(cells.size(), 10u);
  EXPECT_EQ(cells[5], "-");  // Omega log
  EXPECT_EQ(cells[8], "-");  // psi
  EXPECT_EQ(text.find("drive rate ripple measured by the encoders"), std::string::npos);
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_FALSE(j["runs"][0].contains("main_encoder"));
  EXPECT_FALSE(j["runs"][0].contains("platform_control"));
}

TEST_F(ReduceRenderNoEncoders, AGapInALogIsNamedWithItsLength) {
  // Lines 200 to 259 of the first log left out: 60 samples, a gap of 61 sample steps (no encoder, whose angle
  // would turn by more than the reduction bridges).
  const std::string file = options_.logs.front().path;
  std::ifstream in(file);
  std::string kept;
  std::size_t n = 0;
  for (std::string line; std::getline(in, line); ++n)
    if (n < 200 || n >= 260) kept += line + "\n";
  in.close();
  std::ofstream(file) << kept;
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  const LoggedRun& first = r.logs.runs.front();
  ASSERT_EQ(first.log.gaps, 1);
  const std::string text = render::text(r);
  EXPECT_TRUE(line_starting(text, fmt::format("run '{}': 1 gap(s) in the log, the longest {} s between samples; {} s "
                                              "of its {} s missing",
                                              first.measured.name, number(first.log.longest_gap),
                                              number(first.log.missing), number(first.log.duration))))
      << text;
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["runs"][0]["gaps"]["count"], 1);
  EXPECT_EQ(j["runs"][0]["gaps"]["longest_s"].get<double>(), first.log.longest_gap);
}

}  // namespace reduce_render_test
}  // namespace ccal

// The time base and an encoder's error (uncertainty/chain_inputs.hpp) against what they do to a test's logs:
// logs of the bundled example written from the model, then read with their time column scaled by 1 + ε (a
// clock fast by ε) or with an angle error in an encoder's column, and reduced as `ccal reduce` reduces them.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

// Each run's log, with every line's cells passed through `edit(column, value)`.
template <class Edit>
std::vector<std::pair<std::size_t, CsvTable>> edited_logs(const Config& config, Edit edit) {
  const Experiment ex = config.experiment();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Observations<double> obs = observe<double>(ex, zero, zero, config.identification);
  const std::vector<double> means(obs.output.data(), obs.output.data() + obs.output.size());
  const std::vector<RunLogFile> files = write_run_logs(config, zero, means, default_log_step(config));
  std::vector<std::pair<std::size_t, CsvTable>> out;
  for (std::size_t j = 0; j < files.size(); ++j) {
    std::istringstream in(files[j].text);
    std::string line, text;
    std::getline(in, line);
    text = line + "\n";
    while (std::getline(in, line)) {
      std::vector<double> cells;
      std::istringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');) cells.push_back(std::stod(cell));
      for (std::size_t c = 0; c < cells.size(); ++c) {
        text += fmt::format("{}{:.17g}", c ? "," : "", edit(c, cells[c]));
      }
      text += "\n";
    }
    out.emplace_back(j, parse_csv(text, files[j].name));
  }
  return out;
}

Eigen::VectorXd reduced(const Config& config, const std::vector<std::pair<std::size_t, CsvTable>>& logs) {
  RunLogOptions o;
  o.output_scale = output_unit_si(config.instrument.output_unit);
  o.pulse_weight = config.instrument.quantum;
  const LogReduction r = reduce_logs(config, logs, o, ModelMode::exact);
  return identify_coefficients<double>(r.observations, config.identification);
}

// The example with both encoders logged, its machine without errors and its instrument without noise, so that
// the logs differ by the one input alone.
Config quiet_example() {
  Config config = bundled_example();
  config.centrifuge.errors.setZero();
  config.instrument.noise_density = 0;
  return config;
}

Eigen::VectorXd measured_sensitivity(const Config& config, int parameter) {
  Experiment ex = config.experiment();
  ex.chain.main_rate_measured = ex.chain.platform_rate_measured = true;
  ex.chain.main_ripple_measured = ex.chain.platform_ripple_measured = true;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  return sensitivities(ex, config.identification, {parameter}, zero, zero, ModelMode::exact).total.col(0);
}

TEST(ChainInputsLogs, TheTimeBaseIsAReductionOfLogsWhoseTimeIsScaled) {
  // A clock fast by ε stamps t (1 + ε): the output's rate reads low by ε and so do both encoders' rates, which
  // the model then takes for the runs' speeds. The reductions share every count, so their difference is ε's
  // alone. The column is the model's prediction over runs T (1 + ε) long at rates / (1 + ε), by a central
  // difference (truncation O(h⁴) at h = 1e-4), and first order (ε² ~ 1e-12 of it); the two agree to 1e-6 of
  // the largest shift here, tolerance 1e-4.
  const Config config = quiet_example();
  const double eps = 1e-6;
  const auto base = edited_logs(config, [](std::size_t, double v) { return v; });
  const auto fast = edited_logs(config, [&](std::size_t c, double v) { return c == 0 ? v * (1 + eps) : v; });
  const Eigen::VectorXd shift = (reduced(config, fast) - reduced(config, base)) / eps;
  const Eigen::VectorXd s = measured_sensitivity(config, chain_parameter({ChainKind::time_base, 0}));
  for (Eigen::Index k = 0; k < s.size(); ++k)
    EXPECT_NEAR(s[k], shift[k], 1e-4 * shift.cwiseAbs().maxCoeff()) << config.identification.free_terms[std::size_t(k)];
}

TEST(ChainInputsLogs, AnEncodersErrorIsAReductionOfLogsWhoseAngleCarriesIt) {
  // The main-axis encoder reads θ1 + c cos θ1: the ripple fit takes it for the drive's ripple (k s, −k c) and
  // the model carries that ripple, which the machine does not have. K̂ is curved in the ripple: the reduction's
  // shift departs from the column by 1.2e-2 relative at c = 1e-6 rad, 1.2e-3 at 1e-7, 1.2e-4 at 1e-8 (second
  // order, measured here), so c = 1e-8 rad and a tolerance of 1e-3 of the largest shift.
  const Config config = quiet_example();
  const double c = 1e-8;
  const auto base = edited_logs(config, [](std::size_t, double v) { return v; });
  const auto read = edited_logs(config, [&](std::size_t col, double v) { return col == 2 ? v + c * std::cos(v) : v; });
  const Eigen::VectorXd shift = (reduced(config, read) - reduced(config, base)) / c;
  const Eigen::VectorXd s =
      measured_sensitivity(config, chain_parameter({ChainKind::encoder, encoder_index({1, 1, false})}));
  for (Eigen::Index k = 0; k < s.size(); ++k)
    EXPECT_NEAR(s[k], shift[k], 1e-3 * shift.cwiseAbs().maxCoeff()) << config.identification.free_terms[std::size_t(k)];
  EXPECT_GT(shift.cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace ccal::test

#pragma once
// The fixture of the in-process tests of `reduce` (tests/verbs/reduce_test.cpp, run_check_test.cpp): the
// bundled example with known, compensated errors (the model of the runs is their truth), simulated, and its
// run logs written into a folder of this process, each named for its run in `options_.logs`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"
#include "verbs_support.hpp"

namespace ccal::test {

class SimulatedLogs : public ::testing::Test {
 protected:
  // `folder`: the name of the folder in the temporary directory (the process id appended); `columns`: the
  // columns each log keeps from the first (0: every column; 2: time and the output, no encoder to tell one
  // run's log from another's).
  explicit SimulatedLogs(std::string folder, std::size_t columns = 0)
      : folder_(std::move(folder)), columns_(columns) {}

  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / (folder_ + "-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    config_ = parse_config(example_with_errors(true), "compensated.toml");
    sim_ = verbs::simulate(config_);
    const Eigen::VectorXd& means = sim_.observations.output;
    const auto logs = write_run_logs(config_, config_.centrifuge.errors,
                                     std::vector<double>(means.data(), means.data() + means.size()),
                                     default_log_step(config_));
    for (std::size_t r = 0; r < logs.size(); ++r) {
      std::ofstream out(dir_ / logs[r].name);
      out << (columns_ == 0 ? logs[r].text : first_columns(logs[r].text));
      options_.logs.push_back({config_.plan.runs[r].name, (dir_ / logs[r].name).string()});
    }
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  Config config_;
  verbs::SimulateResult sim_;
  verbs::ReduceOptions options_;

 private:
  // The log's text with the first columns_ columns of each line (comment lines whole).
  std::string first_columns(const std::string& text) const {
    std::istringstream in(text);
    std::string kept;
    for (std::string line; std::getline(in, line);) {
      std::size_t end = std::string::npos;  // the comma after the last column kept
      for (std::size_t k = 0, from = 0; k < columns_; ++k, from = end + 1)
        if ((end = line.find(',', from)) == std::string::npos) break;
      kept += (line.starts_with("#") ? line : line.substr(0, end)) + "\n";
    }
    return kept;
  }

  std::string folder_;
  std::size_t columns_;
};

}  // namespace ccal::test

#pragma once
// Running the built ccal program from a test: a fixture with a private folder per test, the exit code and
// both output streams of a command line, and the checks of a bad-input failure.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include "test_paths.hpp"

namespace ccal::test {

namespace fs = std::filesystem;

const std::string kProgram = CCAL_BINARY_DIR + "/ccal";
const std::string kExample = CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml";
// The bundled lab example: its configuration and the truth its simulated logs are made from.
const std::string kLab = CCAL_SOURCE_DIR + "/examples/lab.toml";
const std::string kLabTruth = CCAL_SOURCE_DIR + "/examples/lab_truth.toml";
// The paper's set-up as published: the bundled example without the drives' rate ripple and rate noise.
const std::string kPaperExample = CCAL_SOURCE_DIR + "/tests/data/wang_ren_2014_paper.toml";

struct Result {
  int code = -1;
  std::string out, err;
};

inline std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("ccal_cli_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs ccal with the given arguments (already shell-quoted where needed) in the test's folder.
  Result run(const std::string& args) const {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string command = "cd " + quote(dir_.string()) + " && " + quote(kProgram) + " " + args + " >" +
                                quote(out.string()) + " 2>" + quote(err.string());
    const int status = std::system(command.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read(out);
    r.err = read(err);
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  // Writes a configuration file into the test's folder and returns its name (relative to the folder).
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return name;
  }

  // The example with one line replaced (1-based) or extra lines appended after a given line.
  std::string example_with_line(int line, const std::string& text) const {
    std::istringstream in(read(kExample));
    std::string out, l;
    for (int k = 1; std::getline(in, l); ++k) out += (k == line ? text : l) + "\n";
    return out;
  }

  static int line_of(const std::string& text, const std::string& needle) {
    std::istringstream in(text);
    std::string l;
    for (int k = 1; std::getline(in, l); ++k)
      if (l.starts_with(needle)) return k;
    return -1;
  }

  // A bad input: exit code 2, one line on stderr starting "ccal: error: ", containing every hint.
  static void expect_bad_input(const Result& r, std::initializer_list<std::string> hints) {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_TRUE(r.err.starts_with("ccal: error: ")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    for (const auto& h : hints) EXPECT_NE(r.err.find(h), std::string::npos) << "'" << h << "' in " << r.err;
  }

  fs::path dir_;
};

}  // namespace ccal::test

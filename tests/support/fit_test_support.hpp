#pragma once
// Shared by the least-squares tests: names, random designs and relative errors.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "ccal/reduction/fit.hpp"

namespace ccal::fit_test {

using ccal::FitMethod;
using ccal::FitOptions;
using ccal::FitProblem;
using ccal::FitResult;
using ccal::IllPosedFit;
using Eigen::MatrixXd;
using Eigen::VectorXd;

inline double relative_error(const VectorXd& estimate, const VectorXd& truth) {
  return (estimate - truth).norm() / truth.norm();
}

// A random design whose columns differ in magnitude as calibration columns do (1 to 450).
inline MatrixXd random_design(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  MatrixXd h(rows, cols);
  const double magnitudes[] = {1.0, 450.0, 3.7, 0.02, 120.0, 9.0};
  for (Eigen::Index k = 0; k < cols; ++k) {
    for (Eigen::Index i = 0; i < rows; ++i) h(i, k) = magnitudes[k % 6] * uniform(rng);
  }
  return h;
}

inline std::vector<std::string> names_of(int count) {
  std::vector<std::string> names;
  for (int k = 0; k < count; ++k) names.push_back(fmt::format("T{}", k));
  return names;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace ccal::fit_test

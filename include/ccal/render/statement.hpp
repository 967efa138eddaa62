#pragma once
// The calibration statement (verbs/statement.hpp) on its own, as `--statement-out FILE` of `ccal reduce` and
// `ccal identify` writes it and Python's Statement exports it: JSON (the "statement" object of those verbs'
// JSON reports: per coefficient value, U, k, p, ν_eff, interval, rounded figures; the covariance matrices; the
// modelled output per run; an infinite ν is null) and CSV (one row per coefficient, full precision and rounded,
// with its row of the combined covariance in columns cov_<coefficient>; an infinite ν is "inf").
#include <string>

#include "ccal/verbs/statement.hpp"

namespace ccal::render {

std::string text(const verbs::CalibrationStatement& statement);  // as the command line prints it
std::string json(const verbs::CalibrationStatement& statement);
std::string csv(const verbs::CalibrationStatement& statement);

}  // namespace ccal::render

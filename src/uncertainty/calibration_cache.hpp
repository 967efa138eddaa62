#pragma once
// What the Monte Carlo's trials of one calibration model share (montecarlo.hpp's CalibrationModel::cache),
// computed once by calibration_model. Private to the library; tests and benchmarks read it to check the
// kernels against the reference path.

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "../reduction/paper_nodes.hpp"
#include "ccal/reduction/run_means.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

struct CalibrationTrialCache {
  // The analyst's side of the observation equations does not change from trial to trial: H⁺ of the model's
  // design and the known part of each run mean (rate term and fixed terms), so a trial only reduces the
  // truth.
  Eigen::MatrixXd design_pinv;
  Eigen::VectorXd known_part;
  // The truth's run means in exact mode (run_means.hpp): the same rule and chain as average_run, without its
  // per-call set-up.
  std::shared_ptr<const RunMeanKernel> run_means;
  // In paper mode: the error-independent part of each run's paper reduction.
  std::vector<detail::PaperRunNodes> paper_nodes;
  // The measuring chain's inputs among the sources: each its column ∂ȳ/∂x at the actual errors
  // (chain_inputs.hpp), runs × sources, zero for every other source.
  Eigen::MatrixXd chain_columns;
  bool any_chain = false;
  // What each source's draw is, in source order: an error of the layout (source, its index), a run's rate
  // noise (source, the run) or an input of the measuring chain (source): sorted once, not per trial.
  std::vector<std::pair<std::size_t, Eigen::Index>> layout_draws, noise_draws;
  std::vector<std::size_t> chain_draws;
};

}  // namespace ccal

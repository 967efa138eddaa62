#pragma once
// What a calibration test is and what it identifies, without how it is computed: the experiment (geometry,
// error layout, site, plan, instrument, the drives' noise), the identification spec, and the observations a
// test yields (run means and the model's regressors, docs/model.md §8–9).

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "ccal/core/frames.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"
#include "ccal/setup/measuring_chain.hpp"

namespace ccal {

struct Experiment {
  Geometry geometry;
  ErrorLayout layout{1};
  Site site;
  TestPlan plan;
  InstrumentModel instrument;
  DriveNoise rate_noise;  // the drives' random rate noise (Type A scatter of the run means)
  MeasuringChain chain;   // the measuring chain's declared inputs, what a test measured, a truth's errors
};

// What is identified: the free terms, the terms held at known values, and the columns the observation file
// carries (free and fixed terms' regressors).
struct IdentificationSpec {
  std::vector<std::string> free_terms{"K0", "K2", "K3"};
  std::map<std::string, double> fixed_terms;  // id → known value (SI); the paper holds K1 fixed
  bool compensate = false;                    // regressors from the known ([errors]) values instead of zero
  // Paper mode only: keep the pose errors in the K2 and K3 terms too (the reconstruction's "incl. cross
  // terms" column), not in K1 only as the paper does.
  bool paper_cross_terms = false;
};

template <class S>
struct Observations {
  std::vector<std::string> runs;
  std::vector<std::string> columns;  // term ids of the regressor columns (free, then fixed)
  Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> regressors;  // runs × columns, model means
  VecX<S> output;                                               // truth means [output SI]
  VecX<S> known_rate;                                           // model ⟨s_ω ω_IA⟩ [output SI]
  VecX<S> input;                                                // model ⟨a_i⟩ [g]
};

// The observation columns of a spec: free terms then fixed terms.
std::vector<std::string> observation_columns(const IdentificationSpec& spec);

}  // namespace ccal

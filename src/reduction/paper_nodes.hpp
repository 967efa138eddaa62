#pragma once
// What the paper's reduction of a run (observe.hpp's paper_average) needs that does not depend on the errors,
// computed once for repeated evaluation (the Monte Carlo's trials in paper mode). Private to the library.

#include <utility>
#include <vector>

#include "ccal/reduction/observe.hpp"

namespace ccal::detail {

// The quadrature on the nominal rate and, per node, the paper form's error-free IA input and rate and their
// sensitivity rows (non-zero entries).
struct PaperRunNodes {
  double rate = 0;  // nominal Ω [rad/s]
  std::vector<double> weight, cos_gamma, sin_gamma;
  std::vector<double> coriolis;         // the constant Coriolis term of a_i [g]
  std::vector<double> nominal_rate_ia;  // error-free ω_IA [rad/s]
  std::vector<std::vector<std::pair<int, double>>> force_row, rate_row;  // ∂a_i/∂e, ∂ω_IA/∂e (Δω excluded)
};
PaperRunNodes paper_run_nodes(const Experiment& ex, const ccal::Run& run, const std::vector<TermSpec>& terms);
// paper_average from the nodes of the run (same result as observe.hpp's paper_average).
template <class S>
RunAverage<S> paper_average(const Experiment& ex, const PaperRunNodes& nodes, const VecX<S>& e,
                            const InstrumentModel* instrument, const std::vector<TermSpec>& terms,
                            bool cross_terms);

}  // namespace ccal::detail

#pragma once
// How the measuring chain's inputs (setup/measuring_chain.hpp, docs/model.md §10.7) move the run means a
// reduction fits: the column ∂ȳ_j/∂x of each, per run, through the exact chain where the input acts on the
// centrifuge's motion as the instrument senses it, and exactly where it acts on the reading:
//   output_gain    ȳ_j                    the reading is (1 + x) ȳ
//   output_offset  1                      the reading is ȳ + x
//   time_base      −∂ȳ_j^model/∂x         a clock fast by x stamps a run T (1 + x) long, and an encoder's
//                  (− ȳ_j, counted)       rate low by 1 + x: the model sees runs that sweep the same angles
//                                         more slowly and longer, its prediction moves (through the exact chain),
//                                         and a counted output (pulses) is read / (1 + x)
//   K_f (fixed)    Z_j                    its regressor: the truth's K_f is the lab's value + x
//   g              ∂ȳ_j/∂g                the truth's gravity and the unit of its g-levels are g + x at the
//                                         same speeds (the model keeps the lab's g), through the exact chain
//   encoder<d>_c<k> k ∂ȳ_j/∂ripple<d>_s<k>  when the drive's ripple is measured from the encoder: an angle
//   encoder<d>_s<k> −k ∂ȳ_j/∂ripple<d>_c<k> error c cos kq + s sin kq is read as the ripple (k s, −k c), so
//                                          the truth's ripple is the model's less that
//   declared       Σ_t Z_t s_t             its sensitivities s on the terms t, through the terms' regressors
#include <Eigen/Core>
#include <vector>

#include "ccal/reduction/observe.hpp"

namespace ccal {

// The columns (runs × parameters, output SI per SI unit of each input) of the chain parameters given, at the
// truth errors `at` of the layout (the model's errors: `at` when spec.compensate, else zero).
Eigen::MatrixXd chain_output_columns(const Experiment& ex, const IdentificationSpec& spec,
                                     const std::vector<int>& parameters, const Eigen::VectorXd& at,
                                     ModelMode mode, const ReductionOptions& reduction = {});

// The experiment whose site's gravity is g + dg (m/s²), its runs at the same speeds (the g-levels, in the
// new g, scaled by g/(g + dg)): the truth of a machine whose local g is off the lab's by dg.
Experiment with_gravity_error(const Experiment& ex, double dg);

// The simulated machine of a truth with the chain's errors (code → value, truth minus the lab's value): its
// gravity off by g's, its instrument's terms off by the fixed terms' and by the declared inputs' sensitivities,
// its runs T/(1 + τ) long (a clock fast by τ times the plan's T) from the same angles.
Experiment with_chain_errors(const Experiment& ex, const std::vector<std::pair<int, double>>& errors);
// The run means as the measuring chain reads them: (1 + gain) ȳ + offset, and a counted output / (1 + time_base).
void read_through_chain(Eigen::VectorXd& means, const InstrumentModel& instrument,
                        const std::vector<std::pair<int, double>>& errors);

// Whether the instrument's output is counted against the clock (pulses of its quantum, read as a rate).
bool output_read_against_clock(const InstrumentModel& instrument);

}  // namespace ccal

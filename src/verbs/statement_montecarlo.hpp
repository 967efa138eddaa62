#pragma once
// The Monte Carlo check of a calibration statement (JCGM 101 §8; docs/model.md §10.5), private to the library.
// The statement's quantity is propagated by the Monte Carlo method as a whole:
//
//   y = K̂ + b − C (f(e) − f(0)) + L_N z_N + √(ν/χ²) L_E z_E
//
// with e the tolerances drawn from their distributions (their groups sharing a draw; not the drives' rate noise,
// which the fit's scatter holds), f the exact calibration model (the plan simulated and identified, SI), C the
// factor from SI to the fit's unit of each coefficient, z standard normal, L_N L_Nᵀ the Type A covariance of the
// noise model (known, normal), L_E L_Eᵀ the part estimated from the residuals (the fit's scatter, or the charged
// excess) and χ² drawn with its ν degrees of freedom: that part is the scaled and shifted multivariate t of a
// least-squares fit (JCGM 102 §6.5.3). Each run's modelled output follows as
// ŷ + hᵀ(y − K̂). The Student-t interval y ∓ U of each quantity is then validated against the Monte Carlo's
// probabilistically symmetric interval (δ from u_c with two significant digits), and where it is not, the Monte
// Carlo's interval is the one stated (uncertainty/statement.hpp, check_by_monte_carlo).
#include <vector>

#include "ccal/verbs/statement.hpp"
#include "statement_type_a.hpp"

namespace ccal::verbs {

// The most trials the check runs, as a multiple of the requested (statement_trials): beyond, an unsettled
// verdict keeps the Student-t interval and says so.
inline constexpr std::uint64_t kStatementTrialsCap = 10;

// Runs the Monte Carlo of the options (nothing for statement_trials = 0 or a configuration without
// tolerances) and checks every coefficient and modelled output of `statement`. to_fit: per coefficient of the
// fit, SI → the fit's unit.
void check_statement_by_monte_carlo(const Config& config, const Identification& identification,
                                    const std::vector<double>& to_fit, const TypeAParts& type_a,
                                    const StatementOptions& options,
                                    CalibrationStatement& statement);

}  // namespace ccal::verbs

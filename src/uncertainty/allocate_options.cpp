// The allocation's options table: the one home of the names, ranges and help that `ccal allocate`, Python's
// allocate() and the report's allocation section bind to, and that allocate_tolerances checks.
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/option_rows.hpp"

namespace ccal {
namespace {

constexpr OptionSpec<AllocateOptions> kAllocateRows[] = {
    {"targets",
     &AllocateOptions::targets,
     "COEFF=U",
     "COEFF=U: the allowed expanded uncertainty (half-width of the coverage interval) of a free coefficient, "
     "in its unit (output unit per g^n) or with a unit, e.g. K3=1e-6 or \"K3=1e-6 deg/s/g^3\"; one per "
     "coefficient",
     {},
     true},
    rows::coverage_probability(&AllocateOptions::coverage_probability,
                               "Coverage probability p of the targets, in {range}"),
    rows::mode<&AllocateOptions::mode>(
        "Kinematics of the sensitivities and the verification: exact or paper; "
        "default: the configuration's [identification] mode"),
    {"max_scale", &AllocateOptions::max_scale, "X",
     "No tolerance is loosened by more than this factor (1e-6 to 1e6)", kMaxScaleRange},
    {"let_others_grow", &AllocateOptions::let_others_grow, "",
     "Let the coefficients without a target grow beyond their configured expanded uncertainty (default: each "
     "is held at it)"},
    rows::verify_trials(&AllocateOptions::verify_trials,
                        "Monte Carlo trials of the verification on the allocated tolerances (0: none)"),
    rows::seed(&AllocateOptions::seed, "Seed of the verification"),
    rows::threads(&AllocateOptions::threads, "Threads of the verification (0: the OpenMP default)"),
};

}  // namespace

OptionTable<AllocateOptions> options_of(std::type_identity<AllocateOptions>) { return kAllocateRows; }

}  // namespace ccal

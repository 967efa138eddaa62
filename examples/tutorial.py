"""A lab's path through ccal on the bundled centrifuge, in Python (docs/tutorial.md does it by commands):
the error budget, what dominates it, the Monte Carlo check, tighter tolerances, the simulated test and its run
logs, their reduction, and the calibration's result with its uncertainty. Run it with the module on the path:

    PYTHONPATH=build/python /usr/bin/python3 examples/tutorial.py

The test suite runs it (docs.commands runs docs/tutorial.md, which runs this script for its last step).
"""

import os
import tempfile

import numpy as np

import ccal

HERE = os.path.dirname(os.path.abspath(__file__))


def step(title):
    print(f"\n== {title}")


# 1. The error budget of the bundled centrifuge (Wang & Ren 2014): what its tolerances cost K0, K2, K3.
cfg = ccal.bundled_example()
budget = ccal.budget(cfg)
step("1. budget: the centrifuge's tolerances propagated to the coefficients")
print(budget.display())

# 2. What dominates: the sources with the largest shares of u(K3)².
step("2. the five largest contributors to u(K3)^2")
k3 = budget.coefficients.index("K3")
for i in np.argsort(-budget.share[:, k3])[:5]:
    print(f"{budget.source_ids[i]:<12} {100 * budget.share[i, k3]:5.1f} %")

# 3. The Monte Carlo method (JCGM 101) confirms the budget, or says where its linearisation fails.
step("3. Monte Carlo check of the budget")
mc = ccal.monte_carlo(cfg, trials=20_000)
print(mc.display())

# 4. Tighter tolerances: the largest ones for which U(K3) is at most 1e-3 deg/s/g^3.
step("4. tolerances for U(K3) <= 1e-3 deg/s/g^3")
allocation = ccal.allocate(cfg, {"K3": 1e-3})
print(allocation.display())
unit_of = dict(zip(cfg.error_ids, cfg.error_units))
tight = cfg
for s in allocation.sources:
    unit = unit_of[s.id]
    tight = tight.with_tolerance(s.id, s.allocated_bound, unit=None if unit == "1" else unit)
u_tight = ccal.budget(tight).display().rows[k3]
print(f"budget with the allocated tolerances: U(K3) = {u_tight['expanded_uncertainty']:.4g} {u_tight['unit']}")

# 5. A better plan instead of tighter tolerances: ccal.design(cfg), as `ccal design` (docs/tutorial.md §5).

# 6. The test on the lab's centrifuge (examples/lab.toml: the bundled one as the lab knows it, a noisy PIGA
#    counting pulses), as the run logs it records: the simulated machine has the errors of examples/lab_truth.toml,
#    which the lab does not know; 7. their reduction to the coefficients.
step("6-7. the test's run logs, reduced to the coefficients")
lab = ccal.load_config(os.path.join(HERE, "lab.toml"))
simulation = ccal.simulate(lab, seed=1, truth=os.path.join(HERE, "lab_truth.toml"))
with tempfile.TemporaryDirectory() as folder:
    logs = simulation.write_logs(folder)
    reduction = ccal.reduce(lab, logs)
print(reduction.display())

# 8. The result: the calibration statement (JCGM 100 §7), as `ccal reduce --statement` gives it: the fit's
#    standard error (Type A) and the centrifuge's budget (Type B) combined, U = k u_c with k from Student's t.
#    Its values are SI, as every value of ccal and as the simulated instrument's (known only here): they compare
#    as they are; display_scale gives the figures in the statement's units, and to_dict() its rounded figures.
step("8. the calibration statement (p = 95 %: Student's t, or the Monte Carlo's interval where the check asks)")
with tempfile.TemporaryDirectory() as folder:
    statement = ccal.reduce(lab, simulation.write_logs(folder), statement=True).statement
truth = dict(zip(lab.instrument_terms, lab.instrument_coefficients))
rounded = {name: c["rounded"] for name, c in statement.to_dict()["coefficients"].items()}
for name, unit, scale, (low, high), method in zip(statement.names, statement.units, statement.display_scale,
                                                  statement.intervals, statement.interval_methods):
    r = rounded[name]
    outside = "" if low <= truth[name] <= high else "   OUTSIDE its interval"
    print(f"{name} = {r['estimate']} {unit}, [{r['interval'][0]}, {r['interval'][1]}] ({method})   "
          f"(the simulated instrument has {truth[name] * scale:.6g}){outside}")

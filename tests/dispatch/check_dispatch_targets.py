#!/usr/bin/env python3
"""The library's cloned loops (src/core/cloned_loops.hpp) give the same bits on each instruction set they are
compiled for: dispatch_digest (SHA-256 of their work: Φ⁻¹ of the draws, the bundled example's Monte Carlo, the
lab statement's Monte Carlo check) run natively and under qemu-user's emulation of a processor without AVX-512
(Haswell: the x86-64-v3 clones) and of one without AVX2 (Nehalem: the baseline clones); each run names the clone
it took. Usage: check_dispatch_targets.py DISPATCH_DIGEST [TRIALS]. Exit 1 on two digests that differ or a
clone not taken as expected, 77 (skipped) when no level could be compared with another; a level the machine
or the emulator lacks is named and skipped."""
import shutil
import subprocess
import sys

LEVELS = ["x86-64-v4", "x86-64-v3", "default"]
# qemu-user's processor models (TCG, QEMU 7.2) whose features select each clone below AVX-512.
EMULATED = {"x86-64-v3": "Haswell", "default": "Nehalem"}


def run(command):
    out = subprocess.run(command, capture_output=True, text=True, timeout=600)
    if out.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({out.returncode}): {out.stderr.strip()}")
    target, digest = out.stdout.split()
    return target, digest


def main(program, trials="2000"):
    native, digest = run([program, trials])
    print(f"native: {native} {digest}")
    digests = {native: digest}
    qemu = shutil.which("qemu-x86_64")
    for level in LEVELS[LEVELS.index(native) + 1:]:
        if qemu is None:
            print(f"{level}: not checked (no qemu-x86_64; Debian's qemu-user)")
            continue
        target, d = run([qemu, "-cpu", EMULATED[level], program, trials])
        print(f"{level} (qemu -cpu {EMULATED[level]}): {target} {d}")
        if target != level:
            print(f"{level}: the emulated {EMULATED[level]} took the {target} clone; not checked")
            continue
        digests[level] = d
    for level in LEVELS[:LEVELS.index(native)]:
        print(f"{level}: not checked (this processor lacks it, and the emulator has no AVX-512)")
    if len(digests) < 2:
        print("only one instruction set run: nothing compared")
        return 77
    if len(set(digests.values())) != 1:
        print("FAIL: the clones give different bits: " + ", ".join(f"{k} {v}" for k, v in digests.items()))
        return 1
    print(f"the same bits on {', '.join(digests)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))

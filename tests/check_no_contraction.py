#!/usr/bin/env python3
"""The library is compiled without floating-point contraction (CMakeLists.txt, -ffp-contract=off): no fused
multiply-add instruction in its code, also in the AVX2 and AVX-512 clones of its node loops, so that every
instruction set computes the bits baseline x86-64 computes. Usage: check_no_contraction.py LIBRARY
(libccal.a). Exit 1 naming the functions with an FMA instruction; 0 with a note where objdump is missing or
the library is not x86-64 code."""
import re
import shutil
import subprocess
import sys

FMA = re.compile(r"\bv?f(n?)m(add|sub)(sub|add)?\d*[ps][sd]\b|\bvfmaddsub|\bvfmsubadd")


def main(library):
    if shutil.which("objdump") is None:
        print("no objdump: not checked")
        return 0
    text = subprocess.run(["objdump", "-d", "--no-show-raw-insn", library], capture_output=True, text=True,
                          check=True).stdout
    if "x86-64" not in text:
        print("not x86-64 code: not checked")
        return 0
    function, found = None, {}
    for line in text.splitlines():
        header = re.match(r"^[0-9a-f]+ <(.*)>:$", line)
        if header:
            function = header.group(1)
        elif FMA.search(line):
            found[function] = found.get(function, 0) + 1
    for name, count in sorted(found.items()):
        print(f"{library}: {count} fused multiply-add instruction(s) in {name}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))

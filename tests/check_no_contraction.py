#!/usr/bin/env python3
"""The library is compiled without floating-point contraction (CMakeLists.txt, -ffp-contract=off): no fused
multiply-add instruction in its code, also in the AVX2 and AVX-512 clones of its node loops, so that every
instruction set computes the bits baseline x86-64 computes. Usage: check_no_contraction.py LIBRARY
(libccal.a). Exit 1 naming the functions with an FMA instruction; 0 with a note where objdump is missing or
the library is not x86-64 code.

One exception: the bodies compiled once per instruction set (src/core/per_isa.hpp) take the exact error of a
product, a·b − fl(a·b), by one fused multiply-subtract in their AVX2 and AVX-512 namespaces (isa_v3, isa_v4),
where baseline x86-64 takes the same exact value by Dekker's product (src/core/exact_products.inc). So in those
namespaces' functions vfmsub…pd is allowed, and every other fused instruction still fails."""
import re
import shutil
import subprocess
import sys

FMA = re.compile(r"\bv?f(n?)m(add|sub)(sub|add)?\d*[ps][sd]\b|\bvfmaddsub|\bvfmsubadd")
# The per-ISA bodies' exact product errors (the mangled names hold the namespace: 6isa_v3, 6isa_v4).
EXACT_PRODUCT = re.compile(r"\bvfmsub(132|213|231)pd\b")
PER_ISA = re.compile(r"6isa_v[34]")


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
            if function and PER_ISA.search(function) and EXACT_PRODUCT.search(line):
                continue
            found[function] = found.get(function, 0) + 1
    for name, count in sorted(found.items()):
        print(f"{library}: {count} fused multiply-add instruction(s) in {name}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))

#!/usr/bin/env python3
"""The include rules of docs/architecture.md: a library header or source in layer L includes only headers of
L and of the layers below it (core < model < setup < reduction < io < intake < uncertainty < history < verbs
< render), plus version.hpp; nothing under python/ includes a file of apps/; a layer's internals
(include/ccal/<layer>/detail/) are included by that layer only; a source's relative include of another
layer's private header (../<layer>/x.hpp) follows the same order; library headers include no private header
of src/. Exit 1 with one line per violation."""
import pathlib
import re
import sys

LAYERS = ["core", "model", "setup", "reduction", "io", "intake", "uncertainty", "history", "verbs", "render"]
RANK = {name: k for k, name in enumerate(LAYERS)}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def layer_of(path, root):
    """The layer of a library file (include/ccal/<layer>/… or src/<layer>/…), None for any other file."""
    rel = path.relative_to(root).parts
    if rel[:2] == ("include", "ccal") and len(rel) > 3:
        return rel[2]
    if rel[0] == "src" and len(rel) > 2:
        return rel[1]
    return None


def front_end_problems(root):
    """The Python module is a front end beside the program, not on it: nothing under python/ includes a file of
    apps/ (what both need is in the library, or in a library of its own such as embed/report_scripts)."""
    problems = []
    app_headers = {p.name for p in (root / "apps").rglob("*.hpp")}
    for path in sorted((root / "python").rglob("*.[ch]pp")):
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if m and ("apps/" in m.group(1) or pathlib.PurePosixPath(m.group(1)).name in app_headers
                      and not (path.parent / m.group(1)).exists()):
                problems.append(f"{path.relative_to(root)}:{n}: includes '{m.group(1)}' of apps/; a front end "
                                "takes what it shares with the program from the library")
    return problems


def main(root):
    root = pathlib.Path(root).resolve()
    problems, checked = [], 0
    files = list((root / "include" / "ccal").rglob("*.hpp")) + list((root / "src").rglob("*.[ch]pp"))
    for path in sorted(files):
        layer = layer_of(path, root)
        if layer is None:
            if path.name != "version.hpp" and path.parent.name != "src":
                problems.append(f"{path.relative_to(root)}: outside every layer folder")
            continue
        if layer not in RANK:
            problems.append(f"{path.relative_to(root)}: unknown layer '{layer}'; accepted: {', '.join(LAYERS)}")
            continue
        text = path.read_text(encoding="utf-8")
        for n, line in enumerate(text.splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            target = m.group(1)
            checked += 1
            private = target.split("/")
            if path.is_relative_to(root / "src") and len(private) == 3 and private[0] == "..":
                # a private header of another layer's sources: the same rank rule
                if private[1] not in RANK:
                    problems.append(f"{path.relative_to(root)}:{n}: '{target}' is not in a layer folder")
                elif RANK[private[1]] > RANK[layer]:
                    problems.append(f"{path.relative_to(root)}:{n}: layer '{layer}' includes '{target}' of the "
                                    f"higher layer '{private[1]}'")
                continue
            if not target.startswith("ccal/"):
                if path.suffix == ".hpp" and path.is_relative_to(root / "include"):
                    problems.append(f"{path.relative_to(root)}:{n}: installed header includes '{target}', "
                                    "not part of the installed tree")
                continue
            parts = target.split("/")
            if parts == ["ccal", "version.hpp"]:
                continue
            if len(parts) == 4 and parts[2] == "detail" and parts[1] in RANK:
                # a layer's internals (ccal/<layer>/detail/): for that layer's own templates only
                if parts[1] != layer:
                    problems.append(f"{path.relative_to(root)}:{n}: '{target}' is internal to layer "
                                    f"'{parts[1]}'; include its public header instead")
                continue
            if len(parts) != 3 or parts[1] not in RANK:
                problems.append(f"{path.relative_to(root)}:{n}: '{target}' is not in a layer folder")
                continue
            if RANK[parts[1]] > RANK[layer]:
                problems.append(f"{path.relative_to(root)}:{n}: layer '{layer}' includes '{target}' of the "
                                f"higher layer '{parts[1]}'")
    problems += front_end_problems(root)
    for p in problems:
        print(p)
    print(f"{len(files)} files, {checked} includes checked, {len(problems)} violation(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1]))

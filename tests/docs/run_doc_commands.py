"""Runs every command of the documentation, so that the docs cannot rot (ctest: docs.commands).

From README.md and docs/*.md it takes, in order of appearance:
  - fenced ```sh / ```bash blocks: run as one bash script each (`set -e`: every line must succeed);
  - fenced ```python blocks: run with the Python the module is built for;
  - fenced ```console blocks: each line "$ command" is run, and what it prints must be the lines that follow it
    (up to the next "$ " line), exactly, but for the run's timing and thread count ("2 threads, 1.3 s");
    `--update` rewrites those lines with what the commands print now (docs/tutorial.md is made so);
  - indented code lines that start with `ccal <command>` (docs/cli.md's examples), each on its own; a synopsis
    line (one with `[OPTION]`-style brackets or `<…>`) is not a command.
A block (or indented line group) right after the line `<!-- doc-test: skip: <reason> -->` is not run (e.g. one
that installs packages); docs/testing.md lists the rule. The commands of one document run in one temporary
folder, in order, so that one can read what an earlier one wrote; the folder holds a copy of examples/ and
tests/data/, `build` is the build folder (for `./build/ccal` and `build/python`), `ccal` is on PATH and HOME
is a folder of its own (for `cmake --install … --prefix "$HOME/.local"`).

    python3 tests/docs/run_doc_commands.py SOURCE_DIR BUILD_DIR PYTHON [--update] [FILE.md …]
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = re.compile(r"^<!-- doc-test: skip: (.+) -->\s*$")
FENCE = re.compile(r"^```(\w*)\s*$")
SYNOPSIS = re.compile(r"\[(--|[A-Z])|<[a-z]")
COMMAND = re.compile(r"^    (ccal [a-z-].*)$")
TIMEOUT = 600  # s, for the slowest command (an adaptive Monte Carlo on a loaded machine)


def blocks(path):
    """(kind, text, line, skip reason) of every runnable block of a Markdown file, in order."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out, skip, k = [], None, 0
    while k < len(lines):
        line = lines[k]
        m = SKIP.match(line)
        if m:
            skip = m.group(1)
            k += 1
            continue
        fence = FENCE.match(line)
        if fence:
            start, body = k + 1, []
            k += 1
            while k < len(lines) and not lines[k].startswith("```"):
                body.append(lines[k])
                k += 1
            kind = {"sh": "sh", "bash": "sh", "python": "python", "console": "console"}.get(fence.group(1))
            if kind == "console":
                for step in console_steps(body, start):
                    out.append(("console", step, step[2], skip))
            elif kind:
                out.append((kind, "\n".join(body) + "\n", start, skip))
            skip = None
            k += 1
            continue
        if line.startswith("    "):
            start, commands = k + 1, []
            while k < len(lines) and (lines[k].startswith("    ") or not lines[k].strip()):
                c = COMMAND.match(lines[k])
                if c and not SYNOPSIS.search(c.group(1)):
                    commands.append(c.group(1))
                k += 1
            for c in commands:
                out.append(("sh", c + "\n", start, skip))
            skip = None
            continue
        if line.strip():
            skip = None
        k += 1
    return out


def console_steps(body, start):
    """(command, expected output lines, line number, index of its first output line in body, count)."""
    steps = []
    for k, line in enumerate(body):
        if line.startswith("$ "):
            steps.append([line[2:], [], start + k + 1, k + 1, 0])
        elif steps:
            steps[-1][1].append(line)
            steps[-1][4] += 1
    return [tuple(s) for s in steps]


VOLATILE = [(re.compile(r"\d+ threads?, [0-9.]+ ?s"), "N threads, T s"),
            (re.compile(r"[0-9.]+(e[+-]?[0-9]+)? (trials|evaluations)/s"), r"R \2/s"),
            (re.compile(r"\(commit [0-9a-f]+\)"), "(commit C)")]


def normalised(lines):
    text = "\n".join(line.rstrip() for line in lines).strip("\n")
    for pattern, replacement in VOLATILE:
        text = pattern.sub(replacement, text)
    return text


def prepare(folder, source, build):
    shutil.copytree(os.path.join(source, "examples"), os.path.join(folder, "examples"))
    shutil.copytree(os.path.join(source, "tests", "data"), os.path.join(folder, "tests", "data"))
    os.symlink(os.path.abspath(build), os.path.join(folder, "build"))
    os.makedirs(os.path.join(folder, "home"))


def run_document(path, source, build, python, update=False):
    failures, ran, skipped, rewrites = [], 0, [], []
    with tempfile.TemporaryDirectory() as folder:
        prepare(folder, source, build)
        env = dict(os.environ, HOME=os.path.join(folder, "home"),
                   PATH=os.path.abspath(build) + os.pathsep + os.environ.get("PATH", ""),
                   PYTHONPATH=os.path.join(os.path.abspath(build), "python"))
        for kind, text, line, skip in blocks(path):
            where = f"{os.path.relpath(path, source)}:{line}"
            if skip:
                skipped.append(f"{where}: {skip}")
                continue
            script = text[0] if kind == "console" else text
            command = [python, "-c", script] if kind == "python" else ["bash", "-e", "-o", "pipefail", "-c", script]
            try:
                p = subprocess.run(command, cwd=folder, env=env, capture_output=True, text=True, timeout=TIMEOUT)
                code, out, err = p.returncode, p.stdout, p.stderr
            except subprocess.TimeoutExpired:
                code, out, err = "timeout", "", f"more than {TIMEOUT} s"
            ran += 1
            status = "ok" if code == 0 else f"FAILED ({code})"
            if code == 0 and kind == "console":
                shown = out.rstrip("\n").split("\n") if out.strip() else []
                if update:
                    rewrites.append((text, shown))
                elif normalised(shown) != normalised(text[1]):
                    status = "OUTPUT DIFFERS"
                    failures.append(f"{where}: the output shown is not what `{script}` prints now (run with "
                                    f"--update to rewrite it):\n--- shown\n{normalised(text[1])}\n--- printed\n"
                                    f"{normalised(shown)}")
            print(f"{where}: {kind}: {status}: {script.strip().splitlines()[0][:100]}", flush=True)
            if code != 0:
                failures.append(f"{where}: exit {code}\n{script}{err[-2000:]}")
    if update and rewrites:
        rewrite(path, rewrites)
    return ran, failures, skipped


def rewrite(path, rewrites):
    """Replaces the output lines of each console step by what it printed."""
    lines = open(path, encoding="utf-8").read().split("\n")
    for (command, _, line, first, count), shown in sorted(rewrites, key=lambda r: -r[0][2]):
        begin = line  # 0-based index of the first output line: the "$ " line is line (1-based) - 1
        lines[begin:begin + count] = shown
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def main(argv):
    source, build, python = argv[1:4]
    update = "--update" in argv[4:]
    files = [a for a in argv[4:] if a != "--update"] or [os.path.join(source, "README.md")] + sorted(
        os.path.join(source, "docs", f) for f in os.listdir(os.path.join(source, "docs")) if f.endswith(".md"))
    total, failures, skipped = 0, [], []
    for path in files:
        ran, failed, skips = run_document(path, source, build, python, update)
        total, failures, skipped = total + ran, failures + failed, skipped + skips
    print(f"\n{total} blocks run, {len(failures)} failed, {len(skipped)} skipped by a marker:")
    for s in skipped:
        print("  skipped " + s)
    for f in failures:
        print("\n" + f)
    return 1 if failures or total == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/env python3
"""The size rules of docs/architecture.md: no C++ or Python file of the project over 600 lines, and no function
body of the library, the program, the Python module or the benchmarks over 60 lines. One exemption: the Python
module's registration functions (in python/bind_*.cpp, named bind_*), declarative chains of .def calls, may
reach 100 lines. The C++ bodies compiled once per instruction set (src/**/*.inc, core/per_isa.hpp) are held to
the same rules. Functions are found by their braces after comments and
string literals are blanked: a brace block opened at namespace or class scope that is not a namespace, class,
struct, enum or union is a function body, named by the identifier before the first parenthesis of its head.
Exit 1 with one line per violation."""
import pathlib
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 60
# The Python module's registration functions: python/bind_*.cpp, a function named bind_* (a chain of .def calls).
MAX_BINDING_LINES = 100
FILE_DIRS = ["include", "src", "apps", "python", "bench", "tests", "fuzz", "scripts"]
FUNCTION_DIRS = ["include", "src", "apps", "python", "bench"]
SUFFIXES = {".cpp", ".hpp", ".inc", ".py"}


def blank_literals(text):
    """Comments and string/char literals replaced by spaces of the same shape (line numbers kept)."""
    def blank(m):
        return re.sub(r"[^\n]", " ", m.group(0))
    pattern = re.compile(r'//[^\n]*|/\*.*?\*/|R"([^(\s]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                         re.S)
    return pattern.sub(blank, text)


SCOPE = re.compile(r"\b(namespace|struct|class|enum|union)\b[^()]*$|extern\s+$")


def function_bodies(text):
    """(first line, lines) of every function body at namespace or class scope."""
    return [(first, lines) for first, lines, _ in named_function_bodies(text)]


def function_name(head):
    """The name of the function whose head (the text before its body's brace) is `head`: the identifier, with its
    qualification, before the head's first parenthesis ("HistoryStore::open"); "" when there is none."""
    m = re.search(r"([A-Za-z_~][\w:~]*)\s*(?:<[^()]*>)?\s*\(", head)
    return m.group(1) if m else ""


def named_function_bodies(text):
    """(first line, lines, name) of every function body at namespace or class scope."""
    text = blank_literals(text)
    kinds, found, start, line, name = [], [], None, 1, ""
    for i, ch in enumerate(text):
        if ch == "\n":
            line += 1
        elif ch == "{":
            head = text[max(0, i - 400):i]
            head = head[max(head.rfind(";"), head.rfind("}"), head.rfind("{")) + 1:]
            kind = "scope" if SCOPE.search(head) else "block"
            if kind == "block" and all(k == "scope" for k in kinds):
                # The name from the head with empty braces (a default argument's {}) left in.
                context = re.sub(r"\{\s*\}", "  ", text[max(0, i - 600):i])
                context = context[max(context.rfind(";"), context.rfind("}"), context.rfind("{")) + 1:]
                start, name = line, function_name(context)
            kinds.append(kind)
        elif ch == "}" and kinds:
            if kinds.pop() == "block" and all(k == "scope" for k in kinds) and start is not None:
                found.append((start, line - start + 1, name))
                start = None
    return found


def function_limit(rel, name):
    """The most lines a function of file `rel` (relative to the root) named `name` may have."""
    if rel.parts[0] == "python" and rel.name.startswith("bind_") and name.startswith("bind_"):
        return MAX_BINDING_LINES
    return MAX_FUNCTION_LINES


def main(root):
    root = pathlib.Path(root).resolve()
    problems, files = [], 0
    for folder in FILE_DIRS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in SUFFIXES or "node_modules" in path.parts:
                continue
            files += 1
            text = path.read_text(encoding="utf-8")
            rel = path.relative_to(root)
            n = text.count("\n")
            if n > MAX_FILE_LINES:
                problems.append(f"{rel}: {n} lines (at most {MAX_FILE_LINES}: split it by concept)")
            if path.suffix != ".py" and rel.parts[0] in FUNCTION_DIRS:
                for first, length, name in named_function_bodies(text):
                    limit = function_limit(rel, name)
                    if length > limit:
                        problems.append(f"{rel}:{first}: {name or 'a function'} of {length} lines (at most "
                                        f"{limit}: split it into named steps)")
    for p in problems:
        print(p)
    print(f"{files} files checked, {len(problems)} violation(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1]))

"""The type stubs python/ccal.pyi against the module: they are what python/make_stubs.py writes from it, and
(read independently, with ast) they name exactly the module's public functions, classes, properties and
methods, no more and no fewer."""

import ast
import os
import sys
import unittest

import ccal

SOURCE = os.path.join(os.path.dirname(__file__), "..", "..", "python")
sys.path.insert(0, SOURCE)
import make_stubs  # noqa: E402

STUBS = os.path.join(SOURCE, "ccal.pyi")
FORWARDED = make_stubs.FORWARDED


def module_names():
    return {n for n in vars(ccal) if not n.startswith("_")} | {"__version__", "__commit__"}


def class_names(cls):
    own = {n for n, v in vars(cls).items() if not n.startswith("_") and
           (isinstance(v, property) or callable(v)) and not isinstance(v, type)}
    own |= set(vars(cls).get("__annotations__", {}))
    inner = FORWARDED.get(cls.__name__)
    if inner:
        own |= {n for n, v in vars(getattr(ccal, inner)).items() if isinstance(v, property) and not n.startswith("_")}
    return own


def stub_names(tree):
    top, classes = set(), {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            top.add(node.name)
            members = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members.add(item.name)
                elif isinstance(item, ast.AnnAssign):
                    members.add(item.target.id)
            classes[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            top.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
    return top, classes


class Stubs(unittest.TestCase):
    def test_stubs_are_what_the_generator_writes(self):
        with open(STUBS, encoding="utf-8") as f:
            self.assertEqual(f.read(), make_stubs.stub_text(ccal),
                             "python/ccal.pyi is out of date: PYTHONPATH=build/python /usr/bin/python3 "
                             "python/make_stubs.py > python/ccal.pyi")

    def test_stubs_name_exactly_what_the_module_has(self):
        with open(STUBS, encoding="utf-8") as f:
            top, classes = stub_names(ast.parse(f.read()))
        self.assertEqual(top, module_names())
        for name, members in classes.items():
            cls = getattr(ccal, name)
            if issubclass(cls, Exception):
                continue
            with self.subTest(cls=name):
                self.assertEqual(members, class_names(cls))


if __name__ == "__main__":
    unittest.main()

"""Signatures for inspect: pybind11 writes "name(arg: type = default, ...) -> type" as the first line of a
function's docstring; a Python wrapper carries it as __signature__, which inspect.signature reads."""

import ast
import difflib
import inspect
import re


class DefaultText:
    """A default value shown as pybind11 wrote it, when it is not a Python literal."""

    def __init__(self, text):
        self.text = text

    def __repr__(self):
        return self.text


def split_top_level(text):
    """The comma-separated parts of `text` that are not inside brackets."""
    parts, depth, current = [], 0, ""
    for ch in text:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    if current.strip():
        parts.append(current.strip())
    return parts


def signature_from_doc(doc, name, keywords=None):
    """The signature on the first line of a pybind11 docstring, and the rest of the docstring. A bare `*`
    makes the parameters after it keyword-only; `**kwargs` stands for a verb's options, `keywords` (a list of
    (name, default, type, help) from the compiled module's _option_keywords), which become keyword-only
    parameters and a paragraph of the docstring."""
    lines = (doc or "").split("\n")
    match = re.match(r"^\s*" + re.escape(name) + r"\((.*)\)(?: -> (.*))?$", lines[0]) if lines else None
    if not match:
        raise ValueError(f"ccal: no signature in the docstring of {name}")
    parameters, options, kind, options_doc = [], [], inspect.Parameter.POSITIONAL_OR_KEYWORD, []
    for part in split_top_level(match.group(1)):
        if part == "*":
            kind = inspect.Parameter.KEYWORD_ONLY
            continue
        if part.startswith("**"):
            for keyword, default, annotation, help_text in keywords or ():
                options.append(inspect.Parameter(keyword, inspect.Parameter.KEYWORD_ONLY, default=default,
                                                 annotation=annotation))
                options_doc.append(f"    {keyword} ({annotation}, default {default!r}): {help_text}")
            continue
        part_name, _, rest = part.partition(":")
        annotation, _, default_text = rest.partition(" = ")
        default = inspect.Parameter.empty
        if default_text:
            try:
                default = ast.literal_eval(default_text.strip())
            except (ValueError, SyntaxError):
                default = DefaultText(default_text.strip())
        parameters.append(inspect.Parameter(part_name.strip(), kind, default=default,
                                            annotation=annotation.strip() or inspect.Parameter.empty))
    # The options come before the binding's own keyword-only parameters (progress, keep_samples).
    first_own = next((k for k, p in enumerate(parameters) if p.kind == inspect.Parameter.KEYWORD_ONLY),
                     len(parameters))
    parameters[first_own:first_own] = options
    signature = inspect.Signature(parameters, return_annotation=match.group(2) or inspect.Signature.empty)
    text = "\n".join(lines[1:]).strip()
    if options_doc:
        text += "\n\nOptions (keywords; the command line's flags of the same names):\n" + "\n".join(options_doc)
    return signature, text


def with_signature(function, name, qualname, keywords=None):
    """`function` (a pybind11 function) wrapped so that inspect.signature and help() show its signature."""
    signature, doc = signature_from_doc(function.__doc__, name, keywords)

    def wrapper(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            # pybind11's "incompatible function arguments" lists C++ overloads and the arguments' reprs: Python's
            # own words for a call its signature does not take (a missing argument, a mistyped keyword) instead.
            if "incompatible function arguments" not in str(error):
                raise
            problem = call_problem(signature, name, args, kwargs)
            if problem is None:
                raise
            raise TypeError(problem) from None

    wrapper.__name__ = name
    wrapper.__qualname__ = qualname
    wrapper.__module__ = "ccal"
    wrapper.__doc__ = doc
    wrapper.__signature__ = signature
    return wrapper


def call_problem(signature, name, args, kwargs):
    """What is wrong with a call `signature` does not take, in Python's words with a did-you-mean for a mistyped
    keyword; None when it takes it."""
    try:
        signature.bind(*args, **kwargs)
    except TypeError as why:
        names = list(signature.parameters)
        hints = []
        for keyword in kwargs:
            if keyword not in signature.parameters:
                close = difflib.get_close_matches(keyword, names, n=1)
                hints.append(f"'{keyword}' is no keyword" + (f": did you mean '{close[0]}'?" if close else ""))
        return f"{name}(): {why}" + "".join(f"; {hint}" for hint in hints) + f"; accepted: {', '.join(names)}"
    return None


def is_pybind_function(value):
    return type(value).__name__ in ("builtin_function_or_method", "instancemethod")


def copy_identity(wrapper, function):
    """`wrapper` named, documented and signed as `function`; returns it."""
    for attribute in ("__name__", "__qualname__", "__module__", "__doc__", "__signature__"):
        setattr(wrapper, attribute, getattr(function, attribute))
    return wrapper

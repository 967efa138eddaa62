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
    options = {keyword[0] for keyword in keywords or ()}  # checked by the module itself, in its own words

    def wrapper(*args, **kwargs):
        # pybind11 takes True for a number (1.0): refused first, as the module's keywords refuse it.
        problem = bool_problem(signature, qualname, args, kwargs, options)
        if problem is not None:
            raise TypeError(problem)
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            # pybind11's "incompatible function arguments" lists C++ overloads and the arguments' reprs: Python's
            # own words for a call its signature does not take (a missing argument, a mistyped keyword) instead.
            if "incompatible function arguments" not in str(error):
                raise
            problem = call_problem(signature, name, args, kwargs) or argument_problem(signature, qualname, args,
                                                                                      kwargs)
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
        accepted = ", ".join(names) if names else "no arguments"
        return f"{name}(): {why}" + "".join(f"; {hint}" for hint in hints) + f"; accepted: {accepted}"
    return None


def parse_annotation(text):
    """A pybind11 type name ("Dict[str, Union[float, str]]") as (name, [arguments])."""
    name, bracket, rest = text.strip().partition("[")
    if not bracket:
        return name.strip(), []
    return name.strip(), [parse_annotation(part) for part in split_top_level(rest.rstrip()[:-1])]


def described(annotation, article=True):
    """A type in words: "a dict of str → number or str"; the parts of a container without their article."""
    name, arguments = annotation
    words = {"str": "str", "float": "number", "int": "integer", "bool": "True or False", "object": "anything",
             "Any": "anything"}
    if name == "Dict":
        return f"a dict of {described(arguments[0], False)} → {described(arguments[1], False)}"
    if name == "List":
        return f"a list of {described(arguments[0], False)}"
    if name == "Optional":
        return f"{described(arguments[0], article)} or None"
    if name == "Union":
        return " or ".join("None" if a[0] == "None" else described(a, article) for a in arguments)
    if name.startswith("numpy."):
        return f"a {array_dimensions(annotation)}-D array of numbers" if arguments else "an array of numbers"
    text = words.get(name, name)
    if not article or name in ("bool", "object", "Any"):
        return text
    return ("an " if text[0] in "aeiou" else "a ") + text


def array_dimensions(annotation):
    """The dimensions of a pybind11 array type: numpy.ndarray[numpy.float64[m, n]] 2, [m, 1] (a vector) 1."""
    shape = annotation[1][0][1] if annotation[1] and annotation[1][0][1] else []
    return sum(1 for size in shape if size[0] != "1") or 1


def mismatch(value, annotation, where):
    """(where, annotation) of the first part of `value` that is not of `annotation`, None if it is (or the type is
    not one this checks). Only called for a call pybind11 refused: it names the argument, pybind11 decides."""
    from . import _ccal
    name, arguments = annotation
    if name == "None":
        return None if value is None else (where, annotation)
    if name in ("Optional", "Union"):
        options = arguments + ([("None", [])] if name == "Optional" else [])
        found = [mismatch(value, a, where) for a in options]
        if all(found):  # of the alternatives' mismatches, one deeper inside the value names its place best
            deeper = [f for f in found if f[0] != where]
            return deeper[0] if len(deeper) == 1 else (where, annotation)
        return None
    if name == "str":
        ok = isinstance(value, (str, bytes))
    elif name == "bool":
        ok = isinstance(value, bool) or type(value).__name__.startswith("bool")
    elif name in ("int", "float"):
        numeric = hasattr(value, "__index__") or (name == "float" and hasattr(value, "__float__"))
        # A NumPy array (also of one element) has __float__ but is no number.
        ok = numeric and not isinstance(value, (str, bytes)) and getattr(value, "ndim", 0) == 0
    elif name == "Dict":
        if not isinstance(value, dict):
            return where, annotation
        for key, item in value.items():
            found = mismatch(key, arguments[0], f"{where}: key {key!r}") or mismatch(item, arguments[1],
                                                                                    f"{where}[{key!r}]")
            if found:
                return found
        return None
    elif name == "List":
        # A sequence (or an array): a set or a dict has no order to take its items in.
        if isinstance(value, (str, bytes, dict, set, frozenset)) or not hasattr(value, "__len__") or not hasattr(
                value, "__getitem__"):
            return where, annotation
        for index, item in enumerate(value):
            found = mismatch(item, arguments[0], f"{where}[{index}]")
            if found:
                return found
        return None
    elif name.startswith("ccal."):
        cls = getattr(_ccal, name[len("ccal."):], None)
        ok = cls is None or isinstance(value, cls)
    elif name.startswith("numpy.") and arguments:
        import numpy
        try:
            array = numpy.asarray(value)
        except (TypeError, ValueError):  # a ragged list
            return where, annotation
        # Numbers (bool, int, float) of at most the binding's dimensions; text or objects are none.
        ok = array.ndim <= array_dimensions(annotation) and array.dtype.kind in "biuf"
    else:
        return None
    return None if ok else (where, annotation)


def argument_problem(signature, name, args, kwargs):
    """Which argument of a call the signature takes has a type pybind11 refused, in the words of the module's other
    argument checks: "<function>(): <argument>: expected <accepted>, got <type> (<repr>)"; None if none is found."""
    for parameter, value in signature.bind(*args, **kwargs).arguments.items():
        kind = signature.parameters[parameter].kind
        annotation = signature.parameters[parameter].annotation
        if kind in (inspect.Parameter.VAR_KEYWORD, inspect.Parameter.VAR_POSITIONAL) or not isinstance(annotation,
                                                                                                       str):
            continue
        found = mismatch(value, parse_annotation(annotation), parameter)
        if found:
            where, expected = found
            part = value if where == parameter else eval_part(value, where[len(parameter):])
            text = " ".join(repr(part).split())  # one line: an array's repr spans several
            text = text if len(text) <= 80 else text[:77] + "..."
            whole = "" if where == parameter else f"; accepted: {described(parse_annotation(annotation))}"
            config = expected in (("ccal.Config", []), ("Optional", [("ccal.Config", [])]))
            if config and (isinstance(part, str) or hasattr(part, "__fspath__")):
                whole += "; a configuration file is read by ccal.load_config(path)"
            return f"{name}(): {where}: expected {described(expected)}, got {type(part).__name__} ({text}){whole}"
    return None


def is_array(value):
    """A NumPy array (or another array type) of one or more dimensions: no number, even of one element."""
    return not isinstance(value, (str, bytes)) and getattr(value, "ndim", 0) != 0 and hasattr(value, "shape")


def bool_for_number(value, annotation, where):
    """The place (and the expected type) where `value` holds True or False for a number the annotation takes, and
    no bool, or an array for a number (numpy.array([0.05]) would be taken for 0.05 by its __float__ in some
    arguments and refused in others: it is refused in all), or anything but True or False for a bool (1 is no flag,
    as the options' flags say); None if there is none."""
    name, arguments = annotation
    if (isinstance(value, bool) or is_array(value)) and name in ("float", "int"):
        return where, annotation
    if name == "bool" and not (isinstance(value, bool) or type(value).__name__.startswith("bool")):
        return where, annotation
    if name in ("Optional", "Union"):
        if any(a[0] == "bool" for a in arguments):
            return None
        if isinstance(value, bool) or is_array(value):
            # Optional[Union[float, str]]: the alternatives of the inner Union too
            flat = [b for a in arguments for b in (a[1] if a[0] in ("Optional", "Union") else [a])]
            if any(a[0] == "bool" for a in flat):
                return None
            numbers = [a for a in flat if a[0] in ("float", "int")]
            arrays = [a for a in flat if a[0].startswith("numpy.") or a[0] in ("List", "object", "Any")]
            if numbers and not arrays:
                return where, annotation
            if isinstance(value, bool):
                return None
            # an array for a list: its items checked below
        for a in arguments:
            found = bool_for_number(value, a, where)
            if found:
                return found
        return None
    if name == "Dict" and isinstance(value, dict):
        for key, item in value.items():
            found = bool_for_number(item, arguments[1], f"{where}[{key!r}]")
            if found:
                return found
    if name == "List" and (isinstance(value, (list, tuple)) or is_array(value)):
        for index, item in enumerate(value):  # an array's rows too: a 2-D array is no list of numbers
            found = bool_for_number(item, arguments[0], f"{where}[{index}]")
            if found:
                return found
    return None


def complex_for_real(value, annotation, where):
    """The place (and the expected type) where `value` is a complex array for an array of real numbers, whose
    imaginary parts the conversion would drop with no more than a warning; None if it is not one."""
    name, arguments = annotation
    if name in ("Optional", "Union"):
        return next(filter(None, (complex_for_real(value, a, where) for a in arguments)), None)
    if name.startswith("numpy.") and value is not None and not isinstance(value, (str, bytes)):
        import numpy
        try:
            if numpy.iscomplexobj(value):
                return where, annotation
        except (TypeError, ValueError):  # a ragged list: its own problem, said once pybind11 refuses it
            return None
    return None


def bool_problem(signature, name, args, kwargs, options=()):
    """A bool given for a number of the signature's arguments (not the verb's option keywords, `options`, which the
    module checks itself), or a complex array for an array of real numbers."""
    try:
        bound = signature.bind(*args, **kwargs).arguments
    except TypeError:
        return None  # the call's own problem, said after pybind11 refuses it
    for parameter, value in bound.items():
        annotation = signature.parameters[parameter].annotation
        if parameter in options or not isinstance(annotation, str):
            continue
        found = bool_for_number(value, parse_annotation(annotation), parameter)
        if found:
            where, expected = found
            part = value if where == parameter else eval_part(value, where[len(parameter):])
            text = " ".join(repr(part).split())  # one line: an array's repr spans several
            return f"{name}(): {where}: expected {described(expected)}, got {type(part).__name__} ({text})"
        if complex_for_real(value, parse_annotation(annotation), parameter):
            return (f"{name}(): {parameter}: expected an array of real numbers, got complex numbers; accepted: real "
                    f"numbers (numpy.real(...) when the imaginary parts are 0)")
    return None


def eval_part(value, path):
    """The part of `value` a mismatch's place names: "[0]", "['K3']" or ": key 3"."""
    if path.startswith(": key "):
        return ast.literal_eval(path[len(": key "):])
    for index in re.findall(r"\[(.*?)\](?=\[|$)", path):
        value = value[ast.literal_eval(index)]
    return value


def is_pybind_function(value):
    return type(value).__name__ in ("builtin_function_or_method", "instancemethod")


def copy_identity(wrapper, function):
    """`wrapper` named, documented and signed as `function`; returns it."""
    for attribute in ("__name__", "__qualname__", "__module__", "__doc__", "__signature__"):
        setattr(wrapper, attribute, getattr(function, attribute))
    return wrapper

# The Python side of the module `ccal`, run in the module's namespace when it is imported (embedded in the
# extension at build time, python/CMakeLists.txt): signatures for inspect, readable repr and Jupyter tables,
# the display-unit view of every result (display(), to_frame()), pickling, and the docstrings of the
# properties bound without one (_PROPERTY_DOCS, from python/property_docs.py, run before this file; docs/python.md).
import ast as _ast
import html as _html
import inspect as _inspect
import json as _json
import math as _math
import os as _os
import re as _re
import tempfile as _tempfile

import numpy as _np

# ---------------------------------------------------------------------------------------------------------
# Signatures: pybind11 writes "name(arg: type = default, ...) -> type" as the first docstring line; a Python
# wrapper carries it as __signature__, which inspect.signature reads.


class _DefaultText:
    """A default value shown as pybind11 wrote it, when it is not a Python literal."""

    def __init__(self, text):
        self.text = text

    def __repr__(self):
        return self.text


def _split_top_level(text):
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


def _signature_from_doc(doc, name):
    """The signature on the first line of a pybind11 docstring, and the rest of the docstring."""
    lines = (doc or "").split("\n")
    match = _re.match(r"^\s*" + _re.escape(name) + r"\((.*)\)(?: -> (.*))?$", lines[0]) if lines else None
    if not match:
        raise ValueError(f"ccal: no signature in the docstring of {name}")
    parameters = []
    for part in _split_top_level(match.group(1)):
        part_name, _, rest = part.partition(":")
        annotation, _, default_text = rest.partition(" = ")
        default = _inspect.Parameter.empty
        if default_text:
            try:
                default = _ast.literal_eval(default_text.strip())
            except (ValueError, SyntaxError):
                default = _DefaultText(default_text.strip())
        parameters.append(_inspect.Parameter(part_name.strip(), _inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                             default=default, annotation=annotation.strip() or
                                             _inspect.Parameter.empty))
    signature = _inspect.Signature(parameters, return_annotation=match.group(2) or _inspect.Signature.empty)
    return signature, "\n".join(lines[1:]).strip()


def _with_signature(function, name, qualname):
    signature, doc = _signature_from_doc(function.__doc__, name)

    def wrapper(*args, **kwargs):
        return function(*args, **kwargs)

    wrapper.__name__ = name
    wrapper.__qualname__ = qualname
    wrapper.__module__ = "ccal"
    wrapper.__doc__ = doc
    wrapper.__signature__ = signature
    return wrapper


def _is_pybind_function(value):
    return type(value).__name__ in ("builtin_function_or_method", "instancemethod")


def _classes():
    return [v for v in list(globals().values())
            if isinstance(v, type) and getattr(v, "__module__", "") == "ccal" and
            type(v).__name__ == "pybind11_type"]


# ---------------------------------------------------------------------------------------------------------
# The display-unit view: a table of the result's main values in the units the command line shows, with a
# unit column, taken from the result's JSON (which the command line prints in display units).


class Table:
    """Rows of values in display units (those of the command line), each with its unit where it has one.
    str() is an aligned text table, _repr_html_ an HTML table (Jupyter), rows a list of dicts, to_frame() a
    pandas DataFrame (pandas is optional)."""

    title: "str"  # what the table shows
    columns: "List[str]"  # the column names; a unit column, or the unit in the name, says the values' units
    rows: "List[Dict[str, Any]]"  # one dict per row, column name → value

    def __init__(self, title, columns, rows):
        self.title = title
        self.columns = list(columns)
        self.rows = [dict(zip(self.columns, row)) for row in rows]

    @staticmethod
    def _cell(value):
        if isinstance(value, float):
            return f"{value:.6g}"
        if isinstance(value, (list, tuple)):
            return "[" + ", ".join(Table._cell(v) for v in value) + "]"
        return "" if value is None else str(value)

    def __str__(self):
        cells = [[self._cell(r[c]) for c in self.columns] for r in self.rows]
        widths = [max([len(c)] + [len(row[k]) for row in cells]) for k, c in enumerate(self.columns)]
        lines = [self.title, "  ".join(c.ljust(w) for c, w in zip(self.columns, widths)).rstrip()]
        lines += ["  ".join(v.ljust(w) for v, w in zip(row, widths)).rstrip() for row in cells]
        return "\n".join(lines)

    def __repr__(self):
        return str(self)

    def _repr_html_(self):
        head = "".join(f"<th>{_html.escape(c)}</th>" for c in self.columns)
        body = "".join("<tr>" + "".join(f"<td>{_html.escape(self._cell(r[c]))}</td>" for c in self.columns) +
                       "</tr>" for r in self.rows)
        return (f"<table><caption>{_html.escape(self.title)}</caption><thead><tr>{head}</tr></thead>"
                f"<tbody>{body}</tbody></table>")

    def to_frame(self) -> "Any":
        """The table as a pandas DataFrame (pandas is not a dependency of ccal: ImportError without it)."""
        try:
            import pandas
        except ImportError as e:
            raise ImportError("to_frame() needs pandas, which ccal does not require; install it (Debian: "
                              "apt-get install python3-pandas) or use .rows") from e
        return pandas.DataFrame([[r[c] for c in self.columns] for r in self.rows], columns=self.columns)


def _coefficient_rows(coefficients, fields):
    return [[name, c.get("unit", "")] + [c.get(f) for f in fields] for name, c in coefficients.items()]


def _display_budget(r, j):
    rows = [[c["id"], c["unit"], c["standard_uncertainty"], c["expanded_uncertainty"]] for c in j["coefficients"]]
    return Table(f"budget of {j['config']} ({j['mode']}, k = {j['coverage_factor']:g})",
                 ["coefficient", "unit", "standard_uncertainty", "expanded_uncertainty"], rows)


def _display_montecarlo(r, j):
    rows = [[name, c["unit"], c["mean"], c["std_dev"], c["symmetric_interval"][0], c["symmetric_interval"][1],
             c["lpu"]["expanded_uncertainty"], c["lpu"]["validated"]] for name, c in j["coefficients"].items()]
    return Table(f"Monte Carlo of {j['config']} ({j['trials']} trials, p = {j['coverage_probability']:g})",
                 ["coefficient", "unit", "mean", "std_dev", "low", "high", "lpu_expanded", "validated"], rows)


def _display_allocation(r, j):
    rows = [[name, c["unit"], c.get("target"), c["configured_expanded"], c["allocated_expanded"],
             c.get("verdict", "")] for name, c in j["coefficients"].items()]
    return Table(f"allocation for {j['config']} (p = {j['coverage_probability']:g})",
                 ["coefficient", "unit", "target", "configured_expanded", "allocated_expanded", "verdict"], rows)


def _display_identification(r, j):
    rows = _coefficient_rows(j["identification"]["coefficients"], ["value", "std_error"])
    return Table(f"{j['command']} of {j['config']}: identified coefficients",
                 ["coefficient", "unit", "value", "std_error"], rows)


def _display_force(r, j):
    rows = [[axis, j["specific_force_g"][axis], j["angular_rate_deg_per_s"][axis]] for axis in ("IA", "PA", "OA")]
    return Table(f"force of {j['config']}: run {j['run']['name']} at {j['run']['time_s']:g} s ({j['mode']})",
                 ["axis", "specific_force [g]", "angular_rate [deg/s]"], rows)


_DISPLAY = {"Budget": _display_budget, "MonteCarlo": _display_montecarlo, "Allocation": _display_allocation,
            "Simulation": _display_identification, "Reduction": _display_identification,
            "SensedInput": _display_force}


def _display_config(c):
    rows = [[r.name, r.g_level, r.duration, r.mode, r.mounting] for r in c.runs]
    return Table(f"configuration {c.source}: {len(c.runs)} runs, {len(c.tolerances)} tolerances",
                 ["run", "g_level [g]", "duration [s]", "platform", "mounting"], rows)


def _display_fit(f):
    rows = [[n, v, s] for n, v, s in zip(f.names, f.value, f.std_error)]
    return Table(f"fit: {len(f.names)} terms, {f.dof} degrees of freedom (values in the units of the data)",
                 ["term", "value", "std_error"], rows)


# ---------------------------------------------------------------------------------------------------------
# repr: the verb results, Config and Fit as their display table; every other class as its fields.


def _short(value):
    if isinstance(value, _np.ndarray):
        return _np.array2string(value, precision=6, threshold=6, edgeitems=2)
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (list, tuple)) and len(value) > 6:
        return "[" + ", ".join(_short(v) for v in value[:3]) + f", … ({len(value)} in all)]"
    if isinstance(value, list):
        return "[" + ", ".join(_short(v) for v in value) + "]"
    if type(type(value)).__name__ == "pybind11_type":
        return f"<ccal.{type(value).__name__}>"
    return repr(value)


def _fields(cls):
    return [n for n, v in vars(cls).items() if isinstance(v, property) and not n.startswith("_")]


def _fields_repr(self):
    cls = type(self)
    parts = []
    for name in _fields(cls):
        try:
            parts.append(f"{name}={_short(getattr(self, name))}")
        except Exception as e:  # a field that cannot be read is shown as such, never hides the rest
            parts.append(f"{name}=<{type(e).__name__}>")
    return f"ccal.{cls.__name__}(" + ", ".join(parts) + ")"


def _table_repr(self):
    return f"ccal.{type(self).__name__}\n{self.display()}"


def _table_html(self):
    return self.display()._repr_html_()


# ---------------------------------------------------------------------------------------------------------
# Pickling. A Config is pickled as its origin (the TOML text it was read from, or the bundled example) and
# the derivations applied to it; a verb's result as the call that made it (its Config, its options, and for
# `reduce` the contents of its logs): unpickling computes it again, which gives the same bits (every
# computation is deterministic, the Monte Carlo for any thread count), and checks that the JSON is the one
# pickled, so that a result from another version of ccal is refused rather than silently different.

_VOLATILE = {"wall_time_s", "threads", "trials_per_s"}


def _normalised(value):
    if isinstance(value, dict):
        return {k: _normalised(v) for k, v in value.items() if k not in _VOLATILE}
    if isinstance(value, list):
        return [_normalised(v) for v in value]
    if isinstance(value, str):
        return _re.sub(r", \d+ threads?, [0-9.]+ s", "", value)
    return value


def _restore_config(origin, edits):
    kind, *args = origin
    cfg = _raw["bundled_example"]() if kind == "bundled" else _raw["parse_config"](*args)
    cfg._ccal_origin = origin
    cfg._ccal_edits = ()
    for method, method_args, method_kwargs in edits:
        cfg = getattr(cfg, method)(*method_args, **method_kwargs)
    return cfg


def _config_reduce(self):
    origin = getattr(self, "_ccal_origin", None)
    if origin is None:
        raise TypeError("this ccal.Config cannot be pickled: it was not made by load_config, parse_config, "
                        "bundled_example or a with_… method of one")
    return _restore_config, (origin, self._ccal_edits)


def _restore_result(verb, config, kwargs, logs, pickled_json, pickled_text=None):
    kwargs = dict(kwargs)
    with _tempfile.TemporaryDirectory() as folder:
        paths = {}
        if logs is not None:
            files = {}
            for k, (run, original, data) in enumerate(logs):
                path = _os.path.join(folder, f"{k}_{_os.path.basename(original)}")
                with open(path, "wb") as f:
                    f.write(data)
                files[run] = path
                paths[path] = original
            kwargs["logs"] = files
        result = _raw[verb](config, **kwargs)
    _remember_call(result, verb, config, kwargs, logs, paths)
    if _normalised(_json.loads(result.to_json())) != _normalised(_json.loads(pickled_json)):
        raise ValueError(f"ccal: a pickled {type(result).__name__} computed again gives other numbers (pickled "
                         f"by another version of ccal?); this is ccal {__version__}")
    if pickled_text is not None:  # a reduction's text report names its logs as given, aligned to their names
        result._ccal_text = pickled_text
    return result


def _remember_call(result, verb, config, kwargs, logs, paths):
    result._ccal_call = (verb, config, {k: v for k, v in kwargs.items() if k not in ("logs", "progress")}, logs)
    result._ccal_paths = paths  # temporary log copies of an unpickled reduction → the original paths


def _result_reduce(self):
    verb, config, kwargs, logs = self._ccal_call
    return _restore_result, (verb, config, kwargs, logs, self.to_json(), None if logs is None else str(self))


def _original_paths(text, paths, quote):
    """The JSON of an unpickled reduction, whose logs were read from temporary copies, with the original paths."""
    for temporary, original in paths.items():
        text = text.replace(quote(temporary), quote(original))
    return text


# ---------------------------------------------------------------------------------------------------------
# Putting it together.

_raw = {}
_VERB_RESULTS = {"budget": "Budget", "sensed_input": "SensedInput", "simulate": "Simulation",
                 "reduce": "Reduction", "monte_carlo": "MonteCarlo", "allocate": "Allocation"}


def _verb(name, function):
    signature = function.__signature__

    def wrapper(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)
        call = dict(bound.arguments)
        config = call.pop("config")
        logs = None
        if name == "reduce":
            logs = []
            for run, path in call["logs"].items():
                try:
                    with open(path, "rb") as f:
                        logs.append((run, path, f.read()))
                except (OSError, TypeError):
                    logs = None  # the verb itself reports the file that cannot be read
                    break
        result = function(*args, **kwargs)
        _remember_call(result, name, config, call, logs, {})
        return result

    for attribute in ("__name__", "__qualname__", "__module__", "__doc__", "__signature__"):
        setattr(wrapper, attribute, getattr(function, attribute))
    return wrapper


def _config_origin(name, function):
    def wrapper(*args, **kwargs):
        cfg = function(*args, **kwargs)
        bound = function.__signature__.bind(*args, **kwargs)
        bound.apply_defaults()
        a = bound.arguments
        if name == "bundled_example":
            cfg._ccal_origin = ("bundled",)
        elif name == "parse_config":
            cfg._ccal_origin = ("text", a["text"], a["source"])
        else:
            with open(a["path"], encoding="utf-8", newline="") as f:
                cfg._ccal_origin = ("text", f.read(), str(a["path"]))
        cfg._ccal_edits = ()
        return cfg

    for attribute in ("__name__", "__qualname__", "__module__", "__doc__", "__signature__"):
        setattr(wrapper, attribute, getattr(function, attribute))
    return wrapper


def _config_edit(name, method):
    def wrapper(self, *args, **kwargs):
        derived = method(self, *args, **kwargs)
        if getattr(self, "_ccal_origin", None) is not None:
            derived._ccal_origin = self._ccal_origin
            derived._ccal_edits = self._ccal_edits + ((name, args, kwargs),)
        return derived

    for attribute in ("__name__", "__qualname__", "__module__", "__doc__", "__signature__"):
        setattr(wrapper, attribute, getattr(method, attribute))
    return wrapper


def _install():
    g = globals()
    # Functions of the module: signatures, then the verbs and the readers remember what made their results.
    for name, value in list(g.items()):
        if not name.startswith("_") and _is_pybind_function(value):
            _raw[name] = value
            g[name] = _with_signature(value, name, name)
    for name in _VERB_RESULTS:
        g[name] = _verb(name, g[name])
    for name in ("bundled_example", "load_config", "parse_config"):
        g[name] = _config_origin(name, g[name])
    # Methods of the classes.
    for cls in _classes():
        for name, value in list(vars(cls).items()):
            if not name.startswith("_") and _is_pybind_function(value):
                setattr(cls, name, _with_signature(value, name, f"{cls.__name__}.{name}"))
    for name in ("with_tolerance", "without_tolerance", "with_error", "with_plan"):
        setattr(Config, name, _config_edit(name, getattr(Config, name)))
    Config.__reduce__ = _config_reduce
    # Docstrings of the properties bound without one.
    for cls in _classes():
        for name in _fields(cls):
            doc = _PROPERTY_DOCS.get(f"{cls.__name__}.{name}")
            if doc is not None:
                p = vars(cls)[name]
                setattr(cls, name, property(p.fget, None, None, doc))
    # repr and the display view.
    for cls in _classes():
        cls.__repr__ = _fields_repr
    for verb, class_name in _VERB_RESULTS.items():
        cls = g[class_name]
        _verb_result_methods(cls, _DISPLAY[class_name], cls.__str__, cls.to_json, cls.config)
    _write_logs.__module__, _write_logs.__qualname__ = "ccal", "Simulation.write_logs"
    Simulation.write_logs = _write_logs
    for cls, build in ((Config, _display_config), (Fit, _display_fit)):
        _table_methods(cls, build)


_INNER = {"Budget": "budget", "SensedInput": "input", "Simulation": "observations", "Reduction": "logs",
          "MonteCarlo": "monte_carlo", "Allocation": "allocation"}


def _named(cls, name, f):
    f.__name__, f.__qualname__, f.__module__ = name, f"{cls.__name__}.{name}", "ccal"
    setattr(cls, name, f)


def _verb_result_methods(cls, build, text, to_json, original_config):
    """display, to_json (the log paths of an unpickled reduction as given), to_dict, to_frame, config, str,
    dir, repr, _repr_html_ and pickling of a verb's result."""

    def display(self) -> "Table":
        """The main values in display units (those of the command line), each with its unit."""
        return build(self, _json.loads(self.to_json()))

    def json_text(self) -> "str":
        """The report as the CLI's JSON (text)."""
        return _original_paths(to_json(self), getattr(self, "_ccal_paths", {}), lambda p: _json.dumps(p)[1:-1])

    def text_report(self):
        return getattr(self, "_ccal_text", None) or text(self)

    def to_dict(self) -> "Dict[str, Any]":
        """The report as the CLI's JSON, parsed (dict)."""
        return _json.loads(self.to_json())

    def to_frame(self) -> "Any":
        """display() as a pandas DataFrame (pandas is optional: ImportError without it)."""
        return self.display().to_frame()

    def config(self) -> "Config":
        """The configuration the result was computed from [Config]."""
        call = getattr(self, "_ccal_call", None)
        return call[1] if call else original_config.fget(self)

    def names(self):
        return sorted(set(object.__dir__(self)) | set(dir(type(getattr(self, _INNER[cls.__name__])))))

    for name, f in (("display", display), ("to_json", json_text), ("to_dict", to_dict), ("to_frame", to_frame)):
        _named(cls, name, f)
    cls.__str__ = text_report
    cls.__dir__ = names
    cls.config = property(config, None, None, config.__doc__)
    cls.__repr__ = _table_repr
    cls._repr_html_ = _table_html
    cls.__reduce__ = _result_reduce


def _table_methods(cls, build):
    def display(self) -> "Table":
        """The main values as a table (Config: the runs; Fit: the terms), each with its unit."""
        return build(self)

    def to_frame(self) -> "Any":
        """display() as a pandas DataFrame (pandas is optional: ImportError without it)."""
        return self.display().to_frame()

    _named(cls, "display", display)
    _named(cls, "to_frame", to_frame)
    cls.__repr__ = _table_repr
    cls._repr_html_ = _table_html

def _write_logs(self, folder: "str", step: "Optional[float]" = None) -> "Dict[str, str]":
    """Writes the runs' logs into `folder` (created if missing), as `ccal simulate --logs-out` does; returns
    {run name: path}, what reduce() takes."""
    _os.makedirs(folder, exist_ok=True)
    paths = {}
    for run, (name, text) in zip(self.config.runs, self.run_logs(step)):
        paths[run.name] = _os.path.join(folder, name)
        with open(paths[run.name], "w", encoding="utf-8") as f:
            f.write(text)
    return paths



_install()

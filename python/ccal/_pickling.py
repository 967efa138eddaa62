"""Pickling. A Config is pickled as its origin (the TOML text it was read from, or the bundled example) and the
derivations applied to it. A result is pickled by value: every attribute's value (NumPy arrays, numbers, text,
its parts each by value in turn, its Config by origin), its texts (str(), to_json(), to_csv(), a Report's
to_html() without the charting scripts the module holds) and the exceptions its attributes raise, compressed;
unpickling rebuilds it without computing anything, as a stored result (StoredResult) of the same name, attributes
and methods, which isinstance() takes for its class. A Config of a result that has no origin is one the result's
own configuration gives: one of its instruments, or a Design's designed Config, stored as the design's
configuration and its designed runs (Config._design_config, checked against the original when pickling). One
exception: a Simulation's run_logs() and logs_manifest() (and write_logs()) simulate again from the stored call
when called (the logs are about 1 MB compressed for examples/lab.toml; the same bits: the simulation is
deterministic, checked against the stored JSON)."""

import builtins
import json
import os
import pickle
import hashlib
import re
import struct
import tempfile
import zlib

import numpy as np

from . import _ccal

_VOLATILE = {"wall_time_s", "threads", "trials_per_s", "cache_seconds", "search_seconds"}  # what differs between two
# runs of the same call
_TEXTS = ("to_json", "to_csv", "__str__", "to_html")  # the texts of a result, stored as they are (a page without
# its charting scripts)
# Methods that compute from arguments: the stored call is run again when one is called (class → verb, methods).
_RECOMPUTED = {"Simulation": ("simulate", ("run_logs", "logs_manifest"))}
_FORMAT = 1  # of the stored tree


def _normalised(value):
    if isinstance(value, dict):
        return {k: _normalised(v) for k, v in value.items() if k not in _VOLATILE}
    if isinstance(value, list):
        return [_normalised(v) for v in value]
    if isinstance(value, str):
        return re.sub(r", \d+ threads?, [0-9.]+ s", "", value)
    return value


def restore_config(origin, edits):
    kind, *args = origin
    cfg = _ccal.bundled_example() if kind == "bundled" else _ccal.parse_config(*args)
    cfg._ccal_origin = origin
    cfg._ccal_edits = ()
    for method, method_args, method_kwargs in edits:
        cfg = getattr(cfg, method)(*method_args, **method_kwargs)
    return cfg


def config_reduce(self):
    origin = getattr(self, "_ccal_origin", None)
    if origin is None:
        raise TypeError("this ccal.Config cannot be pickled: it was not made by load_config, parse_config, "
                        "bundled_example or a with_… or instrument() method of one")
    return restore_config, (origin, self._ccal_edits)


# --- Results by value -------------------------------------------------------------------------------------------

def _fields(cls):
    return [n for n, v in vars(cls).items() if isinstance(v, property) and not n.startswith("_")]


class _Node(tuple):
    """(class name, values, raises, texts, call) of a stored object of the module."""


class _Array(tuple):
    """(array, writeable) of a NumPy array."""


class _Instrument(tuple):
    """(k,): the configuration of the k-th instrument of the stored result's own configuration."""


class _Derived(tuple):
    """(base, method, args): the configuration getattr(base, method)(*args), base a stored configuration (a
    Design's designed Config: its configuration's _design_config of the designed runs)."""


class _Page(tuple):
    """(head, tail, sha256): a report page without its charting scripts' text, which goes between head and tail
    (ccal._ccal._report_script_text(), whose SHA-256 is sha256)."""


def _is_bound(value):
    return isinstance(type(value), type(_ccal.Config)) or isinstance(value, StoredResult)  # the module's metaclass


def _visible(value):
    """Everything of a value that Python sees, to the last bit: two configurations with equal _visible are the
    same to every attribute."""
    if isinstance(value, float):
        return ("float", struct.pack("<d", value))
    if isinstance(value, np.ndarray):
        return ("array", value.dtype.str, value.shape, value.tobytes())
    if _is_bound(value):
        return (type(value).__name__,) + tuple((f, _visible(getattr(value, f))) for f in _fields(type(value)))
    if isinstance(value, (list, tuple)):
        return (type(value).__name__,) + tuple(_visible(v) for v in value)
    if isinstance(value, dict):
        return ("dict",) + tuple((k, _visible(v)) for k, v in value.items())
    return value


def _run_values(run):
    return (run.name, run.g_level, run.duration, run.mode, run.initial_phase, run.terminal_phase, run.arm_azimuth,
            run.mounting)


def _page_stored(page):
    scripts = _ccal._report_script_text()
    at = page.find(scripts)
    if at < 0 or page.find(scripts, at + 1) >= 0:
        return page
    return _Page((page[:at], page[at + len(scripts):], hashlib.sha256(scripts.encode()).hexdigest()))


def _page_restored(stored):
    if not isinstance(stored, _Page):
        return stored
    head, tail, sha = stored
    scripts = _ccal._report_script_text()
    if hashlib.sha256(scripts.encode()).hexdigest() != sha:
        raise ValueError("ccal: a pickled Report's page was made with other charting scripts than this module's "
                         f"(pickled by another version of ccal?); this is ccal {_ccal.__version__}")
    return head + scripts + tail


def _own_config(top):
    """The configuration a result was made from, as given to its call (with its origin), or None."""
    call = getattr(top, "_ccal_call", None)
    config = call[1] if call else getattr(top, "_ccal_config", None)
    if config is None and "config" in _fields(type(top)):
        config = getattr(top, "config", None)
    return config if getattr(config, "_ccal_origin", None) is not None else None


class _Snapshot:
    """Walks a result into a tree of plain values: a _Node for an object of the module, an _Array for a NumPy
    array, an _Instrument or a _Derived for a configuration the result's own configuration gives, lists, tuples
    and dicts of them, numbers, text and Configs."""

    def __init__(self, top):
        self.known = []  # (tree, Config, _visible): the configurations a Config without origin may be
        self.preferred = []  # those a Design's field holds, looked at first
        self.top_config = _own_config(top)
        if self.top_config is not None:
            self.known.append((self.top_config, self.top_config, _visible(self.top_config)))
            for k, one in enumerate(self.top_config.instruments):
                self.known.append((_Instrument((k,)), one, _visible(one)))

    def config(self, cfg, where):
        if getattr(cfg, "_ccal_origin", None) is not None:
            return cfg
        key = _visible(cfg)
        for tree, _, known in self.preferred + self.known:
            if known == key:
                return tree
        raise TypeError(f"this result cannot be pickled: its {where} is a ccal.Config that was not made by "
                        "load_config, parse_config, bundled_example or a with_… or instrument() method of one")

    def value(self, v, where):
        if isinstance(v, np.ndarray):
            return _Array((v.copy(), bool(v.flags.writeable)))
        if isinstance(v, _ccal.Config):
            return self.config(v, where)
        if _is_bound(v):
            return self.node(v, where)
        if isinstance(v, (list, tuple)):
            return type(v)(self.value(x, where) for x in v)
        if isinstance(v, dict):
            return {k: self.value(x, where) for k, x in v.items()}
        return v

    def design_configs(self, design, where):
        """A Design's configurations by field: `designed` and `after`'s its configuration with the designed runs,
        `before`'s with the expected measured inputs charged (verbs/design.cpp); several instruments: the runs
        given to each, no inputs charged."""
        config = design.config
        base = self.value(config, f"{where}.config")
        several = bool(design.instruments)
        configs = {}
        for field, args in (("designed", (tuple(map(_run_values, design.designed.runs)), not several, several)),
                            ("before", (None, True, False))):
            made = config._design_config(*args)
            configs[field] = [(_Derived((base, "_design_config", args)), made, _visible(made))]
        configs["after"] = configs["designed"]
        return configs

    def node(self, obj, where):
        cls = type(obj)
        name = cls.__name__
        values, raises = {}, {}
        preferred = self.design_configs(obj, where) if name == "Design" else {}
        for field in _fields(cls):
            outer, self.preferred = self.preferred, preferred.get(field, []) + self.preferred
            try:
                values[field] = self.value(getattr(obj, field), f"{where}.{field}")
            except TypeError:
                raise
            except Exception as e:  # e.g. MonteCarlo.samples without keep_samples: raised again when read
                raises[field] = (type(e).__name__, str(e))
            finally:
                self.preferred = outer
        texts = {t: _text_of(obj, t) for t in _TEXTS if _has_text(cls, t)}
        call = getattr(obj, "_ccal_call", None)
        if name in _RECOMPUTED and call is not None:
            call = (call[0], self.value(call[1], f"{where}.config"), call[2])
        else:
            call = None
        return _Node((name, values, raises, texts, call))


def _text_of(obj, name):
    if name == "__str__":
        return str(obj)
    text = getattr(obj, name)()
    return _page_stored(text) if name == "to_html" else text


def _has_text(cls, name):
    original = getattr(cls, "_ccal_original", cls)
    if name == "__str__":
        return "__str__" in vars(original)
    return callable(getattr(original, name, None))


def result_reduce(self):
    tree = _Snapshot(self).node(self, f"ccal.{type(self).__name__}")
    return restore_stored, (_FORMAT, zlib.compress(pickle.dumps(tree, protocol=pickle.HIGHEST_PROTOCOL), 9))


def restore_stored(form, data):
    if form != _FORMAT:
        raise ValueError(f"ccal: a pickled result of format {form} (of a later version of ccal?); this is ccal "
                         f"{_ccal.__version__}, which reads format {_FORMAT}")
    return _Rebuild().node(pickle.loads(zlib.decompress(data)))


class _Rebuild:
    """The stored objects of a tree of _Snapshot."""

    def __init__(self):
        self.top_config = None

    def value(self, v):
        if isinstance(v, _Node):
            return self.node(v)
        if isinstance(v, _Array):
            array, writeable = v
            array.flags.writeable = writeable
            return array
        if isinstance(v, _Instrument):
            return self.top_config.instruments[v[0]]
        if isinstance(v, _Derived):
            base, method, args = v
            return getattr(self.value(base), method)(*args)
        if isinstance(v, (list, tuple)):
            return type(v)(self.value(x) for x in v)
        if isinstance(v, dict):
            return {k: self.value(x) for k, x in v.items()}
        return v

    def node(self, tree):
        name, values, raises, texts, call = tree
        if self.top_config is None and isinstance(values.get("config"), _ccal.Config):
            self.top_config = values["config"]
        obj = stored_class(name).__new__(stored_class(name))
        obj._ccal_values = {k: self.value(v) for k, v in values.items()}
        obj._ccal_raises = raises
        obj._ccal_texts = texts
        obj._ccal_stored_call = call and (call[0], self.value(call[1]), call[2])
        obj._ccal_recomputed = None
        return obj


class StoredResult:
    """A result of ccal unpickled by value: the attributes, texts and methods of its class (whose name it has, and
    which isinstance() takes it for), read from what was pickled; nothing is computed again (but a Simulation's
    run_logs() and logs_manifest(), which simulate again from the stored call)."""

    def _ccal_get(self, name):
        if name in self._ccal_raises:
            kind, message = self._ccal_raises[name]
            exception = getattr(_ccal, kind, None)
            if not (isinstance(exception, type) and issubclass(exception, BaseException)):
                exception = getattr(builtins, kind, RuntimeError)
            raise exception(message)
        value = self._ccal_values[name]
        if isinstance(value, np.ndarray) and value.flags.writeable:
            return value.copy()  # as the binding, a fresh array each time
        if isinstance(value, (list, dict)):
            return type(value)(value)
        return value

    def _ccal_recompute(self):
        """The result computed again from its stored call (Simulation.run_logs), checked against the stored JSON."""
        if self._ccal_recomputed is None:
            if self._ccal_stored_call is None:
                raise TypeError(f"this unpickled ccal.{type(self).__name__} cannot compute that: it is one "
                                "instrument's part of a result, which holds the call")
            verb, config, kwargs = self._ccal_stored_call
            result = getattr(_ccal, verb)(config, **kwargs)
            if _normalised(json.loads(result.to_json())) != _normalised(json.loads(self.to_json())):
                raise ValueError(f"ccal: a pickled {type(self).__name__} computed again gives other numbers "
                                 f"(pickled by another version of ccal?); this is ccal {_ccal.__version__}")
            self._ccal_recomputed = result
        return self._ccal_recomputed

    def __reduce__(self):
        return result_reduce(self)


_STORED = {}


def _text_method(name):
    def text(self):
        return _page_restored(self._ccal_texts[name])
    text.__name__ = name
    return text


def _recomputed_method(name, original):
    def method(self, *args, **kwargs):
        return getattr(self._ccal_recompute(), name)(*args, **kwargs)
    method.__name__, method.__doc__ = name, getattr(original, "__doc__", None)
    return method


def _property(name, doc):
    return property(lambda self: self._ccal_get(name), None, None, doc)


def stored_class(name):
    """The class of a stored `name` (ccal.Budget → a StoredResult named Budget): its attributes as properties of
    the stored values, the texts stored, and the methods the package adds in Python (display(), to_dict(), …),
    which read those."""
    if name in _STORED:
        return _STORED[name]
    original = getattr(_ccal, name)
    ns = {"__module__": "ccal", "__qualname__": name, "__doc__": original.__doc__, "_ccal_original": original}
    for field in _fields(original):
        ns[field] = _property(field, vars(original)[field].__doc__)
    for attr, value in vars(original).items():
        if isinstance(value, staticmethod) or (
                type(value).__name__ == "function" and attr not in ("__dir__", "__reduce__", "__getattr__", *_TEXTS)):
            ns[attr] = value  # the Python-level methods: display, to_dict, to_frame, repr, write_logs, …
    for text in _TEXTS:
        if _has_text(original, text):
            ns[text] = _text_method(text)
    for method in _RECOMPUTED.get(name, ((), ()))[1]:
        ns[method] = _recomputed_method(method, getattr(original, method))
    inner = vars(original).get("_inner")
    if inner is not None:
        ns["_inner"] = inner

        def forward(self, attr):
            if attr.startswith("_"):
                raise AttributeError(attr)
            return getattr(self._ccal_get(inner), attr)

        def names(self):
            return sorted(set(object.__dir__(self)) | set(dir(self._ccal_get(inner))))

        ns["__getattr__"], ns["__dir__"] = forward, names
    _STORED[name] = type(name, (StoredResult,), ns)
    return _STORED[name]


def stand_ins_count_as_their_class(classes):
    """isinstance(stored, ccal.Budget) is True for a Budget unpickled by value: the classes' metaclass, the
    module's, with an instance check that also takes the stored results named for the class."""
    meta = type(classes[0])

    class ResultType(meta):
        def __instancecheck__(cls, obj):
            return type.__instancecheck__(cls, obj) or getattr(type(obj), "_ccal_original", None) is cls

    for cls in classes:
        cls.__class__ = ResultType


# --- Results as their call (pickles of ccal before results pickled by value) -----------------------------------

def restore_result(verb, config, kwargs, logs, pickled_json, pickled_text=None):
    kwargs = dict(kwargs)
    with tempfile.TemporaryDirectory() as folder:
        paths = {}
        if isinstance(logs, dict):  # a folder with its manifest: the same files, at the same places in a copy
            copy = os.path.join(folder, "logs")
            for name, data in logs["files"]:
                path = os.path.join(copy, name)
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "wb") as f:
                    f.write(data)
            kwargs["logs"] = copy
            paths[copy] = logs["folder"]
        elif logs is not None:
            files = {}
            for k, (run, original, data) in enumerate(logs):
                path = os.path.join(folder, f"{k}_{os.path.basename(original)}")
                with open(path, "wb") as f:
                    f.write(data)
                files[run] = path
                paths[path] = original
            kwargs["logs"] = files
        result = getattr(_ccal, verb)(config, **kwargs)
    remember_call(result, verb, config, kwargs, paths)
    if _normalised(json.loads(result.to_json())) != _normalised(json.loads(pickled_json)):
        raise ValueError(f"ccal: a pickled {type(result).__name__} computed again gives other numbers (pickled "
                         f"by another version of ccal?); this is ccal {_ccal.__version__}")
    if pickled_text is not None:  # a reduction's text report names its logs as given, aligned to their names
        result._ccal_text = pickled_text
    return result


def remember_call(result, verb, config, kwargs, paths=None):
    result._ccal_call = (verb, config, {k: v for k, v in kwargs.items() if k not in ("logs", "progress")})
    result._ccal_paths = paths or {}  # temporary log copies of a reduction unpickled as its call → the originals


def original_paths(text, paths, quote):
    """The JSON of a reduction unpickled as its call, whose logs were read from temporary copies, with the original
    paths."""
    for temporary, original in paths.items():
        text = text.replace(quote(temporary), quote(original))
    return text

"""Puts the package together when it is imported: the compiled functions and methods get signatures, the
verbs and the configuration readers remember what made their results (for pickling), and the classes get
their repr and display view. The properties' docstrings are those of the bindings (python/bind_*.cpp)."""

from . import _ccal, _pickling, _results, _tables
from ._signatures import copy_identity, is_pybind_function, with_signature

# The verbs and their result classes.
VERB_RESULTS = {"budget": "Budget", "sensed_input": "SensedInput", "simulate": "Simulation", "reduce": "Reduction",
                "monte_carlo": "MonteCarlo", "allocate": "Allocation"}


def compiled_classes():
    """The classes of the compiled module (ccal._ccal), but its exceptions."""
    return [v for k, v in vars(_ccal).items()
            if isinstance(v, type) and not k.startswith("_") and not issubclass(v, BaseException)]


def _verb(name, function):
    signature = function.__signature__

    def wrapper(*args, **kwargs):
        result = function(*args, **kwargs)  # first: its messages name a mistyped keyword's likely intent
        call = dict(signature.bind(*args, **kwargs).arguments)
        _pickling.remember_call(result, name, call.pop("config"), call)
        return result

    return copy_identity(wrapper, function)


def _report(function):
    """report(), remembering its configuration and its call for the page's provenance (Report.to_html)."""
    signature = function.__signature__

    def wrapper(*args, **kwargs):
        result = function(*args, **kwargs)
        arguments = signature.bind(*args, **kwargs).arguments
        result._ccal_config = arguments.pop("config")
        result._ccal_keywords = {**arguments.pop("kwargs", {}), **arguments}
        return result

    return copy_identity(wrapper, function)


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

    return copy_identity(wrapper, function)


def _config_edit(name, method):
    def wrapper(self, *args, **kwargs):
        derived = method(self, *args, **kwargs)
        if getattr(self, "_ccal_origin", None) is not None:
            derived._ccal_origin = self._ccal_origin
            derived._ccal_edits = self._ccal_edits + ((name, args, kwargs),)
        return derived

    return copy_identity(wrapper, method)


def _methods(classes):
    """Signatures of the methods."""
    for cls in classes:
        for name, value in list(vars(cls).items()):
            if not name.startswith("_") and is_pybind_function(value):
                setattr(cls, name, with_signature(value, name, f"{cls.__name__}.{name}"))


def install(namespace):
    """Fills `namespace` (that of the package ccal) with the public API: the compiled module's names, its
    functions wrapped, and the Python classes."""
    # The compiled classes and functions are bound with `ccal` as their module (python/module.cpp); so is Table.
    _tables.Table.__module__ = "ccal"
    keywords = getattr(_ccal, "_option_keywords", {})
    for name, value in vars(_ccal).items():
        if not name.startswith("_"):
            namespace[name] = (with_signature(value, name, name, keywords.get(name)) if is_pybind_function(value)
                               else value)
    for name in (*VERB_RESULTS, "design"):
        namespace[name] = _verb(name, namespace[name])
    namespace["report"] = _report(namespace["report"])
    for name in ("bundled_example", "load_config", "parse_config"):
        namespace[name] = _config_origin(name, namespace[name])
    namespace["Table"] = _tables.Table
    classes = compiled_classes()
    _methods(classes)
    Config = _ccal.Config
    for name in ("with_tolerance", "without_tolerance", "with_error", "with_plan", "instrument"):
        setattr(Config, name, _config_edit(name, getattr(Config, name)))
    Config.__reduce__ = _pickling.config_reduce
    # Results pickle by value.
    by_value = [cls for cls in classes if cls is not Config]
    for cls in by_value:
        cls.__reduce__ = _pickling.result_reduce
    namespace["StoredResult"] = _pickling.StoredResult
    _pickling.stand_ins_count_as_their_class(by_value)
    for cls in classes:
        cls.__repr__ = _results.fields_repr
    for class_name in VERB_RESULTS.values():
        cls = getattr(_ccal, class_name)
        _results.verb_result_methods(cls, _tables.DISPLAY[class_name])
    _results.statement_methods(_ccal.Statement)
    _results.json_table_methods(_ccal.History, _results.history_table)
    _results.budget_methods(_ccal.Budget, _tables.display_budget_sources)
    _results.json_table_methods(_ccal.Identification, _tables.DISPLAY["Identification"])
    _ccal.Simulation.write_logs = _results.write_logs
    _results.table_methods(Config, _tables.display_config)
    _results.table_methods(_ccal.Fit, _tables.display_fit)
    _results.report_methods(_ccal.Report)
    _results.design_methods(_ccal.Design)

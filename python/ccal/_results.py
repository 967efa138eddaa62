"""What the classes gain in Python: repr (a verb's result, Config and Fit as their display table, every other
class as its fields), Jupyter tables, display(), to_dict(), to_frame(), and Simulation.write_logs."""

import json
import os
import tempfile

import numpy as np

from . import _ccal, _pickling
from ._tables import Table  # noqa: F401 (named by the annotations below)


def _short(value):
    if isinstance(value, np.ndarray):
        return np.array2string(value, precision=6, threshold=6, edgeitems=2)
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (list, tuple)) and len(value) > 6:
        return "[" + ", ".join(_short(v) for v in value[:3]) + f", … ({len(value)} in all)]"
    if isinstance(value, list):
        return "[" + ", ".join(_short(v) for v in value) + "]"
    if isinstance(type(value), type(_ccal.Config)) or isinstance(value, _pickling.StoredResult):  # the module's
        return f"<ccal.{type(value).__name__}>"
    return repr(value)


def fields(cls):
    """The public properties of a class, in the order they were bound."""
    return [n for n, v in vars(cls).items() if isinstance(v, property) and not n.startswith("_")]


def fields_repr(self):
    cls = type(self)
    parts = []
    for name in fields(cls):
        try:
            parts.append(f"{name}={_short(getattr(self, name))}")
        except Exception as e:  # a field that cannot be read is shown as such, never hides the rest
            parts.append(f"{name}=<{type(e).__name__}>")
    return f"ccal.{cls.__name__}(" + ", ".join(parts) + ")"


def _table_repr(self):
    return f"ccal.{type(self).__name__}\n{self.display()}"


def _table_html(self):
    return self.display()._repr_html_()


def _named(cls, name, f):
    f.__name__, f.__qualname__, f.__module__ = name, f"{cls.__name__}.{name}", "ccal"
    setattr(cls, name, f)


def verb_result_methods(cls, build):
    """display, to_json (the log paths of an unpickled reduction as given), to_dict, to_frame, config, str,
    dir, repr, _repr_html_ and pickling of a verb's result; `build` makes its display table. cls._inner names
    the inner result whose attributes the result forwards (python/bindings.hpp)."""
    inner = cls._inner
    text, to_json, original_config = cls.__str__, cls.to_json, cls.config

    def display(self) -> "Table":
        """The main values in display units (those of the command line), each with its unit."""
        return build(self, json.loads(self.to_json()))

    def json_text(self) -> "str":
        """The report as the CLI's JSON (text)."""
        return _pickling.original_paths(to_json(self), getattr(self, "_ccal_paths", {}),
                                        lambda p: json.dumps(p)[1:-1])

    def text_report(self):
        return getattr(self, "_ccal_text", None) or text(self)

    def to_dict(self) -> "Dict[str, Any]":
        """The report as the CLI's JSON, parsed (dict)."""
        return json.loads(self.to_json())

    def to_frame(self) -> "Any":
        """display() as a pandas DataFrame (pandas is optional: ImportError without it)."""
        return self.display().to_frame()

    def config(self) -> "Config":
        """The configuration the result was computed from [Config]."""
        call = getattr(self, "_ccal_call", None)
        return call[1] if call else original_config.fget(self)

    def names(self):
        return sorted(set(object.__dir__(self)) | set(dir(type(getattr(self, inner)))))

    for name, f in (("display", display), ("to_json", json_text), ("to_dict", to_dict), ("to_frame", to_frame)):
        _named(cls, name, f)
    cls.__str__ = text_report
    cls.__dir__ = names
    cls.config = property(config, None, None, config.__doc__)
    cls.__repr__ = _table_repr
    cls._repr_html_ = _table_html


def json_table_methods(cls, build):
    """display, to_dict, to_frame, repr and _repr_html_ of a result whose display() `build` makes from its JSON
    (identify_file()'s, history()'s)."""

    def display(self) -> "Table":
        return build(self, json.loads(self.to_json()))

    display.__doc__ = build.__doc__

    def to_dict(self) -> "Dict[str, Any]":
        """The report as the CLI's JSON, parsed (dict)."""
        return json.loads(self.to_json())

    def to_frame(self) -> "Any":
        """display() as a pandas DataFrame (pandas is optional: ImportError without it)."""
        return self.display().to_frame()

    for name, f in (("display", display), ("to_dict", to_dict), ("to_frame", to_frame)):
        _named(cls, name, f)
    cls.__repr__ = _table_repr
    cls._repr_html_ = _table_html


def history_table(self, d) -> "Table":
    """One row per coefficient and calibration (superseded ones left out): the date, the value, U, unit and E_n
    against the calibration before."""
    rows = []
    recorded = {c["id"]: c["coefficients"] for c in d["calibrations"]}  # the statements' figures, in their units
    for h in self.coefficients:
        en = {e.to_index: e.value if e.defined else None for e in h.normalised_errors}
        for i, (date, record) in enumerate(zip(h.dates, h.ids)):
            c = recorded[record][h.name]
            rows.append([h.name, date, c["value"], c["expanded_uncertainty"], h.unit, en.get(i)])
    return Table(f"calibration history of {d['serial']}", ["coefficient", "date", "value", "U", "unit", "E_n"], rows)


def _statement_rows(d):
    """Per coefficient of a statement's JSON: its name, its rounded figures, the columns between value/U and the
    interval (unit, k, p, nu_eff: inf for a normal part alone) and those after it (significant, method)."""
    for name, c in d["coefficients"].items():
        nu = c["effective_dof"]
        yield (name, c["rounded"], [c["unit"], c["coverage_factor"], d["coverage_probability"],
                                    float("inf") if nu is None else nu], [c["significant"], c["interval_method"]])


def statement_methods(cls):
    """Statement.display(), to_dict(), to_frame(), to_uncertainties(), repr and _repr_html_."""

    def display(self) -> "Table":
        """One row per coefficient: the value and U rounded as the certificate writes them (two significant
        digits of U, JCGM 100 §7.2.6), unit, k, p, nu_eff, the interval, whether it excludes 0 and how it was
        obtained (student_t, or monte_carlo where the JCGM 101 §8 check refused the Student-t one)."""
        d = json.loads(self.to_json())
        rows = [[name, r["estimate"], r["expanded_uncertainty"], *common, r["interval"][0], r["interval"][1], *last]
                for name, r, common, last in _statement_rows(d)]
        return Table(f"calibration statement, p = {100 * d['coverage_probability']:g} % (U to two significant "
                     "digits)", ["coefficient", "value", "U", "unit", "k", "p", "nu_eff", "low", "high",
                                 "significant", "interval_method"], rows)

    def to_dict(self) -> "Dict[str, Any]":
        """The statement as to_json() writes it, parsed (dict)."""
        return json.loads(self.to_json())

    def to_frame(self) -> "Any":
        """One row per coefficient as a pandas DataFrame indexed by the coefficient, for computing: value (the
        corrected estimate), U, low and high as numbers in the coefficient's unit, k, p, nu_eff (inf for a normal
        part alone), significant and interval_method; then the certificate's rounded figures as text of their own
        (value_rounded, U_rounded, low_rounded, high_rounded), so that 0.02000 keeps its digits. pandas is
        optional: ImportError without it."""
        d = json.loads(self.to_json())
        rows = [[name, c["corrected_estimate"], c["expanded_uncertainty"], *common, c["interval"][0], c["interval"][1],
                 *last, r["estimate"], r["expanded_uncertainty"], r["interval"][0], r["interval"][1]]
                for (name, r, common, last), c in zip(_statement_rows(d), d["coefficients"].values())]
        return Table("calibration statement", ["coefficient", "value", "U", "unit", "k", "p", "nu_eff", "low",
                                               "high", "significant", "interval_method", "value_rounded",
                                               "U_rounded", "low_rounded", "high_rounded"], rows).to_frame()

    def to_uncertainties(self) -> "Dict[str, Any]":
        """The corrected estimates as correlated numbers of the package uncertainties (optional: ImportError
        without it), {name: ufloat} with the combined covariance, so that a function of them carries its
        uncertainty: e.g. the modelled output K0 + K2 a² + K3 a³ at any g-level a."""
        try:
            import uncertainties
        except ImportError as e:
            raise ImportError("to_uncertainties() needs the package uncertainties, which ccal does not require; "
                              "install it (Debian: apt-get install python3-uncertainties) or use .covariance"
                              ) from e
        values = uncertainties.correlated_values(list(self.values), np.asarray(self.covariance),
                                                 tags=list(self.names))
        return dict(zip(self.names, values))

    for name, f in (("display", display), ("to_dict", to_dict), ("to_frame", to_frame),
                    ("to_uncertainties", to_uncertainties)):
        _named(cls, name, f)
    cls.__repr__ = _table_repr
    cls._repr_html_ = _table_html


def budget_methods(cls, build):
    """Budget.sources_table() and .sources_frame(): the budget per source."""

    def sources_table(self) -> "Table":
        """One row per source: its id, bound and unit, and each coefficient's effect and share, in display
        units."""
        return build(self, json.loads(self.to_json()))

    def sources_frame(self) -> "Any":
        """sources_table() as a pandas DataFrame indexed by the source id (pandas is optional: ImportError
        without it)."""
        return self.sources_table().to_frame()

    _named(cls, "sources_table", sources_table)
    _named(cls, "sources_frame", sources_frame)


def table_methods(cls, build):
    """display, to_frame, repr and _repr_html_ of a class shown as a table (Config, Fit)."""

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


def write_logs(self, folder: "str", step: "Union[float, str, None]" = None, log_layout: "Optional[str]" = None) -> "Dict[str, str]":
    """Writes the runs' logs and their manifest.toml into `folder` (created if missing), as `ccal simulate
    --logs-out` does (log_layout: a layout file's path, as `--log-layout`); returns {run name: path}, what
    reduce() takes (as does the folder itself)."""
    path = os.fspath(folder) if isinstance(folder, (str, bytes, os.PathLike)) else None
    if path is None:
        raise TypeError(f"Simulation.write_logs(): folder: expected a folder's path (str or os.PathLike), got "
                        f"{type(folder).__name__}")
    if not path:
        raise _ccal.InputError("Simulation.write_logs(): folder: the path is empty; accepted: a folder's path (made "
                               "if missing)")
    if os.path.exists(path) and not os.path.isdir(path):
        raise _ccal.InputError(f"Simulation.write_logs(): folder: '{os.fsdecode(path)}' is a file, not a folder; "
                               f"accepted: a folder's path (made if missing)")
    logs = self.run_logs(step, log_layout)
    manifest = self.logs_manifest(log_layout)
    os.makedirs(folder, exist_ok=True)
    paths = {}
    for run, (name, text) in zip(self.config.runs, logs):
        paths[run.name] = os.path.join(folder, name)
        with open(paths[run.name], "w", encoding="utf-8") as f:
            f.write(text)
    with open(os.path.join(folder, "manifest.toml"), "w", encoding="utf-8") as f:
        f.write(manifest)
    return paths


write_logs.__module__, write_logs.__qualname__ = "ccal", "Simulation.write_logs"


def config_call_text(config):
    """The Python expression that made a configuration, for a page's provenance: its reader and each edit."""
    origin = getattr(config, "_ccal_origin", None) or ("unknown",)
    if origin[0] == "bundled":
        text = "ccal.bundled_example()"
    elif origin[0] == "text" and origin[2].endswith(".toml") and os.path.exists(origin[2]):
        text = f"ccal.load_config({origin[2]!r})"
    elif origin[0] == "text":
        text = f"ccal.parse_config(..., source={origin[2]!r})"
    else:
        text = "config"
    for name, args, kwargs in getattr(config, "_ccal_edits", ()):
        parts = [repr(a) for a in args] + [f"{k}={v!r}" for k, v in kwargs.items()]
        text += f".{name}({', '.join(parts)})"
    return text


# What a file's extension says it holds (as `ccal report --pdf` reads a name): a PDF is not written under another's.
_OTHER_FORMATS = {".html": "an HTML", ".htm": "an HTML", ".json": "a JSON", ".csv": "a CSV", ".txt": "a text",
                  ".toml": "a TOML", ".npy": "a NumPy"}


def check_pdf_path(path):
    """InputError for a path to_pdf() cannot or should not write: empty, a folder, or named for another format."""
    text = os.fsdecode(os.fspath(path)) if isinstance(path, (str, bytes, os.PathLike)) else None
    if text is None:
        raise TypeError(f"Report.to_pdf(): path: expected a file's path (str or os.PathLike), got "
                        f"{type(path).__name__}")
    if not text:
        raise _ccal.InputError("Report.to_pdf(): path: the path is empty; accepted: a file path, e.g. report.pdf")
    if os.path.isdir(text):
        raise _ccal.InputError(f"Report.to_pdf(): path: '{text}' is a folder; accepted: a file path, e.g. "
                               f"report.pdf")
    folder = os.path.dirname(os.path.abspath(text))
    if not os.path.isdir(folder):
        raise _ccal.InputError(f"Report.to_pdf(): path: cannot write '{text}': its folder '{os.path.dirname(text)}' "
                               f"does not exist; accepted: a file in an existing folder")
    other = _OTHER_FORMATS.get(os.path.splitext(text)[1].lower())
    if other:
        raise _ccal.InputError(f"Report.to_pdf(): path: '{text}' names {other} file, and to_pdf writes PDF; "
                               f"accepted: FILE.pdf")


def report_methods(cls):
    """Report.to_html(): the page of `ccal report`, its provenance naming the configuration's text and the
    Python call that made the report; Report.config: the configuration given (pickled by its origin)."""
    original_config = cls.config

    def config(self) -> "Config":
        """The configuration the report was made from [Config]."""
        return getattr(self, "_ccal_config", None) or original_config.fget(self)

    def to_html(self) -> "str":
        """The self-contained HTML page (as `ccal report -o report.html` writes it), with the configuration's
        text, its SHA-256 and the call that made the report in its provenance."""
        config = getattr(self, "_ccal_config", None)
        origin = getattr(config, "_ccal_origin", None) or ("unknown",)
        config_text = origin[1] if origin[0] == "text" else None
        keywords = getattr(self, "_ccal_keywords", {})
        call = ", ".join([config_call_text(config)] + [f"{k}={v!r}" for k, v in keywords.items()])
        return self._html(config_text, f"ccal.report({call})")

    def to_pdf(self, path: "str") -> "None":
        """The page printed to PDF (A4, the page count at the foot) as `ccal report --pdf FILE` prints it,
        through headless Chromium (Debian's chromium, or the program named by CCAL_CHROMIUM), written to path;
        an existing file is replaced only once the PDF is complete."""
        check_pdf_path(path)
        data = self._print_pdf(self.to_html())
        folder = os.path.dirname(os.path.abspath(path))
        fd, temporary = tempfile.mkstemp(prefix=".ccal-", suffix=".pdf", dir=folder)
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            # mkstemp's file is its owner's alone (0600); the PDF gets the mode any new file gets (the umask's).
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(temporary, 0o666 & ~umask)
            os.replace(temporary, path)
        except BaseException:
            if os.path.exists(temporary):
                os.remove(temporary)
            raise

    _named(cls, "to_html", to_html)
    _named(cls, "to_pdf", to_pdf)
    cls.config = property(config, None, None, config.__doc__)


def design_methods(cls):
    """Design.config: the configuration given (pickled by its origin); config_text(), which a Design unpickled
    by value has too."""
    original_config = cls.config

    def config(self) -> "Config":
        """The configuration the design was made from [Config]."""
        call = getattr(self, "_ccal_call", None)
        return call[1] if call else original_config.fget(self)

    def config_text(self, original: "str") -> "str":
        """The configuration text `original` with its [plan] replaced by the designed one (as --plan-out)."""
        return _ccal._config_with_plan(original, self.designed)

    _named(cls, "config_text", config_text)
    cls.config = property(config, None, None, config.__doc__)

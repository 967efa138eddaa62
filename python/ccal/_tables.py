"""The display-unit view of a result: a table of its main values in the units the command line shows, with a
unit column, taken from the result's JSON (which the command line prints in display units)."""

import html


def _pandas():
    try:
        import pandas
    except ImportError as e:
        raise ImportError("to_frame() needs pandas, which ccal does not require; install it (Debian: "
                          "apt-get install python3-pandas) or use .rows") from e
    return pandas


class Table:
    """Rows of values in display units (those of the command line), each with its unit where it has one.
    str() is an aligned text table, _repr_html_ an HTML table (Jupyter), rows a list of dicts, to_frame() a
    pandas DataFrame indexed by the first column's values (a coefficient, source, run, term or axis; pandas
    is optional)."""

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
        head = "".join(f"<th>{html.escape(c)}</th>" for c in self.columns)
        body = "".join("<tr>" + "".join(f"<td>{html.escape(self._cell(r[c]))}</td>" for c in self.columns) +
                       "</tr>" for r in self.rows)
        return (f"<table><caption>{html.escape(self.title)}</caption><thead><tr>{head}</tr></thead>"
                f"<tbody>{body}</tbody></table>")

    def to_frame(self) -> "Any":
        """The table as a pandas DataFrame, indexed by the first column's values (e.g. frame.loc["K3"]), which
        it keeps as a column (pandas is not a dependency of ccal: ImportError without it)."""
        pandas = _pandas()
        index = [r[self.columns[0]] for r in self.rows] if self.columns else None
        return pandas.DataFrame([[r[c] for c in self.columns] for r in self.rows], columns=self.columns,
                                index=index)


def _coefficient_rows(coefficients, fields):
    return [[name, c.get("unit", "")] + [c.get(f) for f in fields] for name, c in coefficients.items()]


def display_budget(r, j):
    rows = [[c["id"], c["unit"], c["standard_uncertainty"], c["expanded_uncertainty"]] for c in j["coefficients"]]
    return Table(f"budget of {j['config']} ({j['mode']}, k = {j['coverage_factor']:.3g}, "
                 f"p = {100 * j['coverage_probability']:.4g} %)",
                 ["coefficient", "unit", "standard_uncertainty", "expanded_uncertainty"], rows)


def display_budget_sources(r, j):
    """One row per source: its id, bound and unit (display units), and each coefficient's effect (in the
    coefficient's display unit) and share of its variance; then the rest of a GUM budget line (EA-4/02): the
    description, x_i and u(x_i) in the bound's unit, the divisor, the type, ν_i (inf) and each coefficient's c_i
    per that unit."""
    coefficients = [(c["id"], c["unit"]) for c in j["coefficients"]]
    columns = ["source", "bound", "unit", "distribution"]
    columns += [f"effect {k} [{unit}]" for k, unit in coefficients] + [f"share {k}" for k, _ in coefficients]
    columns += ["name", "estimate", "standard_uncertainty", "divisor", "type", "dof"]
    columns += [f"c {k} [{unit} per unit]" for k, unit in coefficients]
    rows = [[s["id"], s["bound"], s["unit"], s["distribution"]] + [s["effect"][k] for k, _ in coefficients] +
            [s["share"][k] for k, _ in coefficients] +
            [s["name"], s["estimate"], s["standard_uncertainty"], s["divisor"], s["type"],
             float("inf") if s["dof"] is None else s["dof"]] +
            [s["sensitivity"][k] for k, _ in coefficients] for s in j["sources"]]
    return Table(f"budget of {j['config']} per source ({j['mode']}; effect: sensitivity × u, signed; share: of "
                 "the coefficient's variance)", columns, rows)


def display_montecarlo(r, j):
    rows = [[name, c["unit"], c["mean"], c["std_dev"], c["symmetric_interval"][0], c["symmetric_interval"][1],
             c["lpu"]["expanded_uncertainty"], c["lpu"]["validated"]] for name, c in j["coefficients"].items()]
    return Table(f"Monte Carlo of {j['config']} ({j['trials']} trials, p = {j['coverage_probability']:g})",
                 ["coefficient", "unit", "mean", "std_dev", "low", "high", "lpu_expanded", "validated"], rows)


def display_allocation(r, j):
    rows = [[name, c["unit"], c.get("target"), c["configured_expanded"], c["allocated_expanded"],
             c.get("verdict", "")] for name, c in j["coefficients"].items()]
    return Table(f"allocation for {j['config']} (p = {j['coverage_probability']:g})",
                 ["coefficient", "unit", "target", "configured_expanded", "allocated_expanded", "verdict"], rows)


def display_identification(r, j):
    """The identified coefficients in the table's units, with their standard errors."""
    rows = _coefficient_rows(j["identification"]["coefficients"], ["value", "std_error"])
    return Table(f"{j['command']} of {j['config']}: identified coefficients",
                 ["coefficient", "unit", "value", "std_error"], rows)


def display_identify(r, j):
    rows = _coefficient_rows(j["coefficients"], ["value", "std_error"])
    return Table(f"identify of {j['file']}: identified coefficients ({j['rows']} rows)",
                 ["coefficient", "unit", "value", "std_error"], rows)


def display_force(r, j):
    rows = [[axis, j["specific_force_g"][axis], j["angular_rate_deg_per_s"][axis]] for axis in ("IA", "PA", "OA")]
    return Table(f"force of {j['config']}: run {j['run']['name']} at {j['run']['time_s']:g} s ({j['mode']})",
                 ["axis", "specific_force [g]", "angular_rate [deg/s]"], rows)


# The display table of each verb's result class.
def per_instrument(build):
    """`build` of one instrument's JSON, for a result of several instruments too (its JSON's `instruments`, each
    with its id and the whole result's other keys): each instrument's rows in turn, after an instrument column."""

    def table(r, j):
        each = j.get("instruments")
        if not (isinstance(each, list) and each and isinstance(each[0], dict) and "id" in each[0]):
            return build(r, j)
        whole = {k: v for k, v in j.items() if k != "instruments"}
        tables = [build(r, {**whole, **one}) for one in each]
        rows = [[one["id"]] + [row[c] for c in t.columns] for one, t in zip(each, tables) for row in t.rows]
        return Table(f"{tables[0].title}; instruments {', '.join(one['id'] for one in each)}",
                     ["instrument"] + tables[0].columns, rows)

    table.__doc__ = build.__doc__
    return table


DISPLAY = {name: per_instrument(build) for name, build in (
    ("Budget", display_budget), ("MonteCarlo", display_montecarlo), ("Allocation", display_allocation),
    ("Simulation", display_identification), ("Reduction", display_identification), ("SensedInput", display_force),
    ("Identification", display_identify))}


def display_config(c):
    rows = [[r.name, r.g_level, r.duration, r.mode, r.mounting] for r in c.runs]
    return Table(f"configuration {c.source}: {len(c.runs)} runs, {len(c.tolerances)} tolerances",
                 ["run", "g_level [g]", "duration [s]", "platform", "mounting"], rows)


def display_fit(f):
    """The terms in display units (value × display_scale; a fit of plain arrays: its data's units, unit '')."""
    rows = [[n, u, v * k, s * k] for n, u, k, v, s in zip(f.names, f.units, f.display_scale, f.value, f.std_error)]
    return Table(f"fit: {len(f.names)} terms, {f.dof} degrees of freedom",
                 ["term", "unit", "value", "std_error"], rows)

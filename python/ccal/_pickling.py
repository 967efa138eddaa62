"""Pickling. A Config is pickled as its origin (the TOML text it was read from, or the bundled example) and
the derivations applied to it; a verb's result as the call that made it (its Config, its options, and for
`reduce` the contents of its logs): unpickling computes it again, which gives the same bits (every
computation is deterministic, the Monte Carlo for any thread count), and checks that the JSON is the one
pickled, so that a result from another version of ccal is refused rather than silently different."""

import json
import os
import re
import tempfile
import tomllib

from . import _ccal

_VOLATILE = {"wall_time_s", "threads", "trials_per_s"}  # what differs between two runs of the same call


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
                        "bundled_example or a with_… method of one")
    return restore_config, (origin, self._ccal_edits)


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
    remember_call(result, verb, config, kwargs, logs, paths)
    if _normalised(json.loads(result.to_json())) != _normalised(json.loads(pickled_json)):
        raise ValueError(f"ccal: a pickled {type(result).__name__} computed again gives other numbers (pickled "
                         f"by another version of ccal?); this is ccal {_ccal.__version__}")
    if pickled_text is not None:  # a reduction's text report names its logs as given, aligned to their names
        result._ccal_text = pickled_text
    return result


def remember_call(result, verb, config, kwargs, logs, paths):
    result._ccal_call = (verb, config, {k: v for k, v in kwargs.items() if k not in ("logs", "progress")}, logs)
    result._ccal_paths = paths  # temporary log copies of an unpickled reduction → the original paths


def result_reduce(self):
    verb, config, kwargs, logs = self._ccal_call
    if verb == "reduce" and logs is None:
        raise TypeError(f"this ccal.{type(self).__name__} cannot be pickled: its logs could not be read again "
                        "when it was made")
    return restore_result, (verb, config, kwargs, logs, self.to_json(), None if logs is None else str(self))


def original_paths(text, paths, quote):
    """The JSON of an unpickled reduction, whose logs were read from temporary copies, with the original paths."""
    for temporary, original in paths.items():
        text = text.replace(quote(temporary), quote(original))
    return text


def read_folder(folder):
    """{"folder": as given, "files": [(name, bytes)]}: a folder's manifest.toml and the logs its [runs] name
    (inside the folder, as the manifest requires), or None when one cannot be read."""
    try:
        with open(os.path.join(folder, "manifest.toml"), "rb") as f:
            manifest = f.read()
        names = [n for n in tomllib.loads(manifest.decode("utf-8")).get("runs", {}).values() if isinstance(n, str)]
        files = [("manifest.toml", manifest)]
        for name in names:
            with open(os.path.join(folder, name), "rb") as f:
                files.append((name, f.read()))
    except (OSError, TypeError, ValueError, AttributeError):
        return None
    return {"folder": os.fspath(folder), "files": files}


def read_logs(logs):
    """[(run, path, bytes)] of reduce()'s logs, the folder's files (read_folder) for a folder, or None when one
    cannot be read (reduce itself reports it)."""
    contents = []
    if isinstance(logs, (str, os.PathLike)):
        return read_folder(logs)
    if not isinstance(logs, dict):
        return None
    for run, path in logs.items():
        try:
            with open(path, "rb") as f:
                contents.append((run, path, f.read()))
        except (OSError, TypeError):
            return None
    return contents

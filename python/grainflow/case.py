"""Cases: a case file (or text) plus the keys set on it, validated as ``grainflow run --set`` does."""
import math
import os
import re
import tomllib

from . import _grainflow
from .errors import InputError

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_value(value):
    """A Python value as TOML: numbers, booleans, strings, lists and dicts (inline tables)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value) or math.isinf(value):
            return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(value, dict):
        parts = []
        for k, v in value.items():
            name = k if _BARE_KEY.match(k) else toml_value(str(k))
            parts.append(f"{name} = {toml_value(v)}")
        return "{ " + ", ".join(parts) + " }"
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return toml_value(value.tolist())
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"no TOML form for a value of type {type(value).__name__}")


def _lookup(table, key):
    node = table
    for part in key.split("."):
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                raise KeyError(key)
            node = node[int(part)]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            raise KeyError(key)
    return node


class Case:
    """A validated case. Build it with :meth:`from_file` or :meth:`from_string`.

    ``case["contact.friction"]`` reads a key as the run uses it (defaults filled in, every
    assignment applied: the values of ``resolved_case.toml``); ``case["contact.friction"] = 0.3``
    sets one, checked at once exactly as ``grainflow run --set`` checks it (a bad key or value
    raises :class:`InputError` and leaves the case as it was).
    """

    def __init__(self, core):
        self._core = core
        self._resolved = None

    @classmethod
    def from_file(cls, path, set=None):
        """The case file at ``path`` with the assignments in ``set`` ({dotted key: value})."""
        path = os.fspath(path)
        text = _grainflow.CaseCore.read_file(path)
        return cls(_grainflow.CaseCore(text, path, _assignments(set)))

    @classmethod
    def from_string(cls, text, set=None, label="<string>"):
        """A case from its TOML text; relative file names in it are read from the current folder
        (or from ``label``'s folder when ``label`` is a path)."""
        return cls(_grainflow.CaseCore(text, label, _assignments(set)))

    def __getitem__(self, key):
        if self._resolved is None:
            self._resolved = tomllib.loads(self._core.resolved_toml())
        try:
            return _lookup(self._resolved, key)
        except KeyError:
            raise KeyError(f"{self._core.label}: no key '{key}' in the case as run") from None

    def __setitem__(self, key, value):
        self._core = _grainflow.CaseCore(self._core.text, self._core.label,
                                         list(self._core.overrides) + [f"{key}={toml_value(value)}"])
        self._resolved = None

    def with_values(self, values):
        """A copy with each {dotted key: value} of ``values`` set (this case unchanged)."""
        return Case(_grainflow.CaseCore(self._core.text, self._core.label,
                                        list(self._core.overrides) + _assignments(values)))

    def copy(self):
        return Case(self._core)

    @property
    def path(self):
        """Where the case came from: its file, or the label of its text."""
        return self._core.label

    @property
    def engine(self):
        return self._core.engine

    @property
    def dimension(self):
        return self._core.dimension

    @property
    def overrides(self):
        """The assignments made to the case, in order, as ``--set KEY=VALUE`` would give them."""
        return list(self._core.overrides)

    def to_toml(self):
        """The case as run, every default filled in (``resolved_case.toml``)."""
        return self._core.resolved_toml()

    def check(self):
        """What ``grainflow check`` prints, as a dict: ``{"case": path, "valid": True, label: text}``
        with one entry per line of the report (values as printed, units included)."""
        report = {"case": self._core.label, "valid": True}
        for line in self._core.check_text().splitlines():
            if not line.startswith("  "):
                continue
            parts = re.split(r"\s{2,}", line.strip(), maxsplit=1)
            label = parts[0]
            value = parts[1] if len(parts) > 1 else ""
            while label in report:  # a label printed twice keeps both
                label += "'"
            report[label] = value
        return report

    def __repr__(self):
        return f"<grainflow.Case {self._core.label!r} ({self.engine}, {self.dimension}D, {len(self._core.overrides)} set)>"


def _assignments(values):
    if not values:
        return []
    if isinstance(values, dict):
        return [f"{k}={toml_value(v)}" for k, v in values.items()]
    raise TypeError("set= takes a dict {dotted key: value}")


__all__ = ["Case", "InputError", "toml_value"]

"""particula.Case: a case as Python data, with the keys of a case file.

    case = particula.Case({"name": "pile", "domain": {"min": [0, 0], "max": [0.02, 0.02]},
                           "resolution": {"d0": 2e-4}, "fluid": {"nu": 1e-6, "gravity": [0, -9.81]},
                           "time": {"end": 0.5}})
    case.add_body(shape="circle", radius=5e-4, center=[0.01, 0.015], density=1500)
    case["fluid.rho0"] = 1000                 # dotted keys, as --set takes them ("body.0.density")
    case.check()                              # CaseError (a ValueError) naming the key, as the CLI
    print(case.to_toml())                     # the case file; Case.from_toml(text) reads it back
    particula.run_case(case, "runs/pile")     # or particula.Simulation(case)

Bodies and walls are the lists `case.bodies` and `case.walls` (the [[body]] and [[wall]] tables),
changed in place or with add_body / remove_body / add_wall / remove_wall. A Case holds what one
writes in a file: keys left out take their defaults when the case is checked or run
(`case.resolved()` gives every key). Line numbers in a CaseError of a Case refer to
`case.to_toml()`.
"""
import copy
import json
import numbers
import os
import re
import tomllib

from . import _core
from .overrides import override_list, toml_scalar

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k):
    return k if _BARE_KEY.match(k) else json.dumps(k)


def _value(v, path):
    """A Python value as TOML text (numbers, booleans, strings, lists and inline tables)."""
    if hasattr(v, "tolist") and not isinstance(v, (str, bytes)):  # NumPy scalars and arrays
        v = v.tolist()
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    scalar = toml_scalar(v)
    if scalar is not None:
        return scalar
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x, "%s[%d]" % (path, i)) for i, x in enumerate(v)) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join("%s = %s" % (_key(str(k)), _value(x, path + "." + str(k))) for k, x in v.items()) + "}"
    raise TypeError("case key '%s': %r is not a TOML value (a str, bool, number, list or dict)" % (path, v))


def _is_table_array(v):
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _emit(table, path, out):
    """Appends `table`'s keys to out: its values first, then its tables and arrays of tables."""
    for k, v in table.items():
        if not isinstance(v, dict) and not _is_table_array(v):
            out.append("%s = %s" % (_key(str(k)), _value(v, ".".join(path + [str(k)]))))
    for k, v in table.items():
        sub = path + [str(k)]
        if isinstance(v, dict):
            out.append("")
            out.append("[%s]" % ".".join(_key(p) for p in sub))
            _emit(v, sub, out)
        elif _is_table_array(v):
            for element in v:
                out.append("")
                out.append("[[%s]]" % ".".join(_key(p) for p in sub))
                _emit(element, sub, out)


def to_toml(data):
    """A case dict as the text of a case file."""
    if not isinstance(data, dict):
        raise TypeError("a case is a dict of the case file's keys, not %s" % type(data).__name__)
    out = []
    _emit(data, [], out)
    return "\n".join(out).lstrip("\n") + "\n"


def _split(key):
    if not isinstance(key, str) or not key:
        raise TypeError("a case key is a dotted str such as 'fluid.nu' or 'body.0.density', not %r" % (key,))
    return key.split(".")


class Case:
    """A case file's keys as Python data (see the module's docstring).

    Case(data) takes a dict with the TOML's keys (bodies and walls as lists of dicts under "body"
    and "wall"); it is copied. Case.from_file(path) and Case.from_toml(text) read a case file.
    """

    SOURCE = "<particula.Case>"

    def __init__(self, data=None):
        if data is None:
            data = {}
        if isinstance(data, Case):
            data = data.data
        if not isinstance(data, dict):
            raise TypeError("Case(data): data is a dict of the case file's keys, not %s" % type(data).__name__)
        self.data = copy.deepcopy(data)
        to_toml(self.data)  # a value TOML cannot hold raises TypeError now, naming its key

    @classmethod
    def from_toml(cls, text):
        """The case of a case file's text. A TOML syntax error raises CaseError."""
        try:
            return cls(tomllib.loads(text))
        except tomllib.TOMLDecodeError as e:
            from .errors import CaseError
            raise CaseError("%s: %s" % (cls.SOURCE, e), file=cls.SOURCE, message=str(e)) from None

    @classmethod
    def from_file(cls, path):
        """The case of the case file at `path`, as written (defaults are not filled in)."""
        with open(os.fspath(path), "rb") as f:
            text = f.read().decode("utf-8")
        return cls.from_toml(text)

    def to_toml(self):
        """The text of a case file with these keys."""
        return to_toml(self.data)

    def resolved(self, overrides=None):
        """The case as particula resolves it (every default filled in, overrides applied) as a
        dict; raises CaseError (a ValueError) with the CLI's message, naming the key."""
        return tomllib.loads(_core.resolved_case_text(self.to_toml(), self.SOURCE, override_list(overrides)))

    def check(self, overrides=None):
        """Raises CaseError when particula would refuse the case; returns the case."""
        self.resolved(overrides)
        return self

    @property
    def name(self):
        return self.data.get("name")

    # ---- dotted keys, as --set takes them

    def _parent(self, parts, create):
        node = self.data
        for i, p in enumerate(parts[:-1]):
            if isinstance(node, list):
                try:
                    node = node[int(p)]
                except (ValueError, IndexError):
                    raise KeyError(".".join(parts[:i + 1])) from None
                continue
            if p not in node:
                if not create:
                    raise KeyError(".".join(parts[:i + 1]))
                node[p] = {}
            node = node[p]
        return node

    def __getitem__(self, key):
        parts = _split(key)
        node = self._parent(parts, False)
        try:
            return node[int(parts[-1])] if isinstance(node, list) else node[parts[-1]]
        except (ValueError, IndexError, KeyError):
            raise KeyError(key) from None

    def __setitem__(self, key, value):
        parts = _split(key)
        _value(value, key)  # TypeError for a value TOML cannot hold
        node = self._parent(parts, True)
        if isinstance(node, list):
            node[int(parts[-1])] = copy.deepcopy(value)
        else:
            node[parts[-1]] = copy.deepcopy(value)

    def __delitem__(self, key):
        parts = _split(key)
        node = self._parent(parts, False)
        try:
            del node[int(parts[-1]) if isinstance(node, list) else parts[-1]]
        except (ValueError, IndexError, KeyError):
            raise KeyError(key) from None

    def __contains__(self, key):
        try:
            self[key]
            return True
        except KeyError:
            return False

    # ---- bodies and walls

    @property
    def bodies(self):
        """The [[body]] tables, a list of dicts (changed in place)."""
        return self.data.setdefault("body", [])

    @property
    def walls(self):
        """The [[wall]] tables, a list of dicts (changed in place)."""
        return self.data.setdefault("wall", [])

    @staticmethod
    def _add(items, kind, table, keys):
        entry = dict(table or {})
        entry.update(keys)
        _value(entry, kind)
        items.append(copy.deepcopy(entry))
        return len(items) - 1

    @staticmethod
    def _index(items, kind, which):
        if isinstance(which, bool) or not isinstance(which, (numbers.Integral, str)):
            raise TypeError("%s: an index or a name, not %r" % (kind, which))
        if isinstance(which, str):
            names = [x.get("name") for x in items]
            if which not in names:
                raise KeyError("no %s named %r (the names are %s)" % (kind, which, [n for n in names if n]))
            return names.index(which)
        if not -len(items) <= which < len(items):
            raise IndexError("%s index %d: the case has %d" % (kind, which, len(items)))
        return int(which) % len(items)

    def add_body(self, body=None, **keys):
        """Appends a [[body]] table (a dict, and/or its keys as keyword arguments, e.g.
        shape="circle", radius=5e-4, center=[x, y], density=1500); returns its index."""
        return self._add(self.bodies, "body", body, keys)

    def remove_body(self, which):
        """Removes the body of index or name `which`; returns its table."""
        return self.bodies.pop(self._index(self.bodies, "body", which))

    def add_wall(self, wall=None, **keys):
        """Appends a [[wall]] table; returns its index."""
        return self._add(self.walls, "wall", wall, keys)

    def remove_wall(self, which):
        """Removes the wall of index or name `which`; returns its table."""
        return self.walls.pop(self._index(self.walls, "wall", which))

    def copy(self):
        return Case(self.data)

    def __eq__(self, other):
        return isinstance(other, Case) and self.data == other.data

    def __repr__(self):
        return "<particula.Case %r: %d bodies, %d walls>" % (self.name, len(self.data.get("body", [])),
                                                            len(self.data.get("wall", [])))


def case_source(case_or_file):
    """(file name for messages, TOML text or None) of a Case or a case file path."""
    if isinstance(case_or_file, Case):
        return Case.SOURCE, case_or_file.to_toml()
    if isinstance(case_or_file, dict):
        return Case.SOURCE, Case(case_or_file).to_toml()
    return os.fspath(case_or_file), None

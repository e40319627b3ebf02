"""gonio.Stack: a layer stack in Python, from a TOML file, a TOML string or a dict of the vocabulary's keys
(stacks/README.md), changed in place (`stack.layers[0].roughness = 0.2`) and given to gonio.simulate as it is.

The stack is parsed and checked by gonio itself (gonio._core, the parser `gonio check` uses), so every key, range and
refusal is the command line's: a bad value raises gonio.StackError with the file and line, or, for a stack built
from a dict, the key (`layers[1].roughness`) and the reason.
"""
import copy
import json
import math
import re

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


class Layer(dict):
    """One [[layer]] of a stack: its keys as a dict, and as attributes (layer.roughness)."""

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(f"the layer has no key {key!r} (its keys: {', '.join(self) or 'none'})") from None

    def __setattr__(self, key, value):
        self[key] = value

    def __delattr__(self, key):
        del self[key]


def _toml_key(k):
    return k if _BARE_KEY.match(k) else json.dumps(k)


def _toml_value(v, where):
    """A value as TOML: numbers, strings, booleans, lists (numpy arrays too) and inline tables."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if hasattr(v, "tolist") and not isinstance(v, (str, bytes)):   # a numpy array or scalar
        v = v.tolist()
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)   # a TOML basic string: JSON's escapes are TOML's
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, where) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_toml_key(str(k))} = {_toml_value(x, where)}" for k, x in v.items()) + " }"
    raise TypeError(f"{where}: a {type(v).__name__} is not a stack value (numbers, strings, lists, tables)")


class Stack:
    """A layer stack: its own keys (name, description, exterior_ior, ...) and its layers, top to bottom.

        stack = gonio.Stack.from_toml("stacks/plastic.toml")
        stack = gonio.Stack({"name": "glaze", "layer": [{"type": "dielectric", "ior": 1.5, "roughness": 0.1},
                                                        {"type": "lambertian", "albedo": [0.8, 0.2, 0.1]}]})
        stack.layers[0].roughness = 0.3      # a sweep is a loop
        print(stack.check())                  # gonio check's description (raises gonio.StackError)
    """

    def __init__(self, keys=None, layers=None):
        keys = dict(keys or {})
        given = keys.pop("layer", None)
        if given is None:
            given = keys.pop("layers", None)
        if layers is not None:
            given = layers
        object.__setattr__(self, "keys", keys)
        object.__setattr__(self, "layers", [Layer(y) for y in (given or [])])
        object.__setattr__(self, "_source", None)   # (text, path, the keys and layers it parsed to)

    @staticmethod
    def from_string(text, path="<string>"):
        """A stack from its TOML text; `path` names it in messages and outputs."""
        import tomllib
        from ._core_loader import checked_text, core
        checked_text(text, path, None, core().check_stack)   # refused as the command line refuses it
        s = Stack(tomllib.loads(text))
        object.__setattr__(s, "_source", (text, path, s._state()))
        return s

    @staticmethod
    def from_toml(path):
        """A stack file (stacks/*.toml), read as `gonio simulate FILE` reads it: its text is what the outputs
        record, and its lines what a refusal names."""
        with open(path, encoding="utf-8") as fh:
            return Stack.from_string(fh.read(), str(path))

    def __getattr__(self, key):
        try:
            return self.keys[key]
        except KeyError:
            raise AttributeError(f"the stack has no key {key!r}") from None

    def __setattr__(self, key, value):
        if key in ("keys", "layers"):
            object.__setattr__(self, key, [Layer(y) for y in value] if key == "layers" else dict(value))
        else:
            self.keys[key] = value

    def copy(self):
        return copy.deepcopy(self)

    def _state(self):
        return copy.deepcopy((self.keys, [dict(y) for y in self.layers]))

    def to_dict(self):
        """The stack as a dict of the vocabulary's keys, its layers under "layer"."""
        d = copy.deepcopy(self.keys)
        d["layer"] = [dict(y) for y in self.layers]
        return d

    def toml(self):
        """(text, path, where): the TOML gonio parses. A stack read from a file and not changed since is the file's
        own text (its outputs then record it byte for byte, as the command line's do); else the text is written
        from the keys, `where` mapping each of its lines to the key it holds."""
        if self._source is not None and self._source[2] == self._state():
            return self._source[0], self._source[1], None
        lines, where = [], {}
        for k, v in self.keys.items():
            lines.append(f"{_toml_key(str(k))} = {_toml_value(v, k)}")
            where[len(lines)] = str(k)
        for i, layer in enumerate(self.layers):
            lines += ["", "[[layer]]"]
            where[len(lines)] = f"layers[{i}]"
            for k, v in layer.items():
                lines.append(f"{_toml_key(str(k))} = {_toml_value(v, f'layers[{i}].{k}')}")
                where[len(lines)] = f"layers[{i}].{k}"
        path = self._source[1] + " (changed)" if self._source is not None else "<dict>"
        return "\n".join(lines) + "\n", path, where

    def check(self):
        """gonio check's description of the stack; raises gonio.StackError for a stack gonio refuses."""
        from ._core_loader import core, checked
        return checked(self, lambda text, path: core().check_stack(text, path))

    def __repr__(self):
        return f"gonio.Stack({self.to_dict()!r})"

"""A data-only file format for in-memory state: JSON for the structure, numpy arrays
beside it, both in one ``.npz`` archive read with ``allow_pickle=False``.

Maps are shared between robots and people, so nothing in a map directory may be able
to run code when it is read (``pickle`` can). :func:`dump_state` writes plain values
(``None``, booleans, numbers, strings), lists, tuples, sets, deques, dicts, numpy arrays
and scalars, pydantic models, and instances of the classes it is given; :func:`load_state`
rebuilds them, creating objects only of those classes, by name, without calling their
constructors. Anything else in a file is an error (:class:`StateFormatError`).
"""

from __future__ import annotations

import io
import json
import os
import zipfile
from collections import deque
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import BaseModel, ValidationError

# The archive member that holds the JSON structure.
_STRUCTURE = "__structure__"
_TAG = "$"


class StateFormatError(ValueError):
    """A state file that is not what :func:`dump_state` writes, or names a class that
    is not allowed."""


class _Encoder:
    def __init__(self, classes: dict[str, type]) -> None:
        self.names = {cls: name for name, cls in classes.items()}
        self.arrays: dict[str, np.ndarray] = {}

    def encode(self, value: Any) -> Any:
        if value is None or isinstance(value, bool | str):
            return value
        if isinstance(value, int | float):
            return self._number(value)
        if isinstance(value, np.generic):
            return self._number(value.item())
        if isinstance(value, np.ndarray):
            if value.dtype == object:
                raise TypeError("arrays of Python objects cannot be stored as data")
            key = f"a{len(self.arrays)}"
            self.arrays[key] = value
            return {_TAG: "array", "key": key}
        if isinstance(value, list):
            return [self.encode(v) for v in value]
        if isinstance(value, tuple):
            return {_TAG: "tuple", "items": [self.encode(v) for v in value]}
        if isinstance(value, set | frozenset):
            return {_TAG: "set", "items": [self.encode(v) for v in value]}
        if isinstance(value, deque):
            items = [self.encode(v) for v in value]
            return {_TAG: "deque", "items": items, "maxlen": value.maxlen}
        if isinstance(value, dict):
            pairs = [[self.encode(k), self.encode(v)] for k, v in value.items()]
            return {_TAG: "dict", "items": pairs}
        name = self.names.get(type(value))
        if name is None:
            raise TypeError(f"{type(value).__qualname__} is not among the classes to store")
        if isinstance(value, BaseModel):
            return {_TAG: "model", "class": name, "fields": self.encode(value.model_dump())}
        return {_TAG: "object", "class": name, "fields": self.encode(dict(vars(value)))}

    @staticmethod
    def _number(value: int | float) -> Any:
        if isinstance(value, float) and not np.isfinite(value):
            return {_TAG: "float", "repr": repr(value)}  # JSON has no inf / nan
        return value


class _Decoder:
    def __init__(self, classes: dict[str, type], arrays: dict[str, np.ndarray]) -> None:
        self.classes = classes
        self.arrays = arrays

    def decode(self, node: Any) -> Any:
        if node is None or isinstance(node, bool | int | float | str):
            return node
        if isinstance(node, list):
            return [self.decode(v) for v in node]
        if not isinstance(node, dict) or not isinstance(node.get(_TAG), str):
            raise StateFormatError(f"unexpected element {str(node)[:60]!r}")
        tag = node[_TAG]
        if tag == "array":
            key = node.get("key")
            if key not in self.arrays:
                raise StateFormatError(f"array {key!r} is missing from the file")
            return self.arrays[key]
        if tag == "float":
            if node.get("repr") not in ("inf", "-inf", "nan"):
                raise StateFormatError(f"bad number {node.get('repr')!r}")
            return float(node["repr"])
        if tag in ("tuple", "set", "deque"):
            items = [self.decode(v) for v in self._list(node, "items")]
            if tag == "tuple":
                return tuple(items)
            if tag == "set":
                return set(items)
            maxlen = node.get("maxlen")
            if maxlen is not None and (not isinstance(maxlen, int) or maxlen < 0):
                raise StateFormatError(f"bad deque length {maxlen!r}")
            return deque(items, maxlen=maxlen)
        if tag == "dict":
            out = {}
            for pair in self._list(node, "items"):
                if not isinstance(pair, list) or len(pair) != 2:
                    raise StateFormatError("a dict entry must be a [key, value] pair")
                out[self.decode(pair[0])] = self.decode(pair[1])
            return out
        if tag in ("model", "object"):
            return self._instance(node, tag)
        raise StateFormatError(f"unknown element type {tag!r}")

    @staticmethod
    def _list(node: dict[str, Any], key: str) -> list[Any]:
        items = node.get(key)
        if not isinstance(items, list):
            raise StateFormatError(f"'{key}' must be a list")
        return items

    def _instance(self, node: dict[str, Any], tag: str) -> Any:
        name = node.get("class")
        cls = self.classes.get(name) if isinstance(name, str) else None
        if cls is None:
            raise StateFormatError(f"class {name!r} is not allowed in this file")
        fields = self.decode(node.get("fields"))
        if not isinstance(fields, dict) or not all(isinstance(k, str) for k in fields):
            raise StateFormatError(f"the fields of {name} must be a table of names")
        if tag == "model":
            if not issubclass(cls, BaseModel):
                raise StateFormatError(f"{name} is not a settings model")
            try:
                return cls.model_validate(fields)
            except ValidationError as exc:
                raise StateFormatError(f"{name}: {exc.errors()[0].get('msg', exc)}") from exc
        obj: Any = object.__new__(cls)
        vars(obj).update(fields)
        return obj


def class_table(classes: Iterable[type]) -> dict[str, type]:
    """Class name → class, for :func:`dump_state` / :func:`load_state`; names must be
    unique."""
    out: dict[str, type] = {}
    for cls in classes:
        if cls.__name__ in out and out[cls.__name__] is not cls:
            raise ValueError(f"two classes are named {cls.__name__}")
        out[cls.__name__] = cls
    return out


def dump_state(value: Any, path: str | Path, classes: dict[str, type]) -> Path:
    """Write ``value`` to ``path`` atomically (write, fsync, rename); :class:`TypeError`
    names a value of a type that cannot be stored."""
    enc = _Encoder(classes)
    structure = json.dumps(enc.encode(value), allow_nan=False, separators=(",", ":"))
    members = dict(enc.arrays)
    members[_STRUCTURE] = np.frombuffer(structure.encode("utf-8"), dtype=np.uint8)
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as fh:
        with zipfile.ZipFile(fh, "w", compression=zipfile.ZIP_STORED) as archive:
            for name, array in members.items():  # the layout np.savez writes
                with archive.open(f"{name}.npy", "w", force_zip64=True) as out:
                    np.lib.format.write_array(out, np.asanyarray(array), allow_pickle=False)
        fh.flush()
        os.fsync(fh.fileno())
    tmp.replace(path)
    return path


def load_state(path: str | Path, classes: dict[str, type]) -> Any:
    """Read a file :func:`dump_state` wrote, creating objects only of ``classes``;
    :class:`StateFormatError` when it is anything else (damaged, or another format)."""
    try:
        data = Path(path).read_bytes()
        with np.load(io.BytesIO(data), allow_pickle=False) as archive:
            arrays = {k: archive[k] for k in archive.files}
    except (OSError, ValueError, EOFError, KeyError, zipfile.BadZipFile) as exc:
        raise StateFormatError(f"{path} is not a readable state archive ({exc})") from exc
    raw = arrays.pop(_STRUCTURE, None)
    if raw is None or raw.dtype != np.uint8 or raw.ndim != 1:
        raise StateFormatError(f"{path} has no structure member")
    try:
        structure = json.loads(raw.tobytes().decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        raise StateFormatError(f"{path}: the structure is not JSON ({exc})") from exc
    try:
        return _Decoder(classes, arrays).decode(structure)
    except (TypeError, RecursionError) as exc:  # an unhashable key, nesting too deep
        raise StateFormatError(f"{path}: {exc}") from exc

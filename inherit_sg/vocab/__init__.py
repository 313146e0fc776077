"""Vocabularies as versioned data files.

Everything the system knows about words lives in TOML files under
``inherit_sg/vocab/data/`` rather than in Python literals: the request lexicon
(``lexicon.toml``), object kinds with synonyms, general terms and parts
(``objects.toml``), functions and problem statements (``functions.toml``), room types with
aliases and evidence (``rooms.toml``), functional-area rules (``areas.toml``) and colour
names (``colours.toml``). ``docs/vocabulary.md`` documents each file.

Each file carries ``version`` (an integer, raised on every change of meaning). The
vocabulary as a whole is identified by :func:`vocabulary_info`: the versions of all files
and a digest of their bytes. A map records it, with the label space it was built with, in
``map.json`` (as Spark-DSG keeps its label space with the graph), so a map built with
other words can be recognised.

Tables are parsed once per process (:func:`load_table` is cached); callers must treat
them as read-only.
"""

from __future__ import annotations

import hashlib
import tomllib
from functools import cache, lru_cache
from pathlib import Path
from typing import Any

from inherit_sg.errors import ConfigError

DATA_DIR = Path(__file__).resolve().parent / "data"
# Files of the vocabulary, in the order their digest is taken.
TABLES = ("lexicon", "objects", "functions", "rooms", "areas", "colours")


class VocabularyError(ConfigError):
    """A vocabulary file is missing or malformed."""


def table_path(name: str) -> Path:
    """Path of the vocabulary file ``name`` (``"objects"`` → ``…/data/objects.toml``)."""
    if name not in TABLES:
        raise VocabularyError(f"unknown vocabulary table {name!r}; known: {', '.join(TABLES)}")
    return DATA_DIR / f"{name}.toml"


@cache
def load_table(name: str) -> dict[str, Any]:
    """The parsed TOML of vocabulary file ``name``; raises :class:`VocabularyError`
    naming the file when it is missing, unreadable or lacks an integer ``version``."""
    path = table_path(name)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise VocabularyError(f"vocabulary file {path} is missing") from None
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise VocabularyError(f"vocabulary file {path} cannot be read: {exc}") from None
    version = data.get("version")
    if not isinstance(version, int) or isinstance(version, bool):
        raise VocabularyError(f"vocabulary file {path} needs an integer 'version'")
    return data


def require(data: dict[str, Any], key: str, kind: type | tuple[type, ...], where: str) -> Any:
    """``data[key]`` checked to be of ``kind``; :class:`VocabularyError` naming ``where``."""
    if key not in data:
        raise VocabularyError(f"{where}: missing {key!r}")
    value = data[key]
    if not isinstance(value, kind):
        raise VocabularyError(f"{where}: {key!r} has the wrong type ({type(value).__name__})")
    return value


def string_list(data: dict[str, Any], key: str, where: str) -> tuple[str, ...]:
    """``data[key]`` (absent = empty) as a tuple of lower-case strings."""
    value = data.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise VocabularyError(f"{where}: {key!r} must be a list of strings")
    return tuple(v.strip().lower() for v in value)


@lru_cache(maxsize=1)
def vocabulary_info() -> dict[str, Any]:
    """``{"versions": {file: version}, "digest": sha256 of the files (16 hex)}`` of the
    vocabulary files present."""
    digest = hashlib.sha256()
    versions: dict[str, int] = {}
    for name in TABLES:
        path = table_path(name)
        if not path.is_file():
            continue
        digest.update(name.encode() + b"\0" + path.read_bytes())
        versions[name] = int(load_table(name)["version"])
    return {"versions": versions, "digest": digest.hexdigest()[:16]}

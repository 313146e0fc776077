"""Object kinds (``objects.toml``): canonical labels and their synonyms, kind-of
relations, general words ("seat", "storage"), parts, and the default detector prompts.

A map stores a canonical label per object (:func:`canonical_label` brings dataset and
detector names to it: "Bedside Table", "sofa_chair"); a request word means one or more
kinds (:func:`labels_for`: "couch" → the sofa, "seat" → every kind of seat), and a
kind may be a kind of another (:func:`is_kind_of`: an office chair is a chair, so a
request for a chair may be met by one). Lookups are case-insensitive, read ``_``, ``-`` and
``#`` as spaces, and try a phrase as written first and then with its last word
lemmatised (spaCy lemmatises some singular words wrongly on their own, "glass" →
"glas", so the written form must win).

The file is parsed and checked once per process; :func:`clear_caches` forgets it.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from inherit_sg.nlp import lemma_phrase
from inherit_sg.vocab import VocabularyError, load_table, require, string_list

_FILE = "objects.toml"
_TOP_KEYS = frozenset({"version", "kinds", "general"})
_KIND_KEYS = frozenset({"synonyms", "is_a", "parts", "detect", "placement"})
# Where in its room a kind typically stands (a kitchen island in the middle).
_PLACEMENTS = frozenset({"wall", "corner", "centre"})
_GENERAL_KEYS = frozenset({"words", "is_a", "typical"})
# Separators that dataset labels use for spaces ("sofa_chair", "bath#cabinet", "t-shirt").
_SEPARATORS = re.compile(r"[_#\-\s]+")
# Punctuation dropped from the ends of a phrase ("toaster?", "step;").
_EDGE_PUNCT = "?!,;:\"'()[]{}"
# Qualifiers of dataset labels dropped when the whole label is unknown.
_QUALIFIERS = re.compile(r"\([^)]*\)?")
_TRAILING_NUMBER = re.compile(r"\s*\d+$")


@dataclass(frozen=True)
class Kind:
    """One object kind: its canonical label, synonyms, direct ``is_a`` parents, own
    parts (file order), whether it is a default detector prompt, and where in its room
    it typically stands ("" when nowhere in particular)."""

    label: str
    synonyms: tuple[str, ...]
    is_a: tuple[str, ...]
    parts: tuple[str, ...]
    detect: bool
    placement: str = ""


@dataclass(frozen=True)
class General:
    """One general word: its name, the phrases for it, the general words or kinds it
    falls under, and its most typical kinds."""

    name: str
    words: tuple[str, ...]
    is_a: tuple[str, ...]
    typical: tuple[str, ...]


@dataclass(frozen=True)
class ObjectVocabulary:
    """The parsed and checked ``objects.toml``; every table is read-only.

    ``phrases`` maps every kind phrase (labels and synonyms) to its label,
    ``general_words`` every general phrase to its general's name, ``ancestors`` each
    label to what it is a kind of (transitively; nearest first), ``members`` each kind
    label or general name to itself (when a kind) and the kinds under it, typical first,
    ``parts`` each label to its own and inherited parts.
    """

    version: int
    kinds: dict[str, Kind]
    general: dict[str, General]
    phrases: dict[str, str]
    general_words: dict[str, str]
    ancestors: dict[str, tuple[str, ...]]
    members: dict[str, tuple[str, ...]]
    parts: dict[str, tuple[str, ...]]
    all_parts: frozenset[str]


def normalise(phrase: str) -> str:
    """``phrase`` as the vocabulary spells phrases: lower case, ``_``, ``-`` and ``#``
    read as spaces, runs of spaces collapsed, end punctuation dropped ("Sofa_Chair?" →
    "sofa chair")."""
    text = _SEPARATORS.sub(" ", phrase.lower()).strip().strip(_EDGE_PUNCT).strip()
    return " ".join(text.split())


def _variants(key: str) -> tuple[str, ...]:
    """``key`` (normalised), then without dataset qualifiers when it has any: a
    parenthesis, what follows ``/`` or ``\\`` and a trailing number ("towels (rolled)",
    "window / other room", "stairs 2", "window2" → "towels", "window", "stairs",
    "window")."""
    bare = _QUALIFIERS.sub(" ", key)
    bare = re.split(r"[/\\]", bare, maxsplit=1)[0]
    bare = normalise(_TRAILING_NUMBER.sub("", normalise(bare)))
    return (key,) if not bare or bare == key else (key, bare)


def _quoted(name: str) -> str:
    return f'"{name}"' if not re.fullmatch(r"[a-z0-9]+", name) else name


def _check_phrase(phrase: str, where: str, field: str) -> None:
    if not phrase:
        raise VocabularyError(f"{where}: {field!r} has an empty phrase")
    if normalise(phrase) != phrase:
        raise VocabularyError(
            f"{where}: {field!r} phrase {phrase!r} must be lower case with single spaces "
            "(no '_', '-' or '#', no punctuation at the ends)"
        )


def _phrases(entry: dict[str, Any], key: str, where: str) -> tuple[str, ...]:
    value = entry.get(key, [])
    if not isinstance(value, list):
        raise VocabularyError(f"{where}: {key!r} must be a list of strings")
    for item in value:
        if not isinstance(item, str):
            raise VocabularyError(
                f"{where}: {key!r} must be a list of strings, not {type(item).__name__} ({item!r})"
            )
        _check_phrase(item, where, key)
    out = string_list(entry, key, where)
    seen: set[str] = set()
    for phrase in out:
        if phrase in seen:
            raise VocabularyError(f"{where}: {key!r} lists {phrase!r} twice")
        seen.add(phrase)
    return out


def _table(data: dict[str, Any], key: str, where: str) -> dict[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise VocabularyError(f"{where}: [{key}] must be a table")
    return value


def _entry(name: Any, entry: Any, section: str, allowed: frozenset[str]) -> str:
    """Where-string of ``[section.name]`` after checking the name and the table's keys."""
    where = f"{_FILE} [{section}.{_quoted(str(name))}]"
    if not isinstance(name, str):
        raise VocabularyError(f"{where}: the name must be a string")
    _check_phrase(name, where, "name")
    if not isinstance(entry, dict):
        raise VocabularyError(f"{where} must be a table")
    unknown = sorted(set(entry) - allowed)
    if unknown:
        raise VocabularyError(
            f"{where}: unknown field {unknown[0]!r} (known: {', '.join(sorted(allowed))})"
        )
    return where


def _parse_kinds(data: dict[str, Any]) -> tuple[dict[str, Kind], dict[str, str]]:
    table = require(data, "kinds", dict, _FILE)
    if not table:
        raise VocabularyError(f"{_FILE}: needs at least one [kinds.<label>] table")
    kinds: dict[str, Kind] = {}
    phrases: dict[str, str] = {}
    for label, entry in table.items():
        where = _entry(label, entry, "kinds", _KIND_KEYS)
        detect = entry.get("detect", False)
        if not isinstance(detect, bool):
            raise VocabularyError(f"{where}: 'detect' must be true or false")
        placement = entry.get("placement", "")
        if placement and placement not in _PLACEMENTS:
            raise VocabularyError(f"{where}: 'placement' must be one of {sorted(_PLACEMENTS)}")
        kind = Kind(
            label=label,
            synonyms=_phrases(entry, "synonyms", where),
            is_a=_phrases(entry, "is_a", where),
            parts=_phrases(entry, "parts", where),
            detect=detect,
            placement=placement,
        )
        if label in kind.is_a:
            raise VocabularyError(f"{where}: 'is_a' names the kind itself")
        for phrase in (label, *kind.synonyms):
            other = phrases.get(phrase)
            if other is not None:
                first = f"[kinds.{_quoted(other)}]"
                raise VocabularyError(
                    f"{where}: 'synonyms' phrase {phrase!r} is already a phrase of {first}; "
                    "a phrase may name one kind only"
                )
            phrases[phrase] = label
        kinds[label] = kind
    return kinds, phrases


def _parse_general(
    data: dict[str, Any], phrases: dict[str, str]
) -> tuple[dict[str, General], dict[str, str]]:
    general: dict[str, General] = {}
    words: dict[str, str] = {}
    for name, entry in _table(data, "general", _FILE).items():
        where = _entry(name, entry, "general", _GENERAL_KEYS)
        own = _phrases(entry, "words", where)
        item = General(
            name=name,
            words=(name, *(w for w in own if w != name)),
            is_a=_phrases(entry, "is_a", where),
            typical=_phrases(entry, "typical", where),
        )
        if name in item.is_a:
            raise VocabularyError(f"{where}: 'is_a' names the general word itself")
        for word in item.words:
            kind = phrases.get(word)
            if kind is not None and kind != name:
                raise VocabularyError(
                    f"{where}: 'words' phrase {word!r} is already a phrase of "
                    f"[kinds.{_quoted(kind)}]; a general word may share a phrase only "
                    "with the kind of its own name"
                )
            other = words.get(word)
            if other is not None:
                raise VocabularyError(
                    f"{where}: 'words' phrase {word!r} is already a word of "
                    f"[general.{_quoted(other)}]"
                )
            words[word] = name
        general[name] = item
    return general, words


def _ancestors(
    kinds: dict[str, Kind], general: dict[str, General], phrases: dict[str, str]
) -> dict[str, tuple[str, ...]]:
    """Every label's transitive ``is_a`` (nearest first); checks targets and cycles."""
    parents: dict[str, tuple[str, ...]] = {}
    for section, items in (("kinds", kinds), ("general", general)):
        for name, item in items.items():
            where = f"{_FILE} [{section}.{_quoted(name)}]"
            for target in item.is_a:
                if target in kinds or target in general:
                    continue
                hint = ""
                if target in phrases:
                    hint = f" ({target!r} is a synonym of {phrases[target]!r}; use the label)"
                raise VocabularyError(
                    f"{where}: 'is_a' names {target!r}, which is no kind or general word{hint}"
                )
            parents[name] = tuple(dict.fromkeys((*parents.get(name, ()), *item.is_a)))

    state: dict[str, int] = {}  # 1 = on the current path, 2 = done

    def visit(name: str, path: list[str]) -> None:
        if state.get(name) == 2:
            return
        if state.get(name) == 1:
            cycle = " → ".join([*path[path.index(name) :], name])
            raise VocabularyError(f"{_FILE}: 'is_a' goes round in a circle: {cycle}")
        state[name] = 1
        for parent in parents.get(name, ()):
            visit(parent, [*path, name])
        state[name] = 2

    for name in parents:
        visit(name, [])

    out: dict[str, tuple[str, ...]] = {}
    for label in kinds:
        seen: dict[str, None] = {}
        frontier = list(parents.get(label, ()))
        while frontier:  # breadth first: nearest parents first
            nxt: list[str] = []
            for name in frontier:
                if name not in seen and name != label:
                    seen[name] = None
                    nxt.extend(parents.get(name, ()))
            frontier = nxt
        out[label] = tuple(seen)
    return out


def _members(
    kinds: dict[str, Kind], general: dict[str, General], ancestors: dict[str, tuple[str, ...]]
) -> dict[str, tuple[str, ...]]:
    """Kind label or general name → the kinds a request for it means; checks that every
    general covers a kind and that its typical kinds are under it."""
    covered: dict[str, list[str]] = {}
    for label in kinds:
        for name in ancestors[label]:
            covered.setdefault(name, []).append(label)
    out: dict[str, tuple[str, ...]] = {}
    for name in dict.fromkeys((*kinds, *general)):
        under = covered.get(name, [])
        typical: tuple[str, ...] = ()
        if name in general:
            where = f"{_FILE} [general.{_quoted(name)}]"
            if not under:
                raise VocabularyError(
                    f"{where}: no kind falls under it (name it in some kind's 'is_a')"
                )
            typical = general[name].typical
            for label in typical:
                if label not in under:
                    raise VocabularyError(
                        f"{where}: 'typical' names {label!r}, which is not a kind under it"
                    )
        head = [name] if name in kinds else []
        rest = sorted(set(under) - set(typical))
        out[name] = tuple(dict.fromkeys((*head, *typical, *rest)))
    return out


def _parts(
    kinds: dict[str, Kind], ancestors: dict[str, tuple[str, ...]]
) -> dict[str, tuple[str, ...]]:
    out: dict[str, tuple[str, ...]] = {}
    for label, kind in kinds.items():
        inherited = [p for a in ancestors[label] if a in kinds for p in kinds[a].parts]
        out[label] = tuple(dict.fromkeys((*kind.parts, *inherited)))
    return out


@lru_cache(maxsize=1)
def vocabulary() -> ObjectVocabulary:
    """The parsed ``objects.toml``, checked: raises :class:`VocabularyError` naming the
    kind or general word and the field on malformed input (a phrase under two kinds, an
    ``is_a`` naming nothing known or going round in a circle, a non-string list item, an
    unknown field, ...)."""
    data = load_table("objects")
    unknown = sorted(set(data) - _TOP_KEYS)
    if unknown:
        raise VocabularyError(
            f"{_FILE}: unknown top-level key {unknown[0]!r} (known: {', '.join(sorted(_TOP_KEYS))})"
        )
    kinds, phrases = _parse_kinds(data)
    general, words = _parse_general(data, phrases)
    ancestors = _ancestors(kinds, general, phrases)
    members = _members(kinds, general, ancestors)
    parts = _parts(kinds, ancestors)
    return ObjectVocabulary(
        version=int(data["version"]),
        kinds=kinds,
        general=general,
        phrases=phrases,
        general_words=words,
        ancestors=ancestors,
        members=members,
        parts=parts,
        all_parts=frozenset(p for k in kinds.values() for p in k.parts),
    )


def clear_caches() -> None:
    """Forget the parsed file (after the file or ``DATA_DIR`` changed; tests)."""
    vocabulary.cache_clear()
    is_kind_of.cache_clear()


def _forms(key: str) -> Iterator[str]:
    """``key`` as written, then with its last word lemmatised (when that differs). Lazy:
    a phrase found as written never loads the lemmatiser (spaCy's pipeline costs a map
    build about 300 MB when its labels are all known kinds)."""
    yield key
    lemma = lemma_phrase(key)
    if lemma != key:
        yield lemma


def _label(key: str, voc: ObjectVocabulary) -> str | None:
    for form in _forms(key):
        label = voc.phrases.get(form)
        if label is not None:
            return label
    return None


def _name(key: str, voc: ObjectVocabulary) -> tuple[str, bool] | None:
    """(kind label or general name, whether general) that ``key`` (normalised) names; a
    kind phrase wins over a general word of the same spelling."""
    for form in _forms(key):
        label = voc.phrases.get(form)
        if label is not None:
            return label, False
        name = voc.general_words.get(form)
        if name is not None:
            return name, True
    return None


def _kind(label: str, voc: ObjectVocabulary) -> str | None:
    """``label`` if it is a kind, else the kind the phrase names."""
    key = normalise(label)
    return key if key in voc.kinds else canonical_label(key)


def canonical_label(phrase: str) -> str | None:
    """The canonical label of the kind ``phrase`` names ("couches" → "sofa", "Bedside
    Table" → "nightstand", "sofa_chair" → "armchair", "window#/#other#room" →
    "window"); None for unknown phrases and for general words ("seat")."""
    voc = vocabulary()
    for key in _variants(normalise(phrase)):
        label = _label(key, voc)
        if label is not None:
            return label
    return None


def labels_for(phrase: str) -> tuple[str, ...]:
    """The kinds a request word means, most likely first.

    A kind phrase means its kind (``("sofa",)`` for "couches", ``("table",)`` for
    "table"; the kinds under it meet it through :func:`is_kind_of` and
    :func:`kinds_under`). A general word means every kind under it, its ``typical``
    kinds first and the others sorted ("seat" → chair, sofa, armchair, stool, bench,
    ...; "bin" → trash can, recycle bin, ...). A longer phrase ending in a known phrase
    means what its longest known tail means ("kitchen trash can" → trash can, "metal
    shelving unit" → shelf, "comfortable seating" → the seats). Anything else: ``()``.
    """
    voc = vocabulary()
    for key in _variants(normalise(phrase)):
        words = key.split()
        for start in range(len(words)):
            found = _name(" ".join(words[start:]), voc)
            if found is not None:
                name, general = found
                return voc.members[name] if general else (name,)
    return ()


def names_general(phrase: str, name: str) -> bool:
    """Whether ``phrase`` is one of the words of the general word ``name`` ("decoration",
    "decorations" for [general.decoration]), as opposed to a synonym of a kind of the same
    name ("knickknack", "ornament": the decoration kind, not paintings or vases)."""
    voc = vocabulary()
    if name not in voc.general:
        return False
    for key in _variants(normalise(phrase)):
        if any(voc.general_words.get(form) == name for form in _forms(key)):
            return True
    return False


def kinds_under(word: str) -> tuple[str, ...]:
    """Every kind that falls under the kind or general word ``word`` names (itself not
    included), typical first: "chair" → armchair, dining chair, office chair, ...;
    ``()`` for unknown words and kinds with no narrower kind."""
    voc = vocabulary()
    key = normalise(word)
    found = _name(key, voc) if key else None
    if found is None:
        return ()
    name = found[0]
    return tuple(k for k in voc.members[name] if k != name)


def synonyms(label: str) -> tuple[str, ...]:
    """The synonyms of the kind ``label`` names (file order; the label not included);
    ``()`` for unknown labels."""
    voc = vocabulary()
    kind = _kind(label, voc)
    return voc.kinds[kind].synonyms if kind else ()


def is_a(label: str) -> tuple[str, ...]:
    """What the kind ``label`` names is a kind of: parent kinds and general words,
    transitively, nearest first ("armchair" → chair, seat, furniture); ``()`` for unknown
    labels."""
    voc = vocabulary()
    kind = _kind(label, voc)
    return voc.ancestors[kind] if kind else ()


@lru_cache(maxsize=65536)
def is_kind_of(label: str, general: str) -> bool:
    """Whether the kind ``label`` names falls under ``general`` (a kind or general word,
    by any of its phrases): "office chair" is a kind of "chair", "armchair" of "seating".
    False for the same kind and for unknown words. Cached: ranking asks it for every map
    label against every word asked, on every request."""
    voc = vocabulary()
    kind = _kind(label, voc)
    key = normalise(general)
    if kind is None or not key:
        return False
    if key in voc.kinds or key in voc.general:
        name: str | None = key
    else:
        found = _name(key, voc)
        name = found[0] if found else None
    return name is not None and name != kind and name in voc.ancestors[kind]


def typical_placement(label: str) -> str:
    """Where in its room a kind typically stands ("centre", "wall", "corner"), "" when
    nowhere in particular or unknown."""
    voc = vocabulary()
    kind = voc.kinds.get(label)
    return kind.placement if kind is not None else ""


def parts(label: str) -> tuple[str, ...]:
    """Parts and features of the kind ``label`` names, its own first and then those of
    the kinds it is a kind of; ``()`` for unknown labels."""
    voc = vocabulary()
    kind = _kind(label, voc)
    return voc.parts[kind] if kind else ()


def is_part(word: str, label: str | None = None) -> bool:
    """Whether ``word`` names a part of the kind ``label`` names, or of any kind when
    ``label`` is None ("wheels" of an office chair)."""
    voc = vocabulary()
    key = normalise(word)
    if not key:
        return False
    if label is None:
        pool: frozenset[str] | tuple[str, ...] = voc.all_parts
    else:
        pool = parts(label)
    return any(form in pool for form in _forms(key))


def detection_prompts() -> tuple[str, ...]:
    """Canonical labels of the kinds marked ``detect`` (file order): the default text
    prompts of open-vocabulary detectors."""
    return tuple(k.label for k in vocabulary().kinds.values() if k.detect)


def kinds() -> tuple[str, ...]:
    """Every canonical label, in file order."""
    return tuple(vocabulary().kinds)


def phrases() -> dict[str, str]:
    """Every kind phrase (labels and synonyms) → its canonical label, for multi-word
    matching by the request parser (a copy; general words are in
    :func:`general_words`)."""
    return dict(vocabulary().phrases)


def general_words() -> dict[str, str]:
    """Every general phrase → the name of its general word ("seating" → "seat"; a copy)."""
    return dict(vocabulary().general_words)

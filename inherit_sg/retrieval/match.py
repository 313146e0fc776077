"""Resolve word constraints against the map's vocabulary, once per request.

A label, function, room or area constraint is compared with the labels present in the
map, not with every node: a map has a few dozen distinct labels but thousands of
objects. The result (:data:`Matches`) maps a map label (objects) or a node id (rooms,
areas) to ``(similarity, reason)``; nodes absent from it have similarity 0.

Object words are matched in this order, and the reason says which step matched: the
same word (by lemma), a synonym in the object vocabulary ("couch" and "sofa" are both
``sofa``; "bedside table" is a ``nightstand``), a kind of the word asked for ("dining
table" for "table", from the vocabulary's ``is_a`` or the compound's head noun), a more
general word than the one asked for ("light" for "ceiling light", less), then
text-embedding similarity, graded so that only close phrases count. Rooms match by their
label's type, their inferred alternatives (graded by probability), the request's aliases
and related types, then by embedding similarity of their labels and alternatives
(:mod:`inherit_sg.retrieval.room_match`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import numpy as np

from inherit_sg.retrieval.constraints import (
    AreaConstraint,
    Constraint,
    FunctionConstraint,
    LabelConstraint,
    RoomConstraint,
)
from inherit_sg.retrieval.room_match import match_rooms
from inherit_sg.retrieval.similarity import (
    LABEL_COS_HI,
    LABEL_COS_LO,
    TEXT_COS_HI,
    TEXT_COS_LO,
    PhraseSimilarity,
    graded,
)
from inherit_sg.retrieval.snapshot import MapSnapshot, canonical_labels
from inherit_sg.vocab import functions as function_vocab
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab.rooms import room_type

Matches = dict[str, tuple[float, str]]

# Function kinds are listed most likely first; each later kind scores this much less.
FUNCTION_RANK_STEP = 0.08
FUNCTION_MIN = 0.6
# A kind of a listed kind ("wall cabinet" for "cabinet") serves the function too, this
# much below the listed kind itself.
FUNCTION_SUBKIND = 0.05
# Kinds a function phrase merely resembles count at most this much.
FUNCTION_SEMANTIC_MAX = 0.5
# A function the vocabulary does not know: the closest map label counts this much, those
# less than OPEN_FUNCTION_MARGIN (cosine) behind it count less, and nothing counts when
# the closest stays below OPEN_FUNCTION_MIN_COS (measured with the default MiniLM
# embedder: purpose phrases reach 0.35–0.55 with the label that serves them, unrelated
# labels stay below 0.3).
OPEN_FUNCTION_MAX = 0.7
OPEN_FUNCTION_MARGIN = 0.06
OPEN_FUNCTION_MIN_COS = 0.3
# An unknown purpose reads as a known function when one of the vocabulary's phrasings
# of it comes this close (MiniLM: "play my playlist" / "listen to playlist" 0.89, "make a
# phone call" / "make phone call" 0.98; misleading neighbours such as "my plant looks
# thirsty" / "thirsty" stay at or below 0.65).
KNOWN_FUNCTION_MIN_COS = 0.75
# Labels that only resemble the requested one count at most this much.
LABEL_SEMANTIC_MAX = 0.8
# Another word for the requested thing ("wall frame" for "picture"): a map label that is
# the very word asked for leads it by a little.
SYNONYM = 0.97
# A kind of the requested thing by its name ("dining table" for "table").
HYPONYM = 0.9
# A map label more general than the thing asked for ("light" for "ceiling light", "rug"
# for "bath mat"): the detector's word for it may be the general one.
HYPERNYM = 0.7
# ... less by this for every further step up ("light" for "table lamp", after "lamp").
HYPERNYM_STEP = 0.1
# ... plus up to this much by text-embedding resemblance to the word asked for, so that
# "kitchen counter" leads "counter" for "kitchen island".
HYPERNYM_RESEMBLANCE = 0.05
# A sibling kind under the same parent ("sofa chair" for "dining chair": both chairs):
# detectors often use a sibling's word, and text resemblance may say more.
SIBLING = 0.4
# Weaker resemblance than this is ignored.
MIN_MATCH = 0.1


def _clean(text: str) -> str:
    return re.sub(r"\s+\d+$", "", text.strip().lower())


def _semantic(
    out: Matches,
    queries: list[str],
    keys: list[str],
    texts: list[str],
    sim: PhraseSimilarity,
    scale: float,
    lo: float = LABEL_COS_LO,
    hi: float = LABEL_COS_HI,
) -> None:
    """Add graded embedding matches for ``keys`` not matched exactly yet."""
    todo = [(k, t) for k, t in zip(keys, texts, strict=True) if k not in out and t]
    queries = [q for q in dict.fromkeys(queries) if q]
    if not todo or not queries:
        return
    distinct = list(dict.fromkeys(t for _, t in todo))  # many rooms / areas share a label
    cos = sim.matrix(queries, distinct)
    best = cos.argmax(axis=0)
    top = cos[best, np.arange(len(distinct))]
    values = graded(top, lo, hi) * scale
    found = {
        text: (
            float(values[j]),
            f"'{text}' resembles '{queries[best[j]]}' (text embedding, cos {top[j]:.2f})",
        )
        for j, text in enumerate(distinct)
        if values[j] >= MIN_MATCH
    }
    for key, text in todo:
        if text in found:
            out[key] = found[text]


# Answers of is_kind_of for the current object vocabulary: ranking asks it for every map
# label against every word asked, ~500 times a request (2 ms of a request uncached).
_KIND_MEMO: dict[tuple[str, str], bool] = {}
_KIND_MEMO_VOCAB: list[object] = [None]
_KIND_MEMO_MAX = 200_000


def is_kind_of(label: str, general: str) -> bool:
    """Whether ``label`` names a kind of ``general``: by the object vocabulary ("armchair"
    is a chair, a "sofa" a seat), else by its head noun: "dining table" and "table",
    "bookshelf" and "shelf" (a compound with at least three more letters)."""
    voc = object_vocab.vocabulary()
    if _KIND_MEMO_VOCAB[0] is not voc or len(_KIND_MEMO) > _KIND_MEMO_MAX:
        _KIND_MEMO.clear()  # another vocabulary was loaded (or the memo is full)
        _KIND_MEMO_VOCAB[0] = voc
    key = (label, general)
    hit = _KIND_MEMO.get(key)
    if hit is None:
        hit = _KIND_MEMO[key] = _is_kind_of(label, general)
    return hit


def _is_kind_of(label: str, general: str) -> bool:
    label, general = label.lower().strip(), general.lower().strip()
    if not general or label == general:
        return False
    if object_vocab.is_kind_of(label, general):
        return True
    if label.endswith(" " + general):
        return True
    return " " not in general and label.endswith(general) and len(label) - len(general) >= 3


def _kind_only(wanted: set[str], nouns: set[str]) -> set[str]:
    """The asked kinds that share their name with a general word but were asked for by
    a synonym of the kind ("knickknack" asks for the decoration kind, not for paintings
    and vases, which are decorations in the general sense)."""
    voc = object_vocab.vocabulary()
    return {
        w
        for w in wanted
        if w in voc.general and nouns and not any(object_vocab.names_general(n, w) for n in nouns)
    }


def _object_label(
    label: str, wanted: set[str], nouns: set[str], kind_only: frozenset[str] = frozenset()
) -> tuple[float, str] | None:
    """Exact, synonym or kind-of match of one map label, with the step that matched;
    the kinds in ``kind_only`` (:func:`_kind_only`) do not take their general's kinds."""
    low = label.strip().lower()
    canon = canonical_labels(label)
    if low in nouns or (low in wanted and not nouns):
        return 1.0, f"label '{label}' is the word asked for"
    if low in wanted:
        return SYNONYM, f"label '{label}' is a {low}, the kind of the word asked for"
    hit = wanted.intersection(canon)
    if hit:
        return SYNONYM, f"label '{label}' is a {sorted(hit)[0]} (synonyms)"
    broad = sorted(wanted - kind_only)
    kind = next((w for w in broad for c in (low, *canon) if is_kind_of(c, w)), None)
    if kind is not None:
        return HYPONYM, f"a {label} is a kind of {kind} (vocabulary)"
    steps = [
        (_generality(w, c), w) for w in sorted(wanted) for c in (low, *canon) if is_kind_of(w, c)
    ]
    if steps:
        step, general = min(steps)
        value = max(HYPERNYM - HYPERNYM_STEP * step, HYPERNYM_STEP)
        return value, f"a {general} is a kind of {label}, the map's more general word"
    return None


def _parent_kinds(wanted: set[str]) -> dict[str, str]:
    """Each asked kind's parent, when that parent is a kind itself (not a broad class
    such as furniture or seat)."""
    kinds = object_vocab.vocabulary().kinds
    out: dict[str, str] = {}
    for want in sorted(wanted):
        chain = object_vocab.is_a(want)
        if chain and chain[0] in kinds:
            out[want] = chain[0]
    return out


def _sibling(label: str, parents: dict[str, str]) -> tuple[float, str] | None:
    """A map label naming another kind of an asked kind's parent (``parents``, from
    :func:`_parent_kinds`): "sofa chair" and "dining chair" are both chairs."""
    forms = (label.strip().lower(), *canonical_labels(label))
    for want, parent in parents.items():
        if any(f != want and f != parent and is_kind_of(f, parent) for f in forms):
            return SIBLING, f"a {label} and a {want} are both kinds of {parent} (vocabulary)"
    return None


def _generality(specific: str, general: str) -> int:
    """How many steps up the vocabulary's ``is_a`` chain ``general`` lies from
    ``specific`` (0: its parent, or a head noun the vocabulary does not list)."""
    chain = object_vocab.is_a(specific)
    return chain.index(general) if general in chain else 0


def _object_labels(con: LabelConstraint, snap: MapSnapshot, sim: PhraseSimilarity) -> Matches:
    wanted = set(con.labels)
    nouns = {con.noun.strip().lower()} if con.noun else set()
    out: Matches = {}
    labels = sorted(snap.raw_labels())
    general: Matches = {}
    kind_only = frozenset(_kind_only(wanted, nouns))
    for label in labels:
        found = _object_label(label, wanted, nouns, kind_only)
        if found is not None and found[0] <= HYPERNYM:
            general[label] = found  # a more general word: resemblance may say more
        elif found is not None:
            out[label] = found
    queries = [q for q in dict.fromkeys([*con.labels, con.noun]) if q]
    _semantic(out, queries, labels, labels, sim, LABEL_SEMANTIC_MAX)
    parents = {} if con.negated else _parent_kinds(wanted)
    if parents:  # "not a dining chair" says nothing against an armchair
        for label in labels:
            if label in general:
                continue
            found = _sibling(label, parents)
            if found is not None and (label not in out or out[label][0] < found[0]):
                out[label] = found
    if general and queries:
        # among general words, the one closer in meaning to the request leads a little
        names = sorted(general)
        closeness = graded(sim.matrix(queries, names).max(axis=0), LABEL_COS_LO, LABEL_COS_HI)
        for label, near in zip(names, closeness, strict=True):
            value, why = general[label]
            found = (value + HYPERNYM_RESEMBLANCE * float(near), why)
            if label not in out or out[label][0] < found[0]:
                out[label] = found
    return out


def _serving(labels: list[str], kinds: Sequence[str], function: str, how: str = "") -> Matches:
    """Map labels that are (or are a kind of) one of ``kinds``, the kinds that serve
    ``function`` most likely first; ``how`` says how the function was read."""
    rank = {k: i for i, k in enumerate(kinds)}
    out: Matches = {}
    for label in labels:
        canon = canonical_labels(label)
        ranks = [rank[c] for c in canon if c in rank]
        if ranks:
            value = max(FUNCTION_MIN, 1.0 - FUNCTION_RANK_STEP * min(ranks))
            out[label] = (value, f"a {label} serves '{function}'{how}")
            continue
        general = [(rank[g], g) for c in canon for g in object_vocab.is_a(c) if g in rank]
        if general:
            at, kind = min(general)
            value = max(FUNCTION_MIN, 1.0 - FUNCTION_RANK_STEP * at) - FUNCTION_SUBKIND
            out[label] = (value, f"a {label} is a {kind}, which serves '{function}'{how}")
    return out


def _nearest_known_function(
    con: FunctionConstraint, sim: PhraseSimilarity
) -> tuple[str, str, float] | None:
    """The vocabulary function whose phrasing comes closest in meaning to a purpose the
    vocabulary does not know ("play my playlist" reads like "listen to playlist"), as
    (function, phrase, cosine); None unless the closest phrase reaches
    :data:`KNOWN_FUNCTION_MIN_COS`."""
    # single words resemble by spelling as much as by meaning ("wrap" / "wrapper" 0.84):
    # only phrases of two words or more are compared
    asked = [con.function.strip().lower(), con.text.strip().lower()]
    phrases = [p for p in dict.fromkeys(asked) if len(p.split()) > 1]
    known, functions = function_vocab.multiword_sense_phrases()
    if not phrases or not known:
        return None
    known_vectors = sim.fixed_vectors("function phrases", known)
    cos = (sim.vectors(phrases) @ known_vectors.T).max(axis=0)
    best = int(np.argmax(cos))
    if float(cos[best]) < KNOWN_FUNCTION_MIN_COS:
        return None
    return functions[best], known[best], float(cos[best])


def _function_labels(con: FunctionConstraint, snap: MapSnapshot, sim: PhraseSimilarity) -> Matches:
    labels = sorted(snap.raw_labels())
    out = _serving(labels, con.labels, con.function)
    if not con.labels:
        near = _nearest_known_function(con, sim)
        if near is not None:
            function, phrase, cos = near
            how = f", read as '{phrase}' (text embedding, cos {cos:.2f})"
            out = _serving(labels, function_vocab.kinds_serving(function), function, how)
        _open_function(out, con, labels, sim)
        return out
    _semantic(
        out, [con.function], labels, labels, sim, FUNCTION_SEMANTIC_MAX, TEXT_COS_LO, TEXT_COS_HI
    )
    return out


def _open_function(
    out: Matches, con: FunctionConstraint, labels: list[str], sim: PhraseSimilarity
) -> None:
    """A function the vocabulary does not know ("weigh myself on", "make a phone call"):
    the map labels whose names come closest in meaning to the request's own words.

    A purpose phrase resembles the thing that serves it only loosely (cos 0.3–0.5 for
    "wrap myself in" and "a blanket"), so the grading is relative: the closest label
    counts :data:`OPEN_FUNCTION_MAX`, labels within :data:`OPEN_FUNCTION_MARGIN` of it
    count less the further behind they are, and nothing counts when even the closest
    stays below :data:`OPEN_FUNCTION_MIN_COS`."""
    phrases = [p for p in dict.fromkeys([con.text.strip().lower(), con.function]) if p]
    if not phrases or not labels:
        return
    cos = sim.matrix(phrases, [f"a {label}" for label in labels]).max(axis=0)
    best = float(cos.max())
    if best < OPEN_FUNCTION_MIN_COS:
        return
    values = graded(cos, best - OPEN_FUNCTION_MARGIN, best) * OPEN_FUNCTION_MAX
    for label, value, c in zip(labels, values, cos, strict=True):
        if value >= MIN_MATCH and label not in out:
            why = f"'{label}' comes closest to '{phrases[0]}' (text embedding, cos {c:.2f})"
            out[label] = (float(value), why)


def _areas(words: list[str], snap: MapSnapshot, sim: PhraseSimilarity) -> Matches:
    wanted = {_clean(w) for w in words if w}
    out: Matches = {}
    for aid, area in snap.areas.items():
        if _clean(area.label) in wanted:
            out[aid] = (1.0, f"area {aid} is a {area.label}")
    ids = sorted(snap.areas)
    _semantic(out, list(wanted), ids, [snap.areas[a].label.lower() for a in ids], sim, 1.0)
    return out


def resolve_matches(
    con: Constraint, layer: str, snap: MapSnapshot, sim: PhraseSimilarity
) -> Matches | None:
    """What ``con`` matches in the map, or None for constraints checked per node."""
    if isinstance(con, LabelConstraint):
        if layer == "object":
            return _object_labels(con, snap, sim)
        words = [_clean(w) for w in (*con.labels, con.noun) if w]
        if layer == "room":
            rtype = next((room_type(w) for w in words if room_type(w)), None)
            return match_rooms(words, rtype, snap, sim, negated=con.negated)
        if layer == "area":
            return _areas(words, snap, sim)
        return None
    if isinstance(con, FunctionConstraint):
        return _function_labels(con, snap, sim) if layer == "object" else None
    if isinstance(con, RoomConstraint):
        words = [_clean(w) for w in (con.type or "", con.name) if w]
        return match_rooms(
            words,
            con.type,
            snap,
            sim,
            negated=con.negated,
            beside=con.beside,
            opening=con.opening,
        )
    if isinstance(con, AreaConstraint):
        return _areas([con.label], snap, sim)
    return None

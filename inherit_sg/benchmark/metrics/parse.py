"""Parser accuracy against annotated requests (the development set in
``tests/data/dev_requests/*.jsonl``; the annotation guide is ``docs/dev_requests.md``).

Each annotated request names its target (the kind the speaker refers to: a label, ``"*"``
for "the thing", ``null`` for a need without a kind) and its constraints. A parse is
judged on:

- **target**: the parsed target names the annotated kind — the same canonical label
  through the object vocabulary (synonyms count: "couch" = "sofa"), one of the
  annotation's alternatives (``target_also``), or, for a general word ("seat"), one of the
  kinds it covers; ``"*"`` needs a target with no label, ``null`` a function;
- **negations**: every negated constraint annotated is found negated in the parse (by
  kind and what it is about: the room, the landmark, the attribute value, …), and none is
  invented;
- each other constraint kind (relation, attribute, room, floor, superlative, ordinal,
  viewpoint, placement, part, function, label): found / annotated.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inherit_sg.nlp import lemma_phrase
from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Constraint,
    FloorConstraint,
    FunctionConstraint,
    LabelConstraint,
    Landmark,
    PlacementConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
)
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.vocab import colours as colour_vocab
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab import rooms as room_vocab
from inherit_sg.vocab.lexicon import lexicon

Signature = tuple[str, ...]


def load_requests(paths: Iterable[Path]) -> list[dict[str, Any]]:
    """Annotated requests from JSON-lines files, in order."""
    out: list[dict[str, Any]] = []
    for path in paths:
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.strip():
                out.append(json.loads(line))
    return out


def kinds_of(noun: str) -> set[str]:
    """Canonical labels a noun phrase may name (itself lemmatised when unknown)."""
    noun = noun.strip().lower()
    if not noun:
        return set()
    found = set(object_vocab.labels_for(noun))
    canon = object_vocab.canonical_label(noun)
    if canon:
        found.add(canon)
    return found or {lemma_phrase(noun)}


def _landmark_kinds(lm: Landmark | None) -> set[str]:
    if lm is None:
        return set()
    out: set[str] = set()
    for label in (*lm.target.labels, lm.target.noun):
        if label:
            out |= kinds_of(label)
    return out


def _value(word: str) -> str:
    """Canonical attribute value of an annotated or parsed word."""
    word = str(word).strip().lower()
    lx = lexicon()
    colours = colour_vocab.colour_words()
    if word in colours:
        return colours[word]
    last = word.split()[-1] if word.split() else word
    if last in colours and len(word.split()) == 2:
        return colours[last]  # "dark brown" -> brown
    if word in lx.materials:
        return lx.materials[word]
    if word in lx.adjectives:
        return lx.adjectives[word][1]
    return word


def _room(word: str) -> str:
    word = " ".join(str(word).replace("'", " ").replace("-", " ").lower().split())
    return room_vocab.room_type(word) or word


def _part_noun(value: str) -> str:
    words = str(value).strip().lower().split()
    return lemma_phrase(words[-1]) if words else ""


def expected_signatures(exp: dict[str, Any]) -> Signature:
    """Signature of one annotated constraint (what it is about)."""
    kind = exp["kind"]
    if kind == "attribute":
        return ("attribute", _value(exp["value"]))
    if kind == "relation":
        return ("relation", *sorted(kinds_of(str(exp.get("landmark") or ""))))
    if kind == "room":
        return ("room", _room(exp["value"]))
    if kind == "floor":
        return ("floor", str(exp["value"]))
    if kind == "placement":
        return ("placement", str(exp["where"]))
    if kind == "part":
        return ("part", _part_noun(exp["value"]))
    if kind == "label":
        return ("label", *sorted(kinds_of(str(exp["value"]))))
    if kind == "ordinal":  # "not the right one": which side (or the middle) is ruled out
        return ("ordinal", str(exp.get("direction") or ""))
    return (kind,)


def parsed_signature(con: Constraint) -> Signature:
    """Signature of one parsed constraint (comparable with :func:`expected_signatures`)."""
    if isinstance(con, AttributeConstraint):
        if con.key == "part":
            return ("part", _part_noun(con.value))
        return ("attribute", _value(con.value))
    if isinstance(con, RelationConstraint):
        return ("relation", *sorted(_landmark_kinds(con.landmark)))
    if isinstance(con, RoomConstraint):
        return ("room", con.type or _room(con.name))
    if isinstance(con, FloorConstraint):
        return ("floor", str(con.level if con.level is not None else con.relative))
    if isinstance(con, PlacementConstraint):
        return ("placement", con.where)
    if isinstance(con, Superlative) and con.measure in ("ordinal", "middle"):
        return ("ordinal", con.direction or "")
    if isinstance(con, LabelConstraint):
        out: set[str] = set()
        for label in (*con.labels, con.noun):
            out |= kinds_of(label) if label else set()
        return ("label", *sorted(out))
    return (con.kind,)


def _heads(kinds: Iterable[str]) -> set[str]:
    return {k.split()[-1] for k in kinds if k}


def _same(a: Signature, b: Signature) -> bool:
    """Same kind and about the same thing: landmark kinds need only overlap (or share
    their head noun: "heated rail" and "towel rail"); a two-word state matches its last
    word ("turned on" and "on")."""
    if a[0] != b[0]:
        return False
    if a[0] in ("relation", "label"):
        return not a[1:] or not b[1:] or bool(_heads(a[1:]) & _heads(b[1:]))
    if a[0] == "attribute" and len(a) == 2 and len(b) == 2:
        return a[1] == b[1] or a[1].split()[-1] == b[1].split()[-1]
    return a[1:] == b[1:] or len(a) == 1


def target_right(parsed: ParsedQuery, exp: dict[str, Any]) -> bool:
    """Whether the parse's target names the annotated target."""
    target = exp.get("target")
    t = parsed.target
    if not parsed.has_target:
        return False
    has_function = bool(t.function) or any(c.kind == "function" for c in parsed.constraints)
    if target is None:
        return has_function
    if target == "*":
        return not t.labels or t.any
    wanted = kinds_of(str(target))
    for alt in exp.get("target_also", []) or []:
        wanted |= kinds_of(str(alt))
    got: set[str] = set()
    for label in (*t.labels, t.noun):
        if label:
            got |= kinds_of(label)
    if wanted & got:
        return True
    # a more specific kind the words license ("upper cabinet" → wall cabinet, a cabinet)
    return any(object_vocab.is_kind_of(g, w) for g in got for w in wanted)


def _walk_top(parsed: ParsedQuery) -> list[Constraint]:
    return list(parsed.constraints)


@dataclass
class Judgement:
    """How one request was parsed against its annotation."""

    id: str
    text: str
    forms: list[str]
    target_ok: bool
    negations_expected: int
    negations_found: int
    negations_invented: int
    found: Counter[str] = field(default_factory=Counter)
    expected: Counter[str] = field(default_factory=Counter)
    parsed: ParsedQuery | None = None
    error: str | None = None

    @property
    def negations_ok(self) -> bool:
        """Every annotated negation found and none invented."""
        return self.negations_found == self.negations_expected and self.negations_invented == 0


def _match_kind(exp: dict[str, Any], parsed: ParsedQuery) -> bool:
    """Whether a non-negation constraint of the annotation is present in the parse."""
    kind = exp["kind"]
    cons = _walk_top(parsed)
    if kind == "viewpoint":
        vp = parsed.viewpoint
        if vp is None:
            return False
        want_word = str(exp.get("landmark") or "door")
        want = kinds_of(want_word)
        got = _landmark_kinds(vp.landmark)
        rooms = {c.type for c in vp.landmark.constraints if isinstance(c, RoomConstraint)}
        about = bool(want & got) or _room(want_word) in rooms  # "from the hallway"
        return about and (vp.kind == exp.get("view") or len(vp.text.split()) > 6)
    if kind == "ordinal":
        for c in cons:
            if isinstance(c, Superlative) and c.measure in ("ordinal", "middle"):
                k = exp.get("ordinal")
                ok_k = (c.measure == "middle") if k == "middle" else c.ordinal == k
                if ok_k and (exp.get("direction") or None) == c.direction:
                    return True
        return False
    if kind == "superlative":
        for c in cons:
            if isinstance(c, Superlative) and c.measure == exp.get("measure"):
                mark = exp.get("landmark")
                if mark is None:
                    return True
                return bool(kinds_of(str(mark)) & _landmark_kinds(c.landmark))
        return False
    if kind == "relation":
        for c in cons:
            wanted = kinds_of(str(exp.get("landmark") or ""))
            if (
                isinstance(c, RelationConstraint)
                and not c.negated
                and wanted & _landmark_kinds(c.landmark)
            ):
                return True
        return False
    if kind == "function":
        return any(isinstance(c, FunctionConstraint) for c in cons) or bool(parsed.target.function)
    sig = expected_signatures(exp)
    return any(_same(sig, parsed_signature(c)) and not c.negated for c in cons)


def judge(exp: dict[str, Any], parse: Callable[[str], ParsedQuery]) -> Judgement:
    """Parse one annotated request and judge it."""
    text = str(exp["text"])
    forms = list(exp.get("forms", []))
    try:
        parsed = parse(text)
    except Exception as exc:  # a crash is the worst outcome; it is reported, not raised
        n_neg = sum(1 for c in exp.get("constraints", []) if c.get("negated"))
        return Judgement(
            str(exp["id"]), text, forms, False, n_neg, 0, 0, error=f"{type(exc).__name__}: {exc}"
        )
    wanted = [expected_signatures(c) for c in exp.get("constraints", []) if c.get("negated")]
    got = [parsed_signature(c) for c in _walk_top(parsed) if c.negated]
    found = 0
    left = list(got)
    for sig in wanted:
        hit = next((g for g in left if _same(sig, g)), None)
        if hit is not None:
            left.remove(hit)
            found += 1
    judgement = Judgement(
        str(exp["id"]),
        text,
        forms,
        target_right(parsed, exp),
        len(wanted),
        found,
        len(left),
        parsed=parsed,
    )
    for con in exp.get("constraints", []):
        if con.get("negated"):
            continue
        judgement.expected[con["kind"]] += 1
        if _match_kind(con, parsed):
            judgement.found[con["kind"]] += 1
    return judgement


@dataclass
class Report:
    """Totals over a set of judgements."""

    judgements: list[Judgement]

    @property
    def n(self) -> int:
        """Requests judged."""
        return len(self.judgements)

    @property
    def target_accuracy(self) -> float:
        """Share of requests whose target is right."""
        return sum(j.target_ok for j in self.judgements) / max(1, self.n)

    @property
    def negation_recall(self) -> float:
        """Annotated negations found / annotated negations."""
        want = sum(j.negations_expected for j in self.judgements)
        return sum(j.negations_found for j in self.judgements) / max(1, want)

    @property
    def negations_expected(self) -> int:
        """Annotated negations in all."""
        return sum(j.negations_expected for j in self.judgements)

    @property
    def negations_invented(self) -> int:
        """Negations the parser made up."""
        return sum(j.negations_invented for j in self.judgements)

    @property
    def negation_accuracy(self) -> float:
        """Share of requests with an annotated negation whose negations are all right."""
        with_neg = [j for j in self.judgements if j.negations_expected]
        return sum(j.negations_ok for j in with_neg) / max(1, len(with_neg))

    @property
    def crashes(self) -> list[Judgement]:
        """Requests whose parse raised."""
        return [j for j in self.judgements if j.error is not None]

    def constraint_recall(self) -> dict[str, tuple[int, int]]:
        """Per constraint kind: (found, annotated)."""
        found: Counter[str] = Counter()
        wanted: Counter[str] = Counter()
        for j in self.judgements:
            found.update(j.found)
            wanted.update(j.expected)
        return {k: (found[k], wanted[k]) for k in sorted(wanted)}

    def by_form(self) -> dict[str, tuple[int, int]]:
        """Per form tag: (targets right, requests)."""
        right: Counter[str] = Counter()
        total: Counter[str] = Counter()
        for j in self.judgements:
            for form in j.forms:
                total[form] += 1
                right[form] += j.target_ok
        return {k: (right[k], total[k]) for k in sorted(total)}


def evaluate(requests: list[dict[str, Any]], parse: Callable[[str], ParsedQuery]) -> Report:
    """Judge every annotated request with ``parse``."""
    return Report([judge(r, parse) for r in requests])

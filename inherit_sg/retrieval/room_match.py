"""Which rooms of a map a room constraint ("in the TV room") matches, and how well.

A room is matched by the first of these steps that finds it, and the reason says which:

1. **label**: its label names the type asked for (or another type the same word names
   as often: "den" is a family room and a TV room, ``also`` in ``rooms.toml``): fully,
   or when the map inferred the label with little confidence (best type below
   :data:`LABEL_SURE_P`), a little less (down to :data:`LABEL_LO`), so a confidently
   labelled room wins a tie;
2. **alternatives**: the type is among the room's inferred types (``RoomNode.types``):
   fully when it is the best one, else graded by its probability relative to the best
   (:func:`alternative_sim`), so "the TV room" finds a room labelled "living room" that
   holds a TV (when no room's label names the type: otherwise such rooms keep
   :data:`UNLABELLED_SHARE`); a negated constraint weighs alternatives far less
   (:func:`negated_alternative_sim`): "not in the living room" keeps the family room;
3. **aliases**: the request's room words, read through ``rooms.toml`` ("WC" → toilet),
   name its label or an alternative; or a type people name interchangeably with the one
   asked for (``related`` in ``rooms.toml``: "lounge" for a living room) is its label or
   an alternative, at the pair's similarity times :data:`RELATED_SCALE` (not for a
   negated constraint: "outside the dining room" says nothing against the kitchen);
4. **embedding**: when no room matched by the steps above, text-embedding similarity of
   the request's words to each room's label and alternatives.

A qualifier in the request's words (``[qualifiers]`` in ``rooms.toml``) then says which
of the matched rooms is meant (:func:`qualify_rooms`): "the master bathroom" / "the en
suite" is one that opens onto a bedroom, "the guest bathroom" one that does not; "the
master bedroom" the one with its own bathroom (else the largest), "the spare bedroom"
another; "the big bathroom" / "the main bedroom" the largest of the rooms matched in
full, "the small bathroom" the smallest. Matched rooms that are not the one meant keep
:data:`QUALIFIER_MISS` of their similarity, when the map has both kinds.
"""

from __future__ import annotations

import numpy as np

from inherit_sg.retrieval.similarity import LABEL_COS_HI, LABEL_COS_LO, PhraseSimilarity, graded
from inherit_sg.retrieval.snapshot import MapSnapshot
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab.rooms import also_named, related, room_qualifier, room_type

Matches = dict[str, tuple[float, str]]

# A label inferred with probability p matches at LABEL_LO … 1: from LABEL_SURE_P on it
# is sure, within LABEL_TIE_SPAN of 1 by p, so that of two rooms labelled alike the more
# confidently labelled one wins a tie (the WC, not the small bathroom also read as one).
LABEL_LO, LABEL_SURE_P = 0.8, 0.5
LABEL_TIE_SPAN = 0.02
# Alternatives other than the best match in [ALT_LO, ALT_HI] by their probability relative
# to the best one's, when their probability is at least ALT_MIN_P (never above the best).
ALT_LO, ALT_HI = 0.5, 0.95
ALT_MIN_P = 0.1
# For a negated constraint ("not in the living room") an alternative weighs at most this,
# in proportion to p / p_best: a room that only may be one never counts as one for sure.
NEG_ALT_HI = 0.45
# A room that only may be of the type asked for, when another room's label names it,
# keeps this share of its similarity.
UNLABELLED_SHARE = 0.6
# A room of a type related to the one asked for matches at the pair's similarity times this.
RELATED_SCALE = 0.75
# Weaker embedding resemblance than this is ignored.
MIN_MATCH = 0.1
# A matched room that is not the one a qualifier means ("the guest bathroom" for the
# bathroom off the bedroom) keeps this share of its similarity.
QUALIFIER_MISS = 0.6
# The main room of a type keeps this share when another one is asked for ("the second
# bathroom" rules the main one out more surely than "the small bathroom" picks one).
OTHER_MISS = 0.3
# "The big bathroom" with one room labelled a bathroom compares it with the rooms that
# match at least this well (an alternative inferred at half the best type's probability).
SIZE_PEER = 0.7
# A room a "next to" phrase names, when the map has no room of its type, may be one of
# a type this closely related to it (the entryway for "the hall").
RELATED_ANCHOR = 0.6
# The label of a door the map knows leads outside (the way in for "the front bathroom").
ENTRANCE_LABEL = "exterior door"
# Room types a private room opens onto, and those a private bedroom has of its own.
BEDROOMS = frozenset({"bedroom"})
BATHROOMS = frozenset({"bathroom", "toilet"})


def alternative_sim(p: float, p_best: float) -> float | None:
    """Similarity of a room to a type it is inferred to be with probability ``p`` when its
    best type has ``p_best``: 1 for the best, ``ALT_LO`` … ``ALT_HI`` in proportion to
    ``p / p_best`` for others of at least ``ALT_MIN_P``, None below that."""
    if p >= p_best:
        return 1.0
    if p < ALT_MIN_P or p_best <= 0:
        return None
    return ALT_LO + (ALT_HI - ALT_LO) * (p / p_best)


def label_sim(p: float | None) -> float:
    """Similarity of a room to the type its label names, inferred with probability ``p``
    (None: not inferred, as in oracle maps): 1 - ``LABEL_TIE_SPAN`` … 1 from
    ``LABEL_SURE_P`` on (rising with ``p``), down to ``LABEL_LO`` for a label the map was
    unsure of."""
    if p is None:
        return 1.0
    sure = 1.0 - LABEL_TIE_SPAN
    if p >= LABEL_SURE_P:
        return sure + LABEL_TIE_SPAN * (min(p, 1.0) - LABEL_SURE_P) / (1.0 - LABEL_SURE_P)
    return LABEL_LO + (sure - LABEL_LO) * max(p, 0.0) / LABEL_SURE_P


def negated_alternative_sim(p: float, p_best: float) -> float | None:
    """How surely a room is a type it is inferred to be with probability ``p`` (its best
    type has ``p_best``), for a constraint that excludes that type: up to
    :data:`NEG_ALT_HI`, in proportion to ``p / p_best``; None below ``ALT_MIN_P``."""
    if p < ALT_MIN_P or p_best <= 0:
        return None
    return NEG_ALT_HI * min(p / p_best, 1.0)


def room_type_sims(
    rid: str, snap: MapSnapshot, *, negated: bool = False
) -> dict[str, tuple[float, str]]:
    """Every type room ``rid`` may be, with its similarity and how it is known: the type
    its label names (:func:`label_sim`), then its inferred alternatives
    (:func:`alternative_sim`, never above the label's; :func:`negated_alternative_sim`
    when ``negated``: "not in the living room" holds for a family room that might also
    be read as a living room)."""
    out: dict[str, tuple[float, str]] = {}
    alts = snap.room_alternatives.get(rid, ())
    inferred = dict(alts)
    label_type = snap.room_types.get(rid)
    if label_type is not None:
        p = inferred.get(label_type)
        how = "its label" if p is None else f"its label, inferred p={p:.2f}"
        out[label_type] = (label_sim(p), how)
    if alts:
        p_best = alts[0][1]
        top = out[label_type][0] if label_type is not None else label_sim(p_best)
        for rtype, p in alts:
            value = negated_alternative_sim(p, p_best) if negated else alternative_sim(p, p_best)
            if value is not None and rtype not in out:
                out[rtype] = (
                    min(value, top),
                    f"inferred p={p:.2f}, best {alts[0][0]} p={p_best:.2f}",
                )
    return out


def all_room_type_sims(
    snap: MapSnapshot, *, negated: bool = False
) -> dict[str, dict[str, tuple[float, str]]]:
    """:func:`room_type_sims` of every room, by sorted room id (worked out once per
    snapshot: a large map has thousands of rooms and every room constraint reads them)."""
    return snap.memo(
        ("room_type_sims", negated),
        lambda: {rid: room_type_sims(rid, snap, negated=negated) for rid in sorted(snap.rooms)},
    )


def _by_type(rid: str, wanted: str, types: dict[str, tuple[float, str]]) -> tuple[float, str]:
    value, how = types[wanted]
    step = "label" if how.startswith("its label") else "alternatives"
    verb = "is" if value >= 1.0 - LABEL_TIE_SPAN else "may be"
    return value, f"room {rid} {verb} a {wanted} ({step}: {how})"


def _by_alias(
    rid: str,
    asked: str | None,
    named: dict[str, str],
    types: dict[str, tuple[float, str]],
    with_related: bool,
) -> tuple[float, str] | None:
    best: tuple[float, str] | None = None
    for word, rtype in named.items():
        if rtype in types:
            value, how = types[rtype]
            reason = f"'{word}' names a {rtype} (aliases, rooms.toml); room {rid} is one ({how})"
            if best is None or value > best[0]:
                best = (value, reason)
    if not with_related:
        return best
    for wanted in dict.fromkeys([*([asked] if asked else []), *named.values()]):
        for other, similarity in related(wanted).items():
            if other not in types:
                continue
            value = RELATED_SCALE * similarity * types[other][0]
            if best is None or value > best[0]:
                best = (
                    value,
                    f"room {rid} is a {other} ({types[other][1]}), a type people call a "
                    f"{wanted} too (related {similarity:.2f}, rooms.toml)",
                )
    return best


def _by_embedding(out: Matches, words: list[str], snap: MapSnapshot, sim: PhraseSimilarity) -> None:
    """Graded embedding similarity of ``words`` to each room's label and alternatives
    (an alternative's at its :func:`alternative_sim`)."""
    queries = [w for w in dict.fromkeys(words) if w]
    texts: dict[str, list[tuple[str, float]]] = {}
    for rid in sorted(snap.rooms):
        label = snap.rooms[rid].label.strip().lower()
        own = [(label, 1.0)] if label else []
        own += [
            (t, v)
            for t, (v, how) in room_type_sims(rid, snap).items()
            if not how.startswith("its label")
        ]
        texts[rid] = own
    distinct = list(dict.fromkeys(t for own in texts.values() for t, _ in own))
    if not queries or not distinct:
        return
    cos = sim.matrix(queries, distinct)
    best_q = cos.argmax(axis=0)
    top = cos[best_q, np.arange(len(distinct))]
    value = dict(zip(distinct, graded(top, LABEL_COS_LO, LABEL_COS_HI), strict=True))
    index = {t: j for j, t in enumerate(distinct)}
    for rid, own in texts.items():
        scored = [(float(value[t]) * factor, t) for t, factor in own]
        if not scored:
            continue
        score, text = max(scored)
        if score >= MIN_MATCH:
            j = index[text]
            out[rid] = (
                score,
                f"'{text}' of room {rid} resembles '{queries[best_q[j]]}' "
                f"(text embedding, cos {top[j]:.2f})",
            )


def _rooms_by_type(
    words: list[str], rtype: str | None, snap: MapSnapshot, negated: bool
) -> tuple[Matches, frozenset[str]]:
    """Steps 1-3 (label, alternatives, aliases) over every room, and the rooms whose
    label names the type asked for. They read only the snapshot and the vocabulary it
    was built with, so :func:`match_rooms` keeps them per snapshot."""
    out: Matches = {}
    named = {w: t for w in words if w for t in [room_type(w)] if t is not None and t != rtype}
    # "den" names a family room and a TV room alike (``also`` in rooms.toml).
    wanted = [rtype, *(t for w in words if w for t in also_named(w))] if rtype else []
    labelled: set[str] = set()  # rooms whose label names the type asked for
    for rid, types in all_room_type_sims(snap, negated=negated).items():
        exact = [
            (_by_type(rid, t, types), types[t][1].startswith("its label"))
            for t in dict.fromkeys(wanted)
            if t in types
        ]
        if exact:
            out[rid], by_label = max(exact, key=lambda hit: hit[0][0])
            if by_label:
                labelled.add(rid)
            continue
        found = _by_alias(rid, rtype, named, types, with_related=not negated)
        if found is not None and found[0] >= MIN_MATCH:
            out[rid] = found
    return out, frozenset(labelled)


def match_rooms(
    words: list[str],
    rtype: str | None,
    snap: MapSnapshot,
    sim: PhraseSimilarity,
    *,
    negated: bool = False,
    beside: str = "",
    opening: bool = False,
) -> Matches:
    """Room id → (similarity, reason) for a request naming room type ``rtype`` (None when
    its words name no type) with ``words``; see the module docstring for the steps.
    ``negated``: the constraint excludes the rooms ("not in the kitchen"); ``opening``:
    the rooms that open onto a matched room match as well ("the door to the toilet")."""
    key = ("rooms_by_type", tuple(words), rtype, negated)
    typed, labelled = snap.memo(key, lambda: _rooms_by_type(words, rtype, snap, negated))
    out = dict(typed)  # the steps below change it in place
    qualifier = next((q for w in words if w for q in [room_qualifier(w)] if q), None)
    if not negated and qualifier is None and not beside:
        _prefer_labelled(out, labelled)  # (a qualifier or a neighbour says which instead)
    if not out:
        _by_embedding(out, words, snap, sim)
    if qualifier is not None and rtype is not None:
        qualify_rooms(out, qualifier, rtype, snap)
    if beside:
        rooms_beside(out, beside, snap)
    if opening:
        _add_openings(out, snap)
    return out


def _prefer_labelled(out: Matches, labelled: frozenset[str]) -> None:
    """When some rooms' labels name the type asked for (``labelled``), the rooms that
    only may be one (an alternative, an alias's related type) keep
    :data:`UNLABELLED_SHARE` of their similarity: "the family room" is the room the map
    calls one, before the living room that might also be read as one. In place."""
    if not labelled:
        return
    for rid, (value, why) in list(out.items()):
        if rid not in labelled:
            out[rid] = (value * UNLABELLED_SHARE, f"{why}; another room is labelled so")


def _add_openings(out: Matches, snap: MapSnapshot) -> None:
    """Give every room that opens onto a matched room the matched room's similarity
    (a door to the toilet may be mapped in the hall it opens from), in place."""
    for rid, (value, why) in sorted(out.items()):
        for other in sorted(snap.neighbours.get(rid, set())):
            if other in snap.rooms and (other not in out or out[other][0] < value):
                out[other] = (value, f"room {other} opens onto room {rid}: {why}")


def _anchor_rooms(beside: str, snap: MapSnapshot) -> set[str]:
    """The rooms a "next to" phrase names: rooms of that type, else the rooms holding
    the thing it names (the best-matching kind only: the exterior door for "front
    door")."""
    rtype = room_type(beside)
    if rtype is not None:
        found = {r for r, t in snap.room_types.items() if t == rtype}
        if found:
            return found
        # "the bathroom off the hall" in a map with an entryway and no hallway
        near = {t for t, v in related(rtype).items() if v >= RELATED_ANCHOR}
        return {r for r, t in snap.room_types.items() if t in near}
    kinds = set(object_vocab.labels_for(beside))
    if not kinds:
        return set()
    return {
        room
        for oid, canon in snap.canon.items()
        if kinds & set(canon) and (room := snap.room_of.get(oid)) is not None
    }


def rooms_beside(out: Matches, beside: str, snap: MapSnapshot) -> None:
    """Lower the matched rooms that neither hold nor open onto what ``beside`` names to
    :data:`QUALIFIER_MISS` of their similarity, in place; nothing changes unless the
    matched rooms include both kinds."""
    anchors = _anchor_rooms(beside, snap)
    matched = sorted(r for r in out if r in snap.rooms)
    meant = {r for r in matched if r in anchors or snap.neighbours.get(r, set()) & anchors}
    _lower_unmeant(out, matched, meant, f"the one by the {beside} is meant")


def _lower_unmeant(
    out: Matches, matched: list[str], meant: set[str], reason: str, keep: float = QUALIFIER_MISS
) -> None:
    """Lower the ``matched`` rooms not in ``meant`` to ``keep`` of their similarity,
    saying ``reason``; nothing changes unless ``matched`` holds both kinds."""
    if not meant or len(meant) == len(matched):
        return
    for rid in matched:
        if rid not in meant:
            value, why = out[rid]
            out[rid] = (value * keep, f"{why}; but {reason}")


def _opens_onto(rid: str, types: frozenset[str], snap: MapSnapshot) -> bool:
    return any(snap.room_types.get(n) in types for n in snap.neighbours.get(rid, ()))


def _private_rooms(rooms: list[str], rtype: str, snap: MapSnapshot) -> set[str]:
    """The rooms among ``rooms`` a private qualifier means: for bedrooms, the ones with a
    bathroom of their own, else the largest; for other types, the ones off a bedroom."""
    if rtype not in BEDROOMS:
        return {r for r in rooms if _opens_onto(r, BEDROOMS, snap)}
    own = {r for r in rooms if _opens_onto(r, BATHROOMS, snap)}
    if own:
        return own
    sized = [(m.area_m2, r) for r in rooms if (m := snap.rooms[r].mask) is not None]
    return {max(sized)[1]} if sized else set()


def _peers(out: Matches, snap: MapSnapshot) -> list[str]:
    """The matched rooms a qualifier chooses among: those matched at full strength, or,
    when fewer than two are, those matched at least :data:`SIZE_PEER`."""
    full = [r for r, (v, _) in out.items() if r in snap.rooms and v >= LABEL_LO]
    if len(full) < 2:
        full = [r for r, (v, _) in out.items() if r in snap.rooms and v >= SIZE_PEER]
    return full


def _by_entrance(out: Matches, qualifier: str, snap: MapSnapshot) -> None:
    """Lower the compared rooms (:func:`_peers`) other than the one nearest ("the front
    bathroom") or farthest ("the back bedroom") from a door the map knows leads outside,
    to :data:`QUALIFIER_MISS` of their similarity; nothing changes without such a door
    or with fewer than two rooms."""
    doors = [
        p[:2]
        for i, node in snap.objects.items()
        if node.label == ENTRANCE_LABEL and (p := snap.position(i)) is not None
    ]
    masks = {r: m for r in _peers(out, snap) if (m := snap.rooms[r].mask) is not None}
    if not doors or len(masks) < 2:
        return
    reach = sorted((min(m.distance_xy(x, y) for x, y in doors), r) for r, m in masks.items())
    _, meant = reach[0] if qualifier == "front" else reach[-1]
    where = "nearest" if qualifier == "front" else "farthest from"
    _lower_unmeant(out, list(masks), {meant}, f"the {qualifier} one is meant ({where} the way in)")


def _sized_peers(out: Matches, snap: MapSnapshot) -> tuple[list[str], list[tuple[float, str]]]:
    """The compared rooms (:func:`_peers`) and, smallest first, the floor area of those
    with a mask."""
    full = _peers(out, snap)
    return full, sorted((m.area_m2, r) for r in full if (m := snap.rooms[r].mask) is not None)


def _other_than_main(out: Matches, snap: MapSnapshot) -> None:
    """Lower the largest of the compared rooms to :data:`OTHER_MISS` of its similarity:
    "the second bathroom", "the other bedroom" is not the main one; nothing changes with
    fewer than two."""
    full, sized = _sized_peers(out, snap)
    if len(sized) < 2:
        return
    main = sized[-1][1]
    others = {r for _, r in sized[:-1]}
    _lower_unmeant(out, full, others, f"not the main one ({main})", keep=OTHER_MISS)


def _by_size(out: Matches, qualifier: str, snap: MapSnapshot) -> None:
    """Lower the fully matched rooms other than the largest ("the big bathroom", "the
    main bedroom") or the smallest ("the small bathroom") one, by floor area, to
    :data:`QUALIFIER_MISS` of their similarity; the rooms matched at full strength (by
    their label or best type) are compared, or, when fewer than two are, those matched at
    least :data:`SIZE_PEER` (a bathroom the map took for a toilet); nothing changes with
    fewer than two."""
    full, sized = _sized_peers(out, snap)
    if len(sized) < 2:
        return
    area, meant = sized[-1] if qualifier == "largest" else sized[0]
    _lower_unmeant(out, full, {meant}, f"the {qualifier} one is meant ({area:.1f} m²)")


def qualify_rooms(out: Matches, qualifier: str, rtype: str, snap: MapSnapshot) -> None:
    """Lower the matched rooms that are not the one ``qualifier`` ("private", "shared",
    "largest" or "smallest") means to :data:`QUALIFIER_MISS` of their similarity, in
    place; nothing changes unless the matched rooms include both kinds."""
    if qualifier in ("largest", "smallest"):
        _by_size(out, qualifier, snap)
        return
    if qualifier == "other":
        _other_than_main(out, snap)
        return
    if qualifier in ("front", "back"):
        _by_entrance(out, qualifier, snap)
        return
    matched = sorted(r for r in out if r in snap.rooms)
    private = _private_rooms(matched, rtype, snap)
    meant = private if qualifier == "private" else set(matched) - private
    what = {
        ("private", True): "with a bathroom of its own, or the largest",
        ("private", False): "off a bedroom",
        ("shared", True): "not the main bedroom",
        ("shared", False): "not off a bedroom",
    }[(qualifier, rtype in BEDROOMS)]
    _lower_unmeant(out, matched, meant, f"the {qualifier} one is meant ({what})")

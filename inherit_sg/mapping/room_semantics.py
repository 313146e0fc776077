"""Room types, labels and summaries from their contents (the offline stand-in for the
paper's VLM room description from the best viewpoint plus area summaries).

A room's type is inferred as a ranked distribution over the room types of the room
vocabulary (``rooms.toml``, :mod:`inherit_sg.vocab.rooms`): every type is scored by its
prior, the evidence of the object kinds present (negative evidence counts against it),
how far the floor area falls outside the type's typical range, and whether the room is
long and narrow or holds only fixtures; a softmax turns the scores into probabilities.
The room's label is the best type; the alternatives are kept on the Room node.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from inherit_sg.model import RoomMask
from inherit_sg.vocab import objects as object_vocab
from inherit_sg.vocab import rooms as room_vocab
from inherit_sg.wording import with_article

# Weight of ln(prior) in a type's score.
PRIOR_WEIGHT = 0.5
# Score lost per e-fold of floor area outside a type's typical range, and the most lost.
SIZE_WEIGHT = 1.0
SIZE_MAX_PENALTY = 3.0
# A map label counts by the nearest kind it is a kind of at this fraction of its weight.
ANCESTOR_FACTOR = 0.7
# Softmax temperature over the scores.
TEMPERATURE = 1.0
# A room is narrow when its width is below NARROW_WIDTH_M (fully below NARROW_FULL_M)
# and it is at least ELONGATION_MIN times as long as wide (fully at ELONGATION_FULL).
NARROW_WIDTH_M, NARROW_FULL_M = 2.2, 1.2
ELONGATION_MIN, ELONGATION_FULL = 2.0, 4.0
# The catch-all type, labelled plainly "room".
OTHER_TYPE = "other room"
GENERIC_LABEL = "room"
# What a Room node keeps of the distribution.
KEEP_TYPES = 5
KEEP_MIN_P = 0.02

RoomTypes = list[tuple[str, float]]


@dataclass(frozen=True)
class RoomShape:
    """Floor area and shape of a room's footprint: ``width_m`` is the diameter of the
    widest disc that fits in it, ``elongation`` its area over the width squared (about
    length / width for a corridor, about 1.3 for a square room)."""

    area_m2: float
    width_m: float
    elongation: float

    @property
    def narrowness(self) -> float:
        """How much the room is a corridor, 0 (not at all) to 1."""
        thin = (NARROW_WIDTH_M - self.width_m) / (NARROW_WIDTH_M - NARROW_FULL_M)
        long = (self.elongation - ELONGATION_MIN) / (ELONGATION_FULL - ELONGATION_MIN)
        return float(np.clip(thin, 0.0, 1.0) * np.clip(long, 0.0, 1.0))


def room_shape(mask: RoomMask | None) -> RoomShape | None:
    """Area, width and elongation of a room mask (holes, where furniture stands, are
    filled first); None without a mask or with an empty one."""
    if mask is None or not mask.cells.any():
        return None
    cells = ndimage.binary_fill_holes(np.pad(mask.cells.astype(bool), 1))
    area = float(cells.sum()) * mask.resolution**2
    inside = ndimage.distance_transform_edt(cells)[cells]
    # a cell's distance to the nearest outside cell; the widest disc is about twice the
    # largest distance less one cell (a high percentile: one bulging cell is not a room)
    radius = float(np.percentile(inside, 98))
    width = max(2.0 * radius - 1.0, 1.0) * mask.resolution
    return RoomShape(area_m2=area, width_m=width, elongation=area / (width * width))


def _kind_chain(label: str) -> tuple[str, ...]:
    """The map label's kind and what it is a kind of, nearest first; the label itself
    when the object vocabulary does not know it."""
    kind = object_vocab.canonical_label(label)
    if kind is None:
        return (" ".join(label.lower().split()),)
    return (kind, *object_vocab.is_a(kind))


def _evidence(chains: Sequence[tuple[str, ...]], weights: dict[str, float]) -> float:
    total = 0.0
    for chain in chains:
        if chain[0] in weights:
            total += weights[chain[0]]
            continue
        parent = next((k for k in chain[1:] if k in weights), None)
        if parent is not None:
            total += ANCESTOR_FACTOR * weights[parent]
    return total


def _set_evidence(chains: Sequence[tuple[str, ...]], sets: dict[str, tuple[int, float]]) -> float:
    """What the sets of a type say: ``weight`` for every set kind that at least ``count``
    of the objects (``chains``, one per object, repeats counted) are kinds of."""
    total = 0.0
    for kind, (count, weight) in sets.items():
        if sum(1 for chain in chains if kind in chain) >= count:
            total += weight
    return total


def _size_penalty(area_m2: float | None, typical: tuple[float, float] | None) -> float:
    if area_m2 is None or typical is None or area_m2 <= 0:
        return 0.0
    lo, hi = typical
    beyond = max(0.0, math.log(lo / area_m2), math.log(area_m2 / hi))
    return min(SIZE_MAX_PENALTY, SIZE_WEIGHT * beyond)


def room_type_scores(
    labels: Sequence[str],
    area_m2: float | None = None,
    shape: RoomShape | None = None,
    off_entrance: bool = False,
) -> dict[str, float]:
    """The score of every room type (file order) for a room holding objects labelled
    ``labels``, of floor area ``area_m2`` (else the shape's) and ``shape``;
    ``off_entrance``: the room's storey has no exterior door while another one has."""
    every = [" ".join(lab.lower().split()) for lab in labels if lab and lab.strip()]
    raw = set(every)
    chains = list(dict.fromkeys(_kind_chain(lab) for lab in sorted(raw)))
    by_kind = {chain[0]: chain for chain in chains}  # one vote per kind ("couch", "sofa")
    fixtures = room_vocab.fixtures()
    counted = [_kind_chain(lab) for lab in every]  # sets count fixtures too: "3 doors"
    bare = bool(raw) and all(lab in fixtures or _kind_chain(lab)[0] in fixtures for lab in raw)
    area = area_m2 if area_m2 is not None else (shape.area_m2 if shape is not None else None)
    narrowness = shape.narrowness if shape is not None else 0.0
    scores: dict[str, float] = {}
    for name, rtype in room_vocab.room_type_table().items():
        scores[name] = (
            rtype.base
            + PRIOR_WEIGHT * math.log(rtype.prior)
            + _evidence(list(by_kind.values()), rtype.evidence)
            + _set_evidence(counted, rtype.sets)
            - _size_penalty(area, rtype.area)
            + rtype.narrow * narrowness
            + (rtype.bare if bare else 0.0)
            + (rtype.off_entrance if off_entrance else 0.0)
        )
    return scores


def type_evidence(labels: Sequence[str]) -> dict[str, float]:
    """What the object kinds among ``labels`` say about every room type (file order):
    the summed evidence weights of ``rooms.toml``, one vote per kind, and its sets
    (repeats counted), fixtures left out; no prior, size or shape term. Used to tell
    apart the functional parts of a room."""
    fixtures = room_vocab.fixtures()
    every = [" ".join(lab.lower().split()) for lab in labels if lab and lab.strip()]
    objects = [_kind_chain(lab) for lab in every if lab not in fixtures]
    objects = [c for c in objects if c[0] not in fixtures]
    by_kind = {c[0]: c for c in sorted(set(objects))}
    return {
        name: _evidence(list(by_kind.values()), rtype.evidence) + _set_evidence(objects, rtype.sets)
        for name, rtype in room_vocab.room_type_table().items()
    }


def infer_room_types(
    labels: Sequence[str],
    area_m2: float | None = None,
    shape: RoomShape | None = None,
    off_entrance: bool = False,
) -> RoomTypes:
    """The room's type as a ranked distribution: ``[(type, probability), …]`` over every
    room type, best first (ties in file order), probabilities summing to 1. A room with
    no evidence spreads its probability, with "other room" first, or "hallway" when it is
    long and narrow or holds only fixtures. ``off_entrance``: the room's storey has no
    exterior door while another storey has one (see ``off_entrance`` in rooms.toml)."""
    scores = room_type_scores(labels, area_m2, shape, off_entrance)
    names = list(scores)
    values = np.array([scores[n] for n in names], dtype=float) / TEMPERATURE
    weights = np.exp(values - values.max())
    probs = weights / weights.sum()
    order = sorted(range(len(names)), key=lambda i: (-probs[i], i))
    return [(names[i], float(probs[i])) for i in order]


# How much a room keeps of its claim to a one-per-storey type (kitchen, living room) that
# another room of its floor holds more strongly.
SINGLE_DISCOUNT = 0.2


def _discounted(types: Sequence[tuple[str, float]], name: str) -> RoomTypes:
    """``types`` with ``name``'s probability scaled by :data:`SINGLE_DISCOUNT`,
    renormalised and re-ranked (ties keep their order)."""
    scaled = [(t, p * SINGLE_DISCOUNT if t == name else p) for t, p in types]
    total = sum(p for _, p in scaled) or 1.0
    ranked = sorted(enumerate(scaled), key=lambda ip: (-ip[1][1], ip[0]))
    return [(t, p / total) for _, (t, p) in ranked]


def separate_single_types(floors: Sequence[dict[str, RoomTypes]]) -> dict[str, RoomTypes]:
    """The rooms' type distributions after the one-per-storey prior: on each floor (one
    dict room id → distribution per floor), when several rooms come out best as a type
    marked ``single`` in rooms.toml (a second "living room" beside the first is more
    likely the family or TV room), the room with the strongest claim keeps it and the
    others have it discounted, so that they take their next type. Rooms unaffected keep
    their distribution unchanged."""
    single = {name for name, rtype in room_vocab.room_type_table().items() if rtype.single}
    out: dict[str, RoomTypes] = {}
    for rooms in floors:
        current = {rid: list(types) for rid, types in rooms.items()}
        held: dict[str, str] = {}  # single type -> the room that keeps it
        for _ in range(len(single) + 1):
            claims: dict[str, list[tuple[float, str]]] = {}
            for rid, types in current.items():
                if types and types[0][0] in single:
                    claims.setdefault(types[0][0], []).append((types[0][1], rid))
            contested = {t: c for t, c in claims.items() if len(c) > 1 or t in held}
            changed = False
            for name, claimants in sorted(contested.items()):
                keeper = held.get(name) or max(claimants, key=lambda c: (c[0], c[1]))[1]
                held[name] = keeper
                for _p, rid in claimants:
                    if rid != keeper:
                        current[rid] = _discounted(current[rid], name)
                        changed = True
            if not changed:
                break
        out.update(current)
    return out


def room_label(types: Sequence[tuple[str, float]]) -> str:
    """The label of a room with type distribution ``types``: its best type, plainly
    "room" when that is "other room" or unknown."""
    if not types or types[0][0] == OTHER_TYPE:
        return GENERIC_LABEL
    return types[0][0]


def kept_types(types: Sequence[tuple[str, float]]) -> tuple[tuple[str, float], ...]:
    """What a Room node keeps of a distribution: the best type and the next ones of at
    least KEEP_MIN_P, KEEP_TYPES in all, probabilities rounded to 4 places."""
    kept = [(t, round(p, 4)) for k, (t, p) in enumerate(types) if k == 0 or p >= KEEP_MIN_P]
    return tuple(kept[:KEEP_TYPES])


def infer_room_type(
    labels: Sequence[str], area_m2: float | None = None, shape: RoomShape | None = None
) -> str:
    """The label of a room from the labels of its objects (and its size and shape when
    known): the best of :func:`infer_room_types`, "room" when nothing says more."""
    return room_label(infer_room_types(labels, area_m2, shape))


def floor_phrase(level: int | None) -> str:
    """ "the ground floor", "the second floor", …"""
    if level is None:
        return "an unknown floor"
    words = room_vocab.level_words()
    word = words[level] if 0 <= level < len(words) else f"level {level}"
    return f"the {word} floor"


def summarise_room(
    room_label: str, level: int | None, area_summaries: Sequence[str], object_labels: Sequence[str]
) -> str:
    """Room summary: type, floor, its areas and its most common objects."""
    head = f"{with_article(room_label, capital=True)} on {floor_phrase(level)}"
    counts = Counter(lab for lab in object_labels if lab not in ("door", "window"))
    if not counts and not area_summaries:
        return head + ", with nothing mapped in it yet."
    common = ", ".join(lab for lab, _ in counts.most_common(8))
    text = f"{head} containing {common}." if common else head + "."
    if area_summaries:
        text += " " + " ".join(area_summaries)
    return text

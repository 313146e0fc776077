"""Room labels and summaries from their contents (the offline stand-in for the paper's
VLM room description from the best viewpoint plus area summaries). Room types, their
evidence and the floor words come from the room vocabulary (``rooms.toml``,
:mod:`inherit_sg.vocab.rooms`)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

from inherit_sg.vocab import rooms as room_vocab
from inherit_sg.wording import with_article

MIN_EVIDENCE = 2.0
# Labels a room may hold and still be a hallway when nothing else is in it.
HALLWAY_LABELS = frozenset(
    {"door", "window", "painting", "plant", "mirror", "lamp", "stairs", "cabinet"}
)


def infer_room_type(labels: Sequence[str], area_m2: float | None = None) -> str:
    """Most likely room type from the labels of its objects; narrow empty rooms are
    hallways, other rooms without evidence stay plain "room"."""
    present = set(labels)
    scores = {
        rtype: sum(w for lab, w in ev.items() if lab in present)
        for rtype, ev in room_vocab.evidence().items()
    }
    best = max(scores, key=lambda k: scores[k])
    if scores[best] >= MIN_EVIDENCE:
        return best
    if not present - HALLWAY_LABELS:
        return "hallway"
    return "room"


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

"""Multi-turn conversations whose follow-ups need the previous turn (``conversations.jsonl``).

Kinds of follow-up: "the other one" (same scope, the earlier answer excluded), "not that
one, the one in the bedroom" (room switch), "what about upstairs?" (floor switch), "the
red one" (refine by colour), and refine-then-other over three turns. Every turn's targets
are exactly ``truth.evaluate`` of its ``gt_constraints``; follow-up targets always differ
from the previous turn's.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from inherit_sg.ingest.synthetic.jsonl import read_jsonl, write_jsonl
from inherit_sg.ingest.synthetic.query_mining import SceneFacts
from inherit_sg.ingest.synthetic.query_templates import RenderContext, render, templates_for
from inherit_sg.ingest.synthetic.query_text import Phrasing, display
from inherit_sg.ingest.synthetic.scene import ObjectGT, Scene
from inherit_sg.ingest.synthetic.truth import SceneIndex
from inherit_sg.ingest.synthetic.truth_spec import AttributeConstraint, FloorConstraint, ObjectSpec

CONVERSATIONS_FILE = "conversations.jsonl"
MAX_ANSWERS = 3
OTHER_ONE = (
    "Not that one, the other one.",
    "The other one, please.",
    "No, I meant the other one.",
    "That's not it. Take me to the other one.",
)
ROOM_SWITCH = (
    "Not that one, the one in {room}.",
    "No, I meant the one in {room}.",
    "What about the one in {room}?",
    "Actually, I need the {noun} in {room}.",
)
FLOOR_SWITCH = ("What about {floor}?", "And {floor}?", "How about {floor}?")
REFINE = ("The {adj} one.", "I meant the {adj} one.", "The {adj} one, please.")


@dataclass
class TurnGT:
    """One turn: its text and every acceptable target."""

    text: str
    target_ids: list[str]
    target_positions: list[list[float]]
    followup: str = ""  # "", "other_one", "room_switch", "floor_switch", "refine"
    gt_constraints: dict[str, Any] = field(default_factory=dict)


@dataclass
class ConversationGT:
    """A conversation: turns in order."""

    id: str
    turns: list[TurnGT]

    def to_dict(self) -> dict[str, Any]:
        """The ``conversations.jsonl`` line."""
        return {"id": self.id, "turns": [dict(vars(t)) for t in self.turns]}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ConversationGT:
        """Inverse of :meth:`to_dict`."""
        turns = [
            TurnGT(
                text=str(t["text"]),
                target_ids=[str(x) for x in t["target_ids"]],
                target_positions=[[float(v) for v in p] for p in t["target_positions"]],
                followup=str(t.get("followup", "")),
                gt_constraints=dict(t.get("gt_constraints", {})),
            )
            for t in data["turns"]
        ]
        return cls(id=str(data["id"]), turns=turns)


_Turn = tuple[ObjectSpec, str, str]  # spec, text, follow-up kind


class _Builder:
    def __init__(self, facts: SceneFacts, rng: random.Random) -> None:
        self.f = facts
        self.rng = rng

    def match(self, spec: ObjectSpec) -> list[ObjectGT]:
        return self.f.index.match(spec)

    def opening(self, spec: ObjectSpec) -> str | None:
        size = len(self.match(spec))
        phrasing = Phrasing(spec, self.rng.randrange(1 << 30))
        ctx = RenderContext("A", spec, size, 0, phrasing)
        options = templates_for("A")
        self.rng.shuffle(options)
        return next((t for t in (render(o, ctx) for o in options) if t), None)

    def followup(self, options: tuple[str, ...], spec: ObjectSpec, **slots: str) -> str:
        return display(self.rng.choice(options).format(noun=spec.noun, **slots))

    def other_one(self, a: ObjectGT) -> list[_Turn] | None:
        base = replace(self.f.target(a), room=self.f.room(a))
        found = self.match(base)
        if len(found) != 2 or not any(o is a for o in found):
            return None
        first = self._distinguish(base, a)
        if first is None:
            return None
        second = replace(base, exclude_ids=[a.id])
        text = self.opening(first)
        return (
            [(first, text, ""), (second, self.followup(OTHER_ONE, base), "other_one")]
            if text
            else None
        )

    def _distinguish(self, base: ObjectSpec, a: ObjectGT) -> ObjectSpec | None:
        options = [replace(base, relations=[r]) for r in self.f.relation(a, limit=3)]
        colour = a.attributes.get("colour")
        if isinstance(colour, str) and self.f.colour_clear(a):
            options.append(replace(base, attributes=[AttributeConstraint("colour", colour)]))
        return next((s for s in options if [o.id for o in self.match(s)] == [a.id]), None)

    def room_switch(self, a: ObjectGT) -> list[_Turn] | None:
        first = replace(self.f.target(a), room=self.f.room(a))
        before = {o.id for o in self.match(first)}
        if first.room is None or not 1 <= len(before) <= MAX_ANSWERS:
            return None
        for other in self.f.looks_alike(first, a):
            room = self.f.room(other)
            if room is None or room.type == first.room.type:
                continue
            second = replace(first, room=room)
            after = {o.id for o in self.match(second)}
            text = self.opening(first)
            if text and 1 <= len(after) <= MAX_ANSWERS and not after & before:
                ref = Phrasing(second, self.rng.randrange(1 << 30)).room_ref(room)
                follow = self.followup(ROOM_SWITCH, second, room=ref)
                return [(first, text, ""), (second, follow, "room_switch")]
        return None

    def floor_switch(self, a: ObjectGT) -> list[_Turn] | None:
        if not self.f.multi_floor:
            return None
        here, there = (
            ("downstairs", "upstairs")
            if a.floor == self.f.levels[0]
            else ("upstairs", "downstairs")
        )
        room = self.f.room(a) if self.rng.random() < 0.6 else None
        first = replace(self.f.target(a), room=room, floor=FloorConstraint(relative=here))
        second = replace(first, floor=FloorConstraint(relative=there))
        before = {o.id for o in self.match(first)}
        after = {o.id for o in self.match(second)}
        text = self.opening(first)
        if not text or not 1 <= len(before) <= MAX_ANSWERS or not 1 <= len(after) <= MAX_ANSWERS:
            return None
        phrase = Phrasing(second, 0).floor_phrase(FloorConstraint(relative=there))
        return [
            (first, text, ""),
            (second, self.followup(FLOOR_SWITCH, second, floor=phrase), "floor_switch"),
        ]

    def refine(self, a: ObjectGT, then_other: bool = False) -> list[_Turn] | None:
        base = replace(self.f.target(a), room=self.f.room(a))
        found = self.match(base)
        colour = a.attributes.get("colour")
        if not isinstance(colour, str) or not 2 <= len(found) <= (2 if then_other else 4):
            return None
        if not self.f.colour_clear(a):
            return None
        second = replace(base, attributes=[AttributeConstraint("colour", colour)])
        if [o.id for o in self.match(second)] != [a.id]:
            return None
        text = self.opening(base)
        if not text:
            return None
        turns = [(base, text, ""), (second, self.followup(REFINE, second, adj=colour), "refine")]
        if then_other:
            third = replace(base, exclude_ids=[a.id])
            turns.append((third, self.followup(OTHER_ONE, base), "other_one"))
        return turns


def _turn(index: SceneIndex, spec: ObjectSpec, text: str, kind: str) -> TurnGT:
    found = index.match(spec)
    positions = [[float(v) for v in o.centroid] for o in found]
    return TurnGT(text, [o.id for o in found], positions, kind, spec.to_dict())


def generate_conversations(scene: Scene, seed: int, n: int | None = None) -> list[ConversationGT]:
    """Up to ``n`` conversations (default: one per three non-structural objects)."""
    rng = random.Random(seed)
    index = SceneIndex(scene)
    builder = _Builder(SceneFacts(scene, index, rng), rng)
    kinds: list[Callable[[ObjectGT], list[_Turn] | None]] = [
        builder.other_one,
        builder.room_switch,
        builder.floor_switch,
        builder.refine,
        lambda a: builder.refine(a, then_other=True),
    ]
    wanted = n if n is not None else max(5, sum(1 for o in scene.objects if not o.structural) // 3)
    out: list[ConversationGT] = []
    openings: set[str] = set()
    made = [0] * len(kinds)
    # First pass: each kind up to an even share; second pass: fill up with any kind.
    for cap in (-(-wanted // len(kinds)), wanted):
        for anchor in builder.f.anchors():
            if len(out) >= wanted:
                break
            _extend(out, openings, made, cap, [k(anchor) for k in kinds], index)
    return out


def _extend(
    out: list[ConversationGT],
    openings: set[str],
    made: list[int],
    cap: int,
    options: list[list[_Turn] | None],
    index: SceneIndex,
) -> None:
    """Add the first usable option of the kind made least so far (below ``cap``)."""
    for k in sorted(range(len(options)), key=lambda i: (made[i], i)):
        turns = options[k]
        if made[k] >= cap:
            continue
        if turns and turns[0][1].lower() not in openings:
            openings.add(turns[0][1].lower())
            made[k] += 1
            conv_id = f"c{len(out) + 1:04d}"
            out.append(ConversationGT(conv_id, [_turn(index, *t) for t in turns]))
            return


def write_conversations(path: str | Path, conversations: list[ConversationGT]) -> Path:
    """Write JSON lines to ``path`` (a file, or a folder → conversations.jsonl)."""
    return write_jsonl(path, CONVERSATIONS_FILE, (x.to_dict() for x in conversations))


def read_conversations(path: str | Path) -> list[ConversationGT]:
    """Read a ``conversations.jsonl`` file (or the one in a folder)."""
    return read_jsonl(path, CONVERSATIONS_FILE, ConversationGT.from_dict, "conversation")

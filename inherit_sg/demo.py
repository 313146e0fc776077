"""``inherit-sg demo``: the main job a newcomer runs. Generates a two-floor house, maps
it with the offline defaults, and answers showcase requests of every category (with a
negation, a chained constraint and a conversation follow-up), checking each answer
against the house's ground truth."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from inherit_sg.errors import InputError
from inherit_sg.ingest.synthetic.queries import QueryGT, read_queries

# (category, sub-category preference) for the showcase, in the order they are shown
SHOWCASE = (
    ("A", "object in a room or on a floor"),
    ("B", "one landmark"),
    ("C", "chained constraints"),
    ("D", "negation"),
    ("D", "negation"),
    ("E", "descriptive"),
    ("F", "ambiguous or implicit"),
    ("F", "ambiguous or implicit"),
)
WITHIN_M = 1.0


@dataclass
class ShowcaseAnswer:
    """One demo request with its answer and whether the ground truth agrees."""

    category: str
    kind: str
    text: str
    answer: dict[str, Any] | None
    correct: bool
    trace: list[str] = field(default_factory=list)
    total_ms: float = 0.0


def pick_requests(queries: list[QueryGT]) -> list[tuple[str, str, str, list[list[float]]]]:
    """A varied, deterministic selection: per showcase slot, the next unused request of
    that category (preferring different templates)."""
    used: set[str] = set()
    templates: set[str] = set()
    out = []
    for category, kind in SHOWCASE:
        pool = [q for q in queries if q.category == category and q.id not in used]
        fresh = [q for q in pool if q.template not in templates] or pool
        if not fresh:
            continue
        q = fresh[0]
        used.add(q.id)
        templates.add(q.template)
        out.append((category, kind, q.text, q.target_positions))
    return out


def _near(answer: dict[str, Any] | None, targets: list[list[float]]) -> bool:
    if answer is None or not targets:
        return False
    pos = np.asarray(answer["position"], dtype=float)
    return bool(np.min(np.linalg.norm(np.asarray(targets, dtype=float) - pos, axis=1)) <= WITHIN_M)


def run_showcase(map_dir: Path, dataset: Path) -> list[ShowcaseAnswer]:
    """Answer the showcase requests and a conversation follow-up on a built map."""
    from inherit_sg.facade import MapService
    from inherit_sg.ingest.synthetic.query_conversations import read_conversations
    from inherit_sg.retrieval.conversation import Conversation

    conversation = Conversation()
    with MapService.open(map_dir) as service:

        def ask(
            category: str, kind: str, text: str, targets: list[list[float]], follow: bool = False
        ) -> ShowcaseAnswer:
            res = service.query(text, conversation=conversation if follow else None)
            total = res.timings_ms.get("total", 0.0)
            return ShowcaseAnswer(
                category, kind, text, res.answer, _near(res.answer, targets), res.trace, total
            )

        answers = [ask(*request) for request in pick_requests(read_queries(dataset))]
        turns = next((c.turns for c in read_conversations(dataset) if len(c.turns) >= 2), [])
        for i, turn in enumerate(turns[:2]):
            kind = "conversation" if i == 0 else "conversation follow-up"
            answers.append(ask("conv", kind, turn.text, turn.target_positions, follow=True))
    return answers


def prepare_out(out: Path, force: bool) -> None:
    """Create the demo folder; refuse to overwrite a non-empty one without ``force``."""
    if out.exists() and any(out.iterdir()):
        if not force:
            raise InputError(f"{out} is not empty; pass --force to replace the demo there")
        shutil.rmtree(out)
    out.mkdir(parents=True, exist_ok=True)


def generate(
    out: Path, seed: int, width: int, height: int, progress: Callable[[int, int], None]
) -> dict[str, Any]:
    """Write the demo house dataset into ``out/house``."""
    from inherit_sg.ingest.synthetic.generate import generate_house, write_dataset

    house = generate_house(seed, 2)
    return write_dataset(
        house, out / "house", width=width, height=height, progress=progress
    ).to_dict()

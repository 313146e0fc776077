"""Conversation history kept in a JSON file between separate invocations (``inherit-sg
query --conversation FILE``): ``{"format": "inherit-sg-conversation", "turns": [{"query":
<parsed request>, "answer_id": str | null, "candidate_ids": [...]}, ...]}``."""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from inherit_sg.errors import InputError
from inherit_sg.retrieval.conversation import Conversation
from inherit_sg.retrieval.query import ParsedQuery

FORMAT = "inherit-sg-conversation"


def load_conversation(path: str | Path) -> Conversation:
    """The conversation stored in ``path`` (an empty one when the file does not exist);
    InputError naming the file when it is not a conversation."""
    file = Path(path)
    conv = Conversation()
    if not file.exists():
        return conv
    try:
        data = json.loads(file.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise InputError(f"conversation file {file}: cannot read it ({exc})") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise InputError(f"conversation file {file}: not an INHerit-SG conversation")
    for i, turn in enumerate(data.get("turns", []), start=1):
        if not isinstance(turn, dict) or not isinstance(turn.get("query"), dict):
            raise InputError(f"conversation file {file}: turn {i} has no 'query' object")
        ids = turn.get("candidate_ids", [])
        conv.add_turn(ParsedQuery.from_dict(turn["query"]), turn.get("answer_id"), tuple(ids))
    return conv


def save_conversation(conv: Conversation, path: str | Path) -> None:
    """Write ``conv`` to ``path`` atomically (write a temporary file, then rename)."""
    file = Path(path)
    doc = {
        "format": FORMAT,
        "turns": [
            {
                "query": t.query.to_dict(),
                "answer_id": t.answer_id,
                "candidate_ids": list(t.candidate_ids),
            }
            for t in conv.turns
        ],
    }
    file.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".conversation-", dir=file.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            json.dump(doc, fh, indent=1)
        os.replace(tmp, file)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise

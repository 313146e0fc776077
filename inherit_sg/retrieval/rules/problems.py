"""Problem statements that imply a need: "My hands are dirty. Is there something that
could help?" → ``wash hands`` (sink); "It's too dark in here" → ``light``.

The first sentence of a request (the whole request when it is one sentence) is read as a
problem when it is a statement (it opens with a subject and neither asks nor seeks) and
names a state of the lexicon's ``PROBLEMS`` (with its subject, where one is needed). The
statement is then taken out of the request: its nouns are not the target ("hands") and
its adjectives are not attributes ("dark"); the rest ("is there something in the kitchen
that could help") is parsed as usual and gets the function.
"""

from __future__ import annotations

from itertools import pairwise

from inherit_sg.retrieval import lexicon as lx
from inherit_sg.retrieval.constraints import FunctionConstraint
from inherit_sg.retrieval.lexicon_functions import PROBLEMS
from inherit_sg.retrieval.rules.cursor import weighted

# Words a statement about oneself or one's things opens with.
_SUBJECTS = frozenset({
    "i", "it", "my", "the", "our", "this", "these", "those", "there", "someone", "somebody",
    "we", "its", "that", "his", "her", "their", "everything", "all",
})  # fmt: skip
# Words that make the sentence a request rather than a statement of the problem.
_REQUEST_WORDS = frozenset({
    "where", "somewhere", "anywhere", "place", "spot", "find", "show", "take", "want",
    "like", "would", "help", "could", "can", "should", "locate", "looking", "which", "need",
    "let",
})  # fmt: skip
# "needs to stay cold": "need" with a subject other than the speaker states a problem.
_SPEAKER = frozenset({"i", "we"})
# Nouns a statement may open with ("books are piling up", "dishes are stacked").
_PROBLEM_SUBJECTS = frozenset(s for _, subjects, _, _ in PROBLEMS for s in subjects)


def _terms(words: list[str]) -> set[str]:
    terms = {lx.singular(w) for w in words} | set(words)
    return terms | {f"{a} {b}" for a, b in pairwise(words)}


def _is_statement(words: list[str]) -> bool:
    if not words:
        return False
    if words[0] not in _SUBJECTS and lx.singular(words[0]) not in _PROBLEM_SUBJECTS:
        return False
    asks = _REQUEST_WORDS - ({"need"} if words[0] not in _SPEAKER else set())
    return not any(w in asks for w in words)


def match_problem(words: list[str]) -> tuple[str, tuple[str, ...]] | None:
    """The (function, likely kinds) a problem sentence implies, or None."""
    terms = _terms(words)
    loose: tuple[str, tuple[str, ...]] | None = None
    for function, subjects, states, labels in PROBLEMS:
        if not terms.intersection(states):
            continue
        if subjects and terms.intersection(subjects):
            return function, labels
        if not subjects and loose is None:
            loose = (function, labels)
    return loose


def split_problem(words: list[str]) -> tuple[FunctionConstraint | None, list[str]]:
    """A leading problem statement as a function, and the words left to parse."""
    cut = words.index(",") if "," in words else len(words)
    first = words[:cut]
    if not _is_statement(first):
        return None, words
    sense = match_problem(first)
    if sense is None:
        return None, words
    function, labels = sense
    made = FunctionConstraint(
        function=function, labels=labels, weight=weighted("function", None), text=" ".join(first)
    )
    return made, words[cut + 1 :]

"""Request frames decided on the words before parsing.

- *global* questions about a space as a whole ("How does this space encourage both
  group socialisation and solitary relaxation?", "What are the main purposes of these
  areas?"): nothing to find, so the parse is an explicit no-object-target result;
- *refinements* of the previous request ("what about upstairs?", "and in the bedroom?").
"""

from __future__ import annotations

from inherit_sg.retrieval import lexicon as lx

GLOBAL_REASON = "global question about the space as a whole: no object or place to find"

_OPENERS = frozenset({"how", "what", "why", "describe", "explain", "summarize", "summarise"})
_AUX = frozenset({"do", "does", "did", "can", "could", "should", "would", "might", "may", "is",
                  "are", "will", "was", "were"})  # fmt: skip
_PERSONAL = frozenset({"i", "me", "my", "we", "us", "you", "someone", "somebody", "one",
                       "person", "people", "individual", "anyone", "they", "he", "she"})  # fmt: skip
_SUBJECTS = frozenset(
    {
        "space",
        "environment",
        "area",
        "subarea",
        "zone",
        "scene",
        "design",
        "layout",
        "feature",
        "room",
        "building",
        "setting",
        "element",
        "component",
        "lounge",
        "office",
        "place",
        "house",
        "floor",
        "spaces",
        "checkpoint",
        "station",
        "workspace",
        "hub",
    }
)
_PREDICATES = frozenset(
    {
        "support",
        "encourage",
        "balance",
        "complement",
        "serve",
        "cater",
        "contribute",
        "foster",
        "combine",
        "provide",
        "promote",
        "facilitate",
        "design",
        "organize",
        "organise",
        "accommodate",
        "purpose",
        "function",
        "role",
        "interconnect",
        "manage",
        "enhance",
        "create",
        "differ",
        "compare",
        "reflect",
        "arrange",
        "structure",
        "prioritize",
        "prioritise",
        "together",
    }
)
_PURPOSE_NOUNS = frozenset({"purpose", "function", "role", "use", "goal", "aim"})
_REFINE_OPENERS = (("what", "about"), ("how", "about"), ("and", "what", "about"), ("what", "if"))


def _stems(words: list[str]) -> set[str]:
    out = set()
    for w in words:
        out.add(lx.singular(w))
        out.add(lx.verb_lemma(w, _PREDICATES))
    return out


def global_reason(words: list[str]) -> str | None:
    """The no-target reason when ``words`` ask about the space as a whole, else None."""
    if not words or words[0] not in _OPENERS:
        return None
    j = 1
    while j < len(words) and words[j] in _AUX:
        j += 1
    if j < len(words) and words[j] in _PERSONAL:
        return None  # "how can I …", "how do individuals …" seek something to do
    stems = _stems(words)
    # "what is the use of …" asks about the space; "a spot to use the toilet" does not
    nouns = {lx.singular(w) for k, w in enumerate(words) if words[k - 1] != "to"}
    if words[0] == "what" and nouns & _PURPOSE_NOUNS and not stems & {"i", "someone"}:
        return GLOBAL_REASON
    if stems & _SUBJECTS and stems & _PREDICATES:
        return GLOBAL_REASON
    return None


def refine_frame(words: list[str]) -> tuple[bool, list[str]]:
    """(True, rest) when the request refines the previous one ("what about X?")."""
    for opener in _REFINE_OPENERS:
        if tuple(words[: len(opener)]) == opener:
            return True, words[len(opener) :]
    if len(words) >= 2 and words[0] == "and" and words[1] not in ("the", "a"):
        return True, words[1:]
    return False, words

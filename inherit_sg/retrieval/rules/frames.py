"""Request frames decided on the words before parsing.

- *global* questions about a space as a whole ("How does this space encourage both
  group socialisation and solitary relaxation?", "What are the main purposes of these
  areas?"): nothing to find, so the parse is an explicit no-object-target result;
- *refinements* of the previous request ("what about upstairs?", "and in the bedroom?").

The word lists are data (``lexicon.toml`` [frames]); words are compared by lemma too.
"""

from __future__ import annotations

from inherit_sg.retrieval.rules.tokens import Word
from inherit_sg.vocab.lexicon import lexicon

GLOBAL_REASON = "global question about the space as a whole: no object or place to find"


def global_reason(words: list[Word]) -> str | None:
    """The no-target reason when ``words`` ask about the space as a whole, else None."""
    frames = lexicon().frames
    if not words or words[0].text not in frames["openers"]:
        return None
    j = 1
    while j < len(words) and words[j].text in frames["auxiliaries"]:
        j += 1
    if j < len(words) and words[j].text in frames["personal"]:
        return None  # "how can I …", "how do individuals …" seek something to do
    stems = {w.text for w in words} | {w.lemma for w in words}
    stems |= {w.text[:-1] for w in words if w.text.endswith("s")}  # "subareas" (read as JJ)
    # "what is the use of …" asks about the space; "a spot to use the toilet" does not
    nouns = {w.lemma for k, w in enumerate(words) if k == 0 or words[k - 1].text != "to"}
    if words[0].text == "what" and nouns & frames["purpose_nouns"] and not stems & {"i", "someone"}:
        return GLOBAL_REASON
    if stems & frames["subjects"] and stems & frames["predicates"]:
        return GLOBAL_REASON
    return None


def refine_frame(words: list[Word]) -> tuple[bool, list[Word]]:
    """(True, rest) when the request refines the previous one ("what about X?")."""
    texts = [w.text for w in words]
    for opener in lexicon().refine_openers:
        if tuple(texts[: len(opener)]) == opener:
            return True, words[len(opener) :]
    if len(texts) >= 2 and texts[0] == "and" and texts[1] not in ("the", "a"):
        return True, words[1:]
    return False, words

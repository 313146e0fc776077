"""Ways of saying a thing that the grammar would misread, said plainly before spaCy
reads the text (:func:`plain_sayings`, called by :func:`.tokens.normalise`).

Most are negative-looking phrases that rule nothing out ("not bad", "not just long", "no
fewer than three", "there's no way to miss the radiator", "unlike the other one, …",
"you won't need a key, …", a sign's or a title's words), negatives said in a form the
grammar does not read ("dosen't", "dont have no arms", "missing its lace", "lacking"),
and a few that say where or which ("while I'm on the sofa" → near the sofa, "no other
chair in the room is this tall" → the tallest chair). They are applied in the order of
:data:`SAYINGS`.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from inherit_sg.vocab.objects import canonical_label

# "the chair that nobody is sitting in", "a desk no one uses": a thing not in use.
_NOBODY_USES = re.compile(
    r"(?<=[a-z])\s+(?:(that|which)\s+)?(?:nobody|no one|noone|no-one)(?:\s+is|'s)?\s+"
    r"(?:using|uses|used|sitting|sits|sat|working)(?:\s+(?:in|on|at))?(?:\s+(?:right\s+)?now)?"
    r"(?=\s*(?:[,.;!?]|$)|\s+(?:by|near|next|in|on|at|and|but|over|under)\b)",
    re.IGNORECASE,
)
# Misspelt negative contractions: "dosen't", "does'nt", "is'nt".
_MISSPELT_NOT = re.compile(
    r"\b(?:(dos[e]?n)|(does|is|are|was|were|did|do|could|would|should|has|have))'nt\b"
    r"|\bdos[e]?n'?t\b",
    re.IGNORECASE,
)
# "… while I'm on the sofa", "when I'm sitting at my desk", "… and I'm on the couch":
# where the speaker is; the thing sought is near it, not on it.
_WHILE_I_AM_AT = re.compile(
    r"\b(?:while|when|whilst|and)\s+(?:i'm|i\s+am|im)\s+(?:sitting\s+|lying\s+|working\s+)?(?:on|at)\s+",
    re.IGNORECASE,
)
# Sides seen from where the speaker is ("… on my left", "the one on the right"): "when
# I'm on the couch" then says where they sit, which the viewpoint reads.
_SPEAKER_SIDE = re.compile(
    r"\b(?:my|your|ur|the)\s+(?:left|right)\b|\b(?:behind|in\s+front\s+of)\s+me\b",
    re.IGNORECASE,
)


def _near_unless_sided(m: re.Match[str]) -> str:
    """ "while I'm on the sofa" → "near" (the thing sought is by it), unless the request
    says a side from there ("when I'm on the couch, the cushion on my left")."""
    return m.group(0) if _SPEAKER_SIDE.search(m.string) else "near "


# "check if the dishwasher's finished", "the fan's going": "'s" before a state is "is"
# (or "has" before "been"), not a possessive.
_IS_STATE = re.compile(
    r"\b(\w+)'s\s+(?=(?:finished|done|broken|full|empty|open|closed|off|running|going|"
    r"leaking|blocked|stuck|dirty|working|been)\b)",
    re.IGNORECASE,
)


def _is_or_has(m: re.Match[str]) -> str:
    """ "the dishwasher's finished" → "the dishwasher is finished"; "'s been" → "has"."""
    after = m.string[m.end() : m.end() + 4].lower()
    return f"{m.group(1)} {'has' if after == 'been' else 'is'} "


# "the chair where we eat", "the light where we watch telly": a thing said to be where
# the household does something is in the room made for it.
_WHERE_WE = re.compile(
    r"(?<=\w)\s+where\s+(?:we|you|they|the\s+family)\s+(?:usually\s+|all\s+)?"
    r"(eat|have\s+(?:dinner|lunch|breakfast|(?:our\s+)?meals)|cook|sleep|"
    r"watch\s+(?:tv|telly|television|movies|films))\b",
    re.IGNORECASE,
)
_ROOM_OF_DOING = {
    "eat": "dining room",
    "have": "dining room",
    "cook": "kitchen",
    "sleep": "bedroom",
    "watch": "tv room",
}


def _in_room_of_doing(m: re.Match[str]) -> str:
    """ "… where we eat" → " in the dining room" (after a thing, not opening a question)."""
    return f" in the {_ROOM_OF_DOING[m.group(1).split()[0].lower()]}"


# "there's no way to miss the radiator": it cannot be missed, as "you can't miss" says.
_NO_WAY_TO_MISS = re.compile(
    r"\b(?:there's|there\s+is|theres)\s+no\s+way\s+(?:to|you\s+(?:can|could|will|'ll))\s+miss\b",
    re.IGNORECASE,
)
# A double negative of having ("the chair that dont have no arms", "hasnt got no
# cushion"): it has none.
_DOUBLE_NO = re.compile(
    r"\b(?:don't|dont|doesn't|doesnt|hasn't|hasnt|haven't|havent|ain't|aint)\s+"
    r"(?:have|has|got)\s+(?:got\s+)?no\b",
    re.IGNORECASE,
)
# "not just long", "not only a lamp but also …", "not bad looking": no negation.
_NOT_ONLY = re.compile(r"\bnot\s+(?:just|only|merely|simply)\b", re.IGNORECASE)
_NOT_BAD = re.compile(r"\bnot\s+(?:too\s+|that\s+|so\s+)?bad\b", re.IGNORECASE)
# "not too far above the couch", "not that far from the door": near it.
_NOT_FAR = re.compile(
    r"\bnot\s+(?:too|that|so|very)\s+far\s+(?:away\s+)?(?:from|above|below|over|under)\b",
    re.IGNORECASE,
)
# "I not know the english name": a learner's "I don't know".
_I_NOT_KNOW = re.compile(r"\bi\s+(?:not|no)\s+know\b", re.IGNORECASE)
# "the no-slip mat": one adjective, as "non-slip" is.
_NO_HYPHEN = re.compile(r"\bno-(?=[a-z])", re.IGNORECASE)
# "the shoe that's missing its lace": without it ("my missing keys" stays).
_MISSING_PART = re.compile(
    r"\bmissing\s+(?=(?:its|a|an|the|one|some|any|his|her|their|both)\b)", re.IGNORECASE
)
# "no taller than the mug next to it": a size compared with a thing there, which is near;
# "no bigger than a shoebox": a size compared with a thing that is not there (dropped).
# Neither rules anything out.
_NO_COMPARED = re.compile(
    r"\bno\s+(?:bigger|larger|smaller|taller|shorter|wider|higher|longer|heavier|thicker)"
    r"\s+than\s+(?:(the|this|that|these|those|my|your)\b|an?\s+[a-z]+)",
    re.IGNORECASE,
)
# "no other chair in the room is this tall": the tallest chair.
_NO_OTHER_AS = re.compile(
    r"\bno\s+other\s+([a-z]+(?:\s+[a-z]+)?)\s+(?:(?:in|on)\s+(?:the|this)\s+[a-z]+\s+)?"
    r"(?:is|are)\s+(?:this|as|so|that)\s+(tall|big|large|small|long|wide|high|short)"
    r"\b(?:\s+as\s+(?:this\s+one|this|it))?",
    re.IGNORECASE,
)
_MOST = {
    "tall": "tallest", "big": "biggest", "large": "largest", "small": "smallest",
    "long": "longest", "wide": "widest", "high": "highest", "short": "shortest",
}  # fmt: skip
# "no other chair in the room is red": the red chair (a colour or material only).
_NO_OTHER_IS = re.compile(
    r"\bno\s+other\s+([a-z]+)\s+(?:(?:in|on)\s+(?:the|this)\s+[a-z]+\s+)?(?:is|are)\s+([a-z]+)\b",
    re.IGNORECASE,
)
# Remarks that rule nothing out: "unlike the other one, …", "you won't need a key, …".
_UNLIKE_OTHER = re.compile(r"\bunlike\s+the\s+other\s+(?:one|ones|[a-z]+)\s*,?", re.IGNORECASE)
_WONT_NEED = re.compile(
    r"\b(?:you|we|u)\s+(?:won't|will\s+not|wont|don't|do\s+not|dont)\s+need\s+[^,.;!?]*[,.;!?]",
    re.IGNORECASE,
)
# A title or name after "titled" / "called": "the book titled no country for old men".
_TITLED_NO = re.compile(
    r"\b(titled|called|named|entitled)\s+(?:no|not|don't|do\s+not)\b", re.IGNORECASE
)
# Words printed on a thing before its name: "the no shoes doormat", "a do not disturb
# hanger" (the thing named must be one the vocabulary knows).
_PRINTED_NO = re.compile(
    r"\b(the|a|an)\s+(?:no|do\s+not|don't|dont)\s+([a-z]+)\s+([a-z]+)\b", re.IGNORECASE
)
# "no fewer than three pillows", "no more than a metre away": a number, no negation.
_NO_FEWER = re.compile(r"\bno\s+(fewer|more|less)\s+than\b", re.IGNORECASE)
# The words of a sign before the word "sign": "the no smoking sign", "a do not disturb
# sign", "the don't feed the ducks notice".
_SIGN_WORDS = re.compile(
    r"\b(?:no|do\s+not|don't|dont)\s+(?:[a-z]+\s+){1,3}?(?=(?:sign|signs|notice|placard|sticker|"
    r"poster|label|plaque|hanger|tag)\b)",
    re.IGNORECASE,
)
# "a whiteboard with nothing written on it": nothing on it, however it got there.
_NOTHING_PUT = re.compile(
    r"\b(nothing|anything)\s+(?:written|drawn|placed|sitting|lying|left|kept|stored|stuck|put|"
    r"pinned|hanging)\s+(?=(?:on|in|inside)\b)",
    re.IGNORECASE,
)

# "I need a wee really bad": the toilet ("a wee dog" is a small one).
_NEED_A_WEE = re.compile(
    r"\b(need|needs|needed|want|have|having|go\s+for|going\s+for|dying\s+for|desperate\s+for)"
    r"\s+a\s+(?:wee|pee|wee-wee|poo)\b(?=\s*(?:[,.;!?]|$)|\s+(?:really|so|now|asap|and|but|badly|"
    r"urgently|please|where|which|take|quick|quickly|right)\b)",
    re.IGNORECASE,
)

# "mum and dad's bed", "mom n dads room": the parents' (one owner, as the grammar reads).
_BOTH_PARENTS = re.compile(
    r"\b(?:my\s+)?(?:mum|mom|mommy|mummy|mam|dad|daddy|papa|mama)\s+(?:and|n|&)\s+"
    r"(?:mum|mom|mommy|mummy|mam|dad|daddy|papa|mama)(?:'s|s'|s)(?=\s)",
    re.IGNORECASE,
)


def _the_only_one(match: re.Match[str]) -> str:
    """ "no other chair is red" → "the red chair", for a colour or a material; other
    words ("no other chair is there") stay."""
    from inherit_sg.retrieval.rules.tokens import colour_or_material

    kind, word = match.group(1), match.group(2)
    return f"the {word} {kind}" if colour_or_material(word.lower()) else match.group(0)


def _printed_words(match: re.Match[str]) -> str:
    """ "the no shoes doormat" → "the doormat" when the last word names a thing the
    vocabulary knows; other phrases stay."""
    det, thing = match.group(1), match.group(3)
    return f"{det} {thing}" if canonical_label(thing.lower()) is not None else match.group(0)


Replacement = str | Callable[[re.Match[str]], str]
# (pattern, replacement), applied in order by :func:`plain_sayings`.
SAYINGS: tuple[tuple[re.Pattern[str], Replacement], ...] = (
    (_MISSPELT_NOT, lambda m: f"{m.group(2) or 'does'}n't"),
    (_NOTHING_PUT, r"\1 "),
    (_WHILE_I_AM_AT, _near_unless_sided),
    (_WHERE_WE, _in_room_of_doing),
    (_IS_STATE, _is_or_has),
    (_NEED_A_WEE, r"\1 the toilet"),
    (_BOTH_PARENTS, "my parents'"),
    (_NO_WAY_TO_MISS, "you can't miss"),
    (_DOUBLE_NO, "has no"),
    (_NO_OTHER_IS, _the_only_one),
    (_UNLIKE_OTHER, ""),
    (_WONT_NEED, ""),
    (_TITLED_NO, r"\1"),
    (_PRINTED_NO, _printed_words),
    (_NO_OTHER_AS, lambda m: f"the {_MOST[m.group(2).lower()]} {m.group(1)}"),
    (_NOT_ONLY, ""),
    (_NOT_BAD, "good"),
    (_NOT_FAR, "near"),
    (_I_NOT_KNOW, "i don't know"),
    (_NO_HYPHEN, "non-"),
    (_MISSING_PART, "without "),
    (_NO_COMPARED, lambda m: f"near {m.group(1)}" if m.group(1) else ""),
    (_NO_FEWER, lambda m: "at least" if m.group(1).lower() != "more" else "at most"),
    (_SIGN_WORDS, ""),
    (_NOBODY_USES, lambda m: f" {m.group(1) or 'that'} is not in use"),
)


def plain_sayings(text: str) -> str:
    """``text`` with each of :data:`SAYINGS` said plainly."""
    for pattern, replacement in SAYINGS:
        text = pattern.sub(replacement, text)
    return text

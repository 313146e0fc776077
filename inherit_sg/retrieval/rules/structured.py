"""Requests written by software rather than people, read as the phrase a person writes.

A robot stack sends the map requests from task planners, behaviour trees, dashboards and
mission files as often as from people: "Step 3: pick up the sponge", "label:ceiling_fan
room:master_bedroom", ``find_object(name='laptop', near='desk')``,
``{"noun": "lamp", "rel": "next_to", "ref": "bed"}``, "kitchen/counter/mug",
"fridge -kitchen". :func:`plain_request` rewrites such a string into plain words ("the
laptop near the desk in the office") that the parser then reads like any other request;
text a person wrote comes back unchanged.

The keys that are understood (their names, not their order) are listed in the ``_KEYS``
tables below; a key that is not understood ("item_id", "desk") is left out, and a string
with no key understood is not read as key/value pairs at all.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field

from inherit_sg.vocab.rooms import room_type

# A step or role label before the request proper: "Step 3:", "Subtask 2/5:", "Action:",
# "search_query:", "goal =", "lookup ->".
_LABEL_WORDS = (
    r"step|subtask|sub-task|task|action|next action|goal|nav[ _]goal|objective|plan|"
    r"instruction|command|cmd|query|search|search[ _]query|request|req|lookup|intent|"
    r"mission|order|todo|to-do"
)
_STEP_LABEL = re.compile(
    rf"^\s*(?:(?:{_LABEL_WORDS})\b\s*(?:#?\d+(?:\s*(?:/|of)\s*\d+)?)?\s*(?::|=|->|=>)\s*)+",
    re.IGNORECASE,
)
# Numbered steps inside one string: "(1) go to the pantry (2) find the rice cooker".
_NUMBERED_STEP = re.compile(r"(?:^|\s)\(?\d{1,2}[).]\s+(?=[A-Za-z])")
# One key and its operator: "room:", "near=", "room!=", "cup.on ==".
_KEY = re.compile(r"(?:^|(?<=[\s;|,&{(]))([A-Za-z_][\w.]*)\s*(!=|==|=|:|->)\s*")
# A call: "find_object(name='laptop', near='desk')", "locate(cup) where cup.on == 'x'".
_CALL = re.compile(r"^\s*([A-Za-z_][\w.]*)\s*\((.*)\)\s*(?:(?:where|with|if)\b(.*))?$", re.DOTALL)
# A path of places ending in the thing: "warehouse/zone_B/aisle_12/forklift".
_PATH = re.compile(r"^\s*[\w\- ]+(?:/[\w\- ]+){2,}\s*$")
# A word ruled out in a search box: "fridge -kitchen", "blue recycling bin -black".
_MINUS_WORD = re.compile(r"(?:(?<=\s)|^)-(?=[A-Za-z])")
# A place numbered at the end of a keyword query: "fire extinguisher floor 2".
_NUMBERED_PLACE = re.compile(
    r"(\w+)\s+(floor|level|storey|aisle|zone|bay|row|ward|wing|section|room|building|unit)"
    r"\s+(\d+|[A-Za-z]\d*)\s*$",
    re.IGNORECASE,
)
# Words after which a numbered place already has its preposition or determiner.
_BEFORE_PLACE = frozenset({"in", "on", "at", "the", "a", "to", "from", "of", "by", "near"})
_ON_NUMBERED = frozenset({"floor", "level", "storey"})
# A word asking where, at the end of search-box words ("water bottle location").
_WHERE_WORD = re.compile(r"(?<=\w)\s+(?:location|position|whereabouts|where|loc)\s*\??\s*$", re.I)

# What each understood key says (see the module docstring).
_TARGET_KEYS = (
    "object", "obj", "name", "label", "noun", "category", "class", "object_class",
    "objectclass", "item", "target", "thing", "query", "goal", "find", "locate", "search",
    "object_name", "target_object", "entity", "what", "nav_goal", "search_query", "req",
    "request", "lookup", "objective", "intent",
)  # fmt: skip
# Label words that, as the only key of a string, label a sentence ("Goal: find the mug").
_LABEL_KEYS = frozenset(
    {"goal", "nav_goal", "query", "search", "search_query", "req", "request", "lookup",
     "objective", "intent", "target", "find", "locate"}
)  # fmt: skip
_TYPE_KEYS = ("type", "kind", "subtype")
_ATTRIBUTE_KEYS = frozenset(
    {"attr", "attrs", "attribute", "attributes", "color", "colour", "material", "size",
     "adjective", "adj", "desc", "description", "state", "shape", "constraints",
     "constraint", "superlative", "rank", "modifier", "modifiers", "property", "style"}
)  # fmt: skip
_PLACE_KEYS = frozenset(
    {"room", "location", "loc", "area", "place", "zone", "where", "space", "room_name",
     "region", "site", "hint", "location_hint", "room_type"}
)  # fmt: skip
# Place keys whose value is a room by name, known or not ("room: copy room").
_ROOM_KEYS = frozenset({"room", "room_name", "room_type"})
# Words that open a placing phrase of their own ("hint: living room, against the wall").
_PREPOSITIONS = frozenset(
    {"in", "on", "at", "by", "near", "under", "above", "below", "behind", "beside", "next",
     "against", "inside", "over", "between", "across", "opposite", "left", "right", "not"}
)  # fmt: skip
_FLOOR_KEYS = frozenset({"floor", "level", "storey", "story", "floor_number"})
_NEAR_KEYS = frozenset(
    {"near", "next_to", "nextto", "nearby", "close_to", "by", "ref", "reference",
     "landmark", "anchor", "beside", "relative_to", "near_object"}
)  # fmt: skip
# Keys that are a preposition of their own: "on=nightstand", "cup.on == 'nightstand'".
_PREPOSITION_KEYS = {
    "on": "on", "on_top_of": "on top of", "surface": "on", "support": "on", "in": "in",
    "inside": "inside", "container": "in", "under": "under", "below": "below",
    "beneath": "under", "above": "above", "over": "above", "behind": "behind",
    "left_of": "left of", "right_of": "right of", "in_front_of": "in front of",
    "from": "in", "source": "in",
}  # fmt: skip
_RELATION_KEYS = frozenset({"rel", "relation", "predicate", "spatial"})
_EXCLUDE_KEYS = frozenset(
    {"not", "exclude", "excluding", "except", "avoid", "not_in", "exclude_room",
     "exclude_rooms", "excluded", "without", "negative", "neg", "not_room", "ignore"}
)  # fmt: skip
_KNOWN_KEYS = frozenset(
    {*_TARGET_KEYS, *_TYPE_KEYS, *_ATTRIBUTE_KEYS, *_PLACE_KEYS, *_FLOOR_KEYS, *_NEAR_KEYS,
     *_PREPOSITION_KEYS, *_RELATION_KEYS, *_EXCLUDE_KEYS}
)  # fmt: skip
# Call names that ask for a thing ("find_object", "navigate_to", "goto").
_CALL_VERBS = re.compile(
    r"find|locate|search|navigate|nav|go|goto|move|get|fetch|pick|grab|bring|query|look|"
    r"where|detect|ground|point|reach|approach",
    re.IGNORECASE,
)


@dataclass
class _Fields:
    """What key/value pairs said, gathered before the phrase is written."""

    target: str = ""
    kind: str = ""
    attributes: list[str] = field(default_factory=list)
    relations: list[str] = field(default_factory=list)
    places: list[str] = field(default_factory=list)
    floor: str = ""
    excluded: list[str] = field(default_factory=list)
    extra: list[str] = field(default_factory=list)
    relation_word: str = ""


def _words(value: str) -> str:
    """A value as words: quotes, brackets and underscores gone, digits after a name
    kept apart ("bed_7" → "bed 7")."""
    value = value.strip().strip(",;|&").strip()
    value = re.sub(r"[\[\](){}\"'`]", " ", value)
    value = re.sub(r"[_]+", " ", value)
    return re.sub(r"\s+", " ", value).strip()


def _without_number(words: str) -> str:
    """ "bed 7" → "bed": an instance number says which one to a program, not to a map."""
    return re.sub(r"(?:\s+#?\d+)+$", "", words).strip() or words


def _the(words: str) -> str:
    low = words.lower()
    if low.startswith(("the ", "a ", "an ", "my ", "our ", "this ", "that ")):
        return words
    return f"the {words}"


def _place_phrase(words: str, room: bool = False) -> str:
    """ "kitchen" → "in the kitchen"; a thing rather than a room → "at the coat hook";
    "kitchen/counter" → "at the counter in the kitchen"; "living room, against the wall"
    → "in the living room against the wall"."""
    if "/" in words:
        parts = [p.strip() for p in words.split("/") if p.strip()]
        rooms = [p for p in parts if room_type(p) is not None]
        things = [f"at {_the(p)}" for p in parts if p not in rooms][-1:]
        return " ".join([*things, *(f"in {_the(r)}" for r in reversed(rooms))])
    out = []
    for n, part in enumerate(p.strip() for p in words.split(",")):
        if not part:
            continue
        if part.split()[0].lower() in _PREPOSITIONS:
            out.append(part)
        elif room_type(part) is not None or (room and n == 0):
            out.append(f"in {_the(part)}")
        else:
            out.append(f"at {_the(part)}")
    return " ".join(out)


def _floor_phrase(words: str) -> str:
    """ "2" → "on floor 2", "ground" → "on the ground floor", "3F" → "on floor 3"."""
    first = words.split()[0] if words.split() else words
    number = re.match(r"^-?\d+", first)
    if number:
        return f"on floor {number.group(0)}"
    if first.lower() in ("floor", "level", "storey", "story") and len(words.split()) > 1:
        return _floor_phrase(" ".join(words.split()[1:]))
    return f"on the {first} floor"


def _take(fields: _Fields, key: str, op: str, value: str) -> bool:
    """Fold one key/value pair into ``fields``; whether its key was understood (a pair
    with no value, or with a key not understood, says nothing)."""
    name = key.lower().rsplit(".", 1)[-1]
    words = _words(value)
    if not words or words in ("?", "*", "none", "null", "any"):
        return False
    negated = op == "!=" or name in _EXCLUDE_KEYS
    prefix, _, inner = name.partition("_")
    if prefix in ("exclude", "excluding", "except", "not", "no", "avoid") and inner:
        negated, name = True, inner  # "exclude_color": a colour ruled out
    if negated and name in _ATTRIBUTE_KEYS:
        fields.excluded.append(f"not {words.replace(',', ' ')}")  # "not white"
        return True
    if negated:
        placed = name in _PLACE_KEYS or "room" in name or room_type(words) is not None
        if words.split()[0].lower() in _PREPOSITIONS:
            fields.excluded.append(f"not {words}")  # "not near window"
        elif placed:
            fields.excluded.append(f"not {_place_phrase(words, room=True)}")
        else:
            fields.excluded.append(f"not {_the(words)}")
        return True
    if name in _TARGET_KEYS:
        if not fields.target:
            fields.target = words
        else:
            fields.attributes.append(words)
    elif name in _TYPE_KEYS:
        fields.kind = words
    elif name in _ATTRIBUTE_KEYS:
        fields.attributes.append(words.replace(",", " "))
    elif name in _FLOOR_KEYS:
        floor, _, rest = words.partition(",")
        fields.floor = _floor_phrase(floor.strip(" ()"))
        fields.extra += [w for w in (_words(rest.strip(" ()")),) if w]
    elif name in _PLACE_KEYS:
        fields.places.append(_place_phrase(_without_number(words), room=name in _ROOM_KEYS))
    elif name in _NEAR_KEYS:
        fields.relations.append(f"{fields.relation_word or 'near'} {_the(words)}")
        fields.relation_word = ""
    elif name in _PREPOSITION_KEYS:
        fields.relations.append(f"{_PREPOSITION_KEYS[name]} {_the(words)}")
    elif name in _RELATION_KEYS:
        fields.relation_word = words.lower()
    else:
        return False
    return True


def _pairs(text: str) -> list[tuple[str, str, str]]:
    """Every ``key op value`` in ``text``: the value runs to the next key."""
    found = list(_KEY.finditer(text))
    out = []
    for n, match in enumerate(found):
        end = found[n + 1].start() if n + 1 < len(found) else len(text)
        out.append((match.group(1), match.group(2), text[match.end() : end]))
    return out


def _phrase(fields: _Fields) -> str | None:
    """The plain phrase for what the pairs said; None when they named nothing."""
    target = fields.target or fields.kind
    if not target:
        return None
    if fields.target and fields.kind and fields.kind.lower() not in target.lower():
        target = f"{fields.kind} {target}"  # "obj: trolley; type: medication"
    if fields.relation_word:  # a relation with no landmark of its own
        fields.attributes.append(fields.relation_word)
    head = " ".join([*fields.attributes, target])
    parts = [_the(head), *fields.relations, *fields.places]
    if fields.floor:
        parts.append(fields.floor)
    return ", ".join([" ".join(parts), *fields.extra, *fields.excluded])


def _from_pairs(text: str) -> str | None:
    """Key/value text ("label:ceiling_fan room:master_bedroom") as a phrase, when it opens
    with a key and at least one key is understood."""
    pairs = _pairs(text)
    if not pairs or text[: _KEY.search(text).start()].strip():  # type: ignore[union-attr]
        return None
    names = [key.lower().rsplit(".", 1)[-1] for key, _, _ in pairs]
    if not any(name in _KNOWN_KEYS for name in names):
        return None
    if len(pairs) == 1 and names[0] in _LABEL_KEYS:
        return None  # "Goal: find the red mug": a label before a sentence
    fields = _Fields()
    understood = [_take(fields, key, op, value) for key, op, value in pairs]
    return _phrase(fields) if any(understood) else None


def _arguments(inside: str) -> list[str]:
    """A call's arguments, split at commas outside quotes and brackets."""
    out, depth, quote, start = [], 0, "", 0
    for i, c in enumerate(inside):
        if quote:
            quote = "" if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            out.append(inside[start:i])
            start = i + 1
    out.append(inside[start:])
    return [a.strip() for a in out if a.strip()]


def _from_call(text: str) -> str | None:
    """A call ("navigate_to('sink', room='kitchen')", "locate(cup) where cup.on ==
    'nightstand'") as a phrase: the first plain argument is the thing."""
    match = _CALL.match(text)
    if match is None or not _CALL_VERBS.search(match.group(1)):
        return None
    fields = _Fields()
    for arg in _arguments(match.group(2)):
        pair = _KEY.match(arg)
        if pair is not None and pair.group(2) in ("=", ":", "!=", "=="):
            _take(fields, pair.group(1), pair.group(2), arg[pair.end() :])
        elif not fields.target:
            fields.target = _words(arg)
    for key, op, value in _pairs(match.group(3) or ""):
        _take(fields, key, op, value)
    return _phrase(fields)


def _from_json(text: str) -> str | None:
    """A JSON object in the text ('query{"noun": "lamp", "rel": "next_to", "ref": "bed"}')
    as a phrase."""
    start, end = text.find("{"), text.rfind("}")
    if start < 0 or end <= start or text[end + 1 :].strip():
        return None
    try:
        data = json.loads(text[start : end + 1])
    except ValueError:
        return None
    if not isinstance(data, dict):
        return None
    fields = _Fields()
    understood = False
    for key, value in data.items():
        if isinstance(value, dict):
            for inner, deeper in value.items():
                understood |= _take(fields, str(inner), ":", str(deeper))
        elif isinstance(value, list):
            for item in value:
                understood |= _take(fields, str(key), ":", str(item))
        elif value is not None:
            understood |= _take(fields, str(key), ":", str(value))
    return _phrase(fields) if understood else None


def _from_path(text: str) -> str | None:
    """ "kitchen/counter/mug" → "the mug at the counter in the kitchen": the last part is
    the thing, a room before it places it, and the part just before it is where it is."""
    if " " in text.strip() or _PATH.match(text) is None:
        return None
    parts = [_without_number(_words(p)) for p in text.strip().split("/") if _words(p)]
    if len(parts) < 3:
        return None
    *before, thing = parts
    phrase = [_the(thing)]
    rooms = [p for p in before if room_type(p) is not None]
    if before[-1] not in rooms:
        phrase.append(f"at {_the(before[-1])}")
    phrase += [f"in {_the(r)}" for r in reversed(rooms)]
    return " ".join(phrase)


def _keyword_query(text: str) -> str:
    """Search-box words: "-kitchen" rules the kitchen out, and a numbered place at the end
    ("fire extinguisher floor 2") is where the thing is."""
    if len(text.split()) > 8 or re.search(r"[.?!]", text):
        return text
    text = _MINUS_WORD.sub("not ", text)

    def placed(match: re.Match[str]) -> str:
        before, word = match.group(1), match.group(2)
        if before.lower() in _BEFORE_PLACE:
            return match.group(0)
        preposition = "on" if word.lower() in _ON_NUMBERED else "in"
        return f"{before} {preposition} {word} {match.group(3)}"

    if _BEFORE_PLACE & set(re.findall(r"[a-z]+", text.lower())):
        return text  # words with grammar of their own
    text = _WHERE_WORD.sub("", text)  # "water bottle location": where it is
    if len(text.split()) > 2:
        text = _NUMBERED_PLACE.sub(placed, text)
    thing, comma, place = text.rpartition(",")
    place = place.strip()
    short = comma and thing.strip() and "," not in thing and len(place.split()) <= 3
    if short and room_type(place) is not None:
        text = f"{thing.strip()} in {_the(place)}"  # "hand towel, powder room"
    return text


def plain_request(text: str) -> tuple[str, str | None]:
    """``text`` rewritten as plain words when software wrote it, with a note saying how it
    was read; text a person wrote comes back as it is, with no note."""
    original = text
    for form, reader in (
        ("a call", _from_call),
        ("JSON", _from_json),
        ("key/value pairs", _from_pairs),
        ("a path", _from_path),
    ):
        for attempt in (text, _STEP_LABEL.sub("", text, count=1)):
            phrase = reader(attempt)
            if phrase is not None:
                return phrase, f"written by software ({form}): read as {phrase!r}"
    text = _STEP_LABEL.sub("", text, count=1)
    if len(_NUMBERED_STEP.findall(text)) > 1:
        text = _NUMBERED_STEP.sub(". ", text).strip(" .")
    text = _keyword_query(text)
    if text != original:
        return text, f"written by software: read as {text!r}"
    return original, None

"""Route instructions that end at a thing (Room-to-Room, RxR, REVERIE style): "Exit the
office and go left. Walk down the hallway and go into the bathroom on your right. Stop at
the tub."

The rooms, doors and landmarks passed on the way are not what is sought: the thing the
route ends at is ("stop at / by / in front of …", "wait by …", "stop once you reach …").
:func:`route_goal` reduces such a request to that phrase, in the last room the route
enters when the phrase names none ("… into the bathroom … Stop at the tub" → "the tub in
the bathroom"). What the route says on the way ("don't go up the stairs") then rules
nothing out about the goal, and when the route last went up or down the stairs the goal
is upstairs or downstairs.
"""

from __future__ import annotations

from inherit_sg.retrieval.rules.tokens import COMMA, IN, THE, Word
from inherit_sg.vocab.rooms import room_words

# Verbs that end a route, and the words between them and the goal phrase.
_STOPPING = frozenset({"stop", "wait", "halt", "pause", "finish"})
_GOAL_WORDS = frozenset({
    "at", "by", "beside", "near", "next", "to", "in", "on", "under", "behind", "facing",
    "beneath", "below", "underneath", "above", "over", "inside", "opposite", "against",
    "front", "of", "right", "just", "directly", "once", "when", "as", "soon", "you",
    "reach", "get", "until", "the", "a", "an",
})  # fmt: skip
_REACHING = frozenset({"reach", "get"})
# Words after a room that place the goal by a thing in it ("the porch next to the flower
# pot": the flower pot).
_BESIDE = frozenset({"next", "by", "beside", "near", "front", "behind", "under", "facing",
                     "opposite", "against", "beneath", "below", "underneath"})  # fmt: skip
# Words before a room that say the route goes into it ("into the bathroom", "enter the den").
_ENTERING = frozenset({"into", "to", "in", "enter", "inside", "reach", "toward", "towards"})
_ARTICLES = frozenset({"the", "a", "an"})


def route_goal(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request reduced to the goal of the route it describes (see the module
    docstring); unchanged when it names no stop at a thing."""
    flat = [w for sentence in sentences for w in sentence]
    found = _goal_start(flat)
    if found is None:
        there = _stop_there(flat)
        if there is None:
            return sentences
        stop, goal = there
    else:
        stop, start = found
        goal = list(flat[start:])
    while goal and goal[-1].text in (".", "!", "?"):
        goal.pop()
    if not goal or not any(w.pos in ("NOUN", "PROPN") for w in goal):
        return sentences
    goal = _past_room(_past_position(goal))
    if not goal:
        return sentences
    if _opens_with_room(goal):  # "wait in the break room": a room, not a thing
        return [goal] if found is None else sentences
    if not _names_room(goal):
        room = _last_room_entered(flat[:stop])
        if room:
            goal += [IN, THE, *room]
    floor = _floor_reached(flat[:stop])
    if floor is not None and not any(w.text in _FLOOR_WORDS for w in goal):
        goal = [floor, COMMA, *goal]  # "upstairs, the umbrella stand by the front door"
    return [goal]


_FLOOR_WORDS = frozenset({"upstairs", "downstairs", "floor", "level", "storey", "story"})
_UPSTAIRS = Word("upstairs", "upstairs", "ADV", "RB", "advmod")
_DOWNSTAIRS = Word("downstairs", "downstairs", "ADV", "RB", "advmod")


def _floor_reached(route: list[Word]) -> Word | None:
    """ "upstairs" / "downstairs" when the route last goes up or down a floor ("go up the
    stairs", "head downstairs"), else None."""
    found = None
    for k, word in enumerate(route):
        if _negated_at(route, k):
            continue
        after = " ".join(w.text for w in route[k + 1 : k + 3])
        if word.text == "upstairs" or (word.text == "up" and after in ("the stairs", "the steps")):
            found = _UPSTAIRS
        elif word.text == "downstairs" or (
            word.text == "down" and after in ("the stairs", "the steps")
        ):
            found = _DOWNSTAIRS
    return found


def _negated_at(words: list[Word], k: int) -> bool:
    """Whether the route step around word ``k`` is one the speaker warns against ("don't
    go into the kitchen", "avoid the stairs")."""
    return any(w.text in ("not", "n't", "never", "avoid") for w in words[max(0, k - 3) : k])


def _after_article(goal: list[Word]) -> int:
    """Where a phrase's words start after its article ("the porch …": 1)."""
    return 1 if goal[0].text in _ARTICLES else 0


def _past_room(goal: list[Word]) -> list[Word]:
    """ "the porch next to the flower pot on the top step": a goal that opens with a room
    and places a thing in it is that thing, in that room."""
    j = _after_article(goal)
    for n in (3, 2, 1):
        room = goal[j : j + n]
        if len(room) == n and _is_room_phrase([w.text for w in room]):
            k = j + n
            while k < len(goal) and goal[k].text in _GOAL_WORDS - _ARTICLES:
                k += 1
            lead = {w.text for w in goal[j + n : k]}
            if k >= len(goal) or not lead & _BESIDE:
                return goal  # "the break room on level 2" stays a room
            return [*goal[k:], IN, THE, *room]
    return goal


_POSITIONS = frozenset({"top", "bottom", "foot", "end", "middle", "side", "edge", "head"})


def _past_position(goal: list[Word]) -> list[Word]:
    """ "the foot of the bed", "the end of the hallway": the thing or place itself."""
    j = _after_article(goal)
    if len(goal) > j + 2 and goal[j].text in _POSITIONS and goal[j + 1].text == "of":
        return goal[j + 2 :]
    return goal


def _opens_with_room(goal: list[Word]) -> bool:
    """Whether a goal phrase is a room or a part of the building ("the break room on
    level 2", "the stairs")."""
    head = []
    for word in goal:
        if word.pos == "ADP":
            break
        head.append(word.text)
    return bool(head) and (
        head[-1] in ("room", "rooms") or any(_is_room_phrase(head[i:]) for i in range(len(head)))
    )


def _goal_start(words: list[Word]) -> tuple[int, int] | None:
    """Where the last stopping verb of a route stands and where its goal phrase starts
    (the first word after the words that lead to it), or None."""
    for k in range(len(words) - 1, -1, -1):
        if words[k].lemma not in _STOPPING or words[k].pos not in ("VERB", "NOUN", "PROPN"):
            continue
        if k > 0 and words[k - 1].text in ("bus", "the", "a"):
            continue  # "the bus stop"
        j = k + 1
        led = False
        while j < len(words) and words[j].text in _GOAL_WORDS:
            if words[j].text == "front" and (j + 1 >= len(words) or words[j + 1].text != "of"):
                break  # "wait at the front door": the door's own word, not "in front of"
            led = led or words[j].text not in _ARTICLES | {"right", "just", "directly"}
            if words[j].lemma in _REACHING:
                led = True
            j += 1
        if not led or j >= len(words) or words[j].tag == "VB":
            return None  # "can't wait to try the new coffee machine"
        start = j
        while start > k + 1 and words[start - 1].text in _ARTICLES:
            start -= 1  # keep the determiner: "the tub"
        return k, start
    return None


_THERE = frozenset({"there", "here"})
_PHRASE_TAGS = frozenset({"DET", "ADJ", "NOUN", "PROPN", "NUM"})


def _stop_there(words: list[Word]) -> tuple[int, list[Word]] | None:
    """Where a route ends with "stop there" ("walk to the big plant and stop there",
    "you'll see a big couch, stop there") and the thing named last before it; None when
    the route does not end so or names no thing before."""
    if len(words) < 2 or words[-1].text not in _THERE:
        return None
    k = len(words) - 2
    if words[k].lemma not in _STOPPING or words[k].pos not in ("VERB", "NOUN", "PROPN"):
        return None
    last = next((j for j in range(k - 1, -1, -1) if words[j].pos in ("NOUN", "PROPN")), None)
    if last is None or any(w.pos == "VERB" for w in words[last + 1 : k]):
        return None  # "put the box down and stop there"? a thing, then another act
    if words[last].lemma == "one":
        return None  # "not the left sink but the right one, stop there": read as a whole
    first = _phrase_start(words, last)
    # "the washing machine in the utility room": the thing, with where it is
    while first > 1 and words[first - 1].text in _PLACING and words[first - 2].pos == "NOUN":
        first = _phrase_start(words, first - 2)
    return k, list(words[first : last + 1])


# Prepositions that place a thing named before a stop ("the fridge in the garage").
_PLACING = frozenset({"in", "inside", "on", "of", "by", "near", "beside"})


def _phrase_start(words: list[Word], last: int) -> int:
    """Where the noun phrase that ends at ``last`` starts (its article, adjectives and
    compounds)."""
    first = last
    while first > 0 and words[first - 1].pos in _PHRASE_TAGS:
        first -= 1
    return first


def _names_room(words: list[Word]) -> bool:
    """Whether a phrase names a room ("… in the gym", "on the landing")."""
    texts = [w.text for w in words]
    return any(
        _is_room_phrase(texts[i : i + n]) for n in (1, 2, 3) for i in range(len(texts) - n + 1)
    )


def _is_room_phrase(texts: list[str]) -> bool:
    """Whether ``texts`` is itself a room name or alias, not a longer phrase ending in one."""
    return " ".join(texts) in room_words()


def _last_room_entered(words: list[Word]) -> list[Word]:
    """The words of the last room the route goes into ("into the bathroom", "enter the
    master bedroom"), or none."""
    best: list[Word] = []
    for k, word in enumerate(words):
        if word.text not in _ENTERING or _negated_at(words, k):
            continue
        j = k + 1
        while j < len(words) and words[j].text in _ARTICLES | {"first", "second", "next"}:
            j += 1
        for n in (3, 2, 1):
            phrase = words[j : j + n]
            if len(phrase) == n and _is_room_phrase([w.text for w in phrase]):
                best = phrase
                break
    return best

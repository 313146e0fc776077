"""Verb phrases that name a function: "where can I wash my hands", "something to sit
on", "a place for a quick snack", "while watching TV".

A verb is read as a verb only in verb position (after "to", a modal, a person, "and",
"for", "while" or at the start); after a determiner it is a noun ("a drink"). The verb
and its object words pick a function sense (:mod:`.functions`). An object reached by a
locative preposition ("sit on a recliner sofa") or by a light verb ("use the printer")
is offered as the request's head.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from inherit_sg.retrieval.constraints import (
    Constraint,
    FunctionConstraint,
    RelationConstraint,
    RoomConstraint,
    Superlative,
)
from inherit_sg.retrieval.rules.cursor import weighted
from inherit_sg.retrieval.rules.functions import (
    Sense,
    has_own_sense,
    knows_verb,
    match_function,
    open_function,
)
from inherit_sg.retrieval.rules.phrase import ANAPHOR, GENERIC, NP, OBJECT, ROOM
from inherit_sg.retrieval.rules.sentences import FETCH_VERBS, PARTICULAR
from inherit_sg.retrieval.rules.tagger import Tok
from inherit_sg.vocab.lexicon import lexicon

if TYPE_CHECKING:
    from inherit_sg.retrieval.rules.grammar import Grammar

# Verbs whose negated object is ruled out: "I don't want the leather chair", "never use
# the red towel".
_CHOICE_VERBS = frozenset(
    {"want", "need", "like", "use", "mean", "choose", "pick", "take", "grab", "bring"}
)
_VERB_CONTEXT = (
    "to", "modal", "seeker", "and", "or", "for", "while", "rel", "wh", "comma", "overb", "sub",
    "neg",
)  # fmt: skip
# Verbs that put their object somewhere: with a named destination, that is the target.
_PLACING_VERBS = frozenset(
    {"put", "place", "set", "drop", "throw", "toss", "dump", "stick", "stash", "hang", "chuck"}
)
_VERB_FILLERS = ("want", "need", "like", "possible", "wish", "mood", "fancy")
# Prepositions inside a verb's object ("a cup of tea", "a place for my coat").
_OBJECT_PREPOSITIONS = frozenset({"of", "for", "to", "with", "about"})
_SPEAKERS = frozenset({"i", "we", "me", "us"})


_LINKING_VERBS = frozenset({"look", "seem", "feel", "sound", "appear"})


def _after_linking_verb(g: Grammar, start: int) -> bool:
    """Whether the word at ``start`` follows "looks" / "seems" / "feels": it says how
    something looks ("my outfit looks cool"), it is no verb of the speaker's."""
    return start > 0 and g.toks[start - 1].lemma in _LINKING_VERBS and g.toks[start - 1].tag != "VB"


def _passive_of_thing(g: Grammar, start: int) -> bool:
    """Whether the verb at ``start`` is a passive said of a thing ("so it gets washed",
    "where they'll be cleaned"): it restates what happens to the thing already named,
    not something the speaker wants to do."""
    tok = g.toks[start]
    if tok.tag != "VBN" or start < 2:
        return False
    aux, subject = g.toks[start - 1], g.toks[start - 2]
    return aux.lemma in ("get", "be") and subject.pos == "PRON" and subject.text not in _SPEAKERS


def _thing_does(g: Grammar, start: int) -> bool:
    """Whether the verb at ``start``, which the vocabulary does not know, says what a thing
    does or what happens to it ("the toilet keeps running", "the loo roll has run out"):
    its subject, past auxiliaries and adverbs, names a thing or a room, not a person."""
    k = start - 1
    while k >= 0 and g.toks[k].has("overb", "be", "have", "modal", "adv", "neg"):
        if g.toks[k].has("seeker", "det", "noun", "room"):
            break
        k -= 1
    if k == start - 1 or k < 0:
        return False  # no auxiliary between: "the chair to nap in" is read elsewhere
    subject = g.toks[k]
    return subject.has("noun", "room", "unk") and not subject.has("seeker")


def verb_reading(tok: Tok) -> str | None:
    """The lemma ``tok`` has as a function or light verb, if any."""
    if tok.has("fverb"):
        return str(tok.tags["fverb"])
    if tok.has("have"):
        return "have"
    verb = tok.tags.get("overb")
    return verb if verb in lexicon().light_verbs else None


def is_verb_here(g: Grammar) -> bool:
    """Whether the current token is a verb in verb position."""
    tok = g.peek()
    if tok is None:
        return False
    if verb_reading(tok) is None:
        return _open_verb_here(g, tok)
    prev = g.peek(-1) if g.i > 0 else None
    if prev is None:
        return not tok.has("room", "noun") or (tok.has("fverb") and g.at("det", k=1))
    if prev.has("wh") and prev.text in ("which", "what", "whose") and tok.has("noun", "room"):
        return False  # "which bin is closest …": "which" picks a thing, "bin" names it
    if prev.has(*_VERB_CONTEXT) or (prev.has("adv") and not prev.has("det")):
        return not prev.has("det")
    if prev.has("filler"):
        if any(w in prev.text for w in _VERB_FILLERS):
            return True
        if tok.has("fverb") and tok.has("super", "adj") and g.at("det", k=1):
            return True  # "please lower the blinds": the verb, not "lower" = lowest
        if prev.text.endswith(" to"):  # "go to relax" (but "go to the study")
            return not tok.has("noun", "room", "unk")
    return False


def _open_verb_here(g: Grammar, tok: Tok) -> bool:
    """Whether a verb the vocabulary does not know opens what the speaker wants to do:
    a base form after "I want to" / "I'd like to" / "I need to" or after "(where) can I"
    / "could we" ("I want to floss", "where can I weigh myself")."""
    if not (tok.has("overb") and tok.tag == "VB") or g.i < 2:
        return False
    prev, before = g.peek(-1), g.peek(-2)
    if prev is None or before is None:
        return False
    if prev.has("to") and before.has("filler"):
        return any(w in before.text for w in _VERB_FILLERS)
    if not (prev.has("seeker") and before.has("modal")):
        return False
    # "where can I …", "can I …"; not "what can I pull down to …", which asks for a thing
    opener = g.peek(-3) if g.i >= 3 else None
    return opener is None or opener.text == "where"


def kept_out(tok: Tok) -> bool:
    """Whether ``tok`` is a verb of going somewhere, whose negation keeps the speaker out
    of the place that follows ("don't go into the garage")."""
    return tok.lemma in lexicon().viewpoint_verbs


def parse_vp(g: Grammar, purpose: bool = False) -> tuple[list[Constraint], NP | None]:
    """Parse a verb phrase at the cursor → function constraints and a head candidate.

    ``purpose``: the phrase says what something is for ("something to weigh myself on",
    "a spot to make a phone call"); a verb the vocabulary does not know, even with a named
    object, then gives a function in the request's own words rather than a head."""
    start = g.i
    tok = g.advance()
    if _passive_of_thing(g, start) or _after_linking_verb(g, start):
        g.notes.append(f"'{tok.text}' said of a thing: not a need of its own")
        return [], None
    verb = verb_reading(tok) or tok.text
    refused = g.take_neg()
    if refused and tok.lemma not in _CHOICE_VERBS and not kept_out(tok):
        g.notes.append(f"negation before verb {tok.text!r} ignored")
    stress = g.take_stress()
    while g.at("adv") and not g.at("prep"):
        g.advance()
    while (particle := g.peek()) is not None and particle.tag == "RP" and g.np_start(1):
        g.advance()  # "wipe down the kitchen island", "pick up the book"
    if tok.lemma in FETCH_VERBS and g.text_at() in ("me", "us") and g.np_start(1):
        g.advance()  # "bring me the juice": the thing comes after whom it is for
    head: NP | None = None
    obj: NP | None = None
    nxt = g.peek()
    lx = lexicon()
    if nxt is not None and nxt.text in lx.locative_prepositions and verb in lx.locative_verbs:
        snap = g.state()
        g.advance()
        place = g.parse_np(landmark=True)
        if place is not None and place.kind == OBJECT and place.known:
            head = place
        else:
            g.restore(snap)
            if place is None:
                g.advance()  # a particle: "something to sit on"
    elif (
        nxt is not None
        and _object_marker(nxt, verb)
        and g.np_start(1)
        and not any(g.at("floor", k=k) for k in (1, 2))  # "… on the first floor"
    ):
        g.advance()  # "dispose of trash", "check for updates", "engage in conversation"
        obj = _objects(g, landmark=verb not in lx.light_verbs)
    elif g.np_start() and not g.at("floor"):
        obj = _objects(g, landmark=verb not in lx.light_verbs)
    if obj is not None:
        verb = _particle_after(g, verb, obj)  # "put some music on": "put on"
    elif (
        head is None and nxt is not None and knows_verb(f"{verb} {nxt.text}") and not g.np_start(1)
    ):
        g.advance()  # "something to stand on (in the kitchen)": a sense of its own
        verb = f"{verb} {nxt.text}"
    by_means = _by_means(g, start)  # "what could I use to get the creases out …"
    if obj is not None and by_means:
        _take_source(g)
    words = [t.text for t in g.toks[start + 1 : g.i]]
    lemmas = [lemma_of(t) for t in g.toks[start + 1 : g.i]]
    own = _before_place(g.toks[start + 1 : g.i])
    sense = match_function(verb, words[:own], obj.words if obj is not None else None, lemmas[:own])
    if sense is None and obj is None and g.at("wh"):
        sense, words = _wh_object(g, verb, words)
    if sense is None and tok.has("wh"):
        # "what's a good spot …", "what lamp is on": a question word, not the verb
        # "what"; a thing named after it is read again as the question's own words
        asked = g.peek(start + 1 - g.i)
        if asked is not None and asked.has("noun"):
            g.i = start + 1
        return [], None
    named = obj is not None and obj.kind == OBJECT and bool(obj.labels)
    if named and refused and tok.lemma in _CHOICE_VERBS:
        assert obj is not None  # "I don't want the leather chair": that one is ruled out
        obj.excluded = True
        g.notes.append(f"'not {tok.text} {obj.noun}': ruled out")
        return [], obj
    if _past(g, start) and (named or _somewhere(obj)):
        # "where did I put my glasses", "I left my keys on …": the thing put is sought
        assert obj is not None
        g.notes.append(f"'{tok.text} {obj.noun}' (past): the object is the target")
        return [], obj
    first = _first_object_word(words)  # "put this …": at hand; "put my …": particular
    going = _destination_relation(obj) if tok.lemma in _PLACING_VERBS and named else None
    if going is not None and obj is not None and first not in _AT_HAND:
        # "put the DVD on the top shelf", "hang the coat on the hook": the thing to move
        # is sought; where it goes says little about where it is now ("put this letter
        # on the desk": the letter is at hand, the desk is sought). It stays a hint: the
        # place to go when the map has no such thing ("put my book on the bedside table")
        hint = replace(going, weight=weighted("relation", "hedge"), text=f"goes {going.text}")
        obj.constraints = [hint if c is going else c for c in obj.constraints]
        g.notes.append(
            f"'{tok.text} {obj.noun} … {going.landmark.target.noun}': the thing moved is "
            "the target, not where it goes"
        )
        return [], obj
    if (
        tok.lemma in _PLACING_VERBS
        and named
        and obj is not None
        and not purpose
        and not _worn(g)
        and _imperative(g, start)
        and first in PARTICULAR - _AT_HAND
    ):
        # "put my slippers by the bed", "put the mug away", "put the apple from the
        # counter in the fridge": one particular thing to move, found first ("put this
        # letter on the desk": the letter is at hand, where it goes is sought)
        g.notes.append(f"'{tok.text} {obj.noun}': the thing moved is the target")
        return [], obj
    at_hand = first in _AT_HAND  # "rinse this in the kitchen sink"
    destination = _destination(obj) if tok.lemma in _PLACING_VERBS or at_hand else None
    if (
        destination is not None
        and obj is not None
        and obj.kind == ANAPHOR
        and any(t.has("noun") for t in g.toks[:start])  # looked back only for a pronoun
    ):
        # "pick up the mug … and put it in the sink": "it" is the thing named before,
        # still the target; where it goes says nothing about where it is
        said = obj.noun or "it"
        g.notes.append(
            f"'{tok.text} {said} … {destination.noun}': where the thing named before goes"
        )
        return [], None
    if destination is not None:
        # "put this in the recycling bin by the back door": where it goes is the target
        g.notes.append(f"'{tok.text} … {destination.noun}': the destination is the target")
        return [], destination
    if named and tok.lemma in _KEEP_VERBS and _asks_where(g, start):
        assert obj is not None
        if not has_own_sense(verb, words, lemmas):
            # "where do we keep the iron?": where the iron is, not a place to store things
            g.notes.append(f"'where … {tok.text} {obj.noun}': the object is the target")
            return [], obj
    if (
        (verb in lx.light_verbs or _imperative(g, start))
        and obj is not None
        and obj.kind == OBJECT
        and obj.known
        and (
            not has_own_sense(verb, words[:own], lemmas[:own])
            or _acts_on_particular(g, start, obj, words, purpose or by_means)
        )
    ):
        # "find a laptop in the work area": a named thing, not a purpose ("laptop" → work);
        # but "take a shower" is the verb's own sense (wash)
        g.notes.append(f"'{tok.text} {obj.noun}': the object is the target")
        return [], obj
    # a verb the vocabulary does not know, with a word it does not know either ("blow my
    # nose"), says what the speaker wants to do; with a known thing ("inspect the
    # heater") the thing is sought
    thing = named and ((obj is not None and obj.known) or verb_reading(tok) is not None)
    if sense is None and (verb in lx.light_verbs or (thing and not purpose)):
        if obj is not None and obj.kind != ANAPHOR:
            g.notes.append(f"'{tok.text} {obj.noun or obj.kind}': the object is the target")
        return [], obj
    if sense is not None and _fetches_particular(tok, obj, words) and not by_means:
        # "bring the juice", "grab me a soda from the fridge": a thing to carry; what
        # it is for only hedges where to look
        assert obj is not None
        g.notes.append(f"'{tok.text} {obj.noun}': a thing fetched, the object is the target")
        serves = match_function(None, obj.words[-1:])  # "soda" → drink; not "pass" → enter
        if serves is None:
            return [], obj
        fetched = FunctionConstraint(function=serves[0], labels=serves[1],
                                     weight=weighted("function", "hedge"), text=obj.noun)  # fmt: skip
        return [fetched], obj
    if sense is None and tok.lemma in lx.mental_verbs:
        return [], None  # "can't tell the colour well", "I don't know the name": no need
    made: list[Constraint] = []
    alone = refused and not any(t.has("noun", "room") for t in g.toks)
    if sense is None and obj is not None and obj.kind == ANAPHOR and knows_verb(verb) and not alone:
        # "what can I pull down to block it?": the verb's senses need their object, said
        # before ("the sun is glaring"), where the need was read already; but "I can't
        # reach it", said alone, is the need
        g.notes.append(f"'{tok.text} {obj.noun or 'it'}': the object was said before")
    elif sense is None and _thing_does(g, start):
        g.notes.append(f"'{tok.text}' said of a thing: not a need of its own")
    else:
        function, labels = sense if sense is not None else (open_function(verb, words), ())
        if sense is None:
            g.notes.append(f"function {function!r} is not in the lexicon (kept as written)")
        span = " ".join([tok.text, *words]).strip()
        weight = weighted("function", stress)
        made.append(FunctionConstraint(function=function, labels=labels, weight=weight, text=span))
    # "use the toilet close to the bookshelf", "get a drink in the kitchen": the object's
    # relations and places place the target
    # but with "what could I use to get the creases out of my shirt" the object is what
    # the thing sought acts on, and where the object is says nothing of where it is
    where = (
        [c for c in obj.constraints if _places_target(c, obj)]
        if obj is not None and not by_means
        else []
    )
    places = list(obj.places) if obj is not None else []
    return [*made, *where, *places, *_done_from(g)], head


# Particles that may stand after a verb's object ("put some music on", "turn it off"),
# and words that may end the clause after them ("… on for me", "… on please").
_TRAILING_PARTICLES = frozenset({"on", "off", "up", "down", "out", "away"})
_CLAUSE_TAILS = frozenset({"please", "for", "now", "again", "then", "."})


def _particle_after(g: Grammar, verb: str, obj: NP) -> str:
    """``verb`` with the particle that follows its object at the end of the clause, when
    the two name a sense with that object ("put some music on": "put on" music); else
    ``verb``. The particle is consumed."""
    tok = g.peek()
    if tok is None or tok.text not in _TRAILING_PARTICLES or " " in verb or g.np_start(1):
        return verb
    after = g.peek(1)
    if after is not None and not (after.has("comma", "and") or after.text in _CLAUSE_TAILS):
        return verb
    phrasal = f"{verb} {tok.text}"
    if not has_own_sense(phrasal, obj.words):
        return verb
    g.advance()
    return phrasal


def _acts_on_particular(g: Grammar, start: int, obj: NP, words: list[str], aside: bool) -> bool:
    """Whether a command does something to one particular named thing ("rinse the dirty
    plate in the sink", "chill the lettuce in the fridge", "heat a cup of coffee in the
    microwave"): the thing is sought, not what the verb is done with. A light verb ("do
    the dishes", "take a shower") keeps its own sense."""
    if aside or not obj.labels or g.toks[start].lemma in lexicon().light_verbs or _worn(g):
        return False
    if not _imperative(g, start):
        return False
    placed = any(isinstance(c, RelationConstraint) for c in obj.constraints)
    return _first_object_word(words) in PARTICULAR or placed


# Words for a thing the speaker has at hand ("put this letter on the desk").
_AT_HAND = frozenset({"this", "these"})


def _first_object_word(words: list[str]) -> str:
    """The word that opens a verb's object, past whom it is for ("put me the …")."""
    return next((w for w in words if w not in ("me", "us")), "")


def _fetches_particular(tok: Tok, obj: NP | None, words: list[str]) -> bool:
    """Whether a verb of fetching takes one particular thing the vocabulary does not
    name ("bring the juice", "grab me a soda from the fridge"), not a kind of thing for
    a purpose ("get a drink"): a definite or possessive word before it, or a source."""
    if tok.lemma not in FETCH_VERBS or obj is None or obj.kind != OBJECT or obj.known:
        return False
    if not obj.words or not obj.labels:
        return False
    opened = next((w for w in words if w not in ("me", "us", "him", "her", "them")), "")
    return opened in PARTICULAR or "from" in words


def _destination_relation(obj: NP | None) -> RelationConstraint | None:
    """The relation saying where a placing verb's object goes ("put this in the bin",
    "put the DVD on the top shelf"): the last named "in" / "on" of the object, since the
    verb's own phrase follows what the object's modifiers say ("the cue that's lying on
    the table back in the rack")."""
    if obj is None:
        return None
    found = None
    for con in obj.constraints:
        if (
            isinstance(con, RelationConstraint)
            and not con.negated
            and con.predicate in ("inside", "on")
            and con.landmark.target.labels
            and con.landmark.target.noun
        ):
            found = con
    return found


def _destination(obj: NP | None) -> NP | None:
    """The named thing a placing verb's object goes in or on, as a phrase of its own with
    its own modifiers; None when there is none."""
    con = _destination_relation(obj)
    if con is None:
        return None
    lm = con.landmark
    return NP(
        kind=OBJECT,
        labels=list(lm.target.labels),
        words=lm.target.noun.split(),
        constraints=list(lm.constraints),
        known=True,
    )


def _places_target(con: Constraint, obj: NP) -> bool:
    """Whether a constraint of a function verb's object places the target: a relation
    ("use the toilet next to the bookshelf"), a nearest/farthest to something ("… closest
    to the bookshelf"), or any measure of an object that names nothing ("somewhere to sit
    closest to the TV"); not "the largest book" of "read the largest book"."""
    if con.kind == "relation":
        return True
    if isinstance(con, Superlative):
        return con.landmark is not None or not obj.labels
    return False


def _done_from(g: Grammar) -> list[Constraint]:
    """Where a function is done from ("watch something from bed", "eat from the counter"):
    near that thing, or in that room; it is not what the request seeks. Empty (cursor
    unmoved) when no such phrase follows."""
    if not g.at("from") or not g.np_start(1):
        return []
    snap = g.state()
    g.advance()
    lm = g.parse_np(landmark=True)
    text = f"from {lm.noun}" if lm is not None else ""
    if lm is not None and lm.kind == OBJECT and lm.labels:
        g.notes.append(f"'{text}': where it is done from, near the target")
        return [
            RelationConstraint(
                predicate="near", landmark=lm.landmark(), weight=g.weight("relation"), text=text
            )
        ]
    if lm is not None and lm.kind == ROOM and lm.room_type is not None:
        room = RoomConstraint(type=lm.room_type, name=lm.noun, text=text, weight=g.weight("room"))
        return [room]
    g.restore(snap)
    return []


def _before_place(toks: list[Tok]) -> int:
    """How many of a verb's object tokens come before a place or landmark phrase: "have
    a meal | next to the seat" is about the meal, not about taking a seat ("a cup of
    tea" keeps its "of")."""
    for k, t in enumerate(toks):
        if k and t.has("prep") and t.text not in _OBJECT_PREPOSITIONS:
            return k
    return len(toks)


def _wh_object(g: Grammar, verb: str, words: list[str]) -> tuple[Sense | None, list[str]]:
    """A clause object ("check how I look", "see what time it is"): the sense its words
    give the verb, consuming them up to the next comma or preposition."""
    snap = g.state()
    extra: list[str] = []
    while (t := g.peek()) is not None and not t.has("comma", "prep", "floor", "and"):
        extra.append(t.text)
        g.advance()
    sense = match_function(verb, [*words, *extra])
    if sense is None:
        g.restore(snap)
        return None, words
    return sense, [*words, *extra]


def lemma_of(tok: Tok) -> str:
    """The token's lemma (a multi-word token is its own lemma)."""
    return tok.lemma if tok.lemma and " " not in tok.text else tok.text


# Verbs of habitual keeping: "where do we keep / store the X" asks where X is.
_KEEP_VERBS = frozenset({"keep", "store"})


def _take_source(g: Grammar) -> None:
    """Read "out of my shirt" / "off the sofa" after the object of a verb that says what a
    thing sought is used for ("… use to get the creases out of my shirt"): where the
    object is taken from belongs to the errand, not to the thing sought."""
    k = 2 if g.text_at() == "out" and g.text_at(1) == "of" else 1
    if g.text_at() in ("out", "off") and g.np_start(k):
        for _ in range(k):
            g.advance()
        g.parse_np(landmark=True)


def _by_means(g: Grammar, start: int) -> bool:
    """Whether the verb at ``start`` says what a thing asked for is used to do ("what
    could I use to get the creases out", "something to get the stain off"): "to" before
    it, and "use" or an open "something" / "anything" / "what" before that."""
    if start < 2 or g.toks[start - 1].text != "to":
        return False
    before = g.toks[max(0, start - 5) : start - 1]
    return any(t.lemma == "use" or t.text in ("something", "anything", "what") for t in before)


def _asks_where(g: Grammar, start: int) -> bool:
    """Whether the clause before token ``start`` asks "where" ("where do we keep …")."""
    return any(t.text == "where" for t in g.toks[:start])


def _worn(g: Grammar) -> bool:
    """Whether the cursor stands on the particle of "put … on" that means wearing ("put
    my boots on near the back door"): "on" with no noun phrase after it."""
    return g.text_at() == "on" and not g.np_start(1)


def _imperative(g: Grammar, start: int) -> bool:
    """Whether the verb at ``start`` opens a command ("draw the drapes", "wipe down the
    kitchen island"): a base-form verb at the start of a clause."""
    tok = g.toks[start]
    after = g.toks[start + 1] if start + 1 < len(g.toks) else None
    # a short command's verb is often tagged as an adjective ("lower the blinds": JJR)
    verb_like = tok.has("fverb") and after is not None and after.has("det")
    if tok.tag != "VB" and not verb_like:
        return False
    prev = g.toks[start - 1] if start > 0 else None
    return prev is None or (prev.has("comma", "and", "filler") and not prev.has("to", "seeker"))


def _somewhere(obj: NP | None) -> bool:
    """Whether ``obj`` is a thing said to be somewhere ("I dropped my keys somewhere"):
    a vague place that carries the thing's kind."""
    return obj is not None and obj.kind == GENERIC and bool(obj.labels)


def _past(g: Grammar, start: int) -> bool:
    """Whether the verb at ``start`` is in the past ("I left", "did I put", "have I
    left"): it reports what happened to its object, it does not ask for a function."""
    tok = g.toks[start]
    if tok.tag in ("VBD", "VBN"):
        return True
    if start > 0 and g.toks[start - 1].text == "to":
        return False  # "I have to change the bulb": a duty, not something done
    before = g.toks[max(0, start - 3) : start]
    return any(t.text in ("did", "had", "have", "has") for t in before)


def _object_marker(tok: Tok, verb: str) -> bool:
    lx = lexicon()
    if tok.has("of"):
        return True
    if tok.text == "on" and verb not in lx.locative_verbs:
        return True  # "check on the bread", "turn on the lamp"
    if tok.has("for"):
        return verb not in lx.locative_verbs
    return tok.text == "in" and verb in lx.light_verbs


def _objects(g: Grammar, landmark: bool = True) -> NP | None:
    """The verb's object, with coordinated ones ("personal items or documents"); parsed
    as the request's head (places and floors attach to it) when ``landmark`` is off."""
    obj = g.parse_np(landmark=landmark)
    while obj is not None and g.at("and", "or") and g.np_start(1) and not g.at("fverb", k=1):
        g.advance()
        more = g.parse_np(landmark=True)
        if more is not None:
            obj.words += [*more.words]
    return obj


def parse_purpose(g: Grammar) -> tuple[list[Constraint], NP | None]:
    """After "to" / "for" / "while": a verb phrase, or a purpose noun ("for a meeting")."""
    tok = g.peek()
    # a verb the vocabulary knows, or any other verb in its base form
    verb = tok is not None and (
        verb_reading(tok) is not None or (tok.has("overb") and tok.tag == "VB")
    )
    if verb and not g.at("det", k=-1):
        return parse_vp(g, purpose=True)
    if not g.np_start():
        return [], None
    snap = g.state()
    purpose = g.parse_np(landmark=True)
    own = snap[0] + _before_place(g.toks[snap[0] : g.i])
    words = [t.text for t in g.toks[snap[0] : own]]
    sense = match_function(None, words, lemmas=[lemma_of(t) for t in g.toks[snap[0] : own]])
    if sense is None:
        g.restore(snap)  # not a purpose: the phrase is parsed as an ordinary one
        return [], None
    function, labels = sense
    made = FunctionConstraint(
        function=function, labels=labels, weight=g.weight("function"), text=" ".join(words)
    )
    # "something for storage near the bed": the purpose phrase's places place the target
    where = [c for c in purpose.constraints if c.kind == "relation"] if purpose else []
    return [made, *where, *(purpose.places if purpose else [])], None

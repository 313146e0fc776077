"""The offline request parser: text → :class:`ParsedQuery`.

Pipeline: check the text; analyse it with spaCy (sentences, tokens, lemmas, tags);
detect the frame (a problem statement, a global question, a refinement); tag words
against the vocabulary (multi-word nouns, prepositions, viewpoint cues, placements) with
open-vocabulary readings by part of speech; parse the noun-phrase grammar sentence by
sentence; assemble weighted constraints. Sentences after the one that names the target
refine it ("This is a white trash can. It is in the corner next to the desk."). Parse
results are cached per text (they are immutable).
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from inherit_sg.retrieval.constraints import (
    AttributeConstraint,
    Constraint,
    RelationConstraint,
    Viewpoint,
)
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.rules.assemble import assemble
from inherit_sg.retrieval.rules.clause import Clause, ClauseParser, parts_of_head, turned_round
from inherit_sg.retrieval.rules.frames import global_reason, refine_frame
from inherit_sg.retrieval.rules.grammar import Grammar
from inherit_sg.retrieval.rules.phrase import (
    ANAPHOR,
    GENERIC,
    GENERIC_AREA,
    NP,
    OBJECT,
    ONE,
    ROOM,
    VAGUE,
)
from inherit_sg.retrieval.rules.problems import open_problem, split_problem
from inherit_sg.retrieval.rules.tagger import tag
from inherit_sg.retrieval.rules.tokens import COMMA, Word, analyse_text, check_query_text
from inherit_sg.vocab.lexicon import lexicon
from inherit_sg.vocab.objects import canonical_label, is_kind_of
from inherit_sg.vocab.rooms import room_type

_VAGUE_HEADS = (GENERIC, GENERIC_AREA, VAGUE)
# Sentences parsed per request (longer texts are talk around the request).
MAX_SENTENCES = 8


def _flat(sentences: list[list[Word]]) -> list[Word]:
    out: list[Word] = []
    for sentence in sentences:
        if out:
            out.append(COMMA)
        out.extend(sentence)
    return out


def _corrects(sentence: list[Word]) -> bool:
    """Whether a sentence opens by correcting the one before ("no wait, I mean …", "no,
    the yellow one")."""
    words = [w.text for w in sentence[:5] if w.text != ","]
    text = " ".join(words)
    if any(text.startswith(c) or text.startswith(f"no {c}") for c in lexicon().corrections):
        return True
    after = [w for w in sentence[1:4] if w.text != ","]
    said_no = bool(sentence) and sentence[0].text == "no" and len(sentence) > 1
    return (
        said_no and sentence[1] is COMMA and bool(after)
        and (after[0].pos == "DET" or after[0].text == "not")
    )  # fmt: skip


def _corrects_details(clause: Clause, more: Clause) -> bool:
    """Fold a correction that names no kind ("…, no wait, the blue one") into the earlier
    head: its attributes replace those of the same key, its places the earlier places.
    False (nothing changed) when the correction names a thing of its own."""
    head, one = clause.head, more.head
    if head is None or one is None or one.kind != ONE or head.kind != OBJECT:
        return False
    if clause.head_negated or head.plural or head.quantity:
        return False  # "Not the big TV, I mean the little one"; "three beds, I mean the middle one"
    keys = {c.key for c in one.constraints if isinstance(c, AttributeConstraint)}
    kept = [
        c for c in head.constraints if not (isinstance(c, AttributeConstraint) and c.key in keys)
    ]
    head.constraints = [*kept, *one.constraints]
    if more.places or one.places:
        clause.places = [*more.places, *one.places]
    return True


def _split_run_on(sentence: list[Word]) -> list[list[Word]]:
    """A statement run on into a request with no stop between them ("the wifi is down
    can you check the router", as speech is transcribed) as two sentences: split before
    "can / could / would / will you" where a finite verb came before."""
    for j in range(2, len(sentence) - 2):
        word = sentence[j]
        if word.tag != "MD" or sentence[j + 1].text != "you" or sentence[j - 1] is COMMA:
            continue
        before = sentence[:j]
        if before[0].text in _QUESTION_OPENERS or before[-1].text in _QUESTION_OPENERS:
            continue  # "where can you …", "the place where can you …"
        if any(w.pos in ("VERB", "AUX") and w.tag in _FINITE for w in before):
            return [before, sentence[j:]]
    return [sentence]


def _without_vocative(sentence: list[Word]) -> list[Word]:
    """The sentence without a name it opens by calling, with no comma after it ("mommy
    I can't find my toothbrush", "honey can you grab the towel"): a bare noun that names
    no known thing or room, followed by "I" / "we" or "can you"."""
    if len(sentence) < 3 or sentence[0].pos not in ("NOUN", "PROPN"):
        return sentence
    nxt, after = sentence[1], sentence[2]
    if not (nxt.text in ("i", "we") or (nxt.tag == "MD" and after.text == "you")):
        return sentence
    word = sentence[0].text
    if canonical_label(word) is not None or room_type(word) is not None:
        return sentence  # "kitchen can you …" keeps its room
    return sentence[1:]


def _aside(part: list[Word]) -> bool:
    """Whether words that open a request only set something aside ("No towels
    required.", "No price changes today", "Don't worry about the paperwork"): "no"
    and a noun with no finite verb after, or "do not worry about …"."""
    texts = [w.text for w in part]
    if texts[:4] == ["do", "not", "worry", "about"]:
        return True
    if len(part) < 2 or texts[0] != "no" or part[0].pos != "DET" or part[1].pos != "NOUN":
        return False
    if texts[1] in _CORRECTION_WORDS or texts[1] in ("one", "ones"):
        return False  # "no wait, the blue one" corrects; "no one's using the projector"
    return not any(
        w.tag in ("VBZ", "VBP", "VBD") and w.lemma not in _NEEDING for w in part[2:]
    )  # "No towels required."


def _without_asides(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without the asides that open it, as a sentence of their own ("No
    signature needed. Take the post trolley …") or before a comma ("No price changes
    today; only move the A-board …"), when a request follows."""
    out: list[list[Word]] = []
    for n, sentence in enumerate(sentences):
        cut = next((j for j, w in enumerate(sentence) if w is COMMA), None)
        if cut is not None and cut + 1 < len(sentence) and _aside(sentence[:cut]):
            out.append(sentence[cut + 1 :])
        elif n + 1 < len(sentences) and _aside(sentence):
            continue
        else:
            out.append(sentence)
    return out


_GREETINGS = frozenset({"hi", "hello", "hey", "dear", "morning", "afternoon", "evening", "good"})
_SIGN_OFFS = frozenset(
    {"thanks", "thank", "cheers", "regards", "best", "many", "kind", "ta", "thx", "love"}
)


def _without_letter_frame(sentences: list[list[Word]]) -> list[list[Word]]:
    """The request without the greeting and sign-off of a message ("Hi Sam, can you grab
    the laptop from my desk? Cheers, Mark"): a greeting and up to three words before a
    comma, and a short last sentence of thanks."""
    if not sentences:
        return sentences
    first = sentences[0]
    if first and first[0].text in _GREETINGS:
        cut = next((j for j, w in enumerate(first[:5]) if w is COMMA), None)
        if cut is not None and cut + 1 < len(first):
            sentences = [first[cut + 1 :], *sentences[1:]]
        elif cut is None and len(first) <= 3 and len(sentences) > 1:
            sentences = sentences[1:]  # "Hi team." / "Good morning."
    last = sentences[-1]
    if len(sentences) > 1 and last and last[0].text in _SIGN_OFFS and len(last) <= 6:
        sentences = sentences[:-1]  # "Thanks, Jen", "Many thanks, Sister Adeyemi"
    return sentences


def _without_rhetorical_not(sentence: list[Word]) -> list[Word]:
    """A question that asks for a yes ("Is it not the blue bowl?", "Was that not the
    lamp by the window?") without its "not": "is it not X" asks whether it is X."""
    if len(sentence) < 4 or sentence[0].lemma != "be" or sentence[0].pos != "AUX":
        return sentence
    if sentence[1].text in _IT_WORDS and sentence[2].text == "not":
        return [*sentence[:2], *sentence[3:]]
    return sentence


def _split_correction(sentence: list[Word]) -> list[list[Word]]:
    """A sentence that corrects itself after a comma ("the red mug, no wait, the blue
    one", "the orange… no, the yellow bucket") as two sentences, the second a correction."""
    for j in range(2, len(sentence) - 1):
        if sentence[j - 1] is COMMA and _corrects(sentence[j:]):
            return [sentence[: j - 1], sentence[j:]]
    return [sentence]


_CORRECTION_WORDS = frozenset(
    {
        "no",
        "wait",
        "sorry",
        "actually",
        "i",
        "mean",
        "meant",
        "rather",
        "correction",
        ",",
        "oh",
        "oops",
        "um",
    }
)


def _after_correction(sentence: list[Word]) -> list[Word]:
    """The sentence without its opening correction words ("no wait, I mean …")."""
    i = 0
    while i < len(sentence) and sentence[i].text in _CORRECTION_WORDS:
        i += 1
    return sentence[i:] or sentence


def _same_thing(head: NP, other: NP) -> bool:
    """Whether a later sentence's subject is the target again ("it", "the one", "the
    chair" after "a chair")."""
    if other.kind in (ANAPHOR, ONE):
        return True
    if other.kind != OBJECT:
        return False
    if set(other.labels) & set(head.labels):
        return True
    # "a kitchen cabinet. It is the cabinet above …", "a rolling chair … the chair …":
    # the same thing named more or less exactly
    return any(
        is_kind_of(mine, theirs) or is_kind_of(theirs, mine)
        for mine in head.labels
        for theirs in other.labels
    )


def _merge_sentence(
    out: Clause, more: Clause, notes: list[str], said: ClauseParser | None = None
) -> None:
    """Fold a later sentence's clause into the request's clause (``said``: the parser
    that read it)."""
    head = out.head
    assert head is not None
    if out.viewpoint is None:
        out.viewpoint = more.viewpoint
    out.excluded_labels += more.excluded_labels
    other = more.head
    if other is not None and more.head_negated and other.kind == OBJECT and other.labels:
        if set(other.labels) == set(head.labels) and other.constraints:
            # "… It's not the armchair by the door": the same kind, its modifiers negated
            cons = [replace(c, negated=not c.negated) for c in other.constraints]
            head.constraints += parts_of_head(head, cons)
            out.places += [replace(c, negated=not c.negated) for c in other.places]
            return
        ClauseParser._exclude(out, other)  # "Under the window, the heater. Not the fan."
        return
    if (
        other is not None
        and out.head_negated
        and not more.head_negated
        and other.kind == OBJECT
        and other.labels
        and not set(other.labels) & set(head.labels)
    ):
        # "Never the good china. Grab a plastic plate.": the first one ruled out
        ClauseParser._exclude(out, head)
        out.head, out.head_negated = other, False
        out.places += more.places
        return
    if other is not None and out.head_negated and other.kind == ONE:
        head.constraints = [replace(c, negated=not c.negated) for c in head.constraints]
        head.constraints += other.constraints
        ClauseParser._negate_head_places(out)  # "Not the bathroom sink. The kitchen one."
        out.places += other.places + more.places
        out.head_negated = False  # "Never use the red towel. Grab a different one."
        return
    if other is None:
        out.places += more.places
        head.constraints += more.pending + more.functions
        return
    if head.kind in (ONE, ANAPHOR) and turned_round(other) and _about_target(head, other, notes):
        return  # "… the one furthest away. There's a soap dish on it."
    if head.kind in (ONE, ANAPHOR) and not head.labels and other.kind == OBJECT and other.labels:
        notes.append(f"{other.noun!r} names the target the first sentence left open")
        other.constraints = head.constraints + other.constraints
        out.head = other
        out.places += more.places
        return
    if head.kind == ROOM and other.kind == OBJECT and other.labels and not more.head_negated:
        if _about_target(head, other, notes):
            return  # "Go to the kitchen. There's a fridge in it."
        # "Go to the lounge. Find the small round table near the bay window."
        notes.append(f"{other.noun!r} is the target; {head.noun!r} is where")
        out.places += [Grammar.room_place(head), *more.places]
        head.constraints += more.pending
        out.head = other
        return
    if _same_thing(head, other):
        head.constraints += more.pending + parts_of_head(head, other.constraints)
        out.places += more.places + other.places
        if other.kind == OBJECT and head.kind in _VAGUE_HEADS:
            out.head = replace(other, constraints=head.constraints + other.constraints)
        return
    if head.kind in _VAGUE_HEADS and other.kind == OBJECT:
        notes.append(f"{other.noun!r} names the target the first sentence left open")
        other.constraints = head.constraints + other.constraints
        out.head = other
        out.places += more.places
        return
    if _about_target(head, other, notes):
        return
    if said is not None and said.said_of_it and other.kind == OBJECT:
        described = said.as_description(other)  # "… It is yellow plastic."
        if described:
            head.constraints += described
            return
    notes.append(f"sentence about {other.noun or other.kind!r} (not the target) ignored")


def _speaker_situation(sentence: list[Word]) -> bool:
    """Whether a sentence says where the speaker is ("I'm sitting on the edge of the bed
    facing the window", "I am at the counter"): "I" / "we", then within three words a
    verb of standing or facing, or "am" / "are" and a preposition."""
    words = sentence[:5]
    if len(words) < 3 or words[0].text not in ("i", "we"):
        return False
    lx = lexicon()
    if words[1].lemma == "be" and words[2].pos == "ADP":
        return True
    return any(w.lemma in lx.viewpoint_verbs or w.lemma in lx.facing_verbs for w in words[1:4])


_FINITE = frozenset({"VBZ", "VBP", "VBD"})
_NEEDING = frozenset({"need", "require", "want"})
_IT_WORDS = frozenset({"it", "them", "this", "that", "those", "these"})
# Dependencies of a clause's own verb (a run-on's first verb hangs off the second: ccomp)
_MAIN_VERB = frozenset({"ROOT", "ccomp", "conj", "parataxis"})
_QUESTION_OPENERS = frozenset({"where", "which", "what", "who", "how", "whose", "when", "why"})
# Words that may come before a request's verb: politeness, discourse openers and the
# modal of a question put as a request ("so could you please check …").
_REQUEST_OPENERS = frozenset(
    {"please", "so", "and", "then", "now", "just", "ok", "okay", "hey", "can", "could",
     "would", "will", "you", "kindly", ","}
)  # fmt: skip


def _is_request(sentence: list[Word]) -> bool:
    """Whether a sentence asks for something to be done ("Can you check the router?",
    "Grab the flashlight from the drawer.", "Please pick up the toys."): after any
    openers, the sentence's root verb in its base form, with no subject but "you"."""
    i = 0
    while i < len(sentence) and sentence[i].text in _REQUEST_OPENERS:
        i += 1
    if i == len(sentence):
        return False
    verb = sentence[i]
    modal = any(w.text in ("can", "could", "would", "will") for w in sentence[:i])
    if modal and not any(w.text == "you" for w in sentence[:i]):
        return False  # "can I …" asks leave, it gives no errand
    # after "can you" the verb is the errand however spaCy attached a run-on's parts
    return verb.pos == "VERB" and verb.tag == "VB" and (verb.dep == "ROOT" or modal)


def _is_statement(sentence: list[Word]) -> bool:
    """Whether a sentence states how things are ("The wifi is down.", "There is a
    bookshelf next to the TV."): its root is a verb, and it is no question and no
    request (a bare phrase, "The plant we never water.", is none)."""
    if not sentence or sentence[0].tag == "MD" or sentence[0].text in _QUESTION_OPENERS:
        return False
    if sentence[0].pos == "AUX" and sentence[0].lemma in ("be", "do", "have"):
        return False  # "Is the stove off?"
    finite = any(
        w.pos in ("VERB", "AUX") and w.tag in _FINITE and w.dep in _MAIN_VERB for w in sentence
    )  # not "The plant that we never water.": a phrase with a relative clause
    return finite and not _is_request(sentence)


def _statement_then_request(
    clause: Clause, first: list[Word], more: Clause, later: list[Word]
) -> bool:
    """Whether a first sentence that states something ("The wifi is down.", "The desk is
    by the window.") is followed by a request for another named thing ("Can you check
    the router?", "Bring me the chair next to it."): the request's object is sought."""
    head = clause.head
    if head is None or head.kind != OBJECT or clause.head_negated or not _asks_for_object(more):
        return False
    assert more.head is not None
    if _object_is_it(later):
        return False  # "The charger is in the conference room, can you bring it to my desk"
    return _is_statement(first) and _is_request(later) and not _same_thing(head, more.head)


def _object_is_it(sentence: list[Word]) -> bool:
    """Whether a request's verb takes "it" / "them" as its object ("bring it to my
    desk"): the errand is about the thing said before."""
    i = 0
    while i < len(sentence) and sentence[i].text in _REQUEST_OPENERS:
        i += 1
    rest = [w.text for w in sentence[i + 1 : i + 3]]
    return bool(rest) and (rest[0] in _IT_WORDS or (rest[-1] in _IT_WORDS and rest[0] == "me"))


def _scene_then_target(clause: Clause, first: list[Word], more: Clause, later: list[Word]) -> bool:
    """Whether a first sentence that sets the scene ("there is a desk in the corner.")
    is followed by a description of another thing placed by it ("the chair in front of
    it is black and has wheels."): that thing, described in its own right, is the
    target, and the first one its landmark."""
    head, other = clause.head, more.head
    if head is None or other is None or head.kind != OBJECT or other.kind != OBJECT:
        return False
    if not other.labels or clause.head_negated or more.head_negated or _same_thing(head, other):
        return False
    texts = [w.text for w in first[:2]]
    if texts[:1] != ["there"] or len(first) < 2 or first[1].lemma != "be":
        return False
    if not later or later[0].text != "the":
        return False
    by_it = [
        c
        for c in other.constraints
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
    ]
    by_name = any(
        isinstance(c, RelationConstraint) and set(c.landmark.target.labels) & set(head.labels)
        for c in other.constraints
    )  # "the range hood above the stove is stainless steel"
    said = [*other.constraints, *(d for c in by_it for d in c.landmark.constraints)]
    return bool(by_it or by_name) and any(isinstance(c, AttributeConstraint) for c in said)


def _description_after_it(head: NP) -> list[Constraint]:
    """What "… next to it is black and has wheels" says after "it": spaCy's parse gives
    it to "it", the sentence says it of its subject."""
    return [
        d
        for c in head.constraints
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
        for d in c.landmark.constraints
        if isinstance(d, AttributeConstraint)
    ]


def _point_it_at(head: NP, context: NP) -> None:
    """Relations of ``head`` placed by "it" ("the chair next to it") take the thing the
    sentence before named as their landmark."""
    landmark = context.landmark()
    head.constraints = [
        replace(c, landmark=landmark, text=c.text.replace(ANAPHOR, context.noun))
        if isinstance(c, RelationConstraint) and c.landmark.target.anaphor
        else c
        for c in head.constraints
    ]


def _scope_left_open(context: Clause, more: Clause) -> list[Constraint]:
    """The room and floor a stating sentence set ("In the family room there is a
    bookshelf …") for a request that names none of its own ("Put the DVD on the top
    shelf.")."""
    assert more.head is not None
    own = {c.kind for c in [*more.places, *more.head.constraints]}
    return [c for c in context.places if c.kind in ("room", "floor") and c.kind not in own]


def _asks_for_object(more: Clause) -> bool:
    """Whether a later sentence asks for a named object of its own ("Which chair is
    closest to my right hand?", "Is the radiator behind me?")."""
    head = more.head
    return head is not None and head.kind == OBJECT and bool(head.labels) and not more.head_negated


def _about_target(head: NP, other: NP, notes: list[str]) -> bool:
    """A later sentence about another thing placed by "it" ("There are books on it"):
    the relation, turned round, describes the target."""
    found = turned_round(other)
    if not found:
        return False
    head.constraints += found
    notes.append(f"'{other.noun} … it': a relation of the target, turned round")
    return True


def _asks_only_for_help(clause: Clause) -> bool:
    """Whether the request names no thing and no function of its own ("is there something
    upstairs that could help?")."""
    head = clause.head
    named = head is not None and (head.kind not in (GENERIC, VAGUE) or bool(head.labels))
    functions = head is not None and any(c.kind == "function" for c in head.constraints)
    return not (named or functions or clause.functions or clause.implied)


def parse_uncached(text: str) -> ParsedQuery:
    """Parse ``text`` without the result cache (for benchmarks)."""
    text = check_query_text(text)
    analysed, fixes = analyse_text(text)
    problem, sentences = split_problem(analysed)
    unknown_problem = open_problem(analysed) if problem is None else None
    words = _flat(sentences)
    reason = global_reason(words) if words or problem is None else None
    if reason is not None:
        return ParsedQuery(text=text, no_target_reason=reason, notes=("frame: global question",))
    if len(sentences) > MAX_SENTENCES:
        sentences = sentences[:MAX_SENTENCES]  # a request is a few sentences; the rest is talk
    notes: list[str] = [f"spelling: {wrong!r} read as {right!r}" for wrong, right in fixes]
    refine = False
    if sentences:
        refine, first = refine_frame(sentences[0])
        sentences = [first, *sentences[1:]] if first else sentences[1:]
    if refine:
        notes.append("frame: refinement of the previous request")
    sentences = [part for sentence in sentences for part in _split_correction(sentence)]
    sentences = [part for sentence in sentences for part in _split_run_on(sentence)]
    sentences = [_without_rhetorical_not(_without_vocative(s)) for s in sentences]
    sentences = _without_asides(_without_letter_frame(sentences))
    clause = Clause()
    situation = False
    for n, sentence in enumerate(sentences):
        tokens = tag(sentence)
        if clause.head is None:
            situation = _speaker_situation(sentence)
            opening = ClauseParser(tokens, notes)
            opening.more_sentences = n + 1 < len(sentences)
            opening.parse(refine, clause)
            continue
        correcting = _corrects(sentence)
        if correcting:
            tokens = tag(_after_correction(sentence))
        later = ClauseParser(tokens, notes)
        later.later = True
        more = later.parse(refine)
        if situation and _asks_for_object(more) and clause.head.kind == OBJECT:
            # "I'm sitting on the sofa and the bookshelf is in front of me. Is the
            # radiator behind me?": the first sentence places the speaker
            assert more.head is not None
            notes.append(f"the first sentence places the speaker; {more.head.noun!r} is sought")
            if more.viewpoint is None:
                more.viewpoint = clause.viewpoint or Viewpoint(
                    kind="from", landmark=clause.head.landmark(), text=clause.head.noun
                )
            clause, situation = more, False
            continue
        situation = False
        if not correcting and _statement_then_request(clause, sentences[0], more, sentence):
            # "The wifi is down. Can you check the router in the hall closet?"
            assert more.head is not None and clause.head is not None
            notes.append(f"the first sentence says how things are; {more.head.noun!r} is asked for")
            _point_it_at(more.head, clause.head)
            more.excluded_labels += clause.excluded_labels
            more.places += _scope_left_open(clause, more)
            clause = more
            continue
        if not correcting and _scene_then_target(clause, sentences[0], more, sentence):
            # "there is a desk in the corner. the chair in front of it is black …"
            assert more.head is not None and clause.head is not None
            notes.append(f"the first sentence sets the scene; {more.head.noun!r} is described")
            more.head.constraints += _description_after_it(more.head)
            _point_it_at(more.head, clause.head)
            more.places += _scope_left_open(clause, more)
            clause = more
            continue
        if correcting and _corrects_details(clause, more):
            notes.append("the correction changes the earlier request's details")
            continue
        if correcting and more.head is not None and more.head.kind == OBJECT:
            notes.append(f"'{more.head.noun}' corrects the earlier request")
            if clause.head is not None and clause.head_negated and clause.head.labels:
                # "Neither the sofa nor the armchair. I meant the beanbag."
                ClauseParser._exclude(more, clause.head)
                more.excluded_labels += clause.excluded_labels
            clause = more  # "can you find the cat? no wait, I mean the cat's carrier"
        else:
            _merge_sentence(clause, more, notes, later)
    if problem is not None:
        notes.append(f"function {problem.function!r} implied by the problem {problem.text!r}")
        clause.implied.append(problem)  # an explicit request ("where can I lie down") leads
    elif unknown_problem is not None and _asks_only_for_help(clause):
        notes.append(f"the statement {unknown_problem.text!r} says what is needed (by meaning)")
        clause.implied.append(unknown_problem)
    return assemble(text, clause, refine, notes, [w.text for w in words])


@lru_cache(maxsize=4096)
def _parse_cached(text: str) -> ParsedQuery:
    return parse_uncached(text)


def parse_rules(text: str) -> ParsedQuery:
    """Parse a request offline; raises :class:`QueryTextError` on bad text."""
    return _parse_cached(check_query_text(text))


class RuleParser:
    """Object form of :func:`parse_rules` (same interface as the LLM parser)."""

    name = "rules"

    def parse(self, text: str) -> ParsedQuery:
        """Parse ``text`` into constraints."""
        return parse_rules(text)

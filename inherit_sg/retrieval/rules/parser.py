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
    LabelConstraint,
    Viewpoint,
)
from inherit_sg.retrieval.query import ParsedQuery
from inherit_sg.retrieval.rules.assemble import assemble
from inherit_sg.retrieval.rules.clause import Clause, ClauseParser, parts_of_head, turned_round
from inherit_sg.retrieval.rules.discourse import (
    asks_for_object,
    count_superlative,
    description_after_it,
    hand_over,
    last_clause,
    one_of_several,
    picks_out,
    point_it_at_view,
    points_back,
    same_thing,
    scene_then_target,
    several_kinds,
    split_at_pick,
    split_scene,
    statement_then_request,
    states_absence,
    thing_the_room_holds,
)
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
from inherit_sg.retrieval.rules.problems import open_problem, split_problem, trailing_problem
from inherit_sg.retrieval.rules.rewording import called_off, errand_now, without_report_frame
from inherit_sg.retrieval.rules.route import route_goal
from inherit_sg.retrieval.rules.sentences import (
    CORRECTION_WORDS,
    comma_after_denied_thing,
    denial_then_choice,
    denies_first,
    fetches_particular,
    place_after_thing,
    prepare,
    without_repeating,
)
from inherit_sg.retrieval.rules.structured import plain_request
from inherit_sg.retrieval.rules.tagger import tag
from inherit_sg.retrieval.rules.tokens import COMMA, Word, analyse_text, check_query_text
from inherit_sg.vocab.lexicon import lexicon

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
    k = 0
    while k < len(sentence) and (sentence[k].text in _NO_WORDS or (k and sentence[k] is COMMA)):
        k += 1  # "no, …", "no no, …", "nope, …"
    said_no = k > 0 and sentence[k - 1] is COMMA
    after = [w for w in sentence[k : k + 3] if w.text != ","]
    return said_no and bool(after) and (after[0].pos == "DET" or after[0].text == "not")


# Words that say no before a correction.
_NO_WORDS = frozenset({"no", "nope", "nah"})


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


def _split_correction(sentence: list[Word]) -> list[list[Word]]:
    """A sentence that corrects itself after a comma ("the red mug, no wait, the blue
    one", "the orange… no, the yellow bucket") as two sentences, the second a correction."""
    for j in range(2, len(sentence) - 1):
        if sentence[j - 1] is COMMA and _corrects(sentence[j:]):
            return [sentence[: j - 1], sentence[j:]]
    return [sentence]


def _after_correction(sentence: list[Word]) -> list[Word]:
    """The sentence without its opening correction words ("no wait, I mean …")."""
    i = 0
    while i < len(sentence) and sentence[i].text in CORRECTION_WORDS:
        i += 1
    return sentence[i:] or sentence


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
    if other is not None and more.head_negated and other.kind == ROOM and head.kind == OBJECT:
        # "… It's in the hall bathroom. Not the master bath, the one the kids use."
        out.places.append(replace(Grammar.room_place(other), negated=True))
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
    if same_thing(head, other):
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


def _another_thing(clause: Clause, more: Clause) -> bool:
    """Whether a later sentence asks for a named thing other than the target so far."""
    return (
        clause.head is not None
        and asks_for_object(more)
        and more.head is not None
        and not same_thing(clause.head, more.head)
    )


def _one_of_the_named(clause: Clause, more: Clause) -> bool:
    """Whether a later sentence names one of the several kinds the target so far joins
    ("a glass cup … and a tube of toothpaste" then "the target is the cup")."""
    head, other = clause.head, more.head
    return (
        head is not None
        and other is not None
        and len(head.labels) > 1
        and bool(other.labels)
        and set(other.labels) < set(head.labels)
        and not more.head_negated
    )


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
    plain, read_as = plain_request(text)
    analysed, fixes = analyse_text(plain)
    analysed = [errand_now(without_report_frame(sentence)) for sentence in analysed]
    problem, sentences = split_problem(route_goal(called_off(analysed)))
    obstacle = None
    if problem is None:
        obstacle, sentences = trailing_problem(sentences)
    unknown_problem = open_problem(analysed) if problem is None and obstacle is None else None
    words = _flat(sentences)
    reason = global_reason(words) if words or problem is None else None
    if reason is not None:
        return ParsedQuery(text=text, no_target_reason=reason, notes=("frame: global question",))
    if len(sentences) > MAX_SENTENCES:
        sentences = sentences[:MAX_SENTENCES]  # a request is a few sentences; the rest is talk
    notes: list[str] = [read_as] if read_as else []
    notes += [f"spelling: {wrong!r} read as {right!r}" for wrong, right in fixes]
    refine = False
    if sentences:
        refine, first = refine_frame(sentences[0])
        sentences = [first, *sentences[1:]] if first else sentences[1:]
    if refine:
        notes.append("frame: refinement of the previous request")
    if sentences:
        sentences = [without_repeating(sentences[0]), *sentences[1:]]
    sentences = [comma_after_denied_thing(sentence) for sentence in denial_then_choice(sentences)]
    sentences = [part for sentence in sentences for part in _split_correction(sentence)]
    if sentences:
        sentences = [*split_scene(sentences[0]), *sentences[1:]]
    sentences = [
        part for n, sentence in enumerate(sentences) for part in split_at_pick(sentence, n > 0)
    ]
    sentences = prepare(sentences)
    clause = Clause()
    situation = False
    placed_speaker = False  # a first sentence only said where the speaker is
    said_again = False  # a later sentence said more of the target ("… It is white.")
    at = next((k for k in range(2, len(sentences)) if points_back(sentences[k])), None)
    if at is not None:
        # "… Behind it, against the wall, is a console table. Go to that.", "… under the
        # desk there is a trash can, pick it. it's small and black"
        notes.append("a later sentence points at the thing named just before it")
        named = last_clause(sentences[at - 1])  # the thing named last, not first
        sentences, pointed = [*sentences[: at - 1], named, *sentences[at + 1 :]], at - 1
    else:
        pointed = -1
    for n, sentence in enumerate(sentences):
        tokens = tag(sentence)
        if clause.head is None:
            if n > 0 and situation and clause.viewpoint is not None:
                # "I am sitting on the couch watching the tv. What is behind me?": the
                # first sentence was all standpoint; what the speaker does says no need
                placed_speaker = True
                words = _flat(sentences[n:])
            situation = _speaker_situation(sentence)
            opening = ClauseParser(tokens, notes)
            opening.more_sentences = n + 1 < len(sentences)
            opening.parse(refine, clause)
            continue
        correcting = _corrects(sentence)
        if correcting:
            tokens = tag(_after_correction(sentence))
        reordered = place_after_thing(sentence)
        fronted = reordered is not sentence  # "to the right of it is a paper cutter"
        if fronted and not correcting:
            tokens = tag(reordered)
        later = ClauseParser(tokens, notes)
        later.later = True
        more = later.parse(refine)
        if situation and asks_for_object(more) and clause.head.kind == OBJECT:
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
        if situation and more.head is None and sentence[0].text in ("what", "which"):
            # "I am sitting on the couch watching the tv. What is behind me?": the first
            # sentence places the speaker; the question asks for whatever is there
            notes.append("the first sentence places the speaker; the question names no thing")
            if more.viewpoint is None and clause.viewpoint is not None:
                more.viewpoint = clause.viewpoint
            clause, situation, placed_speaker = more, False, True
            words = _flat(sentences[n:])  # what the speaker does says no need
            continue
        situation = False
        kinds = several_kinds(sentences[:n])
        if not correcting and one_of_several(kinds, clause, more, sentence):
            # "… there are baskets. The basket on the far left."
            assert clause.head is not None and more.head is not None
            notes.append(f"{more.head.noun!r}: one of the several named before")
            hand_over(clause, more)
            if clause.head.kind == ROOM:  # "The sunroom has lots of plants. I need …"
                more.places.append(Grammar.room_place(clause.head))
            clause = more
            continue
        if not correcting and statement_then_request(clause, sentences[0], more, sentence):
            # "The wifi is down. Can you check the router in the hall closet?"
            assert more.head is not None
            notes.append(f"the first sentence says how things are; {more.head.noun!r} is asked for")
            hand_over(clause, more)
            if not states_absence(sentences[0]):  # "there's no milk left": nothing ruled out
                more.excluded_labels += clause.excluded_labels
            clause = more
            continue
        chosen = picks_out(sentence)
        if not correcting and chosen and _one_of_the_named(clause, more):
            # "… a glass cup with two toothbrushes in it, and a tube of toothpaste
            # beside it. The target is the cup."
            assert clause.head is not None and more.head is not None
            notes.append(f"{more.head.noun!r} is said to be the one of those named")
            clause.head.labels = list(more.head.labels)
            clause.head.words = list(more.head.words)
            clause.head.plural = more.head.plural
            # "… the sofa i need is the one with no pillows on it": what it says of it
            clause.head.constraints += more.head.constraints
            clause.places += more.places
            continue
        if not correcting and (chosen or n == pointed) and _another_thing(clause, more):
            # "find the copier first. the recycling bin on its left side is the one"
            assert more.head is not None
            notes.append(f"{more.head.noun!r} is said to be the one meant")
            hand_over(clause, more)
            more.excluded_labels += clause.excluded_labels
            if clause.head_negated and clause.head is not None:
                ClauseParser._exclude(more, clause.head)  # "anything but the sofa, I want …"
            clause = more
            continue
        if (
            not correcting
            and not said_again
            and scene_then_target(clause, sentences[0], more, sentence, fronted)
        ):
            # "there is a desk in the corner. the chair in front of it is black …"
            assert more.head is not None
            notes.append(f"the first sentence sets the scene; {more.head.noun!r} is described")
            more.head.constraints += description_after_it(more.head)
            hand_over(clause, more)
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
            said_again = said_again or (
                clause.head is not None
                and more.head is not None
                and same_thing(clause.head, more.head)
            )
    if clause.head is not None and clause.head.kind == OBJECT and not clause.head.known:
        clause.fetched = any(fetches_particular(s, clause.head.noun) for s in sentences)
    if obstacle is not None:
        notes.append(f"function {obstacle.function!r}: what stands in the way, {obstacle.text!r}")
        head = clause.head
        if head is not None and head.kind == OBJECT and head.labels:
            clause.implied.append(obstacle)  # "the drapes, please? It's getting dark."
        else:
            clause.functions.insert(0, obstacle)  # "I want to read but it's too dark"
    if problem is not None:
        notes.append(f"function {problem.function!r} implied by the problem {problem.text!r}")
        clause.implied.append(problem)  # an explicit request ("where can I lie down") leads
    elif unknown_problem is not None and not placed_speaker and _asks_only_for_help(clause):
        notes.append(f"the statement {unknown_problem.text!r} says what is needed (by meaning)")
        clause.implied.append(unknown_problem)
    if sentences and denies_first(sentences[0]):
        _denied_details(clause, notes)
    count_superlative(clause, words, notes)
    if len(sentences) == 1:
        thing_the_room_holds(clause, sentences[0], notes)
    point_it_at_view(clause)
    return assemble(text, clause, refine, notes, [w.text for w in words])


def _denied_details(clause: Clause, notes: list[str]) -> None:
    """A denied thing that nothing replaced ("anything but the mug with the chip", "not
    the lamp by the door"): the kind stays, and its details are what is ruled out."""
    head = clause.head
    if not clause.head_negated or head is None or head.kind != OBJECT:
        return
    details = [c for c in head.constraints if not isinstance(c, LabelConstraint)]
    if not details and not clause.negated_head_places:
        return
    head.constraints = [
        replace(c, negated=not c.negated) if c in details else c for c in head.constraints
    ]
    ClauseParser._negate_head_places(clause)
    clause.head_negated = False
    notes.append(f"'not the {head.noun}' alone: the kind stays, its details are ruled out")


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

"""Request templates by category, in the tone of real requests to a home robot.

A template renders one :class:`RenderContext` to text, or returns None when it does not
fit the request's structure (a "Which X is the tallest?" needs a superlative). Template
ids are ``"<category>.<name>"``; the generator spreads requests evenly over the templates
that fit.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from inherit_sg.ingest.synthetic.query_text import Phrasing, display
from inherit_sg.ingest.synthetic.truth_spec import ObjectSpec


@dataclass
class RenderContext:
    """One request to word: its spec, answer size and (for negations) how many it excludes."""

    category: str
    spec: ObjectSpec
    answer_size: int
    excluded: int
    phrasing: Phrasing

    def det(self) -> str:
        """ "the" for a single answer, else "a" or "plural" (a stable choice)."""
        if self.answer_size == 1:
            return "the"
        return self.phrasing.pick(("a", "plural", "a"), "det")


@dataclass(frozen=True)
class Template:
    """A named way of wording requests."""

    id: str
    render: Callable[[RenderContext], str | None]


# Function → (verb phrase, "something to …" object phrase or None, a statement of need).
FUNCTION_WORDING: dict[str, tuple[str, str | None, str]] = {
    "sleep": ("sleep", "sleep on", "I'm exhausted."),
    "lie down": ("lie down", "lie down on", "My back hurts."),
    "store": ("put some things away", "store things in", "There is clutter everywhere."),
    "store clothes": ("put my clothes away", "keep my clothes in", "My clothes are all over."),
    "work": ("get some work done", "work on", "I have emails to answer."),
    "sit": ("sit down", "sit on", "My feet hurt."),
    "relax": ("relax", "relax on", "I want to unwind for a bit."),
    "put things": ("put my things down", "set my things on", "My hands are full."),
    "eat": ("have a meal", None, "I'm hungry."),
    "store books": ("put my books away", "keep my books on", "Books are piling up."),
    "prepare food": ("prepare some food", "chop vegetables on", "I want to make a salad."),
    "wash hands": ("wash my hands", "wash my hands at", "My hands are dirty."),
    "wash dishes": ("wash the dishes", "wash the dishes in", "The dishes are piling up."),
    "cook": ("cook dinner", "cook on", "I want to make pasta."),
    "keep food cold": ("keep food cold", "keep my drinks cold in", "The milk needs to stay cold."),
    "use the toilet": ("use the toilet", None, "I really need to go."),
    "bathe": ("take a bath", "take a bath in", "I want a long soak."),
    "wash": ("wash up", "wash in", "I need to freshen up."),
    "shower": ("take a shower", None, "I just came back from a run."),
    "wash clothes": ("do the laundry", "wash my clothes in", "My clothes are dirty."),
    "dry clothes": ("dry my clothes", "dry my clothes in", "My laundry is still wet."),
    "drive": ("go for a drive", None, "I have to run some errands in town."),
    "repair things": ("fix something", "repair things with", "The shelf is broken."),
    "light": ("get some light", None, "It's too dark in here."),
    "look at yourself": ("check how I look", "check my reflection in", "I want to check my hair."),
    "watch": ("watch something", "watch a movie on", "The game starts soon."),
    "drink": ("get a drink", "drink from", "I'm thirsty."),
    "hold flowers": ("put some flowers", "put these flowers in", "Someone gave me flowers."),
    "read": ("find something to read", "read", "I'm bored."),
    "heat food": ("heat up my food", "heat my leftovers in", "My lunch went cold."),
    "boil water": ("boil some water", "boil water in", "I want to make tea."),
    "dry hands": ("dry my hands", "dry my hands with", "My hands are wet."),
    "tell time": ("check the time", "check the time on", "I don't know what time it is."),
    "carry laundry": ("collect my laundry", "carry my laundry in", "My laundry is on the floor."),
    "look outside": ("look outside", "look outside through", "I want to see the weather."),
    "go upstairs": ("go upstairs", None, "I left my phone on the upper floor."),
    "go downstairs": ("go downstairs", None, "I left my keys on the lower floor."),
    "bake": ("bake something", "bake a cake in", "I promised to bring a cake."),
    "blow my nose": ("blow my nose", "wipe my nose with", "I have a runny nose."),
    "brush my teeth": ("brush my teeth", "brush my teeth with", "I just had garlic bread."),
    "call someone": ("make a phone call", "call my sister on", "I need to call the doctor."),
    "cool down": ("cool down", "cool the room with", "It's really hot in here."),
    "do yoga": ("do some yoga", "do my stretches on", "My back is stiff."),
    "exercise": ("work out", "work out on", "I want to get some exercise."),
    "go for a ride": ("go for a bike ride", "ride", "It's a lovely day outside."),
    "hang my coat": ("hang up my coat", "hang my coat on", "My coat is soaking wet."),
    "iron my clothes": ("iron my shirt", "iron my shirt on", "My shirt is all wrinkled."),
    "keep warm": ("keep warm", "wrap myself in", "I'm cold."),
    "listen to music": ("listen to some music", "play my playlist on", "It's too quiet in here."),
    "make coffee": ("make some coffee", "make an espresso with", "I need a coffee."),
    "make toast": ("make some toast", "toast bread in", "I want toast for breakfast."),
    "mop the floor": (
        "mop the floor",
        "clean the floor with",
        "Someone spilled juice on the floor.",
    ),
    "mow the lawn": ("mow the lawn", "cut the grass with", "The grass is far too long."),
    "pack for a trip": (
        "pack for my trip",
        "pack my things in",
        "I'm leaving for a week tomorrow.",
    ),
    "play": ("play", "play with", "The kids are bored."),
    "play darts": ("play darts", None, "I want to practise my aim."),
    "play music": ("play some music", "play a song on", "I feel like making music."),
    "play ping pong": ("play ping pong", None, "I want a quick game of table tennis."),
    "play pool": ("play pool", None, "I want to shoot some pool."),
    "play video games": ("play video games", "play games on", "I have a new game to try."),
    "print": ("print a document", "print my tickets on", "I need a paper copy of this."),
    "put out a fire": ("put out a fire", "put out the fire with", "Something is burning!"),
    "reach high places": ("reach the top shelf", "climb", "I can't reach the top shelf."),
    "store documents": ("file some papers", "keep my documents in", "My papers are a mess."),
    "store shoes": ("put my shoes away", "keep my shoes on", "My shoes are all over the floor."),
    "sweep the floor": ("sweep the floor", "sweep up with", "There is dust everywhere."),
    "throw away trash": ("throw something away", "throw this wrapper in", "I have some rubbish."),
    "type": ("type something", "type on", "I have a long email to write."),
    "vacuum the floor": (
        "vacuum the floor",
        "clean the carpet with",
        "There are crumbs everywhere.",
    ),
    "warm up": ("warm up", "warm my hands at", "I'm freezing."),
    "water the plants": ("water the plants", "water the plants with", "The plants look dry."),
    "weigh myself": ("weigh myself", "weigh myself on", "I wonder how much I weigh."),
    "write": ("write something down", "write notes on", "I need to sketch an idea."),
}

# Functions that make no sense with a place attached ("go for a drive upstairs").
UNSCOPED_FUNCTIONS = frozenset(
    {"drive", "go upstairs", "go downstairs", "go for a ride", "mow the lawn"}
)


def _sp(text: str) -> str:
    return f" {text}" if text else ""


def _generic(single: str, many: str | None) -> Callable[[RenderContext], str | None]:
    def render(ctx: RenderContext) -> str | None:
        det = ctx.det()
        if det == "plural" and many is None:
            det = "a"
        fmt = many if det == "plural" and many is not None else single
        return fmt.format(np=ctx.phrasing.np(det))

    return render


GENERIC = (
    ("where_is", "Where is {np}?", "Where are {np}?"),
    ("find", "Find {np}.", "Find one of {np}."),
    ("could_you_find", "Could you find {np}?", "Could you find one of {np}?"),
    ("looking_for", "I'm looking for {np}.", None),
    ("take_me", "Take me to {np}.", "Take me to one of {np}."),
    ("please_go", "Please go to {np}.", None),
    ("show_me", "Can you show me {np}?", "Can you show me {np}?"),
    ("navigate", "Navigate to {np}.", None),
    ("help_find", "Help me find {np}, please.", None),
    ("need_get", "I need to get to {np}.", None),
)


def _positive_room(spec: ObjectSpec) -> bool:
    return spec.room is not None and not spec.room.negated and spec.area is None


def _go_room_find(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if not _positive_room(s) or s.room is None:
        return None
    floor = ph.floor_phrase(s.floor) if s.floor is not None else ""
    det = "a" if ctx.det() == "plural" else ctx.det()
    return f"Go to {ph.room_ref(s.room)}{_sp(floor)} and find {ph.np(det, False, False)}."


def _in_room_find(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if not _positive_room(s) or s.room is None:
        return None
    floor = ph.floor_phrase(s.floor) if s.floor is not None else ""
    where = f"In {ph.room_ref(s.room)}{_sp(floor)}"
    if ctx.det() == "plural":
        return f"{where}, where are {ph.np('plural', False, False)}?"
    return f"{where}, where is {ph.np(ctx.det(), False, False)}?"


def _is_there(ctx: RenderContext) -> str | None:
    return f"Is there {ctx.phrasing.np('a')}? Take me to it."


def _which_relation(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if len(s.relations) != 1 or s.room or s.floor or s.attributes or ctx.answer_size != 1:
        return None
    phrase = ph.relations()
    if phrase.startswith("with "):
        return f"Which {ph.noun()} has {phrase[len('with ') :]}? Take me there."
    return f"Which {ph.noun()} is {phrase}? Take me there."


def _there_should_be(ctx: RenderContext) -> str | None:
    return f"There should be {ctx.phrasing.np('a')}; take me to it."


def _head_floor(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if s.floor is None or s.floor.negated:
        return None
    phrase = ph.floor_phrase(s.floor)
    direction = phrase.replace("on the ", "to the ", 1)
    det = "a" if ctx.det() == "plural" else ctx.det()
    return f"Head {direction} and find {ph.np(det, floor=False)}."


def _sup_word(ph: Phrasing) -> str:
    return ph.adjectives().split()[0]


def _which_superlative(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if s.superlative is None or any(not a.negated for a in s.attributes):
        return None
    return f"Which {ph.noun()}{_sp(ph.scope())} is the {_sup_word(ph)}?"


def _of_all(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if s.superlative is None or any(not a.negated for a in s.attributes):
        return None
    return f"Of all the {ph.noun(many=True)}{_sp(ph.scope())}, take me to the {_sup_word(ph)} one."


def _among(ctx: RenderContext) -> str | None:
    s, ph = ctx.spec, ctx.phrasing
    if s.superlative is not None or not s.attributes or ctx.answer_size != 1:
        return None
    return f"Among the {ph.noun(many=True)}{_sp(ph.scope())}, find the {ph.adjectives()} one."


def _want_described(ctx: RenderContext) -> str | None:
    ph = ctx.phrasing
    if ctx.answer_size == 1:
        return f"I want {ph.np('the')}. Where is it?"
    return f"I want {ph.np('a')}. Where can I find one?"


def _d_clause(fmt: str) -> Callable[[RenderContext], str | None]:
    def render(ctx: RenderContext) -> str | None:
        det = "the" if ctx.answer_size == 1 else "a"
        np = ctx.phrasing.np(det)
        return fmt.format(np=np, clause=ctx.phrasing.negated_clause())

    return render


def _d_one(fmt: str) -> Callable[[RenderContext], str | None]:
    def render(ctx: RenderContext) -> str | None:
        ph = ctx.phrasing
        one = ph.excluded_one(ctx.excluded > 1)
        scope = _sp(ph.scope())
        return fmt.format(np=ph.np("a"), noun=ph.noun(), scope=scope, one=one)

    return render


def _f(fmt: str, needs_object: bool = False) -> Callable[[RenderContext], str | None]:
    def render(ctx: RenderContext) -> str | None:
        fn = ctx.spec.function
        if fn is None or fn not in FUNCTION_WORDING:
            return None
        vp, obj, need = FUNCTION_WORDING[fn]
        if needs_object and obj is None:
            return None
        return fmt.format(vp=vp, obj=obj, need=need, scope=_sp(ctx.phrasing.scope()))

    return render


_SPECIFIC: dict[str, list[tuple[str, Callable[[RenderContext], str | None]]]] = {
    "A": [
        ("go_room_find", _go_room_find),
        ("in_room_where", _in_room_find),
        ("is_there", _is_there),
    ],
    "B": [("which", _which_relation), ("there_should_be", _there_should_be)],
    "C": [
        ("head_floor", _head_floor),
        ("go_room_find", _go_room_find),
        ("in_room_where", _in_room_find),
    ],
    "E": [
        ("which_superlative", _which_superlative),
        ("of_all", _of_all),
        ("among", _among),
        ("want_described", _want_described),
    ],
    "D": [
        ("find", _d_clause("Find {np} {clause}.")),
        ("looking_for", _d_clause("I'm looking for {np} {clause}.")),
        ("take_me", _d_clause("Take me to {np} {clause}.")),
        ("where_is", _d_clause("Where is {np} {clause}?")),
        ("could_you_find", _d_clause("Could you find {np} {clause}?")),
        ("show_me", _d_clause("Show me {np} {clause}, please.")),
        ("but_not", _d_one("I need {np}, but not {one}.")),
        ("any_except", _d_one("Go to any {noun}{scope} except {one}.")),
        ("not_that", _d_one("Not {one}. Please go to another {noun}{scope}.")),
        ("other_than", _d_one("Take me to a {noun}{scope} other than {one}.")),
    ],
    "F": [
        ("where_can", _f("Where can I {vp}{scope}?")),
        ("need_somewhere", _f("I need somewhere to {vp}{scope}.")),
        ("anywhere", _f("Is there anywhere to {vp}{scope}?")),
        ("somewhere_i_can", _f("Take me somewhere I can {vp}{scope}.")),
        ("id_like", _f("I'd like to {vp}{scope}. Where should I go?")),
        ("something_to", _f("Could you find me something to {obj}{scope}?", True)),
        ("need_statement", _f("{need} Is there something{scope} that could help?")),
        ("help_place", _f("Help me find a place to {vp}{scope}.")),
        ("good_spot", _f("What's a good spot to {vp}{scope}?")),
        ("want_to", _f("I want to {vp}{scope}. Show me where.")),
    ],
}


def templates_for(category: str) -> list[Template]:
    """All templates of ``category`` (A–C and E also use the generic wrappers)."""
    out = [Template(f"{category}.{name}", fn) for name, fn in _SPECIFIC.get(category, [])]
    if category in ("A", "B", "C", "E"):
        out += [Template(f"{category}.{n}", _generic(one, many)) for n, one, many in GENERIC]
    return out


def render(template: Template, ctx: RenderContext) -> str | None:
    """The template's text for ``ctx`` with display touches, or None when it does not fit."""
    text = template.render(ctx)
    return display(text) if text is not None else None

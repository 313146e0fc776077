"""Vocabulary of the synthetic world: room types, object kinds, colours and materials.

It is shared by the house generator (what to place and how it looks) and the query
generator (how people name things). Retrieval never imports it: the system must earn
its understanding of words from its own lexicon and embeddings.

Two worlds draw from it: the classic one (nine room types, the ``CLASSIC_KINDS``, the
twelve-colour ``COLOURS`` palette, ``AREA_TEMPLATES``) and the default real-world one
(Matterport3D room types, every kind of ``OBJECT_KINDS``, continuous colours named by
:mod:`inherit_sg.ingest.synthetic.colour_naming`, :mod:`inherit_sg.ingest.synthetic.room_contents`).
"""

from __future__ import annotations

from dataclasses import replace

from inherit_sg.ingest.synthetic.catalogue import CLASSIC_EXTRAS, NEW_KINDS
from inherit_sg.ingest.synthetic.kinds import ObjectKind

# Room types with the words people use for them: the classic world's nine and the
# Matterport3D region categories the real-world generator draws (inherit_sg.ingest.synthetic.taxonomy).
ROOM_SYNONYMS: dict[str, tuple[str, ...]] = {
    "bedroom": ("bedroom", "sleeping room"),
    "bathroom": ("bathroom", "washroom", "restroom"),
    "toilet": ("toilet", "powder room", "half bath", "guest toilet"),
    "kitchen": ("kitchen",),
    "living room": ("living room", "sitting room", "front room"),
    "family room": ("family room", "den", "lounge"),
    "tv room": ("tv room", "media room", "television room"),
    "dining room": ("dining room",),
    "office": ("office", "study", "home office"),
    "hallway": ("hallway", "corridor", "hall"),
    "entryway": ("entryway", "foyer", "entrance hall"),
    "closet": ("closet", "walk-in closet"),
    "laundry room": ("laundry room", "laundry", "mudroom"),
    "utility room": ("utility room", "tool room", "boiler room"),
    "garage": ("garage",),
    "porch": ("porch", "terrace", "deck"),
    "balcony": ("balcony",),
    "library": ("library", "reading room"),
    "rec room": ("rec room", "game room", "playroom"),
    "gym": ("gym", "home gym", "workout room"),
    "bar": ("bar", "bar room"),
}

# Named palette: name -> sRGB albedo. Names are what descriptions and queries use.
COLOURS: dict[str, tuple[int, int, int]] = {
    "red": (190, 40, 40),
    "orange": (225, 120, 35),
    "yellow": (225, 200, 50),
    "green": (50, 140, 60),
    "blue": (45, 80, 185),
    "purple": (120, 60, 160),
    "pink": (230, 140, 170),
    "brown": (120, 75, 40),
    "black": (30, 30, 30),
    "white": (235, 235, 230),
    "grey": (128, 128, 128),
    "beige": (215, 195, 160),
}

MATERIALS: tuple[str, ...] = (
    "wood",
    "metal",
    "plastic",
    "fabric",
    "leather",
    "glass",
    "ceramic",
    "stone",
    "wicker",
    "paper",
    "concrete",
)


def _k(label: str, size: tuple[float, float, float], **kw: object) -> ObjectKind:
    kw.setdefault("colours", tuple(COLOURS))
    return ObjectKind(label, size, **kw)  # type: ignore[arg-type]


# fmt: off
CLASSIC_KINDS: dict[str, ObjectKind] = {
    k.label: k
    for k in (
        _k('bed', (1.6, 2.0, 0.55), synonyms=('bed',), functions=('sleep', 'lie down'), colours=('white', 'blue', 'grey', 'beige', 'green'), materials=('wood', 'fabric'), wall=True),
        _k('nightstand', (0.45, 0.4, 0.55), synonyms=('nightstand', 'bedside table'), functions=('store',), colours=('brown', 'white', 'black'), materials=('wood', 'metal'), surface=True),
        _k('wardrobe', (1.2, 0.6, 2.0), synonyms=('wardrobe', 'closet'), functions=('store clothes',), colours=('brown', 'white', 'black'), wall=True),
        _k('dresser', (1.0, 0.5, 0.85), synonyms=('dresser', 'chest of drawers'), functions=('store clothes',), colours=('brown', 'white'), surface=True, wall=True),
        _k('desk', (1.3, 0.65, 0.75), synonyms=('desk', 'writing desk'), functions=('work',), colours=('brown', 'white', 'black'), materials=('wood', 'metal'), surface=True, wall=True),
        _k('chair', (0.5, 0.5, 0.9), synonyms=('chair', 'seat'), functions=('sit',), colours=('red', 'blue', 'black', 'white', 'brown', 'green', 'yellow'), materials=('wood', 'metal', 'plastic')),
        _k('armchair', (0.85, 0.85, 0.9), synonyms=('armchair', 'easy chair'), functions=('sit', 'relax'), colours=('red', 'blue', 'green', 'grey', 'beige', 'brown'), materials=('fabric', 'leather')),
        _k('sofa', (2.0, 0.9, 0.85), synonyms=('sofa', 'couch'), functions=('sit', 'relax', 'lie down'), colours=('grey', 'blue', 'red', 'green', 'beige', 'brown', 'black'), materials=('fabric', 'leather'), wall=True),
        _k('stool', (0.4, 0.4, 0.65), synonyms=('stool',), functions=('sit',), colours=('black', 'brown', 'white', 'red'), materials=('wood', 'metal')),
        _k('coffee table', (1.1, 0.6, 0.42), synonyms=('coffee table', 'low table'), functions=('put things',), colours=('brown', 'black', 'white'), materials=('wood', 'glass'), surface=True),
        _k('dining table', (1.6, 0.9, 0.75), synonyms=('dining table', 'table'), functions=('eat',), colours=('brown', 'white', 'black'), materials=('wood', 'glass'), surface=True),
        _k('table', (1.0, 0.7, 0.74), synonyms=('table',), functions=('put things',), colours=('brown', 'white', 'black', 'grey'), materials=('wood', 'metal'), surface=True),
        _k('tv stand', (1.4, 0.45, 0.5), synonyms=('tv stand', 'tv cabinet'), functions=('store',), colours=('black', 'brown', 'white'), surface=True, wall=True),
        _k('bookshelf', (1.0, 0.35, 1.8), synonyms=('bookshelf', 'bookcase', 'shelf'), functions=('store books',), colours=('brown', 'white', 'black'), surface=True, wall=True),
        _k('cabinet', (0.9, 0.45, 0.9), synonyms=('cabinet', 'cupboard'), functions=('store',), colours=('white', 'brown', 'grey'), materials=('wood', 'metal'), surface=True, wall=True),
        _k('counter', (2.0, 0.6, 0.9), synonyms=('counter', 'kitchen counter', 'worktop'), functions=('prepare food',), colours=('white', 'grey', 'black', 'beige'), materials=('stone', 'wood'), surface=True, wall=True),
        _k('sink', (0.6, 0.5, 0.9), synonyms=('sink', 'washbasin', 'basin'), functions=('wash hands', 'wash dishes'), colours=('white', 'grey'), materials=('ceramic', 'metal'), wall=True),
        _k('stove', (0.6, 0.6, 0.9), synonyms=('stove', 'cooker', 'oven'), functions=('cook',), colours=('black', 'white', 'grey'), materials=('metal',), wall=True),
        _k('refrigerator', (0.7, 0.7, 1.8), synonyms=('refrigerator', 'fridge'), functions=('keep food cold',), colours=('white', 'grey', 'black'), materials=('metal',), wall=True),
        _k('toilet', (0.4, 0.65, 0.8), synonyms=('toilet',), functions=('use the toilet',), colours=('white',), materials=('ceramic',), wall=True),
        _k('bathtub', (1.7, 0.75, 0.55), synonyms=('bathtub', 'tub', 'bath'), functions=('bathe', 'wash'), colours=('white', 'beige'), materials=('ceramic',), wall=True),
        _k('shower', (0.9, 0.9, 2.0), synonyms=('shower',), functions=('shower', 'wash'), colours=('white', 'grey'), materials=('glass',), wall=True),
        _k('washing machine', (0.6, 0.6, 0.85), synonyms=('washing machine', 'washer'), functions=('wash clothes',), colours=('white', 'grey'), materials=('metal',), surface=True, wall=True),
        _k('dryer', (0.6, 0.6, 0.85), synonyms=('dryer', 'tumble dryer'), functions=('dry clothes',), colours=('white', 'grey'), materials=('metal',), surface=True, wall=True),
        _k('car', (1.8, 4.2, 1.45), synonyms=('car',), functions=('drive',), colours=('red', 'blue', 'black', 'white', 'grey'), materials=('metal',)),
        _k('workbench', (1.6, 0.7, 0.9), synonyms=('workbench',), functions=('repair things',), colours=('brown',), surface=True, wall=True),
        _k('plant', (0.45, 0.45, 1.1), synonyms=('plant', 'potted plant', 'houseplant'), functions=('decorate',), colours=('green',), materials=('ceramic',)),
        _k('lamp', (0.4, 0.4, 1.6), synonyms=('lamp', 'floor lamp', 'standing lamp'), functions=('light',), colours=('black', 'white', 'yellow', 'grey'), materials=('metal',)),
        _k('rug', (2.0, 1.4, 0.02), synonyms=('rug', 'carpet'), functions=('decorate',), colours=('red', 'blue', 'beige', 'grey', 'green'), materials=('fabric',)),
        _k('mirror', (0.6, 0.04, 0.9), synonyms=('mirror',), functions=('look at yourself',), colours=('grey',), materials=('glass',), wall=True, mount_height=1.0),
        _k('painting', (0.9, 0.04, 0.6), synonyms=('painting', 'picture'), functions=('decorate',), colours=('blue', 'red', 'green', 'yellow', 'orange', 'purple'), wall=True, mount_height=1.3),
        _k('tv', (1.2, 0.08, 0.7), synonyms=('tv', 'television'), functions=('watch',), colours=('black',), materials=('plastic',), small=True),
        _k('table lamp', (0.25, 0.25, 0.45), synonyms=('table lamp', 'desk lamp', 'lamp'), functions=('light',), colours=('white', 'black', 'yellow', 'red', 'blue'), materials=('metal', 'ceramic'), small=True),
        _k('monitor', (0.6, 0.2, 0.4), synonyms=('monitor', 'computer screen', 'screen'), functions=('work',), colours=('black', 'white'), materials=('plastic',), small=True),
        _k('laptop', (0.35, 0.25, 0.03), synonyms=('laptop', 'notebook computer'), functions=('work',), colours=('grey', 'black'), materials=('metal', 'plastic'), small=True),
        _k('mug', (0.1, 0.1, 0.11), synonyms=('mug', 'cup'), functions=('drink',), colours=('red', 'blue', 'white', 'yellow', 'green', 'black'), materials=('ceramic',), small=True),
        _k('vase', (0.18, 0.18, 0.35), synonyms=('vase',), functions=('hold flowers',), colours=('blue', 'white', 'red', 'green', 'purple'), materials=('ceramic', 'glass'), small=True),
        _k('book', (0.2, 0.15, 0.04), synonyms=('book',), functions=('read',), colours=('red', 'blue', 'green', 'yellow', 'black'), materials=('fabric',), small=True),
        _k('bowl', (0.22, 0.22, 0.09), synonyms=('bowl',), functions=('eat',), colours=('white', 'blue', 'red', 'green'), materials=('ceramic', 'glass'), small=True),
        _k('plate', (0.26, 0.26, 0.03), synonyms=('plate', 'dish'), functions=('eat',), colours=('white', 'blue'), materials=('ceramic',), small=True),
        _k('microwave', (0.5, 0.38, 0.3), synonyms=('microwave', 'microwave oven'), functions=('heat food',), colours=('black', 'white', 'grey'), materials=('metal',), small=True),
        _k('kettle', (0.2, 0.16, 0.25), synonyms=('kettle',), functions=('boil water',), colours=('black', 'white', 'red', 'grey'), materials=('metal', 'plastic'), small=True),
        _k('towel', (0.4, 0.3, 0.08), synonyms=('towel',), functions=('dry hands',), colours=('white', 'blue', 'pink', 'yellow'), materials=('fabric',), small=True),
        _k('clock', (0.3, 0.06, 0.3), synonyms=('clock',), functions=('tell time',), colours=('black', 'white', 'brown'), materials=('plastic', 'wood'), small=True),
        _k('bottle', (0.08, 0.08, 0.28), synonyms=('bottle',), functions=('drink',), colours=('green', 'blue', 'white'), materials=('glass', 'plastic'), small=True),
        _k('toolbox', (0.5, 0.25, 0.25), synonyms=('toolbox', 'tool box'), functions=('repair things',), colours=('red', 'black', 'yellow', 'blue'), materials=('metal', 'plastic'), small=True),
        _k('basket', (0.45, 0.35, 0.3), synonyms=('basket', 'laundry basket'), functions=('carry laundry',), colours=('white', 'blue', 'beige'), materials=('plastic',), small=True),
        _k('door', (0.9, 0.1, 2.05), synonyms=('door', 'doorway'), functions=('go through',), colours=('white', 'brown')),
        _k('window', (1.2, 0.1, 1.2), synonyms=('window',), functions=('look outside',), colours=('white',), materials=('glass',), wall=True, mount_height=0.9),
        _k('stairs', (1.0, 3.0, 3.0), synonyms=('stairs', 'staircase', 'stairway'), functions=('go upstairs', 'go downstairs'), colours=('brown', 'grey', 'white'), materials=('wood', 'stone')),
    )
}
# fmt: on

# Every kind of both worlds: the classic kinds (with their catalogue fields added) and
# the real-world catalogue's.
OBJECT_KINDS: dict[str, ObjectKind] = {
    label: replace(kind, **CLASSIC_EXTRAS.get(label, {})) for label, kind in CLASSIC_KINDS.items()
} | {kind.label: kind for kind in NEW_KINDS}

# What each room type of the classic world contains, as functional groups (the areas):
# group label -> members. The generator picks groups for a room and places each group
# together. The real-world generator uses inherit_sg.ingest.synthetic.room_contents instead.
AREA_TEMPLATES: dict[str, dict[str, tuple[str, ...]]] = {
    "bedroom": {
        "sleeping area": ("bed", "nightstand", "nightstand", "table lamp", "book"),
        "storage area": ("wardrobe", "dresser", "mirror"),
        "reading corner": ("armchair", "lamp", "bookshelf", "book"),
        "work area": ("desk", "chair", "table lamp", "laptop"),
    },
    "bathroom": {
        "washing area": ("sink", "mirror", "towel", "cabinet"),
        "toilet area": ("toilet",),
        "bathing area": ("bathtub", "shower", "towel"),
    },
    "kitchen": {
        "cooking area": ("counter", "stove", "sink", "refrigerator", "kettle", "microwave", "mug"),
        "breakfast area": ("table", "chair", "chair", "bowl", "mug"),
        "storage area": ("cabinet", "bottle"),
    },
    "living room": {
        "tv area": ("sofa", "coffee table", "tv stand", "tv", "rug", "mug", "vase"),
        "reading corner": ("armchair", "lamp", "bookshelf", "book", "plant"),
        "decoration area": ("painting", "plant", "cabinet", "vase", "clock"),
    },
    "dining room": {
        "dining area": (
            "dining table",
            "chair",
            "chair",
            "chair",
            "chair",
            "plate",
            "bowl",
            "vase",
        ),
        "storage area": ("cabinet", "painting", "bottle", "clock"),
    },
    "office": {
        "work area": ("desk", "chair", "monitor", "table lamp", "mug"),
        "storage area": ("bookshelf", "book", "cabinet", "clock"),
        "meeting area": ("table", "chair", "chair", "plant"),
    },
    "hallway": {
        "entrance area": ("cabinet", "mirror", "plant", "painting"),
    },
    "laundry room": {
        "laundry area": ("washing machine", "dryer", "basket", "sink", "towel", "cabinet"),
    },
    "garage": {
        "parking area": ("car",),
        "workshop area": ("workbench", "toolbox", "cabinet", "stool"),
    },
}

# Sizes people talk about, by how an object's volume compares with its kind's typical one.
SIZE_WORDS = ("small", "medium", "large")


def kinds_for_function(function: str) -> list[str]:
    """Labels of object kinds that serve ``function``."""
    return [k.label for k in OBJECT_KINDS.values() if function in k.functions]

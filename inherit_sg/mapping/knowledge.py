"""Everyday knowledge the offline defaults use to name areas and rooms from the objects
they hold. This plays the part of the LLM in the paper's area labelling and of the VLM
in room summaries when no endpoint is configured; every rule is a plain table here."""

from __future__ import annotations

# Functional areas: label -> (anchor objects, supporting objects). A cluster is named by
# the rule with the best evidence (anchors count double).
AREA_RULES: dict[str, tuple[frozenset[str], frozenset[str]]] = {
    "sleeping area": (
        frozenset({"bed"}),
        frozenset({"nightstand", "bedside table", "table lamp", "pillow"}),
    ),
    "dining area": (frozenset({"dining table"}), frozenset({"chair", "plate", "bowl", "vase"})),
    "cooking area": (
        frozenset({"stove", "oven", "refrigerator", "fridge", "counter", "microwave"}),
        frozenset({"sink", "kettle", "cabinet", "bottle", "mug"}),
    ),
    "tv area": (
        frozenset({"tv", "television", "sofa", "couch"}),
        frozenset({"coffee table", "tv stand", "rug", "armchair"}),
    ),
    "work area": (
        frozenset({"desk", "monitor", "laptop"}),
        frozenset({"chair", "table lamp", "office chair"}),
    ),
    "reading corner": (
        frozenset({"bookshelf", "bookcase"}),
        frozenset({"armchair", "lamp", "book"}),
    ),
    "washing area": (frozenset({"sink", "washbasin"}), frozenset({"mirror", "towel", "cabinet"})),
    "toilet area": (frozenset({"toilet"}), frozenset({"toilet paper"})),
    "bathing area": (frozenset({"bathtub", "shower", "bath"}), frozenset({"towel"})),
    "laundry area": (
        frozenset({"washing machine", "dryer"}),
        frozenset({"basket", "laundry basket"}),
    ),
    "parking area": (frozenset({"car"}), frozenset()),
    "workshop area": (frozenset({"workbench", "toolbox"}), frozenset({"stool"})),
    "storage area": (
        frozenset({"wardrobe", "dresser", "cabinet", "closet"}),
        frozenset({"mirror"}),
    ),
    "meeting area": (frozenset({"table"}), frozenset({"chair"})),
    "entrance area": (frozenset({"door"}), frozenset({"mirror", "plant", "cabinet"})),
}

# Room types: type -> {object label: evidence weight}.
ROOM_EVIDENCE: dict[str, dict[str, float]] = {
    "bedroom": {"bed": 3.0, "nightstand": 1.5, "wardrobe": 1.0, "dresser": 1.0},
    "bathroom": {"toilet": 3.0, "bathtub": 3.0, "shower": 3.0, "towel": 0.5, "sink": 0.5},
    "kitchen": {"stove": 3.0, "refrigerator": 3.0, "counter": 2.0, "microwave": 1.5, "kettle": 1.0},
    "living room": {"sofa": 2.5, "tv": 2.0, "coffee table": 2.0, "armchair": 1.0, "tv stand": 1.5},
    "dining room": {"dining table": 3.0},
    "office": {"desk": 2.5, "monitor": 2.0, "laptop": 1.0},
    "laundry room": {"washing machine": 3.0, "dryer": 3.0, "basket": 0.5},
    "garage": {"car": 4.0, "workbench": 2.5, "toolbox": 1.5},
}

# Words for levels in summaries.
ORDINALS = ("ground", "second", "third", "fourth", "fifth")

"""The real-world object catalogue: kinds from the Matterport3D / HM3D / ScanNet
annotation vocabularies, with the words people use, Matterport3D's raw names and
40-class grouping, typical sizes, materials, colour palettes and where each belongs.

``mp3d_rank`` is the row of the kind's most frequent raw name in Matterport3D's category
table (``category_mapping.tsv``, whose rows are ordered by annotation count; the same
table is the ``C`` lines of every ``.house`` file): a low rank is a frequent category.
Kinds without a rank are HM3D / ScanNet categories that Matterport3D names rarely or
otherwise. How often each kind is placed follows these frequencies through the room
contents (:mod:`inherit_sg.ingest.synthetic.room_contents`).

Placement flags are those of :class:`~inherit_sg.ingest.synthetic.kinds.ObjectKind`: ``small``
kinds stand on one of ``rests_on`` (``"floor"``: against a wall when nothing else fits;
``"wall"``: hung on a wall at :data:`~inherit_sg.ingest.synthetic.furnish_real.WALL_HANG` instead),
``wall`` kinds stand against a wall, ``mount_height`` kinds hang on a wall, ``ceiling``
kinds hang from the ceiling, ``window`` kinds dress a window, the rest stand in the room.
"""

from __future__ import annotations

from typing import Any

from inherit_sg.ingest.synthetic.colour_models import CLASSIC_NAMES, palette_for
from inherit_sg.ingest.synthetic.kinds import ObjectKind

Size = tuple[float, float, float]

_TABLE_TOPS = ("dining table", "table", "coffee table", "side table", "console table")
_SHELVES = ("shelf", "bookshelf")
_BED_SEATS = ("bed", "sofa", "armchair", "recliner")


def _k(label: str, size: Size, **kw: Any) -> ObjectKind:
    kw.setdefault("synonyms", (label,))
    material = kw.get("materials", ("wood",))[0]
    kw.setdefault("colours", CLASSIC_NAMES[palette_for(kw.get("palette", ""), material)])
    return ObjectKind(label, size, **kw)


# fmt: off
NEW_KINDS: tuple[ObjectKind, ...] = (
    # --- soft furnishings, lights and window dressing
    _k("pillow", (0.5, 0.35, 0.15), synonyms=("pillow", "cushion", "throw pillow"), materials=("fabric",), palette="textile", small=True, rests_on=_BED_SEATS, mpcat40="cushion", raw=("pillow", "cushion", "throw pillow"), mp3d_rank=9),
    _k("blanket", (0.9, 0.6, 0.05), synonyms=("blanket",), functions=("keep warm",), materials=("fabric",), palette="textile", small=True, rests_on=("bed", "sofa", "armchair"), mpcat40="objects", raw=("blanket",), mp3d_rank=180),
    _k("ceiling light", (0.42, 0.42, 0.12), synonyms=("ceiling light", "light", "light fixture"), functions=("light",), materials=("glass", "metal"), palette="white", ceiling=True, mpcat40="lighting", raw=("light", "ceiling light", "light fixture"), mp3d_rank=11),
    _k("chandelier", (0.7, 0.7, 0.6), synonyms=("chandelier", "light"), functions=("light",), materials=("metal", "glass"), palette="metal", ceiling=True, mpcat40="lighting", raw=("chandelier",), mp3d_rank=110),
    _k("ceiling fan", (1.1, 1.1, 0.35), synonyms=("ceiling fan",), functions=("cool down",), materials=("wood", "metal"), ceiling=True, mpcat40="objects", raw=("ceiling fan",), mp3d_rank=131),
    _k("smoke detector", (0.13, 0.13, 0.05), synonyms=("smoke detector", "smoke alarm"), materials=("plastic",), palette="white", ceiling=True, mpcat40="objects", raw=("smoke alarm", "smoke detector"), mp3d_rank=398),
    _k("wall light", (0.16, 0.12, 0.26), synonyms=("wall light", "sconce", "wall lamp", "light"), functions=("light",), materials=("metal", "glass"), palette="metal", mount_height=1.7, mpcat40="lighting", raw=("wall sconce", "sconce"), mp3d_rank=240),
    _k("curtain", (0.4, 0.06, 2.2), synonyms=("curtain", "drape"), materials=("fabric",), palette="fabric", window=True, mpcat40="curtain", raw=("curtain", "curtains"), mp3d_rank=13),
    _k("blinds", (1.0, 0.03, 0.45), synonyms=("blinds", "window blind", "roller blind"), materials=("plastic", "wood", "fabric"), palette="neutral", window=True, mpcat40="blinds", raw=("blinds",), mp3d_rank=126),
    # --- seats and tables
    _k("dining chair", (0.46, 0.5, 0.95), synonyms=("dining chair", "chair"), functions=("sit",), materials=("wood", "fabric", "metal"), mpcat40="chair", raw=("dining chair",), mp3d_rank=24),
    _k("office chair", (0.62, 0.62, 1.05), synonyms=("office chair", "desk chair", "swivel chair", "chair"), functions=("sit",), materials=("fabric", "leather", "plastic"), palette="fabric", mpcat40="chair", raw=("office chair", "desk chair", "swivel chair"), mp3d_rank=84),
    _k("recliner", (0.9, 0.95, 1.02), synonyms=("recliner", "reclining chair", "armchair"), functions=("sit", "relax"), materials=("leather", "fabric"), mpcat40="chair", raw=("recliner",), mp3d_rank=426),
    _k("ottoman", (0.6, 0.6, 0.42), synonyms=("ottoman", "pouf"), functions=("sit",), materials=("fabric", "leather"), mpcat40="stool", raw=("ottoman",), mp3d_rank=79),
    _k("footstool", (0.45, 0.35, 0.35), synonyms=("footstool",), materials=("wood", "fabric"), mpcat40="stool", raw=("footstool",), mp3d_rank=113),
    _k("bench", (1.2, 0.4, 0.46), synonyms=("bench",), functions=("sit",), materials=("wood", "metal"), wall=True, mpcat40="seating", raw=("bench",), mp3d_rank=48),
    _k("bar stool", (0.4, 0.4, 0.76), synonyms=("bar stool", "stool"), functions=("sit",), materials=("metal", "wood", "leather"), mpcat40="stool", raw=("stool",)),
    _k("outdoor chair", (0.6, 0.62, 0.85), synonyms=("outdoor chair", "patio chair", "garden chair", "chair"), functions=("sit",), materials=("plastic", "wicker", "metal"), mpcat40="chair", raw=("patio chair",), mp3d_rank=579),
    _k("side table", (0.5, 0.5, 0.56), synonyms=("side table", "end table", "table"), functions=("put things",), materials=("wood", "metal", "glass"), surface=True, mpcat40="table", raw=("side table", "end table"), mp3d_rank=72),
    _k("console table", (1.1, 0.36, 0.8), synonyms=("console table", "hall table", "table"), functions=("put things",), materials=("wood", "metal", "glass"), surface=True, wall=True, mpcat40="table", raw=("table",)),
    _k("kitchen island", (1.8, 0.9, 0.92), synonyms=("kitchen island", "island"), functions=("prepare food", "put things"), materials=("stone", "wood"), surface=True, mpcat40="counter", raw=("kitchen island",), mp3d_rank=197),
    _k("bar counter", (2.0, 0.6, 1.05), synonyms=("bar counter",), functions=("put things",), materials=("wood", "stone"), surface=True, wall=True, mpcat40="counter", raw=("bar",), mp3d_rank=270),
    _k("picnic table", (1.6, 1.4, 0.75), synonyms=("picnic table", "garden table", "table"), functions=("eat", "put things"), materials=("wood", "metal"), surface=True, mpcat40="table", raw=("table",)),
    _k("pool table", (2.4, 1.35, 0.8), synonyms=("pool table", "billiard table"), functions=("play pool",), materials=("wood",), palette="natural wood", mpcat40="table", raw=("pool table",), mp3d_rank=274),
    _k("ping pong table", (2.74, 1.53, 0.76), synonyms=("ping pong table", "table tennis table"), functions=("play ping pong",), materials=("wood",), palette="vivid", mpcat40="table", raw=("ping pong table",), mp3d_rank=888),
    # --- storage
    _k("kitchen cabinet", (0.8, 0.6, 0.9), synonyms=("kitchen cabinet", "cabinet", "cupboard"), functions=("store",), materials=("wood", "plastic"), surface=True, wall=True, mpcat40="cabinet", raw=("kitchen cabinet",), mp3d_rank=34),
    _k("wall cabinet", (0.8, 0.35, 0.7), synonyms=("wall cabinet", "cabinet", "cupboard"), functions=("store",), materials=("wood", "plastic"), mount_height=1.45, mpcat40="cabinet", raw=("kitchen upper cabinet", "wall cabinet"), mp3d_rank=292),
    _k("bathroom cabinet", (0.6, 0.4, 0.85), synonyms=("bathroom cabinet", "cabinet"), functions=("store",), materials=("wood", "plastic"), surface=True, wall=True, mpcat40="cabinet", raw=("bath cabinet", "bathroom cabinet"), mp3d_rank=56),
    _k("shelf", (0.9, 0.32, 1.5), synonyms=("shelf", "shelves", "shelving"), functions=("store",), materials=("wood", "metal"), surface=True, wall=True, shelves=True, mpcat40="shelving", raw=("shelf", "shelves", "shelving"), mp3d_rank=22),
    _k("shoe rack", (0.8, 0.32, 0.6), synonyms=("shoe rack", "shoe shelf"), functions=("store shoes",), materials=("wood", "metal"), surface=True, wall=True, shelves=True, mpcat40="shelving", raw=("shoe rack",)),
    _k("wine rack", (0.6, 0.3, 0.9), synonyms=("wine rack",), materials=("wood", "metal"), surface=True, wall=True, shelves=True, mpcat40="shelving", raw=("wine rack", "shelves with wine")),
    _k("sideboard", (1.6, 0.45, 0.85), synonyms=("sideboard", "buffet"), functions=("store",), materials=("wood",), surface=True, wall=True, mpcat40="cabinet", raw=("buffet", "sideboard"), mp3d_rank=697),
    _k("filing cabinet", (0.45, 0.6, 1.0), synonyms=("filing cabinet", "file cabinet", "cabinet"), functions=("store documents",), materials=("metal", "wood"), palette="neutral", surface=True, wall=True, mpcat40="cabinet", raw=("file cabinet",), mp3d_rank=404),
    _k("tool cabinet", (0.7, 0.45, 1.0), synonyms=("tool cabinet", "tool chest", "cabinet"), functions=("repair things",), materials=("metal",), palette="tools", surface=True, wall=True, mpcat40="cabinet", raw=("cabinet",)),
    _k("box", (0.42, 0.32, 0.3), synonyms=("box", "cardboard box"), functions=("store",), materials=("paper", "plastic"), palette="cardboard", small=True, rests_on=("shelf", "floor"), mpcat40="objects", raw=("box", "boxes"), mp3d_rank=44),
    _k("storage bin", (0.55, 0.4, 0.34), synonyms=("storage bin",), functions=("store",), materials=("plastic",), small=True, rests_on=("shelf", "floor"), mpcat40="objects", raw=("storage bin",), mp3d_rank=479),
    _k("trash can", (0.3, 0.3, 0.45), synonyms=("trash can", "bin", "garbage can", "wastebasket", "trash bin"), functions=("throw away trash",), materials=("plastic", "metal"), palette="neutral", wall=True, mpcat40="objects", raw=("trash can", "trashcan", "trash bin", "bin"), mp3d_rank=50),
    _k("coat rack", (0.5, 0.5, 1.75), synonyms=("coat rack", "coat stand", "hat stand"), functions=("hang my coat",), materials=("wood", "metal"), mpcat40="objects", raw=("coat rack", "coat hanger"), mp3d_rank=382),
    # --- kitchen
    _k("oven", (0.6, 0.6, 0.9), synonyms=("oven",), functions=("bake", "cook"), materials=("metal",), palette="appliance", wall=True, mpcat40="appliances", raw=("oven",), mp3d_rank=111),
    _k("dishwasher", (0.6, 0.6, 0.86), synonyms=("dishwasher", "dish washer"), functions=("wash dishes",), materials=("metal",), palette="appliance", surface=True, wall=True, mpcat40="appliances", raw=("dishwasher",), mp3d_rank=206),
    _k("range hood", (0.75, 0.5, 0.5), synonyms=("range hood", "extractor hood", "cooker hood"), materials=("metal",), palette="appliance", mount_height=1.55, mpcat40="objects", raw=("range hood", "stove hood", "kitchen hood"), mp3d_rank=319),
    _k("mini fridge", (0.5, 0.5, 0.85), synonyms=("mini fridge", "minibar"), functions=("keep food cold",), materials=("metal",), palette="appliance", surface=True, wall=True, mpcat40="appliances", raw=("mini fridge",), mp3d_rank=1359),
    _k("coffee machine", (0.26, 0.36, 0.36), synonyms=("coffee machine", "coffee maker"), functions=("make coffee",), materials=("plastic", "metal"), palette="appliance", small=True, rests_on=("counter", "kitchen island", "kitchen cabinet"), mpcat40="appliances", raw=("coffee maker",), mp3d_rank=372),
    _k("toaster", (0.28, 0.18, 0.2), synonyms=("toaster",), functions=("make toast",), materials=("metal", "plastic"), palette="appliance", small=True, rests_on=("counter", "kitchen cabinet"), mpcat40="appliances", raw=("toaster",), mp3d_rank=430),
    _k("pan", (0.28, 0.28, 0.06), synonyms=("pan", "frying pan", "skillet"), functions=("cook",), materials=("metal",), palette="black", small=True, rests_on=("stove", "counter"), mpcat40="objects", raw=("pan",), mp3d_rank=383),
    _k("teapot", (0.22, 0.15, 0.18), synonyms=("teapot",), materials=("ceramic", "metal"), small=True, rests_on=("counter", "dining table", "table", "kitchen island"), mpcat40="objects", raw=("teapot",), mp3d_rank=287),
    _k("cutting board", (0.4, 0.28, 0.02), synonyms=("cutting board", "chopping board"), functions=("prepare food",), materials=("wood", "plastic"), palette="natural wood", small=True, rests_on=("counter", "kitchen island"), mpcat40="objects", raw=("cutting board",), mp3d_rank=822),
    _k("knife block", (0.12, 0.2, 0.25), synonyms=("knife block",), materials=("wood",), palette="natural wood", small=True, rests_on=("counter",), mpcat40="objects", raw=("knife block",)),
    _k("dish rack", (0.45, 0.35, 0.15), synonyms=("dish rack", "dish drainer"), materials=("metal", "plastic"), small=True, rests_on=("counter",), mpcat40="objects", raw=("dish rack",)),
    _k("paper towel", (0.12, 0.12, 0.28), synonyms=("paper towel", "kitchen roll"), functions=("dry hands",), materials=("paper",), palette="white", small=True, rests_on=("counter", "kitchen island"), mpcat40="towel", raw=("paper towel",), mp3d_rank=198),
    _k("jar", (0.1, 0.1, 0.16), synonyms=("jar",), materials=("glass", "ceramic"), small=True, rests_on=("counter", "shelf", "kitchen island"), mpcat40="objects", raw=("jar",), mp3d_rank=408),
    _k("spice rack", (0.42, 0.12, 0.32), synonyms=("spice rack",), materials=("wood", "metal"), small=True, rests_on=("counter",), mpcat40="shelving", raw=("spice rack",), mp3d_rank=1503),
    _k("fruit bowl", (0.3, 0.3, 0.12), synonyms=("fruit bowl", "bowl of fruit"), functions=("eat",), materials=("ceramic", "wicker", "glass"), small=True, rests_on=("dining table", "counter", "kitchen island", "coffee table", "table"), mpcat40="objects", raw=("fruit bowl", "bowl of fruit"), mp3d_rank=366),
    _k("glass", (0.08, 0.08, 0.14), synonyms=("glass", "drinking glass"), functions=("drink",), materials=("glass",), small=True, rests_on=("dining table", "counter", "table", "bar counter", "nightstand", "coffee table"), mpcat40="objects", raw=("glass",), mp3d_rank=204),
    _k("tray", (0.45, 0.32, 0.04), synonyms=("tray",), materials=("wood", "metal", "plastic"), small=True, rests_on=("coffee table", "counter", "ottoman", "dining table"), mpcat40="objects", raw=("tray",), mp3d_rank=265),
    _k("fire extinguisher", (0.16, 0.16, 0.52), synonyms=("fire extinguisher", "extinguisher"), functions=("put out a fire",), materials=("metal",), palette="red", wall=True, mpcat40="objects", raw=("fire extinguisher",), mp3d_rank=162),
    # --- bathroom
    _k("toilet paper", (0.12, 0.12, 0.11), synonyms=("toilet paper", "toilet roll"), materials=("paper",), palette="white", small=True, rests_on=("toilet", "shelf", "bathroom cabinet", "sink"), mpcat40="objects", raw=("toilet paper",), mp3d_rank=64),
    _k("toiletry", (0.08, 0.08, 0.18), synonyms=("toiletry",), materials=("plastic", "glass"), palette="plastic", small=True, rests_on=("sink", "bathroom cabinet", "shelf"), mpcat40="objects", raw=("toiletry", "bathroom countertop object"), mp3d_rank=90),
    _k("soap", (0.09, 0.06, 0.04), synonyms=("soap", "bar of soap"), functions=("wash hands",), materials=("plastic",), palette="ceramic", small=True, rests_on=("sink", "bathroom cabinet"), mpcat40="objects", raw=("soap",), mp3d_rank=192),
    _k("soap dispenser", (0.08, 0.08, 0.18), synonyms=("soap dispenser", "soap pump"), functions=("wash hands",), materials=("plastic", "ceramic", "glass"), small=True, rests_on=("sink", "counter"), mpcat40="objects", raw=("soap dispenser",), mp3d_rank=205),
    _k("toothbrush", (0.03, 0.03, 0.19), synonyms=("toothbrush",), functions=("brush my teeth",), materials=("plastic",), palette="vivid", small=True, rests_on=("sink", "shelf"), mpcat40="objects", raw=("toothbrush",)),
    _k("shampoo", (0.07, 0.05, 0.22), synonyms=("shampoo", "shampoo bottle"), materials=("plastic",), small=True, rests_on=("bathroom cabinet", "shelf", "sink"), mpcat40="objects", raw=("shampoo",), mp3d_rank=359),
    _k("cosmetics", (0.1, 0.06, 0.12), synonyms=("cosmetics", "makeup"), materials=("plastic", "glass"), palette="decor", small=True, rests_on=("dresser", "sink", "bathroom cabinet", "shelf"), mpcat40="objects", raw=("cosmetics",), mp3d_rank=494),
    _k("towel rack", (0.6, 0.1, 0.08), synonyms=("towel rack", "towel bar", "towel rail"), materials=("metal",), palette="metal", mount_height=1.0, mpcat40="objects", raw=("towel bar",), mp3d_rank=257),
    _k("bath mat", (0.8, 0.5, 0.015), synonyms=("bath mat", "bathroom rug"), materials=("fabric",), palette="textile", mpcat40="floor", raw=("bath mat",), mp3d_rank=420),
    _k("toilet brush", (0.12, 0.12, 0.4), synonyms=("toilet brush",), materials=("plastic",), palette="neutral", wall=True, mpcat40="misc", raw=("toilet brush",), mp3d_rank=310),
    _k("scale", (0.32, 0.32, 0.055), synonyms=("scale", "bathroom scale"), functions=("weigh myself",), materials=("glass", "plastic"), palette="neutral", wall=True, mpcat40="objects", raw=("scale",), mp3d_rank=242),
    _k("tissue box", (0.24, 0.12, 0.1), synonyms=("tissue box", "box of tissues"), functions=("blow my nose",), materials=("paper",), palette="decor", small=True, rests_on=("nightstand", "side table", "coffee table", "toilet", "bathroom cabinet", "desk"), mpcat40="objects", raw=("tissue box",), mp3d_rank=132),
    # --- living, bedroom and office things
    _k("decoration", (0.16, 0.16, 0.22), synonyms=("decoration", "ornament", "knickknack"), materials=("ceramic", "glass", "metal", "wood"), palette="decor", small=True, rests_on=(*_SHELVES, "sideboard", "console table", "fireplace", "cabinet", "side table", "dresser", "coffee table"), mpcat40="objects", raw=("decoration", "decor", "decorative object", "knickknack"), mp3d_rank=16),
    _k("statue", (0.2, 0.2, 0.42), synonyms=("statue",), materials=("stone", "metal", "ceramic"), small=True, rests_on=("sideboard", "console table", "side table", "cabinet", *_SHELVES, "fireplace"), mpcat40="objects", raw=("statue", "sculpture"), mp3d_rank=75),
    _k("candle", (0.07, 0.07, 0.15), synonyms=("candle",), functions=("light",), materials=("plastic",), palette="white", small=True, rests_on=("dining table", "coffee table", "sideboard", "fireplace", "side table", "console table", "shelf"), mpcat40="objects", raw=("candle", "candles"), mp3d_rank=149),
    _k("flower pot", (0.22, 0.22, 0.32), synonyms=("flower pot", "plant pot", "flowerpot"), functions=("decorate",), materials=("ceramic",), palette="terracotta", small=True, rests_on=(*_TABLE_TOPS, "shelf", "counter", "floor"), mpcat40="objects", raw=("flowerpot", "plant pot", "flower pot"), mp3d_rank=150),
    _k("speaker", (0.2, 0.22, 0.32), synonyms=("speaker", "loudspeaker"), functions=("listen to music",), materials=("wood", "plastic"), palette="electronics", small=True, rests_on=("tv stand", *_SHELVES, "desk", "floor"), mpcat40="objects", raw=("speaker",), mp3d_rank=151),
    _k("remote", (0.05, 0.18, 0.025), synonyms=("remote", "remote control", "tv remote"), materials=("plastic",), palette="electronics", small=True, rests_on=("coffee table", "sofa", "side table", "tv stand", "armchair", "nightstand"), mpcat40="objects", raw=("remote control",)),
    _k("game console", (0.3, 0.25, 0.07), synonyms=("game console", "video game console"), functions=("play video games",), materials=("plastic",), palette="electronics", small=True, rests_on=("tv stand", "shelf"), mpcat40="objects", raw=("game console",)),
    _k("phone", (0.08, 0.16, 0.02), synonyms=("phone", "telephone", "cell phone"), functions=("call someone",), materials=("plastic",), palette="electronics", small=True, rests_on=("nightstand", "desk", "side table", "coffee table", "counter", "table"), mpcat40="objects", raw=("telephone", "phone"), mp3d_rank=175),
    _k("keyboard", (0.45, 0.15, 0.03), synonyms=("keyboard", "computer keyboard"), functions=("type",), materials=("plastic",), palette="electronics", small=True, rests_on=("desk",), mpcat40="objects", raw=("keyboard",), mp3d_rank=194),
    _k("mouse", (0.06, 0.11, 0.035), synonyms=("mouse", "computer mouse"), materials=("plastic",), palette="electronics", small=True, rests_on=("desk",), mpcat40="objects", raw=("mouse",), mp3d_rank=641),
    _k("printer", (0.45, 0.4, 0.25), synonyms=("printer",), functions=("print",), materials=("plastic",), palette="electronics", small=True, rests_on=("desk", "shelf", "cabinet", "filing cabinet", "table"), mpcat40="objects", raw=("printer",), mp3d_rank=173),
    _k("computer", (0.2, 0.45, 0.42), synonyms=("computer", "desktop computer", "pc"), functions=("work",), materials=("plastic", "metal"), palette="electronics", small=True, rests_on=("desk", "floor"), mpcat40="objects", raw=("computer",), mp3d_rank=360),
    _k("globe", (0.3, 0.3, 0.45), synonyms=("globe",), materials=("plastic",), palette="vivid", small=True, rests_on=("desk", *_SHELVES, "side table"), mpcat40="misc", raw=("globe",), mp3d_rank=481),
    _k("whiteboard", (1.2, 0.03, 0.9), synonyms=("whiteboard",), functions=("write",), materials=("plastic",), palette="white", mount_height=0.95, mpcat40="tv_monitor", raw=("whiteboard",), mp3d_rank=317),
    _k("light switch", (0.08, 0.02, 0.12), synonyms=("light switch", "switch"), materials=("plastic",), palette="white", mount_height=1.2, mpcat40="objects", raw=("light switch", "switch"), mp3d_rank=98),
    _k("thermostat", (0.1, 0.03, 0.1), synonyms=("thermostat",), materials=("plastic",), palette="white", mount_height=1.45, mpcat40="objects", raw=("thermostat",), mp3d_rank=195),
    _k("air conditioner", (0.9, 0.25, 0.3), synonyms=("air conditioner", "ac unit", "air conditioning unit"), functions=("cool down",), materials=("plastic",), palette="white", mount_height=2.05, mpcat40="objects", raw=("air conditioner",), mp3d_rank=154),
    _k("radiator", (0.9, 0.12, 0.6), synonyms=("radiator",), functions=("warm up",), materials=("metal",), palette="white", mount_height=0.12, mpcat40="objects", raw=("radiator", "heater"), mp3d_rank=196),
    _k("fireplace", (1.4, 0.45, 1.1), synonyms=("fireplace", "hearth"), functions=("warm up",), materials=("stone", "concrete"), surface=True, wall=True, mpcat40="fireplace", raw=("fireplace",), mp3d_rank=51),
    _k("fan", (0.42, 0.35, 1.2), synonyms=("fan", "floor fan", "standing fan"), functions=("cool down",), materials=("plastic", "metal"), palette="neutral", mpcat40="objects", raw=("fan",), mp3d_rank=66),
    _k("piano", (1.5, 0.6, 1.25), synonyms=("piano",), functions=("play music",), materials=("wood",), palette="piano", wall=True, mpcat40="objects", raw=("piano",), mp3d_rank=216),
    _k("guitar", (0.38, 0.1, 1.0), synonyms=("guitar",), functions=("play music",), materials=("wood",), palette="natural wood", wall=True, mpcat40="objects", raw=("guitar",), mp3d_rank=250),
    _k("clothes", (0.4, 0.3, 0.12), synonyms=("clothes", "clothing"), materials=("fabric",), palette="textile", small=True, rests_on=("bed", "dresser", "shelf", "washing machine", "dryer", "bench"), mpcat40="clothes", raw=("clothes", "clothing"), mp3d_rank=52),
    _k("hat", (0.3, 0.3, 0.14), synonyms=("hat", "cap"), materials=("fabric",), palette="fabric", small=True, rests_on=("shelf", "dresser", "console table", "bed", "bench"), mpcat40="clothes", raw=("hat",), mp3d_rank=211),
    _k("handbag", (0.35, 0.15, 0.25), synonyms=("handbag", "purse"), materials=("leather", "fabric"), small=True, rests_on=("bed", "bench", "dresser", "console table", "floor"), mpcat40="objects", raw=("purse", "handbag"), mp3d_rank=100),
    _k("bag", (0.4, 0.22, 0.36), synonyms=("bag",), materials=("fabric", "leather"), small=True, rests_on=("bench", "bed", "floor"), mpcat40="objects", raw=("bag",), mp3d_rank=246),
    _k("backpack", (0.32, 0.2, 0.45), synonyms=("backpack", "rucksack"), materials=("fabric",), small=True, rests_on=("floor", "bed", "bench"), mpcat40="objects", raw=("backpack",), mp3d_rank=418),
    _k("suitcase", (0.45, 0.25, 0.65), synonyms=("suitcase", "luggage"), functions=("pack for a trip",), materials=("plastic", "fabric"), palette="plastic", wall=True, mpcat40="objects", raw=("suitcase",), mp3d_rank=385),
    _k("shoe", (0.3, 0.22, 0.12), synonyms=("shoe", "pair of shoes"), materials=("leather", "fabric"), small=True, rests_on=("shoe rack", "shelf", "floor"), mpcat40="objects", raw=("shoes", "shoe"), mp3d_rank=136),
    _k("umbrella", (0.14, 0.14, 0.85), synonyms=("umbrella",), materials=("fabric",), palette="vivid", wall=True, mpcat40="objects", raw=("umbrella",), mp3d_rank=405),
    _k("stuffed animal", (0.26, 0.2, 0.3), synonyms=("stuffed animal", "teddy bear", "plush toy", "soft toy"), materials=("fabric",), palette="decor", small=True, rests_on=("bed", "shelf", "sofa", "armchair"), mpcat40="objects", raw=("stuffed animal", "plush toy"), mp3d_rank=299),
    _k("toy", (0.25, 0.2, 0.16), synonyms=("toy",), functions=("play",), materials=("plastic",), palette="vivid", small=True, rests_on=("floor", "shelf", "coffee table"), mpcat40="objects", raw=("toy",), mp3d_rank=328),
    # --- laundry, utility and garage
    _k("laundry detergent", (0.2, 0.12, 0.28), synonyms=("laundry detergent", "detergent"), materials=("plastic",), palette="vivid", small=True, rests_on=("washing machine", "dryer", "shelf", "cabinet"), mpcat40="objects", raw=("laundry detergent",)),
    _k("ironing board", (1.3, 0.4, 0.9), synonyms=("ironing board",), functions=("iron my clothes",), materials=("metal",), palette="textile", mpcat40="objects", raw=("ironing board",), mp3d_rank=1098),
    _k("bucket", (0.3, 0.3, 0.3), synonyms=("bucket", "pail"), materials=("plastic", "metal"), palette="plastic", wall=True, mpcat40="objects", raw=("bucket",), mp3d_rank=147),
    _k("broom", (0.3, 0.08, 1.3), synonyms=("broom",), functions=("sweep the floor",), materials=("wood", "plastic"), wall=True, mpcat40="objects", raw=("broom",)),
    _k("mop", (0.3, 0.1, 1.3), synonyms=("mop",), functions=("mop the floor",), materials=("plastic",), wall=True, mpcat40="objects", raw=("mop",)),
    _k("vacuum cleaner", (0.3, 0.3, 1.1), synonyms=("vacuum cleaner", "vacuum", "hoover"), functions=("vacuum the floor",), materials=("plastic",), wall=True, mpcat40="appliances", raw=("vacuum cleaner",), mp3d_rank=467),
    _k("ladder", (0.5, 0.15, 1.8), synonyms=("ladder", "step ladder"), functions=("reach high places",), materials=("metal", "wood"), wall=True, mpcat40="stairs", raw=("ladder",), mp3d_rank=209),
    _k("water heater", (0.55, 0.55, 1.5), synonyms=("water heater", "boiler"), materials=("metal",), palette="white", wall=True, mpcat40="objects", raw=("water heater",), mp3d_rank=570),
    _k("furnace", (0.6, 0.75, 1.3), synonyms=("furnace",), functions=("warm up",), materials=("metal",), palette="neutral", wall=True, mpcat40="misc", raw=("furnace",), mp3d_rank=1486),
    _k("electrical panel", (0.45, 0.1, 0.6), synonyms=("electrical panel", "fuse box", "breaker box"), materials=("metal",), palette="grey", mount_height=1.2, mpcat40="board_panel", raw=("panel",), mp3d_rank=203),
    _k("paint can", (0.18, 0.18, 0.2), synonyms=("paint can", "can of paint", "paint tin"), materials=("metal",), small=True, rests_on=("shelf", "workbench", "floor"), mpcat40="objects", raw=("paint can",)),
    _k("bicycle", (0.6, 1.75, 1.05), synonyms=("bicycle", "bike"), functions=("go for a ride",), materials=("metal",), palette="car", mpcat40="objects", raw=("bicycle",), mp3d_rank=602),
    _k("lawn mower", (0.55, 1.2, 1.0), synonyms=("lawn mower", "lawnmower", "mower"), functions=("mow the lawn",), materials=("metal", "plastic"), palette="tools", mpcat40="objects", raw=("lawn mower",)),
    # --- gym, games and outdoors
    _k("treadmill", (0.8, 1.8, 1.4), synonyms=("treadmill", "running machine"), functions=("exercise",), materials=("metal", "plastic"), palette="electronics", mpcat40="gym_equipment", raw=("treadmill",), mp3d_rank=248),
    _k("exercise bike", (0.55, 1.1, 1.2), synonyms=("exercise bike", "stationary bike"), functions=("exercise",), materials=("metal",), palette="electronics", mpcat40="gym_equipment", raw=("exercise bike",), mp3d_rank=409),
    _k("weight bench", (0.5, 1.3, 0.5), synonyms=("weight bench", "workout bench"), functions=("exercise",), materials=("metal", "leather"), palette="black", mpcat40="gym_equipment", raw=("weight bench",), mp3d_rank=1357),
    _k("dumbbell", (0.3, 0.12, 0.12), synonyms=("dumbbell",), functions=("exercise",), materials=("metal",), palette="metal", small=True, rests_on=("floor", "shelf", "weight bench"), mpcat40="gym_equipment", raw=("weights",), mp3d_rank=400),
    _k("exercise ball", (0.65, 0.65, 0.65), synonyms=("exercise ball", "yoga ball", "gym ball"), functions=("exercise",), materials=("plastic",), palette="vivid", mpcat40="gym_equipment", raw=("exercise ball",), mp3d_rank=802),
    _k("yoga mat", (0.6, 1.8, 0.01), synonyms=("yoga mat", "exercise mat"), functions=("do yoga",), materials=("plastic",), palette="vivid", mpcat40="gym_equipment", raw=("exercise mat", "yoga mat"), mp3d_rank=397),
    _k("dartboard", (0.45, 0.04, 0.45), synonyms=("dartboard", "dart board"), functions=("play darts",), materials=("fabric",), palette="black", mount_height=1.5, mpcat40="objects", raw=("dartboard",), mp3d_rank=1570),
    _k("watering can", (0.35, 0.15, 0.3), synonyms=("watering can",), functions=("water the plants",), materials=("plastic", "metal"), palette="vivid", small=True, rests_on=("floor", "shelf", "table"), mpcat40="objects", raw=("watering can",), mp3d_rank=1528),
    _k("lantern", (0.18, 0.18, 0.32), synonyms=("lantern",), functions=("light",), materials=("metal", "glass"), palette="black", small=True, rests_on=("picnic table", "table", "side table", "floor"), mpcat40="objects", raw=("lantern",)),
)
# fmt: on

# Catalogue fields for the kinds the classic world already had (their sizes and flags
# stay as they were).
CLASSIC_EXTRAS: dict[str, dict[str, Any]] = {
    "bed": dict(mpcat40="bed", raw=("bed", "bedframe", "headboard"), mp3d_rank=25),
    "nightstand": dict(
        mpcat40="chest_of_drawers", raw=("nightstand", "bedside table"), mp3d_rank=26
    ),
    "wardrobe": dict(mpcat40="furniture", raw=("wardrobe", "closet"), mp3d_rank=89),
    "dresser": dict(
        mpcat40="chest_of_drawers", raw=("dresser", "drawers", "chest of drawers"), mp3d_rank=76
    ),
    "desk": dict(mpcat40="table", raw=("desk", "computer desk"), mp3d_rank=41),
    "chair": dict(mpcat40="chair", raw=("chair",), mp3d_rank=6),
    "armchair": dict(mpcat40="chair", raw=("sofa chair", "armchair", "easy chair"), mp3d_rank=28),
    "sofa": dict(mpcat40="sofa", raw=("couch", "sofa"), mp3d_rank=23),
    "stool": dict(mpcat40="stool", raw=("stool",), mp3d_rank=32),
    "coffee table": dict(mpcat40="table", raw=("coffee table",), mp3d_rank=46),
    "dining table": dict(mpcat40="table", raw=("dining table", "table"), mp3d_rank=96),
    "table": dict(mpcat40="table", raw=("table", "round table"), mp3d_rank=14),
    "tv stand": dict(mpcat40="furniture", raw=("tv stand",), mp3d_rank=135),
    "bookshelf": dict(mpcat40="shelving", raw=("bookshelf", "bookcase"), mp3d_rank=87),
    "cabinet": dict(mpcat40="cabinet", raw=("cabinet", "cupboard"), mp3d_rank=12),
    "counter": dict(
        mpcat40="counter", raw=("kitchen counter", "counter", "countertop"), mp3d_rank=82
    ),
    "sink": dict(mpcat40="sink", raw=("sink", "washbasin", "bathroom sink"), mp3d_rank=21),
    "stove": dict(
        mpcat40="appliances",
        raw=("stove", "range"),
        mp3d_rank=114,
        palette="appliance",
        synonyms=("stove", "cooker", "range"),
    ),
    "refrigerator": dict(
        mpcat40="appliances", raw=("refrigerator", "fridge"), mp3d_rank=86, palette="appliance"
    ),
    "toilet": dict(mpcat40="toilet", raw=("toilet",), mp3d_rank=27, palette="white"),
    "bathtub": dict(mpcat40="bathtub", raw=("bathtub",), mp3d_rank=54, palette="white"),
    "shower": dict(mpcat40="shower", raw=("shower",), mp3d_rank=181),
    "washing machine": dict(
        mpcat40="appliances", raw=("washing machine",), mp3d_rank=118, palette="appliance"
    ),
    "dryer": dict(
        mpcat40="appliances", raw=("clothes dryer", "dryer"), mp3d_rank=202, palette="appliance"
    ),
    "car": dict(mpcat40="objects", raw=("car",), mp3d_rank=306, palette="car"),
    "workbench": dict(mpcat40="table", raw=("workbench",), palette="natural wood"),
    "plant": dict(
        mpcat40="plant", raw=("plant", "potted plant", "plants"), mp3d_rank=15, palette="plant"
    ),
    "lamp": dict(mpcat40="lighting", raw=("lamp", "floor lamp"), mp3d_rank=18),
    "rug": dict(mpcat40="floor", raw=("rug", "carpet", "mat"), mp3d_rank=78, palette="fabric"),
    "mirror": dict(mpcat40="mirror", raw=("mirror",), mp3d_rank=19),
    "painting": dict(
        mpcat40="picture", raw=("picture", "painting", "photo", "art"), mp3d_rank=4, palette="art"
    ),
    "tv": dict(
        mpcat40="tv_monitor",
        raw=("tv",),
        mp3d_rank=37,
        palette="black",
        rests_on=("tv stand", "dresser", "sideboard", "cabinet", "wall"),
    ),
    "table lamp": dict(
        mpcat40="lighting",
        raw=("table lamp",),
        mp3d_rank=68,
        rests_on=("nightstand", "side table", "desk", "dresser", "console table", "sideboard"),
    ),
    "monitor": dict(
        mpcat40="tv_monitor",
        raw=("monitor", "computer monitor"),
        mp3d_rank=93,
        palette="electronics",
        rests_on=("desk",),
    ),
    "laptop": dict(
        mpcat40="objects",
        raw=("laptop",),
        mp3d_rank=247,
        palette="electronics",
        rests_on=("desk", "table", "coffee table", "bed", "dining table"),
    ),
    "mug": dict(
        mpcat40="objects",
        raw=("cup", "mug"),
        mp3d_rank=207,
        rests_on=(
            "counter",
            "coffee table",
            "table",
            "desk",
            "dining table",
            "kitchen island",
            "nightstand",
        ),
    ),
    "vase": dict(
        mpcat40="objects",
        raw=("vase",),
        mp3d_rank=35,
        rests_on=(
            "dining table",
            "coffee table",
            "sideboard",
            "console table",
            "side table",
            "shelf",
            "bookshelf",
            "cabinet",
            "dresser",
            "table",
        ),
    ),
    "book": dict(
        mpcat40="objects",
        raw=("book", "books"),
        mp3d_rank=57,
        palette="books",
        rests_on=(
            "bookshelf",
            "shelf",
            "nightstand",
            "coffee table",
            "desk",
            "side table",
            "bed",
            "table",
        ),
    ),
    "bowl": dict(
        mpcat40="objects",
        raw=("bowl",),
        mp3d_rank=127,
        rests_on=("dining table", "counter", "kitchen island", "table"),
    ),
    "plate": dict(
        mpcat40="objects",
        raw=("plate",),
        mp3d_rank=134,
        rests_on=("dining table", "table", "kitchen island", "counter"),
    ),
    "microwave": dict(
        mpcat40="appliances",
        raw=("microwave",),
        mp3d_rank=125,
        palette="appliance",
        rests_on=("counter", "kitchen cabinet"),
    ),
    "kettle": dict(
        mpcat40="objects",
        raw=("kettle",),
        mp3d_rank=496,
        rests_on=("counter", "stove", "kitchen island"),
    ),
    "towel": dict(
        mpcat40="towel",
        raw=("towel", "towels"),
        mp3d_rank=20,
        palette="textile",
        rests_on=("sink", "bathroom cabinet", "shelf", "washing machine", "dryer", "bed"),
    ),
    "clock": dict(
        mpcat40="objects",
        raw=("clock",),
        mp3d_rank=112,
        rests_on=(
            "nightstand",
            "shelf",
            "bookshelf",
            "dresser",
            "desk",
            "side table",
            "fireplace",
            "sideboard",
        ),
    ),
    "bottle": dict(
        mpcat40="objects",
        raw=("bottle", "bottles"),
        mp3d_rank=81,
        palette="glass",
        rests_on=(
            "counter",
            "kitchen island",
            "dining table",
            "wine rack",
            "bar counter",
            "shelf",
            "table",
        ),
    ),
    "toolbox": dict(
        mpcat40="objects",
        raw=("toolbox",),
        mp3d_rank=516,
        palette="tools",
        rests_on=("workbench", "shelf", "floor"),
    ),
    "basket": dict(
        mpcat40="objects",
        raw=("basket", "laundry basket"),
        mp3d_rank=107,
        rests_on=("washing machine", "dryer", "shelf", "floor"),
    ),
    "door": dict(mpcat40="door", raw=("door", "doorframe"), mp3d_rank=1),
    "window": dict(mpcat40="window", raw=("window", "window frame"), mp3d_rank=5),
    "stairs": dict(mpcat40="stairs", raw=("stairs", "stair", "steps"), mp3d_rank=77),
}

# Materials of classic kinds as the real world makes them (the classic world keeps its
# own lists): pictures are prints on paper or canvas, books paper, baskets wicker.
REAL_MATERIALS: dict[str, tuple[str, ...]] = {
    "painting": ("paper", "fabric"),
    "book": ("paper",),
    "basket": ("wicker", "plastic"),
    "clock": ("plastic", "wood", "metal"),
    "plant": ("ceramic", "plastic"),
    "lamp": ("metal", "fabric"),
}

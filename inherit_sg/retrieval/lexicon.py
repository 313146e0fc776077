"""English lexicon of the rule-based request parser.

Object nouns with synonyms (canonical label → words; plurals are derived), nouns that
name several kinds ("seat"), room words, place words, colours, materials and other
adjectives, spatial prepositions (→ canonical predicates of
:mod:`inherit_sg.retrieval.constraints`), floor words, superlatives, negation, filler and
politeness phrases, and function phrases ("something to sit on") → object kinds.

Words are lower-case; multi-word entries are space-separated.
"""

from __future__ import annotations

from inherit_sg.retrieval.lexicon_functions import FUNCTIONS, SEATS, STORAGE, TABLES

__all__ = ["FUNCTIONS", "SEATS", "STORAGE", "TABLES", "singular", "verb_lemma"]

# fmt: off
OBJECTS: dict[str, tuple[str, ...]] = {
    "bed": ("double bed", "single bed", "bunk bed", "king bed", "queen bed"),
    "nightstand": ("night stand", "bedside table", "night table", "bedside cabinet"),
    "wardrobe": ("closet", "armoire", "clothes closet"),
    "dresser": ("chest of drawers", "chest of drawer", "chests of drawers", "bureau"),
    "desk": ("writing desk", "office desk", "work desk", "computer desk", "workstation desk"),
    "chair": ("office chair", "desk chair", "dining chair", "kitchen chair", "side chair"),
    "armchair": ("easy chair", "recliner", "lounge chair", "accent chair", "reclining chair"),
    "sofa": ("couch", "settee", "loveseat", "love seat", "sectional", "recliner sofa", "divan"),
    "stool": ("bar stool", "barstool", "footstool", "step stool"),
    "bench": ("park bench", "seating bench"),
    "ottoman": ("pouf", "footrest", "hassock"),
    "coffee table": ("low table", "cocktail table", "tea table"),
    "dining table": ("kitchen table", "dinner table", "breakfast table", "dining tables"),
    "table": ("side table", "end table"),
    "tv stand": ("tv cabinet", "tv unit", "media console", "entertainment center", "tv table"),
    "bookshelf": ("bookcase", "book shelf", "book case", "bookshelves"),
    "shelf": ("shelving", "shelving unit", "wall shelf", "rack"),
    "cabinet": ("cupboard", "storage cabinet", "kitchen cabinet", "sideboard", "credenza"),
    "filing cabinet": ("file cabinet", "filing cabinets", "file drawer"),
    "drawer": ("drawers",),
    "locker": ("lockers", "storage locker"),
    "counter": ("countertop", "worktop", "kitchen counter", "kitchen island", "island", "bar"),
    "sink": ("washbasin", "wash basin", "basin", "kitchen sink", "bathroom sink", "lavabo"),
    "stove": ("cooker", "hob", "range", "cooktop", "stovetop", "gas stove"),
    "oven": ("baking oven",),
    "refrigerator": ("fridge", "mini fridge", "minifridge", "beverage fridge", "cooler", "icebox"),
    "freezer": ("deep freezer",),
    "dishwasher": ("dish washer",),
    "toilet": ("wc", "commode", "loo"),
    "bathtub": ("tub", "bath tub", "bath"),
    "shower": ("shower stall", "shower cabin", "shower cubicle"),
    "washing machine": ("washer", "laundry machine", "clothes washer"),
    "dryer": ("tumble dryer", "clothes dryer", "drier"),
    "car": ("automobile", "vehicle"),
    "bicycle": ("bike", "cycle"),
    "workbench": ("work bench", "tool bench"),
    "toolbox": ("tool box", "tool kit", "toolkit"),
    "plant": ("potted plant", "houseplant", "house plant", "flower pot", "plant pot", "flowers"),
    "lamp": ("floor lamp", "standing lamp", "standing light", "floor light"),
    "table lamp": ("desk lamp", "bedside lamp", "reading lamp", "reading light"),
    "ceiling light": ("ceiling lamp", "light fixture", "chandelier", "pendant light"),
    "rug": ("carpet", "mat", "doormat", "area rug"),
    "mirror": ("looking glass", "wall mirror"),
    "painting": ("picture", "artwork", "art", "poster", "wall art", "photo", "photograph", "frame"),
    "tv": ("television", "tv set", "tv screen", "flat screen", "flatscreen", "telly"),
    "monitor": ("computer screen", "computer monitor", "display"),
    "computer": ("pc", "desktop computer", "desktop", "workstation"),
    "laptop": ("notebook computer", "macbook"),
    "keyboard": ("computer keyboard",),
    "printer": ("copier", "photocopier", "copy machine", "scanner printer"),
    "phone": ("telephone", "smartphone", "cellphone", "cell phone", "mobile phone"),
    "mug": ("cup", "coffee cup", "coffee mug", "teacup", "tea cup"),
    "vase": ("flower vase",),
    "book": ("novel", "notebook", "magazine"),
    "bowl": ("fruit bowl",),
    "plate": ("dish", "dinner plate"),
    "microwave": ("microwave oven",),
    "kettle": ("electric kettle", "tea kettle"),
    "coffee machine": ("coffee maker", "espresso machine", "coffee station"),
    "water dispenser": ("water cooler", "water fountain", "drinking fountain"),
    "vending machine": ("snack machine", "drinks machine", "vending"),
    "towel": ("hand towel", "bath towel"),
    "clock": ("wall clock", "alarm clock"),
    "bottle": ("water bottle",),
    "basket": ("laundry basket", "hamper", "laundry hamper"),
    "box": ("cardboard box", "storage box", "crate"),
    "bag": ("backpack", "handbag", "suitcase", "luggage"),
    "door": ("doorway", "gate", "doors"),
    "window": ("windows", "windowsill", "window sill"),
    "stairs": ("staircase", "stairway", "steps", "stair", "stairwell"),
    "elevator": ("lift",),
    "exit": ("emergency exit", "way out", "exit door", "fire exit"),
    "trash can": ("trashcan", "trash bin", "garbage can", "garbage bin", "waste bin",
                  "wastebasket", "waste basket", "rubbish bin", "dustbin", "litter bin"),
    "recycle bin": ("recycling bin", "recycle station", "recycling station", "recycling",
                    "recycling container"),
    "fire extinguisher": ("extinguisher",),
    "security scanner": ("metal detector", "body scanner", "entry scanner", "security gate",
                         "scanner", "badge reader", "card reader", "turnstile"),
    "register": ("cash register", "checkout", "till", "touchscreen register",
                 "register checkout", "self checkout", "checkout counter", "pos terminal"),
    "whiteboard": ("white board", "blackboard", "chalkboard", "board"),
    "projector": ("projector screen",),
    "napkin holder": ("napkin dispenser", "napkin box"),
    "pillow": ("cushion", "throw pillow"),
    "blanket": ("duvet", "quilt", "throw blanket"),
    "curtain": ("curtains", "drapes", "drape", "blinds"),
    "radiator": ("heater", "space heater"),
    "fan": ("ceiling fan", "standing fan"),
    "fireplace": ("fire place", "hearth"),
    "piano": ("keyboard piano",),
    "coat rack": ("coat hanger", "coat stand", "hat stand", "coat hook"),
    "outlet": ("power outlet", "socket", "wall socket", "power socket", "plug"),
    "sign": ("signboard", "exit sign"),
    "partition": ("divider", "room divider", "screen divider", "cubicle wall"),
    "wall": ("walls",),
    "floor": (),
    "ceiling": (),
}

# Words that name several kinds: any of them may be meant.
SHARED_NOUNS: dict[str, tuple[str, ...]] = {
    "seat": SEATS, "seating": SEATS, "seating area": SEATS, "furniture": (*SEATS, *TABLES),
    "light": ("lamp", "table lamp", "ceiling light"), "lighting": ("lamp", "ceiling light"),
    "screen": ("tv", "monitor"), "bin": ("trash can", "recycle bin"),
    "trash": ("trash can",), "garbage": ("trash can",), "waste": ("trash can", "recycle bin"),
    "storage": STORAGE, "cupboards": ("cabinet",), "surface": (*TABLES, "counter"),
    "oven": ("oven", "stove"),
}

ROOMS: dict[str, tuple[str, ...]] = {
    "bedroom": ("bed room", "master bedroom", "guest room", "guest bedroom", "kids room",
                "children room", "nursery", "sleeping room", "dorm"),
    "bathroom": ("restroom", "washroom", "bath room", "toilet room", "lavatory",
                 "powder room", "shower room", "men room", "women room"),
    "kitchen": ("kitchenette", "cookhouse"),
    "living room": ("lounge", "sitting room", "family room", "den", "tv room", "front room",
                    "living area", "livingroom"),
    "dining room": ("dining hall", "diningroom", "breakfast room"),
    "office": ("study", "home office", "workroom", "study room", "cubicle"),
    "hallway": ("corridor", "hall", "entryway", "entrance hall", "foyer", "passage",
                "passageway", "vestibule", "landing"),
    "laundry room": ("utility room", "laundry"),
    "garage": ("carport",),
    "closet": ("walk in closet", "walkin closet", "storage closet"),
    "pantry": ("larder",),
    "balcony": ("terrace", "patio", "deck", "porch", "veranda"),
    "attic": ("loft",),
    "storage room": ("storeroom", "store room", "storage", "junk room"),
    "conference room": ("meeting room", "boardroom", "board room"),
    "lobby": ("reception", "reception room", "waiting room", "entrance", "entry"),
    "cafeteria": ("canteen", "cafe", "coffee shop", "break room", "breakroom", "lunchroom"),
    "gym": ("fitness room", "exercise room", "workout room"),
    "library": ("reading room",),
    "playroom": ("play room", "game room", "games room"),
    "classroom": ("class room", "lecture room"),
}

# Head nouns of functional-area names ("the reading corner", "the social hub").
AREA_HEADS = frozenset({
    "area", "zone", "corner", "space", "section", "region", "hub", "workspace", "nook",
    "station", "setup", "spot", "part", "side", "quarter", "sector", "bay", "workstation",
})
# Places too vague to name an area: their adjectives describe the target instead.
VAGUE_PLACES = frozenset({
    "environment", "setting", "atmosphere", "surroundings", "ambiance", "ambience", "vibe",
    "building", "house", "home", "scene", "premises", "venue", "location",
})
# Heads that seek "any node" (with a function they mean "whatever serves it").
GENERIC_THINGS = frozenset({
    "place", "spot", "somewhere", "someplace", "something", "anything", "thing", "stuff",
    "option", "item", "object", "location", "anywhere", "destination", "way", "direction",
    "route", "path", "process", "procedure", "mechanism", "method", "means",
})
# Area heads that alone are deictic ("in this area"); others name a place ("the corner").
GENERIC_AREAS = frozenset({"area", "zone", "part", "section", "region", "space", "side"})
# Heads naming a room of unspecified type ("which room has a piano?").
ROOM_WORDS = frozenset({"room", "chamber"})

COLOURS: dict[str, str] = {
    "red": "red", "orange": "orange", "yellow": "yellow", "green": "green", "blue": "blue",
    "purple": "purple", "violet": "purple", "pink": "pink", "brown": "brown",
    "black": "black", "white": "white", "grey": "grey", "gray": "grey", "beige": "beige",
    "cream": "beige", "tan": "beige", "silver": "grey", "gold": "yellow", "golden": "yellow",
    "navy": "blue", "teal": "green", "turquoise": "blue", "maroon": "red", "crimson": "red",
    "ivory": "white", "charcoal": "grey", "olive": "green",
}
MATERIALS: dict[str, str] = {
    "wood": "wood", "wooden": "wood", "timber": "wood", "oak": "wood", "pine": "wood",
    "metal": "metal", "metallic": "metal", "steel": "metal", "iron": "metal",
    "aluminium": "metal", "aluminum": "metal", "chrome": "metal", "brass": "metal",
    "plastic": "plastic", "fabric": "fabric", "cloth": "fabric", "upholstered": "fabric",
    "velvet": "fabric", "cotton": "fabric", "wool": "fabric", "leather": "leather",
    "glass": "glass", "ceramic": "ceramic", "porcelain": "ceramic", "stone": "stone",
    "marble": "stone", "granite": "stone", "concrete": "stone", "wicker": "wicker",
    "rattan": "wicker", "paper": "paper", "cardboard": "paper",
}
# Other adjectives: word -> (attribute key, canonical value).
ADJECTIVES: dict[str, tuple[str, str]] = {
    "small": ("size", "small"), "little": ("size", "small"), "tiny": ("size", "small"),
    "mini": ("size", "small"), "compact": ("size", "small"), "medium": ("size", "medium"),
    "large": ("size", "large"), "big": ("size", "large"), "huge": ("size", "large"),
    "giant": ("size", "large"), "enormous": ("size", "large"), "massive": ("size", "large"),
    "tall": ("height", "tall"), "high": ("height", "tall"), "short": ("height", "short"),
    "low": ("height", "short"), "round": ("shape", "round"), "circular": ("shape", "round"),
    "square": ("shape", "square"), "rectangular": ("shape", "rectangular"),
    "oval": ("shape", "oval"), "long": ("shape", "long"), "open": ("state", "open"),
    "closed": ("state", "closed"), "empty": ("state", "empty"), "full": ("state", "full"),
    "clean": ("state", "clean"), "dirty": ("state", "dirty"), "broken": ("state", "broken"),
    "comfortable": ("other", "comfortable"), "comfy": ("other", "comfortable"),
    "cozy": ("other", "cozy"), "cosy": ("other", "cozy"), "soft": ("other", "soft"),
    "quiet": ("other", "quiet"), "adjustable": ("other", "adjustable"),
    "sliding": ("other", "sliding"), "solid": ("other", "solid"), "old": ("other", "old"),
    "new": ("other", "new"), "modern": ("other", "modern"), "cold": ("other", "cold"),
    "hot": ("other", "hot"), "private": ("other", "private"), "folding": ("other", "folding"),
    "electric": ("other", "electric"), "portable": ("other", "portable"),
    "bright": ("other", "bright"), "dark": ("other", "dark"), "striped": ("other", "striped"),
    "decorative": ("other", "decorative"), "ergonomic": ("other", "ergonomic"),
    "relaxing": ("other", "relaxing"), "lively": ("other", "lively"),
    "well lit": ("other", "bright"), "sunny": ("other", "bright"), "noisy": ("other", "noisy"),
    "convenient": ("other", "convenient"), "secure": ("other", "secure"),
    "safe": ("other", "secure"), "focused": ("other", "quiet"), "peaceful": ("other", "quiet"),
    "calm": ("other", "quiet"), "busy": ("other", "noisy"), "spacious": ("size", "large"),
}
COLOUR_SHADES = frozenset({"light", "dark", "pale", "bright", "deep"})

# Spatial prepositions -> canonical predicate; "in", "at" and "on" also take rooms/floors.
PREPOSITIONS: dict[str, str] = {
    "on": "on", "on top of": "on", "upon": "on", "atop": "on", "onto": "on",
    "under": "under", "below": "under", "beneath": "under", "underneath": "under",
    "above": "above", "over": "above", "hanging over": "above",
    "next to": "next_to", "beside": "next_to", "besides": "next_to", "by": "next_to",
    "alongside": "next_to", "adjacent to": "next_to", "right next to": "next_to",
    "to the side of": "next_to", "at the side of": "next_to", "next door to": "next_to",
    "near": "near", "close to": "near", "near to": "near", "around": "near",
    "in the vicinity of": "near", "not far from": "near", "nearby": "near", "at": "near",
    "close by": "near", "toward": "near", "towards": "near", "through": "near",
    "via": "near", "past": "near",
    "between": "between", "in between": "between",
    "in": "inside", "inside": "inside", "inside of": "inside", "within": "inside",
    "into": "inside",
    "facing": "facing", "opposite": "facing", "opposite to": "facing",
    "opposite of": "facing", "across from": "facing", "across": "facing", "faces": "facing",
    "in front of": "in_front_of", "in front": "in_front_of", "beyond": "behind",
    "behind": "behind", "in back of": "behind", "at the back of": "behind",
    "to the left of": "left_of", "left of": "left_of", "on the left of": "left_of",
    "on the left side of": "left_of", "to the right of": "right_of",
    "right of": "right_of", "on the right of": "right_of", "on the right side of": "right_of",
    "containing": "contains", "holding": "supports", "supporting": "supports",
}
# Prepositions that mean "not near" (a negated near).
AWAY_PREPOSITIONS = frozenset({"far from", "away from", "far away from", "distant from"})
# Prepositions that mean "not in" (a negated inside): "outside the kitchen".
OUTSIDE_PREPOSITIONS = frozenset({"outside", "outside of"})
# "with X <prep> it": the predicate from the target's side.
WITH_INVERSE: dict[str, str] = {
    "on": "supports", "under": "above", "above": "under", "inside": "contains",
    "next_to": "next_to", "near": "near", "in_front_of": "behind", "behind": "in_front_of",
    "facing": "facing", "left_of": "right_of", "right_of": "left_of",
}

SUPERLATIVES: dict[str, str] = {
    "biggest": "largest", "largest": "largest", "smallest": "smallest",
    "tiniest": "smallest", "littlest": "smallest", "tallest": "tallest",
    "highest": "tallest", "shortest": "shortest", "lowest": "shortest",
    "closest": "closest", "nearest": "closest", "farthest": "farthest",
    "furthest": "farthest", "most distant": "farthest", "bigger": "largest",
    "larger": "largest", "smaller": "smallest", "taller": "tallest", "shorter": "shortest",
    "closer": "closest", "nearer": "closest", "farther": "farthest", "further": "farthest",
}
ORDINALS: dict[str, int] = {
    "first": 1, "second": 2, "third": 3, "fourth": 4, "fifth": 5, "sixth": 6, "seventh": 7,
    "eighth": 8, "ninth": 9, "tenth": 10, "1st": 1, "2nd": 2, "3rd": 3, "4th": 4, "5th": 5,
    "last": -1, "final": -1,
}
NUMBERS: dict[str, int] = {
    "zero": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7,
    "eight": 8, "nine": 9, "ten": 10, "a couple of": 2, "a pair of": 2, "both": 2,
}

FLOOR_NOUNS = frozenset({"floor", "level", "storey", "story"})
# Floor phrases -> level (int) or relative word (str).
FLOOR_PHRASES: dict[str, int | str] = {
    "upstairs": "upstairs", "up stairs": "upstairs", "upper floor": "upstairs",
    "upper level": "upstairs", "downstairs": "downstairs", "down stairs": "downstairs",
    "lower floor": "downstairs", "lower level": "downstairs", "ground floor": 0,
    "ground level": 0, "main floor": 0, "top floor": "top", "top level": "top",
    "highest floor": "top", "basement": "bottom", "cellar": "bottom",
    "lowest floor": "bottom", "bottom floor": "bottom",
}

NEGATIONS = frozenset({"not", "no", "never", "none", "nothing", "nowhere", "neither", "non"})
ADVERBS = frozenset({
    "alone", "together", "quietly", "comfortably", "quickly", "very", "fast", "later", "soon",
    "still", "even", "already", "yet", "somewhat", "quite", "rather", "too",
    "together with", "at the same time", "for a while", "for a bit", "a bit", "a little",
    "for a long time", "away", "privately", "easily", "around here", "over there",
})
EXCEPTIONS = frozenset({
    "except", "except for", "other than", "apart from", "excluding", "but not",
    "rather than", "instead of", "besides the", "aside from", "not including",
})
EMPHASIS = frozenset({
    "definitely", "must", "must be", "really", "especially", "only", "exactly",
    "absolutely", "make sure", "important", "particularly", "specifically", "certainly",
})
HEDGES = frozenset({
    "maybe", "perhaps", "preferably", "ideally", "possibly", "probably", "if possible",
    "might be", "kind of", "sort of",
})

DETERMINERS = frozenset({
    "the", "a", "an", "this", "these", "those", "some", "any", "my", "your", "our",
    "their", "his", "her", "its", "each", "every", "all", "all the", "all of the",
    "one of the", "any of the", "some of the", "that", "such",
})
SEEKERS = frozenset({
    "i", "we", "you", "someone", "somebody", "anyone", "anybody", "one", "people", "person",
    "individual", "visitor", "user", "guest", "they", "he", "she", "everyone", "me", "us",
    "employee", "worker", "staff", "friend", "colleague", "others", "other people",
    "group", "team", "coworker", "family", "kid", "child", "myself", "yourself", "themselves",
    "someone else", "somebody else", "everybody", "nobody",
})
MODALS = frozenset({
    "can", "could", "should", "would", "will", "may", "might", "shall", "do", "does", "did",
})
BE_WORDS = frozenset({
    "is", "are", "was", "were", "be", "been", "being", "am", "located", "situated", "placed",
    "positioned", "standing", "sitting", "lying", "hanging", "kept", "stored", "found",
    "set", "mounted", "resting", "seen", "put", "there is", "there are", "made of",
    "made from", "made out of", "built from", "painted", "there should be",
    "there must be", "there ought to be", "there might be", "there may be", "there could be",
})
HAVE_WORDS = frozenset({"has", "have", "having", "had", "got", "contains", "contain"})
REL_PRONOUNS = frozenset({"that", "which", "who", "whose"})
ANAPHORS = frozenset({
    "it", "them", "that one", "this one", "that thing", "this thing", "the same one",
    "the same", "that", "this", "those ones", "these ones", "there", "the previous one",
    "previous one", "the earlier one", "the same thing", "the first one again",
})
OTHER_WORDS = frozenset({"other", "another", "different", "else", "next"})
QUESTION_WORDS = frozenset({"where", "what", "which", "how", "why", "when", "who", "whom"})

# Politeness, request frames and deictic filler; removed before parsing.
FILLER = frozenset({
    "please", "kindly", "among", "amongst", "among all", "out of all", "could you please", "can you please", "would you please",
    "could you", "can you", "would you", "will you", "i am looking for", "looking for",
    "look for", "search for", "searching for", "i want to go to", "i want to find",
    "i would like to find", "i need to find", "i want to get to", "i would like",
    "i want", "i need", "take me to", "bring me to", "guide me to", "lead me to",
    "walk me to", "navigate to", "go to", "head to", "get to", "show me where", "go back to",
    "back to", "return to", "take me back to", "bring me back to",
    "show me", "tell me where", "tell me", "point me to", "point me toward",
    "point me towards", "help me find", "help me locate", "help me get to", "help me",
    "where is", "where are", "where was", "where can i find", "where do i find",
    "where would i find", "where could i find", "where might i find", "where can we find",
    "where will i find", "can i find", "can you find", "find me", "find", "locate",
    "get me", "bring me", "fetch", "is there", "are there", "is there any", "are there any",
    "do you know where", "do you see", "do you know", "the location of", "location of",
    "the position of", "where exactly", "in this area", "in the area", "in this space",
    "in this environment", "in the environment", "in this building", "in the building",
    "in the house", "in this house", "here", "right now", "now", "again", "thanks",
    "thank you", "hey", "hi", "hello", "robot", "ok", "okay", "so", "just", "actually",
    "also", "well", "go", "head", "navigate", "move", "where", "let us", "lets", "i wonder", "wonder", "somewhere here", "in here",
    "at the moment", "currently", "anymore", "any more", "as well", "too", "then", "first of all",
    "want to", "need to", "would like to", "like to", "wanted to", "needed to", "wants to",
    "needs to", "is it possible to", "is it possible", "if possible to", "if", "when",
    "recommend", "suggest", "choose", "pick", "likely", "best", "better", "good", "ideal",
    "hungry", "starving", "thirsty", "tired", "sleepy", "exhausted", "dirty hands",
    "a lot", "a lot of", "lots of", "lots", "very much", "much", "many",
    "suitable", "suited", "great", "nice", "appropriate", "perfect", "most",
})
# Verbs with no function of their own; skipped where they stand as verbs.
OTHER_VERBS = frozenset({
    "want", "need", "like", "see", "know", "think", "get", "give", "make", "let", "say",
    "proceed", "ensure", "check", "try", "allow", "offer", "provide", "serve", "support",
    "help", "keep", "stay", "remain", "become", "seem", "look", "feel", "come", "leave",
    "use", "enjoy", "grab", "hold", "host", "have", "do", "finish", "finished", "start",
    "go", "head", "spend", "stand", "gain", "obtain", "set", "bring", "catch", "engage",
    "follow", "ask", "call",
})
# Subordinators: they end a phrase ("after finishing my meal").
SUBORDINATORS = frozenset({
    "after", "before", "until", "once", "since", "because", "so that", "in order to",
    "unless", "whenever", "as soon as",
})
# Introduce examples of a generic head ("entertainment options like TVs").
EXAMPLE_WORDS = frozenset({"like", "such as", "including", "for example", "e g"})
# Verbs that keep their function through their object ("have a meal", "grab a coffee").
LIGHT_VERBS = frozenset({
    "have", "hold", "host", "enjoy", "grab", "get", "take", "make", "do", "find", "need",
    "want", "use", "catch", "go", "spend", "start", "join", "attend", "engage",
})

IRREGULAR_PLURALS: dict[str, str] = {
    "people": "person", "children": "child", "men": "man", "women": "woman", "feet": "foot",
    "mice": "mouse", "shelves": "shelf", "knives": "knife", "leaves": "leaf",
    "boxes": "box", "glasses": "glass", "dishes": "dish", "benches": "bench",
    "couches": "couch", "watches": "watch", "lunches": "lunch", "sandwiches": "sandwich",
    "wardrobes": "wardrobe", "stoves": "stove", "series": "series", "news": "news",
    "stairs": "stairs", "clothes": "clothes", "scissors": "scissors", "blinds": "blinds",
    "species": "species", "individuals": "individual", "bookshelves": "bookshelf",
    "busses": "bus", "buses": "bus", "indices": "index", "dresses": "dress",
    "refreshments": "refreshment", "belongings": "belonging", "sofas": "sofa",
}
IRREGULAR_VERBS: dict[str, str] = {
    "sat": "sit", "ate": "eat", "eaten": "eat", "slept": "sleep", "lying": "lie",
    "lay": "lie", "kept": "keep", "threw": "throw", "thrown": "throw", "bought": "buy",
    "went": "go", "gone": "go", "took": "take", "taken": "take", "made": "make",
    "met": "meet", "left": "leave", "got": "get", "gotten": "get", "hung": "hang",
    "drank": "drink", "drunk": "drink", "caught": "catch", "held": "hold", "put": "put",
    "saw": "see", "seen": "see", "did": "do", "done": "do", "had": "have", "has": "have",
    "read": "read", "wrote": "write", "written": "write", "fed": "feed", "paid": "pay",
    "stored": "store", "dying": "die", "tying": "tie",
}
# fmt: on


def singular(word: str) -> str:
    """Singular of an English noun by irregular table and suffix rules."""
    if word in IRREGULAR_PLURALS:
        return IRREGULAR_PLURALS[word]
    if len(word) == 3 and word.endswith("s") and word[1] not in "aeiou":
        return word[:-1]  # "tvs", "pcs"
    if len(word) <= 3 or not word.endswith("s") or word.endswith(("ss", "us", "is", "ous")):
        return word
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "xes", "zzes", "sses")):
        return word[:-2]
    return word[:-1]


def verb_lemma(word: str, known: frozenset[str] | set[str]) -> str:
    """Base form of a verb; prefers a form in ``known`` among the suffix-rule candidates."""
    if word in IRREGULAR_VERBS:
        return IRREGULAR_VERBS[word]
    candidates: list[str] = [word]
    for suffix in ("ing", "ed", "es", "s"):
        if word.endswith(suffix) and len(word) > len(suffix) + 2:
            stem = word[: -len(suffix)]
            candidates += [stem, stem + "e"]
            if len(stem) > 2 and stem[-1] == stem[-2]:
                candidates.append(stem[:-1])
            if suffix in ("ed", "es") and stem.endswith("i"):
                candidates.append(stem[:-1] + "y")
    for cand in candidates:
        if cand in known:
            return cand
    return candidates[1] if len(candidates) > 1 else word

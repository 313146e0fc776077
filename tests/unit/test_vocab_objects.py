"""Object vocabulary (objects.toml): the loader on the real file — canonical labels of
synonyms, plurals and dataset names, general words, kind-of relations, parts, detector
prompts — and its checks on malformed files."""

from __future__ import annotations

import tomllib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

import inherit_sg.vocab as vocab
from inherit_sg.vocab import VocabularyError
from inherit_sg.vocab import objects as obj


def _clear() -> None:
    vocab.load_table.cache_clear()
    vocab.vocabulary_info.cache_clear()
    obj.clear_caches()


def _raw() -> dict[str, Any]:
    """The real file as plain TOML, without the loader."""
    return tomllib.loads((vocab.DATA_DIR / "objects.toml").read_text(encoding="utf-8"))


# ------------------------------------------------------------------ canonical labels
@pytest.mark.parametrize(
    ("phrase", "label"),
    [
        ("sofa", "sofa"),
        ("couch", "sofa"),
        ("couches", "sofa"),
        ("  Couch  ", "sofa"),
        ("Bedside Table", "nightstand"),
        ("bedside tables", "nightstand"),
        ("night stand", "nightstand"),
        ("sofa_chair", "armchair"),
        ("sofa-chair", "armchair"),
        ("cushy chair", "armchair"),
        ("arm chair", "armchair"),
        ("easy chair", "armchair"),
        ("bookcase", "bookshelf"),
        ("bookshelves", "bookshelf"),
        ("shelves", "shelf"),
        ("knives", "knife"),
        ("mice", "mouse"),
        ("garbage can", "trash can"),
        ("wastebasket", "trash can"),
        ("telly", "tv"),
        ("t.v.", "tv"),
        ("fridge", "refrigerator"),
        ("picture", "painting"),
        ("photos", "painting"),
        ("cup", "mug"),
        ("rack", "shelf"),
        ("chests of drawers", "dresser"),
        # written forms win over spaCy's lemmas ("glass" → "glas", "clothes" → "clothe")
        ("glass", "glass"),
        ("glasses", "glasses"),
        ("clothes", "clothes"),
        ("stairs", "stairs"),
        # Matterport3D raw categories
        ("kitchen#cabinet", "kitchen cabinet"),
        ("bath#cabinet", "bathroom cabinet"),
        ("kitchen#shelf", "shelf"),
        ("toilet#paper", "toilet paper"),
        ("tabletop#trinket", "decoration"),
        ("sofa#chair", "armchair"),
        ("window#/#other#room", "window"),
        ("stairs#2", "stairs"),
        ("towels#(rolled)", "towel"),
        ("toaster?", "toaster"),
        # ScanNet classes
        ("Kitchen Cabinets", "kitchen cabinet"),
        ("office chair", "office chair"),
        ("recycling bin", "recycle bin"),
        ("mini fridge", "mini fridge"),
        ("paper towel dispenser", "paper towel dispenser"),
        ("whiteboard", "whiteboard"),
    ],
)
def test_canonical_label(phrase: str, label: str) -> None:
    assert obj.canonical_label(phrase) == label


@pytest.mark.parametrize("phrase", ["", "   ", "spaceship", "seat", "furniture", "wheels"])
def test_no_canonical_label_for_unknown_and_general_words(phrase: str) -> None:
    assert obj.canonical_label(phrase) is None


# ------------------------------------------------------------------ request words
def test_labels_for_a_kind_is_that_kind() -> None:
    assert obj.labels_for("couch") == ("sofa",)
    assert obj.labels_for("Bedside tables") == ("nightstand",)
    assert obj.labels_for("chair") == ("chair",)
    assert obj.labels_for("cups") == ("mug",)


def test_labels_for_general_words_lists_typical_kinds_first() -> None:
    seats = obj.labels_for("seat")
    assert seats[:5] == ("chair", "sofa", "armchair", "stool", "bench")
    assert list(seats[5:]) == sorted(seats[5:])
    assert {"office chair", "ottoman", "pew"} <= set(seats)
    assert obj.labels_for("seating") == seats
    assert obj.labels_for("seating area") == seats
    assert obj.labels_for("something to sit on") == ()  # a function (functions.toml)
    assert {"bed", "wardrobe", "sofa", "desk"} <= set(obj.labels_for("furniture"))
    assert obj.labels_for("surface")[:2] == ("table", "counter")
    assert {"desk", "dining table", "kitchen island"} <= set(obj.labels_for("surface"))
    assert obj.labels_for("storage")[:3] == ("cabinet", "shelf", "bookshelf")
    assert obj.labels_for("screen") == ("tv", "monitor", "projector screen")
    assert "trash can" not in obj.labels_for("storage")


def test_labels_for_a_kind_named_like_a_general_word_is_the_kind() -> None:
    assert obj.labels_for("table") == ("table",)
    assert obj.kinds_under("table")[:3] == ("dining table", "coffee table", "side table")
    assert "desk" not in obj.kinds_under("table")  # "the table" is seldom meant for a desk
    assert obj.labels_for("decoration") == ("decoration",)


def test_light_and_bin_are_general_words() -> None:
    assert obj.canonical_label("light") is None
    assert obj.labels_for("lights")[:3] == ("lamp", "ceiling light", "table lamp")
    assert obj.labels_for("lighting") == obj.labels_for("light")
    assert obj.labels_for("bin") == ("trash can", "recycle bin")
    assert obj.labels_for("waste") == obj.labels_for("bins")
    assert "storage bin" not in obj.labels_for("bin")


def test_labels_for_longer_phrases_use_the_longest_known_tail() -> None:
    assert obj.labels_for("kitchen trash can") == ("trash can",)
    assert obj.labels_for("metal shelving unit") == ("shelf",)
    assert obj.labels_for("big comfy red couches") == ("sofa",)
    assert obj.labels_for("comfortable seating") == obj.labels_for("seat")
    assert obj.labels_for("purple spaceship") == ()
    assert obj.labels_for("") == ()


# ------------------------------------------------------------------ kind-of relations
def test_is_a_is_transitive_nearest_first() -> None:
    assert obj.is_a("armchair") == ("chair", "seat", "furniture")
    assert obj.is_a("recliner")[:2] == ("armchair", "chair")
    assert obj.is_a("couch") == obj.is_a("sofa")
    assert obj.is_a("spaceship") == ()


@pytest.mark.parametrize(
    ("label", "general", "expected"),
    [
        ("office chair", "chair", True),
        ("armchair", "chair", True),
        ("armchair", "seating", True),
        ("dining table", "table", True),
        ("desk", "tables", False),
        ("desk", "surface", True),
        ("couch", "furniture", True),
        ("mug", "tableware", True),
        ("wine rack", "shelf", True),
        ("stove", "oven", True),
        ("refrigerator", "appliance", True),
        ("trash can", "bin", True),
        ("trash can", "storage", False),
        ("chair", "chair", False),
        ("sofa", "couch", False),
        ("chair", "armchair", False),
        ("sofa", "table", False),
        ("spaceship", "seat", False),
        ("chair", "spaceship", False),
    ],
)
def test_is_kind_of(label: str, general: str, expected: bool) -> None:
    assert obj.is_kind_of(label, general) is expected


def test_kinds_under() -> None:
    assert {"office chair", "armchair", "recliner"} <= set(obj.kinds_under("chair"))
    assert "chair" not in obj.kinds_under("chair")
    assert obj.kinds_under("seating")[:2] == ("chair", "sofa")
    assert obj.kinds_under("spaceship") == ()


# ------------------------------------------------------------------ synonyms and parts
def test_synonyms() -> None:
    assert {"couch", "settee", "loveseat"} <= set(obj.synonyms("sofa"))
    assert obj.synonyms("couch") == obj.synonyms("sofa")
    assert "sofa" not in obj.synonyms("sofa")
    assert obj.synonyms("spaceship") == ()


def test_parts_include_those_of_parent_kinds() -> None:
    assert {"cushion", "armrest"} <= set(obj.parts("sofa"))
    office = obj.parts("office chair")
    assert office[0] == "wheel" and "leg" in office  # own first, then the chair's
    assert obj.parts("spaceship") == ()


def test_is_part() -> None:
    assert obj.is_part("wheels", "office chair")
    assert obj.is_part("Drawers", "nightstand")
    assert not obj.is_part("wheels", "sofa")
    assert obj.is_part("lids")
    assert obj.is_part("headboard", "bunk bed")
    assert not obj.is_part("spaceship")
    assert not obj.is_part("")


# ------------------------------------------------------------------ the file as a whole
def test_no_phrase_names_two_kinds() -> None:
    owner: dict[str, str] = {}
    for label, entry in _raw()["kinds"].items():
        for phrase in [label, *entry.get("synonyms", [])]:
            assert owner.setdefault(phrase, label) == label, (phrase, owner[phrase], label)
    assert obj.phrases() == owner


def test_every_is_a_target_is_known() -> None:
    data = _raw()
    known = set(data["kinds"]) | set(data["general"])
    for section in ("kinds", "general"):
        for name, entry in data[section].items():
            targets = entry.get("is_a", [])
            assert isinstance(targets, list)
            assert set(targets) <= known, (name, set(targets) - known)


def test_labels_are_canonical_and_counts_are_sane() -> None:
    kinds = obj.kinds()
    assert 300 <= len(kinds) <= 500
    assert all(obj.normalise(k) == k for k in kinds)
    assert all(obj.canonical_label(k) == k for k in kinds)
    phrases = obj.phrases()
    assert all(phrases[k] == k for k in kinds)
    general = obj.general_words()
    assert {"seat", "seating", "furniture", "storage", "surface"} <= set(general)
    # a general word shares a phrase only with the kind of its own name ("table")
    assert all(phrases[w] == general[w] for w in set(general) & set(phrases))


def test_detection_prompts_are_common_canonical_kinds() -> None:
    prompts = obj.detection_prompts()
    assert 80 <= len(prompts) <= 120
    assert len(set(prompts)) == len(prompts)
    assert set(prompts) <= set(obj.kinds())
    assert {"chair", "sofa", "table", "bed", "tv", "toilet", "door"} <= set(prompts)


def test_synthetic_world_words_reach_their_kinds() -> None:
    """Every word the synthetic houses use for a kind reaches it: as the kind, as a
    general word covering it, or as a kind it is a kind of ("table" → dining table)."""
    from inherit_sg.ingest.synthetic.vocabulary import OBJECT_KINDS

    for kind in OBJECT_KINDS.values():
        assert kind.label in obj.kinds()
        for word in (kind.label, *kind.synonyms):
            labels = obj.labels_for(word)
            assert kind.label in labels or any(
                obj.is_kind_of(kind.label, label) for label in labels
            ), (kind.label, word, labels)


# ------------------------------------------------------------------ malformed files
@pytest.fixture
def objects_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> Iterator[Callable[[str], None]]:
    """Write an objects.toml that the loader reads instead of the real one."""

    def write(text: str) -> None:
        (tmp_path / "objects.toml").write_text(text, encoding="utf-8")
        monkeypatch.setattr(vocab, "DATA_DIR", tmp_path)
        _clear()

    yield write
    monkeypatch.undo()
    _clear()


_GOOD = """
version = 3
[general.seat]
words = ["seating"]
typical = ["sofa"]
[kinds.chair]
synonyms = ["side chair"]
is_a = ["seat"]
parts = ["leg", "back"]
detect = true
[kinds."office chair"]
synonyms = ["desk chair"]
is_a = ["chair"]
parts = ["wheel"]
[kinds.sofa]
synonyms = ["couch"]
is_a = ["seat"]
detect = true
"""


def test_a_small_valid_file(objects_file: Callable[[str], None]) -> None:
    objects_file(_GOOD)
    assert obj.vocabulary().version == 3
    assert obj.kinds() == ("chair", "office chair", "sofa")
    assert obj.labels_for("seating") == ("sofa", "chair", "office chair")
    assert obj.canonical_label("Desk_Chairs") == "office chair"
    assert obj.is_a("office chair") == ("chair", "seat")
    assert obj.parts("office chair") == ("wheel", "leg", "back")
    assert obj.detection_prompts() == ("chair", "sofa")
    assert obj.general_words() == {"seat": "seat", "seating": "seat"}


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (
            '[kinds.sofa]\nsynonyms = ["couch"]\n[kinds.bed]\nsynonyms = ["couch"]',
            ["[kinds.bed]", "'couch'", "[kinds.sofa]"],
        ),
        ('[kinds.sofa]\nsynonyms = ["couch", "couch"]', ["[kinds.sofa]", "twice"]),
        ('[kinds.sofa]\nis_a = ["seat"]', ["[kinds.sofa]", "'is_a'", "'seat'"]),
        (
            '[kinds.sofa]\nsynonyms = ["couch"]\n[kinds.armchair]\nis_a = ["couch"]',
            ["[kinds.armchair]", "synonym of 'sofa'"],
        ),
        ('[kinds.sofa]\nsynonyms = ["couch", 3]', ["[kinds.sofa]", "'synonyms'", "int"]),
        ('[kinds.sofa]\nparts = "cushion"', ["[kinds.sofa]", "'parts'", "list of strings"]),
        ('[kinds.sofa]\nsynonym = ["couch"]', ["[kinds.sofa]", "unknown field 'synonym'"]),
        ('[kinds.sofa]\ndetect = "yes"', ["[kinds.sofa]", "'detect'"]),
        ('[kinds.sofa_bed]\nsynonyms = ["futon"]', ["sofa_bed", "lower case"]),
        ('[kinds.sofa]\nsynonyms = ["Couch"]', ["[kinds.sofa]", "'Couch'", "lower case"]),
        ('[kinds.sofa]\nis_a = ["bed"]\n[kinds.bed]\nis_a = ["sofa"]', ["circle", "sofa → bed"]),
        ('[kinds.sofa]\nis_a = ["sofa"]', ["[kinds.sofa]", "itself"]),
        (
            '[general.seat]\nwords = ["couch"]\n[kinds.sofa]\nsynonyms = ["couch"]\nis_a = ["seat"]',
            ["[general.seat]", "'couch'", "[kinds.sofa]"],
        ),
        (
            '[general.seat]\ntypical = ["bed"]\n[kinds.sofa]\nis_a = ["seat"]\n[kinds.bed]',
            ["[general.seat]", "'typical'", "'bed'"],
        ),
        ("[general.seat]\n[kinds.sofa]", ["[general.seat]", "no kind falls under it"]),
        ('[general.seat]\nwords = "seating"\n[kinds.sofa]', ["[general.seat]", "'words'"]),
        ("[general]\nseat = 3\n[kinds.sofa]", ["[general.seat]", "must be a table"]),
        ("[kinds]", ["needs at least one"]),
        ("[things.sofa]", ["unknown top-level key 'things'"]),
        ('[kinds.island]\nplacement = "ceiling"', ["[kinds.island]", "'placement'"]),
    ],
)
def test_malformed_files_are_named(
    objects_file: Callable[[str], None], text: str, expected: list[str]
) -> None:
    objects_file("version = 1\n" + text)
    with pytest.raises(VocabularyError) as err:
        obj.vocabulary()
    for part in expected:
        assert part in str(err.value)


def test_missing_kinds_and_version(objects_file: Callable[[str], None]) -> None:
    objects_file("version = 1\n")
    with pytest.raises(VocabularyError, match="missing 'kinds'"):
        obj.kinds()
    objects_file('[kinds.sofa]\nsynonyms = ["couch"]\n')
    with pytest.raises(VocabularyError, match="version"):
        obj.canonical_label("couch")


def test_known_phrases_do_not_load_the_lemmatiser() -> None:
    """A map build names its objects with known kinds: finding them as written must not
    load spaCy's pipeline (about 300 MB of a build's memory); only an unknown plural does."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from inherit_sg.vocab.objects import canonical_label, is_kind_of\n"
        "assert canonical_label('door') == 'door'\n"
        "assert canonical_label('Exterior Door') == 'exterior door'\n"
        "assert is_kind_of('office chair', 'chair')\n"
        "assert [canonical_label(w) for w in ('stairs', 'clothes', 'blinds')] == "
        "['stairs', 'clothes', 'blinds']\n"
        "assert 'spacy' not in sys.modules, 'spaCy loaded for known phrases'\n"
        "assert canonical_label('couches') == 'sofa'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)

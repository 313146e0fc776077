"""Room, area and colour vocabularies (rooms.toml, areas.toml, colours.toml): loaders on
the real files, room names by alias and tail, and malformed files."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest

import inherit_sg.vocab as vocab
from inherit_sg.mapping.areas import label_area
from inherit_sg.mapping.room_semantics import floor_phrase, infer_room_type
from inherit_sg.perception import colour_names as perception_colours
from inherit_sg.vocab import VocabularyError, areas, colours, objects, rooms


def _clear() -> None:
    vocab.load_table.cache_clear()
    vocab.vocabulary_info.cache_clear()
    rooms.clear_caches()
    areas.clear_caches()
    colours.clear_caches()


@pytest.fixture
def data_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A copy of the vocabulary files that the loaders read instead of the real ones."""
    copy = tmp_path / "data"
    shutil.copytree(vocab.DATA_DIR, copy)
    monkeypatch.setattr(vocab, "DATA_DIR", copy)
    _clear()
    yield copy
    monkeypatch.undo()
    _clear()


# ------------------------------------------------------------------ rooms
MP3D_TYPES = {
    "bathroom", "bedroom", "closet", "dining room", "entryway", "family room", "garage",
    "hallway", "library", "laundry room", "kitchen", "living room", "meeting room", "office",
    "porch", "rec room", "stairs", "toilet", "utility room", "tv room", "gym", "balcony",
    "bar", "classroom", "spa", "other room",
}  # fmt: skip


def test_room_types_are_the_matterport_categories() -> None:
    types = rooms.room_types()
    assert types[:5] == ("bedroom", "bathroom", "toilet", "kitchen", "living room")
    assert set(types) == MP3D_TYPES and len(types) == 26
    ev = rooms.evidence()
    assert list(ev) == list(types)  # every type has evidence
    assert ev["bedroom"]["bed"] == 3.0 and ev["garage"]["car"] == 4.0
    assert ev["toilet"]["bathtub"] < 0 < ev["bathroom"]["bathtub"]  # evidence against
    table = rooms.room_type_table()
    assert table["toilet"].area is not None and table["toilet"].area[1] <= 5
    assert table["hallway"].narrow > 0 and table["hallway"].bare > 0
    assert table["other room"].base > 0 and 0 < table["classroom"].prior < 1
    assert {"door", "window", "light"} <= rooms.fixtures()
    assert rooms.level_words() == ("ground", "second", "third", "fourth", "fifth")


def test_evidence_names_object_kinds() -> None:
    for rtype, weights in rooms.evidence().items():
        for label in weights:
            assert objects.canonical_label(label) == label, (rtype, label)


def test_related_types_are_symmetric() -> None:
    assert rooms.related("laundry room")["utility room"] == 0.8
    assert rooms.related("utility room")["laundry room"] == 0.8
    assert (
        rooms.related("living room")["family room"] == rooms.related("family room")["living room"]
    )
    assert rooms.related("no such room") == {}


def test_aliases_and_room_words() -> None:
    assert "guest room" in rooms.aliases("bedroom")
    assert {"den", "family lounge"} <= set(rooms.aliases("family room"))
    assert {"lounge", "sitting room"} <= set(rooms.aliases("living room"))  # as people say
    assert {"media room", "home theater"} <= set(rooms.aliases("tv room"))
    assert rooms.aliases("no such room") == ()
    words = rooms.room_words()
    assert words["bedroom"] == "bedroom" and words["foyer"] == "entryway"
    assert words["powder room"] == "toilet" and words["wc"] == "toilet"
    assert words["study"] == "office" and words["ensuite"] == "bathroom"
    assert all(words[t] == t for t in rooms.room_types())


@pytest.mark.parametrize(
    ("phrase", "rtype"),
    [
        ("bedroom", "bedroom"),
        ("Master Bedroom", "bedroom"),
        ("guest room", "bedroom"),
        ("bedroom 2", "bedroom"),
        ("bedroom #3", "bedroom"),
        ("upstairs guest bathroom", "bathroom"),
        ("master bath", "bathroom"),
        ("half bath", "toilet"),
        ("WC", "toilet"),
        ("ensuite", "bathroom"),
        ("den", "family room"),
        ("the tv room", "tv room"),
        ("family room 1", "family room"),
        ("sitting room", "living room"),
        ("foyer", "entryway"),
        ("lobby", "entryway"),
        ("corridor", "hallway"),
        ("dining hall", "dining room"),  # the longest tail wins over "hall"
        ("walk-in closet", "closet"),
        ("big storage closet", "closet"),
        ("mudroom", "laundry room"),
        ("tool room", "utility room"),
        ("conference room", "meeting room"),
        ("game room", "rec room"),
        ("terrace", "porch"),
        ("sauna", "spa"),
        ("study", "office"),
        ("room", None),
        ("room 4", None),
        ("", None),
        ("spaceship", None),
    ],
)
def test_room_type(phrase: str, rtype: str | None) -> None:
    assert rooms.room_type(phrase) == rtype


def test_room_labels() -> None:
    assert infer_room_type(["bed", "nightstand", "lamp"]) == "bedroom"
    assert infer_room_type(["toilet", "sink"]) == "toilet"  # no bath or shower
    assert infer_room_type(["toilet", "sink", "bathtub"]) == "bathroom"
    assert infer_room_type(["sofa", "tv", "coffee table"]) == "living room"
    assert infer_room_type(["car"]) == "garage"
    assert infer_room_type(["door", "painting"]) == "hallway"
    assert infer_room_type(["chair", "plant"]) == "room"
    assert floor_phrase(0) == "the ground floor" and floor_phrase(7) == "the level 7 floor"


# ------------------------------------------------------------------ areas
def test_area_rules_cover_real_rooms() -> None:
    rules = areas.area_rules_as_written()
    assert list(rules)[:3] == ["sleeping area", "changing area", "dining area"]
    assert list(rules)[-1] == "entrance area" and len(rules) >= 30
    assert {"bar area", "coat area", "laundry area", "vanity area", "reading corner"} <= set(rules)
    assert {"play area", "workout area"} <= set(rules)
    assert rules["parking area"] == (("car", "motorcycle"), ("bicycle", "garage door", "scooter"))
    assert areas.area_labels() == tuple(rules)
    for label, (anchors, support) in rules.items():
        for kind in (*anchors, *support):
            assert objects.canonical_label(kind) == kind, (label, kind)


def test_area_rules_match_synonyms() -> None:
    anchors, support = areas.area_rules()["sleeping area"]
    assert {"bed", "crib"} <= anchors and {"nightstand", "bedside table"} <= support
    assert label_area(["bed", "nightstand"]) == "sleeping area"
    assert label_area(["bedside table", "bed"]) == "sleeping area"
    assert label_area(["couch", "coffee table", "television"]) == "tv area"
    assert label_area(["table", "chair", "chair"]) == "meeting area"
    assert label_area(["coat rack", "bench", "shoe"]) == "coat area"
    assert label_area(["vanity", "sink", "mirror"]) == "vanity area"
    assert label_area(["treadmill", "dumbbell"]) == "workout area"
    assert label_area(["plant"]) == "plant area"


# ---------------------------------------------------------------- colours
def test_colours_match_the_perception_palette() -> None:
    names = colours.colour_names()
    assert names[0] == "red" and names[-1] == "beige" and len(names) == 12
    protos = colours.prototypes()
    assert list(protos) == list(names)
    assert protos["black"] == ((30, 30, 30), (12, 12, 14))
    assert names == perception_colours.COLOUR_NAMES
    assert perception_colours.name_rgb((40, 45, 120)) == "blue"


def test_colour_and_shade_words() -> None:
    words = colours.colour_words()
    assert words["navy"] == "blue" and words["silver"] == "grey" and words["gray"] == "grey"
    assert all(words[n] == n for n in colours.colour_names())
    assert set(words.values()) == set(colours.colour_names())
    assert colours.shade_words() == frozenset({"light", "dark", "pale", "bright", "deep"})


# ------------------------------------------------------------ bad files
def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new, 1), encoding="utf-8")


def test_bad_evidence_weight_names_file_and_field(data_dir: Path) -> None:
    _edit(data_dir / "rooms.toml", "bed = 3.0", 'bed = "lots"')
    with pytest.raises(VocabularyError, match=r"rooms\.toml \[types\.bedroom\].*'evidence'"):
        rooms.evidence()


def test_alias_naming_two_types_is_refused(data_dir: Path) -> None:
    _edit(data_dir / "rooms.toml", '"kitchenette",', '"kitchenette", "den",')
    with pytest.raises(VocabularyError, match=r"rooms\.toml.*'aliases'.*'den'"):
        rooms.room_words()


def test_aliases_must_be_strings(data_dir: Path) -> None:
    _edit(data_dir / "rooms.toml", 'aliases = ["juliet balcony", "loggia"]', "aliases = [3]")
    with pytest.raises(VocabularyError, match=r"rooms\.toml \[types\.balcony\].*'aliases'"):
        rooms.room_types()


def test_bad_size_and_related_are_refused(data_dir: Path) -> None:
    _edit(data_dir / "rooms.toml", "area = [0.8, 5]", "area = [5, 0.8]")
    with pytest.raises(VocabularyError, match=r"\[types\.toilet\].*'area'"):
        rooms.room_type_table()
    _edit(data_dir / "rooms.toml", "area = [5, 0.8]", "area = [0.8, 5]")
    _edit(data_dir / "rooms.toml", "related = { bathroom = 0.8 }", "related = { atrium = 0.8 }")
    _clear()
    with pytest.raises(VocabularyError, match=r"\[types\.toilet\].*'related'.*atrium"):
        rooms.room_type_table()
    _edit(data_dir / "rooms.toml", "related = { atrium = 0.8 }", "colour = 'white'")
    _clear()
    with pytest.raises(VocabularyError, match=r"\[types\.toilet\].*unknown field 'colour'"):
        rooms.room_types()


def test_area_without_anchors_is_refused(data_dir: Path) -> None:
    _edit(data_dir / "areas.toml", 'anchors = ["car", "motorcycle"]', "anchors = []")
    with pytest.raises(VocabularyError, match=r'areas\.toml \[areas\."parking area"\].*anchors'):
        areas.area_rules()


def test_bad_prototype_names_file_and_field(data_dir: Path) -> None:
    _edit(data_dir / "colours.toml", "[30, 30, 30]", "[30, 30, 300]")
    with pytest.raises(VocabularyError, match=r"colours\.toml \[colours\.black\].*'prototypes'"):
        colours.prototypes()


def test_colour_word_naming_two_colours_is_refused(data_dir: Path) -> None:
    _edit(data_dir / "colours.toml", '["ivory"]', '["ivory", "navy"]')
    with pytest.raises(VocabularyError, match=r"colours\.toml.*'words'.*'navy'"):
        colours.colour_words()


def test_missing_version_or_file_names_the_file(data_dir: Path) -> None:
    _edit(data_dir / "areas.toml", "version = 2", "")
    with pytest.raises(VocabularyError, match=r"areas\.toml needs an integer 'version'"):
        areas.area_rules()
    (data_dir / "colours.toml").unlink()
    with pytest.raises(VocabularyError, match=r"colours\.toml is missing"):
        colours.colour_names()


def test_the_digest_follows_the_files(data_dir: Path) -> None:
    before = vocab.vocabulary_info()
    assert {"rooms", "areas", "colours"} <= set(before["versions"])
    _edit(data_dir / "rooms.toml", '"larder"', '"larder", "cellar"')
    _clear()
    after = vocab.vocabulary_info()
    assert after["digest"] != before["digest"] and rooms.room_type("root cellar") == "closet"


# ------------------------------------------------------------------ lexicon
def test_place_modifier_without_a_landmark_is_refused(data_dir: Path) -> None:
    from inherit_sg.vocab.lexicon import lexicon

    lexicon.cache_clear()
    _edit(data_dir / "lexicon.toml", '"bedside" = "next_to bed"', '"bedside" = "next_to"')
    try:
        with pytest.raises(
            VocabularyError, match=r"place_modifiers.*'bedside'.*predicate landmark"
        ):
            lexicon()
    finally:
        lexicon.cache_clear()


def test_every_place_modifier_names_a_predicate_and_a_known_thing() -> None:
    from inherit_sg.retrieval.constraints import PREDICATES
    from inherit_sg.vocab.lexicon import lexicon

    for word, (predicate, place) in lexicon().place_modifiers.items():
        assert predicate in PREDICATES, word
        assert objects.labels_for(place), word


def test_relation_verb_with_two_landmark_predicate_is_refused(data_dir: Path) -> None:
    from inherit_sg.vocab.lexicon import lexicon

    lexicon.cache_clear()
    _edit(data_dir / "lexicon.toml", '"cover" = "near"', '"cover" = "between"')
    try:
        with pytest.raises(VocabularyError, match=r"relations.verbs.*'cover'.*one-landmark"):
            lexicon()
    finally:
        lexicon.cache_clear()


def test_relation_verbs_and_on_rooms_are_read() -> None:
    from inherit_sg.vocab.lexicon import lexicon

    lx = lexicon()
    assert lx.relation_verbs["cover"] == "near" and lx.relation_verbs["hold"] == "supports"
    assert {"landing", "deck", "porch"} <= lx.on_rooms
    assert all(rooms.room_type(word) for word in ("landing", "deck", "porch", "balcony"))


def test_every_relation_verb_names_a_one_landmark_predicate() -> None:
    from inherit_sg.retrieval.constraints import PREDICATES
    from inherit_sg.vocab.lexicon import lexicon

    for verb, predicate in lexicon().relation_verbs.items():
        assert predicate in PREDICATES and predicate != "between", verb

"""The real-world generator: Matterport3D room types in realistic proportions, open-plan
ground floors, the object catalogue, continuous colours with basic colour names,
material looks, and requests over all of it."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from inherit_sg.ingest.synthetic.catalogue import NEW_KINDS
from inherit_sg.ingest.synthetic.colour_models import PALETTES, sample_colour
from inherit_sg.ingest.synthetic.colour_naming import (
    BASIC_TERMS,
    CENTROIDS,
    colour_term,
    is_clear,
    srgb_to_lab,
)
from inherit_sg.ingest.synthetic.generate import generate_house
from inherit_sg.ingest.synthetic.layout import plan_house
from inherit_sg.ingest.synthetic.queries import PAPER_SHARES, category_shares, generate_queries
from inherit_sg.ingest.synthetic.render_materials import MATERIAL_CODE, finish, pattern
from inherit_sg.ingest.synthetic.room_contents import ROOM_CONTENTS, parse_members
from inherit_sg.ingest.synthetic.taxonomy import ROOM_TYPES
from inherit_sg.ingest.synthetic.truth import ObjectSpec, SceneIndex, evaluate
from inherit_sg.ingest.synthetic.vocabulary import CLASSIC_KINDS, COLOURS, OBJECT_KINDS


@pytest.fixture(scope="module")
def plans():
    return [plan_house(np.random.default_rng(seed), 2, None) for seed in range(60)]


def test_room_types_come_in_realistic_proportions(plans):
    houses = [Counter(r.type for f in p.floors for r in f.rooms) for p in plans]
    for rooms in houses:
        assert set(rooms) <= set(ROOM_TYPES)
        assert rooms["kitchen"] == rooms["living room"] == 1
        assert rooms["bedroom"] >= 1 and rooms["bathroom"] >= 1
    share = {t: sum(t in h for h in houses) / len(houses) for t in ROOM_TYPES}
    for common in ("dining room", "closet", "office", "toilet"):
        assert share[common] >= 0.3, (common, share[common])
    for often in ("entryway", "laundry room"):
        assert share[often] >= 0.15, (often, share[often])
    assert share["family room"] + share["tv room"] >= 0.25
    for rare in ("gym", "library", "bar", "rec room", "porch"):
        assert share[rare] <= 0.12, (rare, share[rare])
    assert len([t for t, s in share.items() if s > 0]) >= 16


def test_open_plan_ground_floors_in_a_good_share(plans):
    open_floors = sum(
        any(r.open_group and r.type in ("kitchen", "living room") for r in p.floors[0].rooms)
        for p in plans
    )
    assert 0.3 <= open_floors / len(plans) <= 0.55


@pytest.fixture(scope="module")
def open_house():
    return generate_house(4, 2, open_plan=True)


def test_open_plan_rooms_share_one_space_without_walls(open_house):
    plan, scene = open_house.plan, open_house.scene
    ground = plan.floors[0]
    core = [r for r in ground.rooms if r.type in ("kitchen", "dining room", "living room")]
    assert len({r.open_group for r in core}) == 1 and core[0].open_group
    assert ground.open_edges
    for edge in ground.open_edges:
        assert edge.kind == "open" and edge.hi - edge.lo >= 1.2
        for wall in ground.walls:  # no wall runs along an open span
            if wall.axis == edge.axis and abs(wall.coord - edge.coord) < 1e-6:
                assert wall.hi <= edge.lo + 1e-6 or wall.lo >= edge.hi - 1e-6
        doored = {frozenset(d.rooms) for d in ground.doors}
        assert frozenset(edge.rooms) not in doored
    # the ground truth keeps every region with its own type and polygon
    by_id = {r.id: r for r in scene.rooms}
    for room in core:
        gt = by_id[room.id]
        assert gt.type == room.type and gt.attributes["open_group"] == room.open_group
        for other in gt.attributes["open_to"]:
            assert room.id in by_id[other].attributes["open_to"]
    walk = open_house.trajectory()
    assert {r.id for r in core} <= set(walk.rooms)


def test_walled_houses_have_no_open_border():
    house = generate_house(4, 2, open_plan=False)
    assert not any(f.open_edges for f in house.plan.floors)
    assert not any(r.attributes.get("open_to") for r in house.scene.rooms)


def test_catalogue_has_over_a_hundred_real_categories():
    used = {m.label for groups in ROOM_CONTENTS.values() for g in groups for m in g.members}
    used |= {a for groups in ROOM_CONTENTS.values() for g in groups for a in g.anchors}
    assert used <= set(OBJECT_KINDS) and len(used) >= 100
    ranked = [OBJECT_KINDS[label] for label in used if OBJECT_KINDS[label].mp3d_rank is not None]
    assert len(ranked) >= 80
    assert all(k.mpcat40 for k in OBJECT_KINDS.values())
    # every kind can still be drawn in a classic palette colour (Matterport3D renders do)
    assert all(k.colours and set(k.colours) <= set(COLOURS) for k in OBJECT_KINDS.values())
    for kind in NEW_KINDS:  # new kinds do not change the classic world's
        assert kind.label not in CLASSIC_KINDS
    for label, kind in CLASSIC_KINDS.items():
        assert OBJECT_KINDS[label].size == kind.size and OBJECT_KINDS[label].small == kind.small
    with pytest.raises(ValueError, match="bad member"):
        parse_members("chair@@2")


def test_houses_hold_appliances_small_objects_and_frequent_kinds_often():
    scenes = [generate_house(seed, 2).scene for seed in range(4)]
    counts = Counter(o.label for s in scenes for o in s.objects if not o.structural)
    for appliance in ("refrigerator", "stove", "microwave", "washing machine", "dishwasher"):
        assert counts[appliance] >= 1, appliance
    assert len(counts) >= 60
    small = sum(n for label, n in counts.items() if OBJECT_KINDS[label].small)
    assert small >= 0.35 * sum(counts.values())
    # frequent Matterport3D categories are frequent here too: the 20 most frequent
    # kinds have a better median rank than the rest
    ranks = [(n, OBJECT_KINDS[label].mp3d_rank) for label, n in counts.items()]
    ranks = sorted((r for r in ranks if r[1] is not None), reverse=True)
    assert np.median([r for _, r in ranks[:20]]) < np.median([r for _, r in ranks[20:]])


def test_basic_colour_terms_name_their_reference_colours():
    assert set(CENTROIDS) == set(BASIC_TERMS) and len(BASIC_TERMS) == 11
    for term, refs in CENTROIDS.items():
        for _, rgb in refs:
            assert colour_term(rgb) == term
    lab = srgb_to_lab(np.array([255, 255, 255]))
    assert lab[0] == pytest.approx(100.0, abs=0.1) and abs(lab[1]) < 0.1 and abs(lab[2]) < 0.1
    for rgb, term in (
        ((250, 250, 247), "white"),
        ((12, 12, 14), "black"),
        ((200, 30, 40), "red"),
        ((30, 100, 180), "blue"),
        ((120, 75, 40), "brown"),
        ((60, 150, 70), "green"),
        ((128, 128, 128), "grey"),
    ):
        assert colour_term(rgb) == term and is_clear(rgb)
    assert not is_clear((215, 195, 160))  # beige sits between grey, brown and yellow


def test_palettes_sample_plausible_colours():
    rng = np.random.default_rng(0)
    for name in PALETTES:
        for _ in range(20):
            assert all(0 <= v <= 255 for v in sample_colour(name, rng))
    plants = Counter(colour_term(sample_colour("plant", rng)) for _ in range(200))
    assert plants["green"] >= 150
    wood = Counter(colour_term(sample_colour("natural wood", rng)) for _ in range(200))
    assert wood["brown"] + wood["orange"] + wood["black"] >= 150
    whites = Counter(colour_term(sample_colour("white", rng)) for _ in range(200))
    assert whites["white"] >= 150


def test_new_materials_render_distinctly():
    pts = np.random.default_rng(1).uniform(0, 1, (4000, 3)).astype(np.float32)
    generic = np.ones(len(pts), np.float32)
    looks = {}
    for name in ("wicker", "paper", "concrete", "wood", "fabric"):
        codes = np.full(len(pts), MATERIAL_CODE[name], np.uint8)
        looks[name] = pattern(codes, pts, generic)
        assert looks[name].std() > 0.01, name
    for a in looks:
        for b in looks:
            if a < b:
                assert not np.allclose(looks[a], looks[b], atol=0.02), (a, b)
    # reflections: metal takes its colour, glass lets little diffuse light through,
    # a ceramic glaze shines white at grazing angles
    n = len(pts)
    normals = np.tile(np.array([[0, -1, 0]], np.float32), (n, 1))
    head_on = np.tile(np.array([[0, 1, 0]], np.float32), (n, 1))
    grazing = np.tile(np.array([[0.98, 0.2, 0]], np.float32), (n, 1))
    grazing /= np.linalg.norm(grazing, axis=1, keepdims=True)
    albedo = np.tile(np.array([[0.8, 0.3, 0.05]], np.float32), (n, 1))
    diffuse, shine = albedo * 0.5, np.zeros(n, np.float32)

    def lit(name: str, view: np.ndarray) -> np.ndarray:
        codes = np.full(n, MATERIAL_CODE[name], np.uint8)
        return finish(codes, diffuse.copy(), albedo, shine, normals, view)[0]

    plastic = lit("plastic", head_on)
    assert np.allclose(plastic, diffuse[0])
    metal = lit("metal", head_on)
    assert metal[0] > metal[2] + 0.1 and not np.allclose(metal, plastic)
    assert lit("glass", head_on).sum() < plastic.sum()
    ceramic = lit("ceramic", grazing) - lit("ceramic", head_on)
    assert ceramic.min() > 0.04 and np.ptp(ceramic) < 0.02


@pytest.fixture(scope="module")
def real_scene():
    return generate_house(12, 2).scene


def test_requests_keep_the_paper_shares_and_exact_answers(real_scene):
    queries = generate_queries(real_scene, 12)
    assert len(queries) >= 200
    shares = category_shares(queries)
    for group, paper in PAPER_SHARES.items():
        assert abs(shares[group] - paper) <= 0.03, (group, shares[group])
    index = SceneIndex(real_scene)
    for q in queries:
        spec = ObjectSpec.from_dict(q.gt_constraints)
        assert q.target_ids == evaluate(real_scene, spec, index), q.text
        for attr in spec.attributes:  # a colour is only asked for when it is clear
            if attr.key == "colour":
                for oid in q.target_ids:
                    rgb = tuple(real_scene.object(oid).attributes["rgb"])
                    if not attr.negated:
                        assert colour_term(rgb) == attr.value
    rooms = {t for q in queries for t in [q.gt_constraints.get("room", {}).get("type")] if t}
    assert rooms - {"kitchen", "living room", "bedroom", "bathroom", "hallway", "dining room"}

"""Material appearance for the renderer: what makes wood, fabric or metal look different.

Each object part made of the object's material (or of a material the part names, such as
a mirror's glass) gets a material code per face. Shading then modulates the Lambertian
light with a deterministic, world-anchored pattern, weights the diffuse light, adds a
specular highlight and a view-dependent reflection of the room (a bright ceiling above
a darker floor), so that a material can be told from pixels alone:

| material | pattern (multiplies the light)                  | diffuse | specular (white)      | reflection                      |
|----------|-------------------------------------------------|---------|-----------------------|---------------------------------|
| wood     | grain: stripes ~5 cm apart, wavy, ±20 %         | 1       | none                  | none                            |
| fabric   | fine weave: 1 cm value noise, ±17 %             | 1       | none                  | none                            |
| leather  | coarse grain: 4 cm value noise, ±14 %           | 1       | faint, broad          | faint sheen at grazing angles   |
| stone    | speckle: sparse dark flecks on 1.5 cm cells     | 1       | none                  | none                            |
| metal    | smooth                                          | 0.55    | strong, broad sheen   | the room, tinted by the metal   |
| ceramic  | smooth                                          | 1       | sharp glaze highlight | clear glaze: white at grazing   |
| plastic  | faint 1 cm noise, ±3 %                          | 1       | weak                  | none                            |
| glass    | smooth                                          | 0.45    | sharp, strong         | the room, strong at grazing     |
| wicker   | basket weave: crossed diagonal strands, ±25 %   | 1       | none                  | none                            |
| paper    | fibres: 3 mm value noise, ±5 %, a little bright | 1       | none                  | none                            |
| concrete | mottling (8 cm) ±9 % and dark pores             | 1       | none                  | none                            |

Code 0 (background and unknown materials) keeps the renderer's generic value noise.
The material names are the renderer's own list (the first eight in the order earlier
datasets used).
"""

from __future__ import annotations

import numpy as np

# Face codes: 0 = no material look, then the renderer's material names in order.
MATERIALS: tuple[str, ...] = (
    "",
    "wood",
    "fabric",
    "leather",
    "stone",
    "metal",
    "ceramic",
    "plastic",
    "glass",
    "wicker",
    "paper",
    "concrete",
)
MATERIAL_CODE: dict[str, int] = {m: i for i, m in enumerate(MATERIALS) if m}

# Per code: specular strength and Blinn-Phong exponent, diffuse weight, reflection
# strength at normal incidence and at grazing angles, and whether the reflection takes
# the surface's colour (metals do).
_SPEC_STRENGTH = np.array([0, 0, 0, 0.06, 0, 0.45, 0.55, 0.08, 0.7, 0, 0, 0], dtype=np.float32)
_SPEC_EXPONENT = np.array([1, 1, 1, 6, 1, 6, 60, 12, 120, 1, 1, 1], dtype=np.float32)
_DIFFUSE = np.array([1, 1, 1, 1, 1, 0.55, 1, 1, 0.45, 1, 1, 1], dtype=np.float32)
_REFLECT_0 = np.array([0, 0, 0, 0, 0, 0.45, 0.03, 0, 0.06, 0, 0, 0], dtype=np.float32)
_REFLECT_90 = np.array([0, 0, 0, 0.08, 0, 0.7, 0.5, 0, 0.75, 0, 0, 0], dtype=np.float32)
_TINTED = np.array([0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0], dtype=np.float32)
_GRAIN_DIR = np.array([0.94, 0.31, 0.12], dtype=np.float32)
# The room as a reflection sees it (linear RGB): floor below, walls around, ceiling above.
_ENV_FLOOR = np.array([0.12, 0.1, 0.08], dtype=np.float32)
_ENV_WALL = np.array([0.45, 0.44, 0.42], dtype=np.float32)
_ENV_CEILING = np.array([0.85, 0.85, 0.83], dtype=np.float32)
_WEAVE_A = np.array([0.71, 0.0, 0.71], dtype=np.float32)
_WEAVE_B = np.array([0.0, 0.71, -0.71], dtype=np.float32)


def material_code(name: str) -> int:
    """The face code of a material name (0 when the renderer has no look for it)."""
    return MATERIAL_CODE.get(name.strip().lower(), 0)


def _hash(cells: np.ndarray) -> np.ndarray:
    """Deterministic values in [-1, 1] for integer 3D cells (N, 3)."""
    c = cells.astype(np.int32).view(np.uint32)
    h = (c[:, 0] * np.uint32(73856093)) ^ (c[:, 1] * np.uint32(19349663))
    h ^= c[:, 2] * np.uint32(83492791)
    h = (h ^ (h >> np.uint32(13))) * np.uint32(1274126177)
    return ((h >> np.uint32(7)) & np.uint32(1023)).astype(np.float32) / np.float32(511.5) - 1.0


def value_noise(points: np.ndarray, cells_per_metre: float) -> np.ndarray:
    """Blocky value noise in [-1, 1] on cubic cells of 1 / ``cells_per_metre`` metres."""
    return _hash(np.floor(points * np.float32(cells_per_metre)))


def pattern(codes: np.ndarray, points: np.ndarray, generic: np.ndarray) -> np.ndarray:
    """Light multiplier per hit point: the material's surface pattern; ``generic`` (the
    renderer's value-noise multiplier) where the code is 0."""
    out = generic.astype(np.float32, copy=True)
    for code, fn in _PATTERNS.items():
        sel = np.flatnonzero(codes == code)
        if sel.size:
            out[sel] = fn(points[sel])
    return out


def _wood(p: np.ndarray) -> np.ndarray:
    along = p @ _GRAIN_DIR
    wobble = 0.012 * np.sin(p[:, 2] * np.float32(9.0) + p[:, 0] * np.float32(4.0))
    stripes = np.sin((along + wobble) * np.float32(2 * np.pi / 0.05))
    return 1.0 + np.float32(0.2) * stripes + np.float32(0.03) * value_noise(p, 50.0)


def _fabric(p: np.ndarray) -> np.ndarray:
    return 1.0 + np.float32(0.17) * value_noise(p, 100.0)


def _leather(p: np.ndarray) -> np.ndarray:
    return 1.0 + np.float32(0.14) * value_noise(p, 25.0)


def _stone(p: np.ndarray) -> np.ndarray:
    n = value_noise(p, 66.0)
    flecks = np.where(n > 0.8, np.float32(-0.45), np.float32(0.0))
    return 1.0 + flecks + np.float32(0.02) * value_noise(p, 20.0)


def _smooth(p: np.ndarray) -> np.ndarray:
    return np.ones(len(p), dtype=np.float32)


def _plastic(p: np.ndarray) -> np.ndarray:
    return 1.0 + np.float32(0.03) * value_noise(p, 100.0)


def _wicker(p: np.ndarray) -> np.ndarray:
    # two sets of strands crossing at right angles, over and under
    a = np.sin(p @ _WEAVE_A * np.float32(2 * np.pi / 0.025))
    b = np.sin(p @ _WEAVE_B * np.float32(2 * np.pi / 0.025))
    return 1.0 + np.float32(0.25) * a * b + np.float32(0.04) * value_noise(p, 120.0)


def _paper(p: np.ndarray) -> np.ndarray:
    return np.float32(1.04) + np.float32(0.05) * value_noise(p, 330.0)


def _concrete(p: np.ndarray) -> np.ndarray:
    mottle = 0.5 * (value_noise(p, 12.5) + value_noise(p + np.float32(0.037), 25.0))
    pores = np.where(value_noise(p, 200.0) > 0.9, np.float32(-0.25), np.float32(0.0))
    return 1.0 + np.float32(0.09) * mottle + pores


_PATTERNS = {
    MATERIAL_CODE["wood"]: _wood,
    MATERIAL_CODE["fabric"]: _fabric,
    MATERIAL_CODE["leather"]: _leather,
    MATERIAL_CODE["stone"]: _stone,
    MATERIAL_CODE["metal"]: _smooth,
    MATERIAL_CODE["ceramic"]: _smooth,
    MATERIAL_CODE["plastic"]: _plastic,
    MATERIAL_CODE["glass"]: _smooth,
    MATERIAL_CODE["wicker"]: _wicker,
    MATERIAL_CODE["paper"]: _paper,
    MATERIAL_CODE["concrete"]: _concrete,
}


def specular(
    codes: np.ndarray, normals: np.ndarray, dirs: np.ndarray, to_light: np.ndarray
) -> np.ndarray:
    """Blinn-Phong specular factor per hit point (0 for matte materials); ``dirs`` point
    from the camera to the surface, ``to_light`` from the surface to the light (unit)."""
    strength = _SPEC_STRENGTH[codes]
    out = np.zeros(len(codes), dtype=np.float32)
    sel = np.flatnonzero(strength > 0)
    if sel.size == 0:
        return out
    half = to_light[sel] - dirs[sel]
    half /= np.maximum(np.linalg.norm(half, axis=1, keepdims=True), np.float32(1e-6))
    cos = np.maximum(np.einsum("ij,ij->i", normals[sel], half), np.float32(0.0))
    out[sel] = strength[sel] * cos ** _SPEC_EXPONENT[codes[sel]]
    return out


def _environment(directions: np.ndarray) -> np.ndarray:
    """Linear RGB of the room seen along unit ``directions``: floor, walls, ceiling."""
    up = directions[:, 2:3]
    below = np.clip(-up, 0.0, 1.0)
    above = np.clip(up, 0.0, 1.0)
    return _ENV_WALL * (1.0 - below - above) + _ENV_FLOOR * below + _ENV_CEILING * above


def finish(
    codes: np.ndarray,
    diffuse: np.ndarray,
    albedo: np.ndarray,
    shine: np.ndarray,
    normals: np.ndarray,
    dirs: np.ndarray,
) -> np.ndarray:
    """Final linear radiance (N, 3): the ``diffuse`` radiance weighted by the material's
    diffuse share, plus its specular ``shine`` and its reflection of the room (Schlick's
    approximation between the normal-incidence and grazing strengths; tinted by
    ``albedo`` for metals). ``dirs`` point from the camera to the surface."""
    out = diffuse * _DIFFUSE[codes][:, None]
    out += shine[:, None]
    r0, r90 = _REFLECT_0[codes], _REFLECT_90[codes]
    sel = np.flatnonzero(r90 > 0)
    if sel.size == 0:
        return out
    n, v = normals[sel], dirs[sel]
    cos = np.clip(-np.einsum("ij,ij->i", n, v), 0.0, 1.0)
    fresnel = r0[sel] + (r90[sel] - r0[sel]) * (1.0 - cos) ** 5
    mirrored = v + 2.0 * cos[:, None] * n
    env = _environment(mirrored.astype(np.float32))
    tint = _TINTED[codes[sel]][:, None]
    env = env * (tint * albedo[sel] + (1.0 - tint))
    out[sel] += fresnel[:, None] * env
    return out

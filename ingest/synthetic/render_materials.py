"""Material appearance for the renderer: what makes wood, fabric or metal look different.

Each object part made of the object's material gets a material code per face. Shading
then modulates the Lambertian light with a deterministic, world-anchored pattern and
adds a specular term, so that a material can be told from pixels alone:

| material | pattern (multiplies the light)                 | specular (white)        |
|----------|------------------------------------------------|-------------------------|
| wood     | grain: stripes ~5 cm apart, wavy, ±20 %        | none                    |
| fabric   | fine weave: 1 cm value noise, ±17 %            | none                    |
| leather  | coarse grain: 4 cm value noise, ±14 %          | faint, broad            |
| stone    | speckle: sparse dark flecks on 1.5 cm cells    | none                    |
| metal    | smooth                                         | strong, broad sheen     |
| ceramic  | smooth                                         | sharp glaze highlight   |
| plastic  | faint 1 cm noise, ±3 %                          | weak                    |
| glass    | smooth                                         | sharp, strong           |

Code 0 (background and unknown materials) keeps the renderer's generic value noise.
"""

from __future__ import annotations

import numpy as np

from inherit_sg.perception.material import MATERIAL_NAMES

# Face codes: 0 = no material look, then the project's material names in order.
MATERIALS: tuple[str, ...] = ("", *MATERIAL_NAMES)
MATERIAL_CODE: dict[str, int] = {m: i for i, m in enumerate(MATERIALS) if m}

# Per code: specular strength and Blinn-Phong exponent.
_SPEC_STRENGTH = np.array([0, 0, 0, 0.06, 0, 0.45, 0.55, 0.08, 0.7], dtype=np.float32)
_SPEC_EXPONENT = np.array([1, 1, 1, 6, 1, 6, 60, 12, 120], dtype=np.float32)
_GRAIN_DIR = np.array([0.94, 0.31, 0.12], dtype=np.float32)


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


_PATTERNS = {
    MATERIAL_CODE["wood"]: _wood,
    MATERIAL_CODE["fabric"]: _fabric,
    MATERIAL_CODE["leather"]: _leather,
    MATERIAL_CODE["stone"]: _stone,
    MATERIAL_CODE["metal"]: _smooth,
    MATERIAL_CODE["ceramic"]: _smooth,
    MATERIAL_CODE["plastic"]: _plastic,
    MATERIAL_CODE["glass"]: _smooth,
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

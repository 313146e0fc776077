"""One kind of object of the synthetic world: how it looks, where it goes, what it is for.

Shared by the classic vocabulary (:mod:`inherit_sg.ingest.synthetic.vocabulary`) and the real-world
catalogue (:mod:`inherit_sg.ingest.synthetic.catalogue`).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ObjectKind:
    """How one kind of object looks, where it goes and what it is for."""

    label: str
    size: tuple[float, float, float]  # typical width, depth, height in metres
    synonyms: tuple[str, ...] = ()
    functions: tuple[str, ...] = ()  # e.g. "sit", "sleep", "wash hands"
    colours: tuple[str, ...] = ()  # classic palette names it comes in
    materials: tuple[str, ...] = ("wood",)
    surface: bool = False  # small objects can stand on it
    small: bool = False  # stands on a surface rather than the floor
    wall: bool = False  # placed against a wall
    mount_height: float = 0.0  # bottom height above the floor (wall-mounted things)
    # Real-world catalogue (inherit_sg.ingest.synthetic.catalogue); the classic world ignores these.
    mpcat40: str = ""  # Matterport3D's 40-class grouping
    raw: tuple[str, ...] = ()  # Matterport3D raw category names, most frequent first
    mp3d_rank: int | None = None  # row of raw[0] in Matterport3D's category table (by count)
    palette: str = ""  # colour palette (colour_models); "" = the material's
    rests_on: tuple[str, ...] = ()  # where a small object belongs, best first ("floor" too)
    ceiling: bool = False  # hangs from the ceiling
    shelves: bool = False  # small objects also stand on its shelf boards
    window: bool = False  # dresses a window (curtains, blinds)

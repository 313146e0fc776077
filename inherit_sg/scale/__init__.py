"""Work around many maps on Ray: ``map build-many`` (one Ray task per map) and
``serve --ray`` (a Ray Serve deployment of the REST app).

Each building keeps its own embedded map (Kuzu + LanceDB directory, one writer); Ray
only schedules the work around the maps. Nothing here is imported unless a command asks
for Ray, and :func:`require_ray` names the install command when Ray is missing.
"""

from __future__ import annotations

from types import ModuleType

from inherit_sg.errors import InputError

INSTALL_HINT = "pip install 'inherit-sg[ray]'  (Ray 2.60 with Ray Serve)"


def require_ray() -> ModuleType:
    """The ``ray`` module, or an :class:`InputError` naming the install command."""
    try:
        import ray
    except ImportError:
        raise InputError(
            f"this command needs Ray, which is not installed: {INSTALL_HINT}"
        ) from None
    return ray

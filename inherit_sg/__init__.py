"""INHerit-SG: incremental hierarchical semantic scene graphs with RAG-style retrieval.

The public API, in a few names::

    from inherit_sg import MapService

    with MapService.open("house-map") as service:
        result = service.query("the chair that is not in the kitchen").model()
        print(result.answer.label, result.answer.position)
        rooms = service.rooms(floor="floor:0")

``MapService`` owns a map directory (reads, queries, Cypher, export, live sessions);
``QueryResponse`` and the listing models are its typed results; ``build_map`` maps a
dataset into a new or existing map; ``InheritSGError`` is the root of every error the
package raises.

Heavy dependencies (torch, sentence-transformers, lancedb) are imported lazily by the
modules that need them, so importing this package and running the light CLI commands
stays fast.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

__all__ = [
    "AreaPage",
    "Config",
    "FloorPage",
    "Hierarchy",
    "InheritSGError",
    "MapService",
    "MapStats",
    "ObjectDetail",
    "ObjectPage",
    "QueryResponse",
    "RoomPage",
    "__version__",
    "build_map",
]

# Where each public name lives; imported on first use (PEP 562), so `import inherit_sg`
# stays light.
_HOMES = {
    "MapService": "inherit_sg.facade",
    "build_map": "inherit_sg.facade",
    "Config": "inherit_sg.config",
    "InheritSGError": "inherit_sg.errors",
    "QueryResponse": "inherit_sg.retrieval.result_models",
    "AreaPage": "inherit_sg.reads.models",
    "FloorPage": "inherit_sg.reads.models",
    "Hierarchy": "inherit_sg.reads.models",
    "MapStats": "inherit_sg.reads.models",
    "ObjectDetail": "inherit_sg.reads.models",
    "ObjectPage": "inherit_sg.reads.models",
    "RoomPage": "inherit_sg.reads.models",
}

if TYPE_CHECKING:
    from inherit_sg.config import Config
    from inherit_sg.errors import InheritSGError
    from inherit_sg.facade import MapService, build_map
    from inherit_sg.reads.models import (
        AreaPage,
        FloorPage,
        Hierarchy,
        MapStats,
        ObjectDetail,
        ObjectPage,
        RoomPage,
    )
    from inherit_sg.retrieval.result_models import QueryResponse


def __getattr__(name: str) -> Any:
    """The public names, imported when first used."""
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'inherit_sg' has no attribute {name!r}")
    import importlib

    return getattr(importlib.import_module(home), name)

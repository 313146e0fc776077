"""Map storage: a map directory with a Kuzu graph (scene graph, embeddings, vector and
full-text indexes) and LanceDB keyframes, behind :class:`MapStore`.

Importing this package is light (Kuzu only); pyarrow and lancedb load on first use.
"""

from inherit_sg.store.kuzu_graph import CypherResult
from inherit_sg.store.mapdir import MapInfo
from inherit_sg.store.readonly import check_read_only
from inherit_sg.store.stats import MapStats
from inherit_sg.store.store import MapStore

__all__ = ["CypherResult", "MapInfo", "MapStats", "MapStore", "check_read_only"]

"""INHerit-SG: incremental hierarchical semantic scene graphs with RAG-style retrieval.

Heavy dependencies (torch, sentence-transformers, lancedb) are imported lazily by the
modules that need them, so importing this package and running the light CLI commands
stays fast.
"""

__version__ = "0.1.0"

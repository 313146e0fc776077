"""End-to-end benchmark of one dataset (``inherit-sg bench``): retrieval accuracy of the
engine and the flat baseline, ablations, mapping speed and quality, storage per node type
and query latency per stage. Uses ground truth only to judge, never to answer."""

"""Cypher DDL of the map, as numbered migrations ``NNNN_name.cypher`` applied in order
and recorded in the map's ``_Migration`` table (see :mod:`inherit_sg.store.migrations`).

Rules for a migration file: statements end with ``;``; every statement is idempotent
(``IF NOT EXISTS``; ``CALL CREATE_*_INDEX`` is skipped when the index exists) so an
interrupted migration can run again; ``{visual_dim}``, ``{text_dim}`` and
``{image_feature_dim}`` are replaced by the map's vector sizes.
"""

from pathlib import Path

SCHEMA_DIR = Path(__file__).resolve().parent

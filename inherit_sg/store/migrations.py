"""Schema migrations: numbered ``schema/NNNN_name.cypher`` files applied in order and
recorded in a ``_Migration(version, name, applied_at)`` node table.

Applying is idempotent: recorded versions are skipped, statements are written to be
re-runnable, and index-creating calls are skipped when the index already exists. A
version is recorded only after all its statements ran, so a migration cut short by a
crash runs again (harmlessly) on the next writable open.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import kuzu

from inherit_sg import schema
from inherit_sg.errors import MapCorruptError, SchemaVersionError
from inherit_sg.store.cypher_lex import TokenKind, split_statements, tokenize
from inherit_sg.store.kuzu_util import index_names, rows, run, table_names

MIGRATION_TABLE = "_Migration"
_FILE_RE = re.compile(r"^(\d{4})_([A-Za-z0-9_]+)\.cypher$")
_PLACEHOLDER_RE = re.compile(r"\{(visual_dim|text_dim|image_feature_dim)\}")
_INDEX_CALLS = ("CREATE_FTS_INDEX", "CREATE_VECTOR_INDEX")


@dataclass(frozen=True)
class Migration:
    """One schema step."""

    version: int
    name: str
    text: str

    def statements(self, dims: Mapping[str, int]) -> list[str]:
        """Statements with the vector-size placeholders filled in."""

        def fill(match: re.Match[str]) -> str:
            return str(int(dims[match.group(1)]))

        return split_statements(_PLACEHOLDER_RE.sub(fill, self.text))


def schema_dir() -> Path:
    """The packaged ``schema/`` folder (found through the package path, which also works
    when an editable install maps it as a namespace package)."""
    return Path(next(iter(schema.__path__)))


def index_call(statement: str) -> tuple[str, str] | None:
    """(table, index) when ``statement`` is ``CALL CREATE_FTS_INDEX('T', 'i', …)`` or
    ``CALL CREATE_VECTOR_INDEX(…)`` (comments ignored), else None."""
    toks = list(tokenize(statement))[:6]
    shape = [t.kind for t in toks]
    if shape != [
        TokenKind.WORD,
        TokenKind.WORD,
        TokenKind.PUNCT,
        TokenKind.STRING,
        TokenKind.PUNCT,
        TokenKind.STRING,
    ]:
        return None
    if toks[0].upper != "CALL" or toks[1].upper not in _INDEX_CALLS:
        return None
    return toks[3].text[1:-1], toks[5].text[1:-1]


def load_migrations(directory: Path | None = None) -> list[Migration]:
    """Migrations found in ``directory`` (default: the packaged ``schema/``), checked to
    be numbered 1, 2, 3, … without gaps or duplicates."""
    folder = directory or schema_dir()
    found: list[Migration] = []
    for file in sorted(folder.glob("*.cypher")):
        match = _FILE_RE.match(file.name)
        if not match:
            raise MapCorruptError(f"{file}: migration files must be named NNNN_name.cypher")
        found.append(Migration(int(match.group(1)), match.group(2), file.read_text("utf-8")))
    for expected, mig in enumerate(found, start=1):
        if mig.version != expected:
            raise MapCorruptError(
                f"{folder}: migration {mig.version:04d}_{mig.name} found where "
                f"version {expected} was expected (gaps or duplicates)"
            )
    return found


def latest_version(migrations: Sequence[Migration] | None = None) -> int:
    """Highest schema version this code knows."""
    migs = load_migrations() if migrations is None else migrations
    return migs[-1].version if migs else 0


def recorded_version(conn: kuzu.Connection) -> int:
    """Highest version recorded in the database (0 for a fresh database)."""
    if MIGRATION_TABLE not in table_names(conn):
        return 0
    found = rows(conn, f"MATCH (m:{MIGRATION_TABLE}) RETURN max(m.version)")
    return int(found[0][0]) if found and found[0][0] is not None else 0


def check_not_newer(conn: kuzu.Connection, map_path: Path, known: int) -> int:
    """Recorded version; SchemaVersionError when the map is newer than this code."""
    have = recorded_version(conn)
    if have > known:
        raise SchemaVersionError(
            f"map {map_path} has schema version {have}, newer than version {known} "
            "known to this INHerit-SG; upgrade INHerit-SG to open it"
        )
    return have


def apply_migrations(
    conn: kuzu.Connection,
    dims: Mapping[str, int],
    map_path: Path,
    migrations: Sequence[Migration] | None = None,
) -> list[int]:
    """Apply the migrations the database lacks; returns the versions applied."""
    migs = load_migrations() if migrations is None else list(migrations)
    have = check_not_newer(conn, map_path, latest_version(migs))
    run(
        conn,
        f"CREATE NODE TABLE IF NOT EXISTS {MIGRATION_TABLE}"
        "(version INT64 PRIMARY KEY, name STRING, applied_at STRING)",
    )
    applied: list[int] = []
    for mig in migs:
        if mig.version <= have:
            continue
        for statement in mig.statements(dims):
            call = index_call(statement)
            if call is not None and call in index_names(conn):
                continue
            try:
                run(conn, statement)
            except RuntimeError as exc:
                raise MapCorruptError(
                    f"map {map_path}: migration {mig.version:04d}_{mig.name} failed at "
                    f"{statement.splitlines()[0]!r}: {exc}"
                ) from None
        run(
            conn,
            f"MERGE (m:{MIGRATION_TABLE} {{version: $v}}) SET m.name = $n, m.applied_at = $t",
            {"v": mig.version, "n": mig.name, "t": datetime.now(UTC).isoformat()},
        )
        applied.append(mig.version)
    return applied

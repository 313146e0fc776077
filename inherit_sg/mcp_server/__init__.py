"""The maps as tools for LLM agents: an MCP server (the official ``mcp`` SDK, installed
with ``pip install 'inherit-sg[mcp]'``) over :class:`~inherit_sg.facade.MapService`, a thin
face like the CLI and REST. ``inherit-sg mcp --map DIR|ROOT`` runs it over stdio or
streamable HTTP (:mod:`.server`); the tools live in :mod:`.tools`, :mod:`.pictures` and
:mod:`.live_tools`, the key rules in :mod:`.access`. Importing this package imports the
SDK: the CLI does so only for the ``mcp`` command."""

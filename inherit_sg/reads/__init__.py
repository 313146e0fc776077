"""The map's reads: listings, node detail, the hierarchy tree and pictures, as typed
results (:mod:`.models`). :class:`~inherit_sg.facade.MapService` exposes them; the CLI and
REST only present them."""

"""The REST service (FastAPI app, routes, web viewer) lives here; it is not built yet."""

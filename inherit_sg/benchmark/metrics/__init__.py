"""Metrics against ground truth: geometry, mapping and retrieval against the simulator's
truth, and parser accuracy on annotated requests. Used by the benchmarks (``inherit-sg
bench``, ``bench/``) and the tests; never by mapping or retrieval."""

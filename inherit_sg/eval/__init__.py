"""Evaluation against simulator ground truth (used by tests and benchmarks only; never by
mapping or retrieval)."""

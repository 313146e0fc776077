"""Offline loading of transformers models and tokenizers from local directories."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from inherit_sg.errors import ModelUnavailableError


def offline_transformers() -> Any:
    """Import transformers with every hub access and progress bar switched off."""
    os.environ.setdefault("HF_HUB_OFFLINE", "1")
    os.environ.setdefault("TRANSFORMERS_OFFLINE", "1")
    os.environ.setdefault("HF_HUB_DISABLE_PROGRESS_BARS", "1")
    try:
        import transformers
        from transformers.utils import logging as hf_logging
    except ImportError as exc:
        raise ModelUnavailableError(f"transformers is not installed: {exc}") from None
    hf_logging.disable_progress_bar()
    return transformers


def load_local(cls: Any, path: Path, what: str, **kwargs: Any) -> Any:
    """``cls.from_pretrained(path)`` without the hub; ModelUnavailableError on failure."""
    if not (path / "config.json").is_file() and not (path / "tokenizer_config.json").is_file():
        raise ModelUnavailableError(f"{what}: {path} holds no config.json")
    try:
        return cls.from_pretrained(path, local_files_only=True, **kwargs)
    except (OSError, ValueError, KeyError, RuntimeError) as exc:
        raise ModelUnavailableError(f"{what}: cannot load from {path}: {exc}") from exc

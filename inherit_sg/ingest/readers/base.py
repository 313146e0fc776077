"""The :class:`FrameSource` protocol every reader satisfies, and a small base class for
readers whose frames are a list fixed when the dataset is opened."""

from __future__ import annotations

import logging
from abc import ABC, abstractmethod
from collections.abc import Iterator
from pathlib import Path
from typing import Protocol, runtime_checkable

from inherit_sg.errors import DatasetError
from inherit_sg.model import Frame, Intrinsics

log = logging.getLogger(__name__)


@runtime_checkable
class FrameSource(Protocol):
    """A posed RGB-D stream: frames in the z-up world with OpenCV camera axes."""

    format_name: str
    intrinsics: Intrinsics

    def __len__(self) -> int: ...

    def __iter__(self) -> Iterator[Frame]: ...

    def read(self, index: int) -> Frame:
        """Load frame ``index`` (0-based position in the stream)."""
        ...


class IndexedReader(ABC):
    """Base for readers with a frame list fixed at open time.

    Subclasses set ``format_name``, ``intrinsics`` and ``frame_ids`` in their constructor
    and implement :meth:`_load`. ``skipped`` maps the ids of frames left out of the stream
    to the reason (no pose, invalid pose, missing image), so callers can report them.
    ``single_file`` readers (one archive holds the dataset) take a file as ``root``.
    """

    format_name: str = ""
    intrinsics: Intrinsics

    def __init__(self, root: str | Path, *, single_file: bool = False) -> None:
        self.root = Path(root)
        if single_file and not self.root.is_file():
            raise DatasetError(f"{self.format_name} file not found: {self.root}")
        if not single_file and not self.root.is_dir():
            raise DatasetError(f"{self.format_name} dataset folder not found: {self.root}")
        self.frame_ids: list[str] = []
        self.skipped: dict[str, str] = {}

    def _skip(self, frame_id: str, reason: str) -> None:
        self.skipped[frame_id] = reason

    def _report_skipped(self) -> None:
        if self.skipped:
            example = next(iter(self.skipped.items()))
            log.warning(
                "%s %s: skipped %d frame(s), e.g. %s (%s)",
                self.format_name,
                self.root,
                len(self.skipped),
                *example,
            )

    def __len__(self) -> int:
        return len(self.frame_ids)

    def __iter__(self) -> Iterator[Frame]:
        for index in range(len(self.frame_ids)):
            yield self.read(index)

    def read(self, index: int) -> Frame:
        """Load frame ``index``; raises IndexError outside ``range(len(self))`` and
        FrameError naming the file when an image is missing or malformed."""
        if not 0 <= index < len(self.frame_ids):
            raise IndexError(f"frame index {index} out of range 0..{len(self.frame_ids) - 1}")
        return self._load(index).validate()

    @abstractmethod
    def _load(self, index: int) -> Frame:
        """Build (unvalidated) frame ``index``."""

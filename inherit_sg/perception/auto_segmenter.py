"""The default segmenter: a frame's own instance masks where it has them, else the
classical class-agnostic segmenter.

Generated walks and some datasets come with instance masks (the ``dataset`` segmenter
reads them); real recordings (Replica, ScanNet, TUM, a robot's camera) usually do not, and
with the ``dataset`` segmenter alone they would map to nothing. The semantic stream
warns once at the first frame without masks (:data:`UNNAMED_WARNING`): its objects are
found by depth and colour and stay unnamed ("object") until a model is configured
(``perception.segmenter = "sam3"`` with ``perception.model_dir``).
"""

from __future__ import annotations

from collections.abc import Sequence

from inherit_sg.model import Frame
from inherit_sg.perception.base import Detection, Segmenter

UNNAMED_WARNING = (
    "objects are found by depth and colour (the classical segmenter) and stay unnamed "
    "until a model is configured; set perception.segmenter = 'sam3' and "
    "perception.model_dir to a local SAM3 checkpoint to name them"
)


class AutoSegmenter:
    """Dataset masks when a frame carries them, the classical segmenter otherwise."""

    name = "auto"
    # A frame without masks is segmented, but it is no evidence that a place is empty: a
    # named object mapped there may come back as an unnamed "object" that does not match.
    needs_instances = True
    # ... and such frames are not blind: they are looked at by the fallback segmenter
    falls_back = True

    def __init__(self, with_masks: Segmenter, without_masks: Segmenter) -> None:
        self.with_masks = with_masks
        self.without_masks = without_masks

    def segment(self, frame: Frame, prompts: Sequence[str] | None = None) -> list[Detection]:
        """Detections of ``frame`` by whichever segmenter can look at it."""
        if frame.instances is not None:
            return self.with_masks.segment(frame, prompts)
        return self.without_masks.segment(frame, prompts)

"""Progress of a long study: now :class:`archrock._progress.Progress` (the one protocol); this
module keeps the 0.6 import path."""

from __future__ import annotations

import time  # noqa: F401 - tests and callers patch progress.time.monotonic

from ..._progress import Progress, check_progress  # noqa: F401

__all__ = ["Progress"]

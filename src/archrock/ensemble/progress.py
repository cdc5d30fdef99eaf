"""Progress output of an ensemble run, on stderr."""

from __future__ import annotations

import sys
import time

__all__ = ["Progress"]


class Progress:
    """Units done out of ``total``: a tqdm bar on stderr, or a line a second without tqdm;
    silent unless ``enabled``. ``desc`` names the study, ``unit`` what is counted (the
    ensemble's samples by default; curves' arches, fragility's analyses)."""

    def __init__(self, total: int, enabled: bool, desc: str = "ensemble", unit: str = "arch"):
        self.bar = None
        self.enabled = enabled
        self.total = total
        self.done = 0
        self.last = 0.0
        self.desc = desc
        self.plural = "samples" if desc == "ensemble" else unit + "s"
        if not enabled:
            return
        try:
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit=unit, desc=desc, file=sys.stderr,
                            dynamic_ncols=True)
        except ImportError:
            self.bar = None

    def update(self, n: int):
        self.done += n
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(n)
        elif time.monotonic() - self.last > 1.0 or self.done == self.total:
            self.last = time.monotonic()
            print(f"{self.desc}: {self.done}/{self.total} {self.plural}", file=sys.stderr,
                  flush=True)

    def note(self, text: str):
        """A line of progress output (above the bar)."""
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.write(text, file=sys.stderr)
        else:
            print(text, file=sys.stderr, flush=True)

    def close(self):
        if self.bar is not None:
            self.bar.close()


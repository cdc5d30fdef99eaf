"""Progress of a long study: counted units, handed on as lines of text.

One protocol for every study (:mod:`archrock._progress`): ``progress`` is None/False (silent),
a callable given one line of text at a time (the library itself then prints nothing: the caller
renders, as the app does), or True, the command line's renderer: a tqdm bar on stderr when it is
a terminal, plain lines otherwise."""

from __future__ import annotations

import sys
import time

from ..._progress import check_progress

__all__ = ["Progress"]

_PLURAL = {"arch": "arches", "analysis": "analyses"}


def _terminal() -> bool:
    """stderr is a terminal (where a bar redraws in place); in a log file or a pipe every redraw
    of a bar would be one more line."""
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


class Progress:
    """Units done out of ``total``: a tqdm bar on stderr when it is a terminal (redrawn at most
    once a second), otherwise plain lines, throttled: a line once at least 1% of the total more
    is done and a second has passed since the last (or once a minute, whatever is done), and the
    last line; so a run writes at most ~100 lines plus one a minute.  Silent unless ``enabled``.
    ``desc`` names the study, ``unit`` what is counted (the ensemble's samples by default;
    curves' arches, fragility's analyses)."""

    #: plain lines: at least this many seconds apart ...
    MIN_INTERVAL_S = 1.0
    #: ... and this fraction of the total apart, unless this many seconds passed
    MIN_FRACTION = 0.01
    HEARTBEAT_S = 60.0

    def __init__(self, total: int, enabled, desc: str = "ensemble", unit: str = "arch"):
        self.bar = None
        # a callable receives the plain lines (never a bar); True renders on stderr
        self.sink = None if enabled is True else check_progress(enabled)
        enabled = enabled is True or self.sink is not None
        self.enabled = enabled
        self.total = total
        self.done = 0
        self.printed = 0  # done at the last plain line
        self.last = time.monotonic()
        self.desc = desc
        self.plural = "samples" if desc == "ensemble" else _PLURAL.get(unit, unit + "s")
        if not enabled or self.sink is not None or not _terminal():
            return
        try:
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit=unit, desc=desc, file=sys.stderr,
                            dynamic_ncols=True, mininterval=self.MIN_INTERVAL_S)
        except ImportError:
            self.bar = None

    def _due(self, now: float) -> bool:
        if self.done >= self.total:
            return self.printed < self.total  # the last line, once
        since = now - self.last
        step = max(1, int(self.MIN_FRACTION * self.total))
        return ((self.done - self.printed >= step and since >= self.MIN_INTERVAL_S)
                or since >= self.HEARTBEAT_S)

    def update(self, n: int):
        self.done += n
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(n)
            return
        now = time.monotonic()
        if self._due(now):
            self.last, self.printed = now, self.done
            pct = f" ({100 * self.done / self.total:.0f}%)" if self.total > 0 else ""
            self._line(f"{self.desc}: {self.done}/{self.total} {self.plural}{pct}")

    def _line(self, text: str):
        if self.sink is not None:
            self.sink(text)
        else:
            print(text, file=sys.stderr, flush=True)

    def note(self, text: str):
        """A line of progress output (above the bar)."""
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.write(text, file=sys.stderr)
        else:
            self._line(text)

    def close(self):
        if self.bar is not None:
            self.bar.close()

"""The one progress protocol of long computations; the library never prints.

A ``progress`` argument (or :attr:`archrock.studies.runner.RunSettings.progress`) is

* None or False: silent;
* a callable given one line of text at a time (throttled, see :class:`Progress`); a callable
  that also has a ``bar(total, desc, unit)`` method may return a bar object (``update(n)``,
  ``write(text)``, ``close()``) that then receives every count: the CLI's renderer
  (:mod:`archrock.cli.runsettings`) draws a tqdm bar that way on a terminal;
* True: the lines go to the ``logging`` logger ``archrock.progress`` at INFO level (to see them
  in Python, configure logging; the CLI renders its own way).

A study counts units with :class:`Progress`; a block of limit analyses
(:func:`archrock.statics.kinematic.limit_progress`) hands its lines to the callable directly.
A foundation module, so every layer checks and uses the argument the same way.
"""

from __future__ import annotations

import logging
import time

from .errors import ArchInputError

__all__ = ["check_progress", "Progress", "LOGGER"]

#: the logger of ``progress=True``
LOGGER = "archrock.progress"

_PLURAL = {"arch": "arches", "analysis": "analyses"}


def _log_line(text: str) -> None:
    logging.getLogger(LOGGER).info(text)


def check_progress(progress):
    """A ``progress`` argument as None (silent; False reads as None) or a callable given one
    line of text (True: the ``archrock.progress`` logger); anything else is refused by name."""
    if progress is False or progress is None:
        return None
    if progress is True:
        return _log_line
    if not callable(progress):
        raise ArchInputError(f"progress: {progress!r}; allowed None, True (lines to the "
                             "'archrock.progress' logger) or a callable given one line of text "
                             "(the CLI passes one that renders on stderr)")
    return progress


class Progress:
    """Units done out of ``total``, handed to the progress sink (module doc): throttled lines, a
    line once at least 1% of the total more is done and a second has passed since the last (or
    once a minute, whatever is done), and the last line, so a run hands over at most ~100 lines
    plus one a minute; or every count to the sink's bar when it gives one.  Silent when
    ``enabled`` is None/False.  ``desc`` names the study, ``unit`` what is counted (the
    ensemble's samples by default; curves' responses, fragility's analyses)."""

    #: lines: at least this many seconds apart ...
    MIN_INTERVAL_S = 1.0
    #: ... and this fraction of the total apart, unless this many seconds passed
    MIN_FRACTION = 0.01
    HEARTBEAT_S = 60.0

    def __init__(self, total: int, enabled, desc: str = "ensemble", unit: str = "arch"):
        self.sink = check_progress(enabled)
        self.enabled = self.sink is not None
        self.total = total
        self.done = 0
        self.printed = 0  # done at the last line
        self.last = time.monotonic()
        self.desc = desc
        self.plural = "samples" if desc == "ensemble" else _PLURAL.get(unit, unit + "s")
        make = getattr(self.sink, "bar", None)
        self.bar = make(total, desc, unit) if callable(make) else None

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
            self._line(now)

    def _line(self, now: float):
        self.last, self.printed = now, self.done
        pct = f" ({100 * self.done / self.total:.0f}%)" if self.total > 0 else ""
        self.sink(f"{self.desc}: {self.done}/{self.total} {self.plural}{pct}")

    def note(self, text: str):
        """A line of progress output (above the bar)."""
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.write(text)
        else:
            self.sink(text)

    def finish(self):
        """The work is done: the last line (or the bar) reads 100%.  A study's total is an
        estimate from above (bisections that end early, responses kept from an earlier run,
        curves with no collapse to refine), so without this the count stopped short (at 80%)."""
        if not self.enabled:
            return
        if self.bar is not None:
            if self.done < self.total:  # the bar's own total is fixed: fill it
                self.bar.update(self.total - self.done)
                self.done = self.total
            return
        self.total = self.done  # what was done is the whole: done/done (100%)
        if self.printed != self.done:
            self._line(time.monotonic())

    def close(self):
        if self.bar is not None:
            self.bar.close()

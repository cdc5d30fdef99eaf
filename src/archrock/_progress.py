"""The progress protocol of long computations: a callable given one line of text, or None.

The library never prints: a study, or a block of limit analyses (:func:`archrock.statics.limit.
limit_progress`), hands its progress lines to the callable it was given; the CLI passes one that
prints them on stderr.  A foundation module, so every layer can check the argument the same way.
"""

from __future__ import annotations

from .errors import ArchInputError

__all__ = ["check_progress"]


def check_progress(progress):
    """A ``progress`` argument: None (silent; False reads as None) or a callable given one line
    of text; anything else is refused by name."""
    if progress is False or progress is None:
        return None
    if not callable(progress):
        raise ArchInputError(f"progress: {progress!r}; allowed None or a callable given one "
                             "line of text (the CLI passes one that prints it on stderr)")
    return progress

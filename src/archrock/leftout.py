"""Why an arch of a study was left out: one type, from where the arch is refused to the summary.

A study over many arches (ensembles, curves, fragility) leaves an arch out only when it has no
answer under the chosen model (:data:`archrock.errors.UNUSABLE_ARCH`).  :class:`LeftOut` says
why: ``reason``, one of the codes of :data:`REASONS` (the keys of every summary's counts), and
``detail``, the message as the arch was refused.  It *is* that message (a ``str``), so it travels
unchanged where a reason always travelled as text (object arrays of the batch path, the
``failed`` lists of the studies' JSON, the ``error`` column of an ensemble's Parquet batches)
while code that needs the reason reads ``.reason`` instead of matching the words.

Text without a type (a batch file written by an earlier release, or a message of the batch path
worded as text) becomes a LeftOut in one place, :meth:`LeftOut.read`, by the forms of the
messages archrock writes (:data:`_FORMS`, first match wins).
"""

from __future__ import annotations

__all__ = ["LeftOut", "REASONS", "count_reasons"]

#: Why an arch of a study has no response, in report order (the keys of every summary's counts).
REASONS = {
    "invalid_draw": "invalid draw (not a valid arch, e.g. neighbouring voussoirs do not overlap)",
    "cannot_stand": "cannot stand under its own weight (k <= 0)",
    "no_mechanism": "no four-hinge mechanism (sliding or crushing governs)",
    "lift_off": "a joint lifts off before any four-hinge mechanism opens (four-link model does "
                "not hold)",
    "four_link_not_applicable": "four-link model not applicable (degenerate mechanism)",
    "impact_not_applicable": "impact model not applicable (it would create energy, or singular)",
    "other": "other",
}

# The forms of the messages archrock words when it refuses an arch (dynamics.batch, the errors
# of UNUSABLE_ARCH, studies.ensemble on moved supports), in the order they are tried:
# (reason, how, words): "prefix" the message starts with one of the words, "word" with one of
# them as a whole word, "contains" it holds one.  A least-loss chain failure is an impact-model
# failure; a valid draw that cannot stand on the study's moved supports is "cannot stand"
# although the batch path words it as a geometry.
_FORMS = (
    ("impact_not_applicable", "prefix", ("least-loss chain:",)),
    ("impact_not_applicable", "word", ("impact",)),
    ("cannot_stand", "contains", ("cannot stand on its moved supports",)),
    ("invalid_draw", "prefix", ("geometry:",)),
    ("invalid_draw", "contains", ("not a valid arch",)),
    ("cannot_stand", "contains", ("cannot stand", "does not stand")),
    ("lift_off", "contains", ("lift-off", "lifts off", "is governed by a")),
    ("no_mechanism", "contains", ("four-hinge mechanism",)),
    ("four_link_not_applicable", "prefix", ("four-link model:", "mechanism ")),
)


class LeftOut(str):
    """Why one arch was left out: the message (``detail``, this string itself) and its
    ``reason`` (a key of :data:`REASONS`).  Immutable; equal to the plain string of its message
    (so a list of reasons compares, prints and serialises as before), and pickles with its
    reason (process pools, Dask)."""

    def __new__(cls, reason: str, detail: str):
        if reason not in REASONS:
            from .errors import ArchInputError

            raise ArchInputError(f"left-out reason: {reason!r}; allowed {', '.join(REASONS)}")
        if not isinstance(detail, str) or not detail:
            from .errors import ArchInputError

            raise ArchInputError(f"left-out detail: {detail!r}; allowed the message, a "
                                 f"non-empty string")
        self = super().__new__(cls, detail)
        object.__setattr__(self, "reason", reason)  # frozen as a frozen dataclass is
        return self

    def __setattr__(self, name, value):
        raise AttributeError(f"LeftOut is immutable: cannot set {name!r}")

    def __delattr__(self, name):
        raise AttributeError(f"LeftOut is immutable: cannot delete {name!r}")

    @property
    def detail(self) -> str:
        return str.__str__(self)

    def __str__(self) -> str:
        return str.__str__(self)

    def __repr__(self) -> str:
        return f"LeftOut({self.reason!r}, {self.detail!r})"

    def __reduce__(self):
        return (LeftOut, (self.reason, self.detail))

    # ------------------------------------------------------------------ constructors
    @classmethod
    def read(cls, text) -> "LeftOut":
        """The LeftOut of a message: itself when it is one; else its reason by the forms of the
        messages archrock writes (:data:`_FORMS`; "other" when none fits)."""
        if isinstance(text, LeftOut):
            return text
        text = str(text)
        for reason, how, words in _FORMS:
            if how == "prefix" and text.startswith(words):
                return cls(reason, text)
            if how == "word" and any(text.startswith(w) and not _word_char(text[len(w):len(w) + 1])
                                     for w in words):
                return cls(reason, text)
            if how == "contains" and any(w in text for w in words):
                return cls(reason, text)
        return cls("other", text or "other")

    @classmethod
    def of(cls, exc: BaseException) -> "LeftOut":
        """The LeftOut of the exception an arch was refused with (its message, as the studies
        listed it before)."""
        return cls.read(str(exc))

    # ------------------------------------------------------------------ summaries
    @property
    def group(self) -> str:
        """The message without its figures and parenthesis: arches left out for the same reason
        and the same words share it (the keys of an ensemble summary's ``failed.reasons``)."""
        import re

        return re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "#", self.detail.split(" (")[0])


def _word_char(c: str) -> bool:
    """Whether ``c`` (one character, or '' at the end) continues a word."""
    return c.isalnum() or c == "_"


def count_reasons(left_out) -> dict:
    """{reason: count} over LeftOut values (or messages, read by :meth:`LeftOut.read`), every
    reason of :data:`REASONS` present, in report order."""
    counts = dict.fromkeys(REASONS, 0)
    for r in left_out:
        counts[LeftOut.read(r).reason] += 1
    return counts

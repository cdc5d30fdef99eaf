"""``--friction MU|none``: the one friction coefficient of a command, stated once.

MU (finite, > 0) is the joints' Coulomb coefficient; ``none`` excludes sliding (Heyman's
hypothesis, stated as such); left out, the package's DEFAULT_FRICTION, said to be the default.
"""

from __future__ import annotations

import argparse

from ._parser import positive_float

__all__ = ["NOT_GIVEN", "friction_or_none", "add_friction_option", "resolve_friction"]

#: The value of ``args.friction`` when the flag was not given (argparse does not convert a
#: default that is not a string).
NOT_GIVEN = object()


def friction_or_none(text: str):
    """argparse type: 'none' (None: sliding excluded) or a finite number > 0."""
    if text.strip().lower() == "none":
        return None
    try:
        return positive_float(text)
    except argparse.ArgumentTypeError as exc:
        raise argparse.ArgumentTypeError(f"{exc}; or 'none' (sliding excluded)") from None


def add_friction_option(p, what: str) -> None:
    """Add ``--friction MU|none`` to parser ``p``; ``what``: what the coefficient is used by."""
    from ..statics.friction import DEFAULT_FRICTION

    p.add_argument("--friction", type=friction_or_none, default=NOT_GIVEN, metavar="MU|none",
                   help=f"Coulomb friction coefficient of every joint (finite, > 0), used by "
                        f"{what}; 'none': sliding excluded (Heyman's hypothesis); default "
                        f"{DEFAULT_FRICTION:g} (archrock's one default)")


def resolve_friction(value) -> tuple[float | None, str]:
    """(mu or None, how it is stated) of ``args.friction``."""
    from ..statics.friction import DEFAULT_FRICTION

    if value is NOT_GIVEN:
        return DEFAULT_FRICTION, f"mu = {DEFAULT_FRICTION:g} (the default; --friction MU|none)"
    if value is None:
        return None, "none: sliding excluded by the user (Heyman's hypothesis)"
    return float(value), f"mu = {value:g} (--friction)"

"""The report's content blocks (paragraphs, tables, figures), its sections' record and the
works it cites: plain data that :mod:`archrock.reports.html` renders."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["Paragraph", "Table", "Figure", "Section", "titled", "REFERENCES"]

#: The paper and the works the report cites (in the order of first use in docs/method.md).
REFERENCES = {
    "paper": "Effect of geometric irregularities on the dynamic response of masonry arches "
             "(EURODYN 2017): the method this package implements (docs/method.md).",
    "heyman": "J. Heyman, The stone skeleton, Int. J. Solids Struct. 2 (1966) 249-279: "
              "no tensile strength, unlimited compressive strength, no sliding.",
    "oppenheim": "I. J. Oppenheim, The masonry arch as a four-link mechanism under base motion, "
                 "Earthquake Eng. Struct. Dyn. 21 (1992) 1005-1017.",
    "delorenzis": "L. De Lorenzis, M. DeJong, J. Ochsendorf, Failure of masonry arches under "
                  "impulse base motion, Earthquake Eng. Struct. Dyn. 36 (2007) 2119-2136.",
    "bisegna": "P. Bisegna, S. Coccia, M. Como et al. (2023): the post-impact mechanism that "
               "keeps the most energy (least-loss law, docs/method.md).",
    "ntc": "NTC 2018: D.M. 17 gennaio 2018, Norme tecniche per le costruzioni, par. 3.2.3 "
           "(spectra) and 8.7.1 (existing masonry, local mechanisms).",
    "circolare": "Circolare 21 gennaio 2019 n. 7 C.S.LL.PP., C8.7.1.2 (kinematic analysis of "
                 "local mechanisms), C8.5.4 (confidence factors).",
    "ec8": "EN 1998-1:2004 par. 3.2.2.2 (elastic spectrum); EN 1998-3:2005 (assessment of "
           "existing buildings; its Annex C, masonry, gives no kinematic procedure for local "
           "mechanisms: docs/codecheck.md).",
    "baker": "J. W. Baker, Efficient analytical fragility function fitting using dynamic "
             "structural analysis, Earthquake Spectra 31 (2015) 579-599.",
    "drucker": "D. C. Drucker, Coulomb friction, plasticity, and limit loads, J. Appl. Mech. 21 "
               "(1954) 71-74; G. Radenkovic (1961): with non-associative friction the "
               "associative limit load is not a lower bound (the governing answer, "
               "docs/assess.md).",
    "ec6": "EN 1996-1-1:2005 (Eurocode 6) par. 3.6.2, eq. (3.5): f_vk = f_vk0 + 0.4 sigma_d, "
           "the characteristic shear strength of masonry, whose coefficient 0.4 on the normal "
           "stress is a design friction coefficient of masonry joints (--friction 0.4 for a "
           "conservative check).",
}

#: The friction coefficient the report takes for masonry joints, and where it comes from: where
#: the multiplier k needs more friction than this, the summary says so beside k and gives the

# ---------------------------------------------------------------------------- content blocks
@dataclass(frozen=True)
class Paragraph:
    """A paragraph of plain text (escaped when rendered)."""

    text: str


@dataclass(frozen=True)
class Table:
    """A table: header cells and rows of cells (strings or numbers, rendered as given)."""

    header: tuple
    rows: tuple
    caption: str = ""


@dataclass(frozen=True)
class Figure:
    """A figure to draw: ``kind`` names a function of ``reports.html.FIGURES``, which draws
    ``payload`` (the section's own objects, not serialised)."""

    kind: str
    caption: str
    payload: object = field(default=None, repr=False, compare=False)


@dataclass(frozen=True)
class Section:
    """One section of the report: key (an identifier, the JSON key), title, blocks, data (the
    numbers behind it, JSON-ready), headline (label, value text) pairs for the summary table,
    and seconds, the time it took."""

    key: str
    title: str
    blocks: tuple = ()
    data: dict = field(default_factory=dict)
    headline: tuple = ()
    seconds: float = 0.0


def titled(key: str, title: str):
    """Decorator naming a section function's key and title (used when it cannot be computed)."""
    def mark(func):
        func.key, func.title = key, title
        return func
    return mark


def _f(x, spec=".4f") -> str:
    if x is None:
        return "-"
    if isinstance(x, float) and not math.isfinite(x):
        return "no collapse in the scan"
    return format(x, spec)


def _optional_missing(key: str, title: str, module: str, what: str) -> Section:
    return Section(key, title, (Paragraph(
        f"{what}: not available in this installation (the module archrock.{module} does not "
        f"import)."),), {"available": False, "module": f"archrock.{module}"})

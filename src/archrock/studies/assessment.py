"""An assessment of one arch: every answer of archrock about it, in one ordered report.

The report is an ordered list of *sections* (:data:`SECTIONS`).  A section is a function
``section(context) -> Section | None``: it computes what it needs (the context caches the
limit analysis and the prepared dynamic model, shared by all), and returns a :class:`Section`
with a title, its content as *blocks* (paragraphs, tables, figures) and ``data``, the numbers
behind it, which go to the report's JSON.  ``None`` leaves the section out.  Blocks are plain
data at this layer; :mod:`archrock.reports.html` (layer 7) renders them, and draws each
:class:`Figure` with the figure function its ``kind`` names (``reports.html.FIGURES``).

Adding a section: write one function (in assessment_statics.py, assessment_dynamics.py or
assessment_timehistory.py, by what it computes) and add it to :data:`SECTIONS`; a new kind of figure
also needs one function in ``reports.html.FIGURES``.  Sections that use an optional part of the
package (:func:`section_defects`, :func:`section_friction`, :func:`section_contact`) import it
inside, and say "not available in this installation" when it does not import.

Nothing here draws or writes files: :func:`assess` returns an :class:`Assessment` (sections,
config, timings); ``reports.html`` turns it into one self-contained HTML file and its JSON.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

from .runner import RunSettings
from ..errors import ArchInputError, ArchrockError
from ..geometry import VoussoirArch
# the sections live in their modules by layer of the answer; their names stay importable here
from .assessment_blocks import (REFERENCES, Figure, Paragraph, Section, Table,  # noqa: F401
                                _f, _optional_missing, titled)  # noqa: F401
from .assessment_statics import (arch_extent, friction_caveat,  # noqa: F401
                                 friction_note, section_friction, section_geometry,  # noqa: F401
                                 section_governing, section_limit, section_piers,
                                 section_supports)
from .assessment_context import AssessConfig, Context  # noqa: F401
from .assessment_dynamics import (section_assumptions, section_codecheck,  # noqa: F401
                                  section_contact, section_curves, section_defects,
                                  section_fragility, section_impact, section_response)
from .assessment_timehistory import section_timehistory  # noqa: F401
from .assessment_crushing import section_crushing  # noqa: F401

__all__ = ["AssessConfig", "Section", "Paragraph", "Table", "Figure", "Context", "Assessment",
           "SECTIONS", "assess", "REFERENCES", "arch_extent"]


SECTIONS: list[Callable[[Context], Section | None]] = [
    section_geometry,
    section_governing,  # the decision: which capacity and which dynamic model govern
    section_limit,
    section_crushing,  # left out where f_c is infinite (docs/crushing-dynamics.md)
    section_piers,  # left out on rigid ground (docs/piers.md)
    section_supports,  # left out on fixed supports (docs/supports.md)
    section_friction, section_impact, section_response,
    section_curves, section_defects, section_fragility, section_contact, section_codecheck,
    section_timehistory,  # beside the code check: its verdict and the check's, side by side
    section_assumptions,
]


@dataclass(frozen=True)
class Assessment:
    """The result of :func:`assess`: the arch, the configuration, the sections in order and the
    total time [s]."""

    arch: VoussoirArch = field(repr=False)
    config: AssessConfig
    sections: tuple
    seconds: float
    version: str = ""

    def section(self, key: str) -> Section:
        return {s.key: s for s in self.sections}[key]

    @property
    def headline(self) -> list:
        """The summary's (label, value) pairs: the governing answer first, then each section's
        in the report's order."""
        first = [s for s in self.sections if s.key == "governing"]
        rest = [s for s in self.sections if s.key != "governing"]
        return [h for s in first + rest for h in s.headline]

    @property
    def governing(self) -> dict | None:
        """The decision record (studies.governing, with the dynamics choice), or None where
        the governing section did not run."""
        sec = {s.key: s for s in self.sections}.get("governing")
        return None if sec is None else sec.data

    @property
    def verdict(self) -> dict:
        """{"status": "pass" | "fail" | "none", "text": the verdict in words}: the governing
        capacity (section Governing answer), then the verification against the site spectrum:
        the time history where it ran on records that meet the codes' selection rules (the
        refined analysis governs), else the code's kinematic check (both mechanisms, every
        check), with the caveat where the code check's no-sliding multiplier is not the
        governing one; "none" with the reason where there is no spectrum or no code check."""
        secs = {s.key: s for s in self.sections}
        cc = secs.get("codecheck")
        caveat = ""
        gov = (self.governing or {}).get("governing")
        lim = secs.get("limit")
        fr = (lim.data.get("friction") or {}).get("caveat") if lim is not None else None
        if gov is not None:
            caveat = (f" Governing capacity: k = {gov['value']:.6f} g ({gov['analysis']}, "
                      f"{'both directions' if gov['direction'] == 'both' else 'M_' + gov['direction']}).")
            if not gov["analysis"].startswith("limit analysis (no sliding)"):
                caveat += (" The code check takes the no-sliding multiplier, which does not "
                           "govern here: " + (fr or gov["why"]) + ".")
        elif fr:
            caveat = (f" This is on Heyman's no-sliding hypothesis: {fr} (section Friction the "
                      f"thrust needs).")
        if cc is None:
            return {"status": "none", "text": "No verdict: the code check was not part of this "
                                              "report."}
        if "error" in cc.data:
            return {"status": "none", "text": f"No verdict: the code check could not be "
                                              f"computed ({cc.data['error']})."}
        passed = cc.data.get("passed")
        if passed is None:
            return {"status": "none", "text": (
                "No verdict: no site spectrum was given (--spectrum FILE, or --ag --f0 --tc-star "
                "--soil, or --ec8-type), so there is no demand to compare the capacity with; the "
                "report gives the arch's capacity (k, a_0*, d_u*) only." + caveat)}
        th = secs.get("timehistory")
        if th is not None and th.data.get("governs"):
            return _timehistory_verdict(th.data, passed, caveat)
        word = "passes" if passed else "FAILS"
        return {"status": "pass" if passed else "fail", "text": (
            f"The arch {word} the kinematic check of NTC 2018 / Circolare 2019 (both mechanisms, "
            f"linear and nonlinear checks) for the given site spectrum." + caveat
            + _timehistory_sentence(th))}

    def to_dict(self) -> dict:
        return {"arch": self.arch.name, "archrock_version": self.version,
                "config": self.config.to_dict(), "seconds": self.seconds,
                "verdict": self.verdict, "governing": self.governing,
                "headline": [list(h) for h in self.headline],
                "sections": {s.key: {"title": s.title, "seconds": s.seconds, "data": s.data}
                             for s in self.sections}}


def _effect_words(rule: dict) -> str:
    e = "unbounded (a record collapses the arch)" if rule["unbounded"] else f"{rule['value']:.3g}"
    return f"{rule['n']} records scaled to the spectrum, {rule['rule']} of the effects E = {e}"


def _timehistory_verdict(data: dict, kinematic_passed: bool, caveat: str) -> dict:
    """The report's verdict where the time history governs (its records meet the codes'
    selection rules): its verdict, with the simplified kinematic check named as such."""
    rule = data["rule"]
    word = "passes" if rule["passed"] else "FAILS"
    same = bool(kinematic_passed) == bool(rule["passed"])
    kin = ("the simplified kinematic check (section Code check) agrees" if same else
           f"the simplified kinematic check (section Code check), which does not govern, "
           f"{'passes' if kinematic_passed else 'fails'}: it replaces the rocking arch by an "
           f"elastic oscillator (section Time-history verification)")
    return {"status": "pass" if rule["passed"] else "fail", "text": (
        f"The arch {word} the time-history verification of NTC 2018 par. 7.3.5 / EN 1998-1 "
        f"par. 4.3.3.4.3 for the given site spectrum ({_effect_words(rule)}; E <= 1 passes), "
        f"which governs: its records meet the codes' selection rules; {kin}." + caveat)}


def _timehistory_sentence(sec) -> str:
    """Where the time history does not govern (its records break a selection rule), its
    verdict as one more sentence after the kinematic check's, said not to govern; "" where it
    did not run."""
    if sec is None or "rule" not in sec.data:
        return ""
    rule = sec.data["rule"]
    return (f" The time history ({_effect_words(rule)}) "
            f"{'passes' if rule['passed'] else 'fails'}, on records that break a selection "
            f"rule: it does not govern (section Time-history verification).")


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("archrock")
    except Exception:
        return "unknown"


def assess(arch: VoussoirArch, config: AssessConfig | None = None, *,
           sections=None, settings=None) -> Assessment:
    """Run every section of :data:`SECTIONS` (or ``sections``) on ``arch``; the ``progress``
    of ``settings`` (a :class:`~archrock.studies.runner.RunSettings` or its dict) receives one
    line per section as it starts and ends."""
    progress = RunSettings.from_dict(settings).only("assess").sink
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    funcs = SECTIONS if sections is None else sections
    ctx = Context(arch, AssessConfig() if config is None else config,
                  progress or (lambda msg: None),
                  engine=any(getattr(f, "key", "") == "contact" for f in funcs))
    ctx.records  # read (and check) the records before any long computation
    out = []
    t_all = time.perf_counter()
    for k, func in enumerate(SECTIONS if sections is None else sections, 1):
        name = func.__name__.removeprefix("section_")
        ctx.progress(f"[{k}/{len(SECTIONS if sections is None else sections)}] {name} ...")
        t0 = time.perf_counter()
        try:
            sec = func(ctx)
        except Exception as exc:  # noqa: BLE001 - one section lost, never the whole report
            # an outcome (an impact law that cannot apply, a ramp whose range the arch does not
            # move in, ...) or anything else: the section says why and the report goes on.  The
            # user's input (arch, configuration, records) is checked before this loop.
            key = getattr(func, "key", name)
            msg = " ".join(str(exc).split()) or type(exc).__name__
            if not isinstance(exc, ArchrockError):
                msg = f"internal error ({type(exc).__name__}): {msg}"
            sec = Section(key, getattr(func, "title", name), (Paragraph(
                f"Not computed: {msg}"),), {"error": msg, "error_type": type(exc).__name__})
            ctx.progress(f"      {name}: not computed ({type(exc).__name__})")
        dt = time.perf_counter() - t0
        if sec is None:
            ctx.progress(f"      {name}: left out")
            continue
        out.append(Section(sec.key, sec.title, sec.blocks, sec.data, sec.headline, round(dt, 3)))
        ctx.progress(f"      {name}: {dt:.1f} s")
    return Assessment(arch, ctx.config, tuple(out), round(time.perf_counter() - t_all, 3),
                      _version())

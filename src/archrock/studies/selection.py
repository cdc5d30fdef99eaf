"""Records for a site: the selection of :mod:`archrock.groundmotion.selection` with the site's
elastic spectrum (:class:`archrock.studies.codecheck.SiteSpectrum`: NTC 2018, EN 1998-1 or a
table) as the target and its PGA, a_g S, as the least mean PGA of the scaled set.

The target is Se itself at the periods where the rules are checked: the selection's log grid over
the period range and the spectrum's corners (T_B, T_C, T_D, a table's rows) inside it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..errors import ArchInputError
from ..groundmotion.selection import (CODE_MIN_RECORDS, GRID_POINTS, RecordSelection,
                                      check_settings, select_records)
from .codecheck import SiteSpectrum

__all__ = ["SelectionConfig", "select_for_site", "scaled_motions", "spectrum_description",
           "site_target"]

@dataclass(frozen=True)
class SelectionConfig:
    """What a selection asks (:func:`archrock.groundmotion.selection.select_records`): ``count``
    records (the codes: >= 7), ``period_range`` [s] where the mean spectrum must reach
    ``lower`` x the target (NTC 2018: 0.15-2.0 s, 90%), ``scale_bounds`` of every factor,
    ``one_per_station``: at most one component of a FEMA P695 record."""

    count: int = CODE_MIN_RECORDS
    period_range: tuple = (0.15, 2.0)
    lower: float = 0.90
    scale_bounds: tuple = (0.5, 4.0)
    one_per_station: bool = True

    def __post_init__(self):
        count, rng, lower, bounds = check_settings(self.count, self.period_range, self.lower,
                                                   self.scale_bounds)
        if not isinstance(self.one_per_station, bool):
            raise ArchInputError(f"one_per_station: {self.one_per_station!r}; allowed true or false")
        for name, value in (("count", count), ("period_range", rng), ("lower", lower),
                            ("scale_bounds", bounds)):
            object.__setattr__(self, name, value)

    def to_dict(self) -> dict:
        d = asdict(self)
        d["period_range"], d["scale_bounds"] = list(self.period_range), list(self.scale_bounds)
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "SelectionConfig":
        known = set(cls.__dataclass_fields__)
        extra = sorted(set(d) - known)
        if extra:
            raise ArchInputError(f"selection: unknown field {extra[0]!r}; allowed "
                                 f"{', '.join(sorted(known))}")
        d = dict(d)
        for name in ("period_range", "scale_bounds"):
            if name in d:
                d[name] = tuple(d[name])
        return cls(**d)


def spectrum_description(spectrum: SiteSpectrum) -> str:
    """One line naming the target: the code and its parameters, or the table's file."""
    if spectrum.kind == "table":
        name = f" {spectrum.source}" if spectrum.source else ""
        return (f"spectrum table{name} (T 0-{spectrum.t_max:g} s), Se(0) = "
                f"{spectrum.pga:.4g} g")
    p = spectrum.parameters
    if spectrum.kind == "ntc":
        return (f"NTC 2018 elastic spectrum, ag = {spectrum.ag:g} g, F0 = {spectrum.f0:g}, "
                f"Tc* = {spectrum.tc_star:g} s, soil {spectrum.soil}, topography "
                f"{spectrum.topography} (a_g S = {spectrum.pga:.4g} g)")
    return (f"EN 1998-1 type {spectrum.spectrum_type} elastic spectrum, ag = {spectrum.ag:g} g, "
            f"ground {spectrum.soil} (a_g S = {spectrum.pga:.4g} g, T_B/T_C/T_D = "
            f"{p['T_B']:g}/{p['T_C']:g}/{p['T_D']:g} s)")


def site_target(spectrum: SiteSpectrum, period_range) -> tuple[np.ndarray, np.ndarray]:
    """Periods [s] and Se [g] of the target over ``period_range`` (module doc), with the
    spectrum's ends 0 and t_max."""
    if not isinstance(spectrum, SiteSpectrum):
        raise ArchInputError(f"spectrum: {type(spectrum).__name__}; allowed a SiteSpectrum")
    lo, hi = period_range
    t_max = spectrum.t_max
    if hi > t_max:
        raise ArchInputError(f"period_range: ({lo:g}, {hi:g}) s; allowed lo < hi within the "
                             f"spectrum's periods 0-{t_max:g} s")
    kinks = [v for k, v in spectrum.parameters.items() if k in ("T_B", "T_C", "T_D")]
    kinks += list(spectrum.periods)  # a table's own rows
    inner = [t for t in kinks if lo < t < hi]
    periods = np.unique(np.concatenate([[0.0, t_max], np.geomspace(lo, hi, GRID_POINTS),
                                        inner]))
    return periods, np.asarray(spectrum.se(periods), float)


def select_for_site(spectrum: SiteSpectrum, motions, config: SelectionConfig | None = None,
                    names=None) -> RecordSelection:
    """``config.count`` of ``motions`` scaled for the site ``spectrum`` (module doc); the
    result's description names the spectrum."""
    cfg = SelectionConfig() if config is None else config
    if not isinstance(cfg, SelectionConfig):
        raise ArchInputError(f"config: {type(cfg).__name__}; allowed a SelectionConfig")
    periods, se = site_target(spectrum, cfg.period_range)
    return select_records(motions, periods, se, count=cfg.count,
                          period_range=cfg.period_range, lower=cfg.lower,
                          scale_bounds=cfg.scale_bounds, pga_min_g=spectrum.pga,
                          one_per_station=cfg.one_per_station, names=names,
                          description=spectrum_description(spectrum))


def scaled_motions(selection: RecordSelection, motions) -> tuple:
    """The chosen records of ``motions`` (the list the selection was made from), each scaled by
    its factor: ``motions[i].scaled(f)`` in the selection's order."""
    if not isinstance(selection, RecordSelection):
        raise ArchInputError(f"selection: {type(selection).__name__}; allowed a "
                             f"RecordSelection")
    motions = list(motions)
    if selection.indices and max(selection.indices) >= len(motions):
        raise ArchInputError(f"motions: {len(motions)} records; allowed the list the selection "
                             f"was made from (index {max(selection.indices)} chosen)")
    return tuple(motions[i].scaled(float(f)) for i, f in zip(selection.indices,
                                                              selection.factors))

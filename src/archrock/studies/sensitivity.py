"""Global sensitivity of the Monte Carlo: which irregularity drives the spread of k_l, k_r and of
the collapse, by Sobol indices (SALib, the optional extra ``sensitivity``).

A random arch of a study is a function of its uniform draws alone (:mod:`archrock.geometry.sampling`):
for each voussoir i, U_span,i, U_thickness,i and U_radius,i on [-1, 1] (and, for a family arch
with a joint tilt, U_tilt,j for each interior joint j = 1..n-1), mapped to the arch by
:func:`archrock.geometry.perturb_voussoirs` (circular) or
:func:`archrock.geometry.irregular.perturb_family` (any family), with the spreads of
:class:`~archrock.geometry.sampling.Spreads`.  :func:`input_layout` names these inputs and
:func:`arches_from_inputs` is the map from an input matrix to arches: the same map the
ensemble's sampler uses, so the variance decomposed here is the ensemble's.

Saltelli's scheme (Saltelli 2002; Saltelli et al. 2010) on a scrambled Sobol sequence
(``SALib.sample.sobol``, no second-order terms) gives N (G + 2) arches for N base samples and G
groups of inputs; they run through the batch engine (:func:`archrock.dynamics.batch.prepare_batch`,
:func:`archrock.dynamics.batch.simulate_batch`); ``SALib.analyze.sobol`` estimates the first-order index
S1 (the share of the output's variance explained by the group alone) and the total index ST
(with all its interactions), with bootstrap confidence intervals.  Groups: ``kind`` (span,
thickness, radius, tilt), ``voussoir`` (the three draws of each voussoir; each tilted joint its
own group) or ``input`` (every draw alone).

On moved supports (a nominal of :func:`archrock.statics.supports.on_moved_supports`, e.g.
``--spread``), the arches are drawn around the base arch and one more input, ``support`` on
[-1, 1], sets the fraction (x + 1) / 2 of the movement each arch takes (docs/supports.md).

Outputs: k_l, k_r, k = min(k_l, k_r) [g] and, with a ground motion (default: the paper's
pulse, a = -1 g, t_p = 0.2 s), the collapse indicator (1 collapsed, 0 not), whose mean is the
collapse probability.  An arch that cannot stand counts as k = 0 and collapsed (Sobol indices
need every run; their number is reported).  sum(S1) is the share of the variance that the
groups explain one at a time (1 - sum(S1): interactions); it is compared with the R^2 of a
linear regression of the output on all the inputs (the variance a linear model explains).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, InvalidSampleError
from ..geometry import Arch, FamilyArch, VoussoirArch, perturb_voussoirs
from ..groundmotion import PulseSpec
from ..geometry.sampling import DEFAULT_SPREADS, Spreads
from .runner import RunSettings

__all__ = ["SobolResult", "sobol_indices", "input_layout", "arches_from_inputs", "GROUPINGS",
           "PAPER_PULSE", "check_sensitivity_work"]

GROUPINGS = ("kind", "voussoir", "input")
#: The paper's pulse: Oppenheim's, a = -1 g, t_p = 0.2 s.
PAPER_PULSE = PulseSpec("oppenheim", -1.0, 0.2)
#: arches prepared and integrated at a time (a progress line after each chunk)
_CHUNK = 4096
#: Work model of a study (module :mod:`archrock.studies.work`), measured on the 2-core development
#: machine: one random circular arch prepared (built and its limit analysis: 1280 in 0.13 s) ...
SAMPLE_ARCH_S = 1e-4
#: ... one random family arch (perturb_family and the polygon's analysis, pure Python: 320 in
#: 5.4 s) ...
SAMPLE_FAMILY_S = 2e-2
#: ... and SALib's bootstrap: seconds per base sample x group x resample x output (1280 arches,
#: 3 groups, 200 resamples, 4 outputs: 0.6 s).
ANALYSE_S = 1e-6
#: SALib's bootstrap holds about six (N, resamples) arrays of 8 bytes at once; above this many
#: bytes the study is refused (memory, not time): 2**17 base samples with 200 resamples.
MAX_BOOTSTRAP_BYTES = 2.0e9
_BOOTSTRAP_ARRAYS = 6
#: Below this relative spread (std / |mean|) an output is constant up to rounding: its indices
#: are not defined (reported as n/a, never computed from the rounding noise).
_CONSTANT_RTOL = 1e-12


def _salib():
    try:
        from SALib.analyze import sobol as analyze
        from SALib.sample import sobol as sample
    except ImportError:
        raise ImportError("SALib is required for Sobol indices: pip install "
                          "'archrock[sensitivity]'") from None
    return sample, analyze


def _check_nominal(nominal, spreads: Spreads):
    if isinstance(nominal, Arch):
        if spreads.tilt:
            raise ArchInputError("spread tilt: the circular Arch has radial joints only; give the "
                                 "nominal as family_arch('circular', ..., exact=False) to tilt them")
        return
    if not isinstance(nominal, FamilyArch) or nominal.recipe is None:
        raise ArchInputError(f"nominal: a {type(nominal).__name__} without a family cannot be "
                             f"perturbed; allowed a circular Arch or an arch of family_arch")


def input_layout(nominal: VoussoirArch, spreads: Spreads | dict | None = None):
    """The inputs of the map from draws to arches: a list of (name, kind, index, row, column)
    (row, column: where the draw sits in a sample's (rows, n) uniforms); kinds span, thickness,
    radius (index: the voussoir) and, with a tilt spread, tilt (index: the interior joint); with
    a strength spread (``spreads.fc``, a nominal of finite f_c) one more, ``fc`` (row -1: not a
    voussoir's draw; the arch's f_c is the nominal's times 1 + x s_fc)."""
    spreads = Spreads.from_dict(spreads)
    _check_nominal(nominal, spreads)
    n = nominal.n
    out = []
    for row, kind in enumerate(("span", "thickness", "radius")):
        out += [(f"{kind}_{i}", kind, i, row, i) for i in range(n)]
    if spreads.tilt:
        out += [(f"tilt_{j}", "tilt", j, 3, j - 1) for j in range(1, n)]
    if spreads.fc:
        if getattr(nominal, "fc", None) is None:
            raise ArchInputError(f"spread fc: {spreads.fc:g} for {nominal.name!r}, whose "
                                 f"compressive strength is infinite; allowed 0 (a strength "
                                 f"spread needs a nominal f_c: --fc MPA)")
        out.append(("fc", "fc", 0, -1, -1))
    return out


def _uniforms(layout, x: np.ndarray, n: int) -> np.ndarray:
    rows = 4 if any(r == 3 for _, _, _, r, _ in layout) else 3
    u = np.zeros((x.shape[0], rows, n))
    for k, (_, _, _, r, c) in enumerate(layout):
        if r >= 0:  # the strength's input is no voussoir draw
            u[:, r, c] = x[:, k]
    return u


def arches_from_inputs(nominal: VoussoirArch, spreads: Spreads | dict | None, x):
    """The arches of input rows ``x`` (B, D) on [-1, 1] (:func:`input_layout`'s order): for a
    circular nominal the arrays (spans [rad], thicknesses [m], radii [m]), each (B, n); for a
    family, or a nominal of finite strength, a list of B arches (an :class:`InvalidSampleError`
    where a row is no valid arch), each with its f_c."""
    spreads = Spreads.from_dict(spreads)
    layout = input_layout(nominal, spreads)
    x = np.asarray(x, float)
    if x.ndim != 2 or x.shape[1] != len(layout):
        raise ArchInputError(f"x: shape {x.shape}; allowed (B, {len(layout)})")
    if np.any(np.abs(x) > 1.0):
        raise ArchInputError("x: every input must be in [-1, 1]")
    u = _uniforms(layout, x, nominal.n)
    fc = getattr(nominal, "fc", None)
    if isinstance(nominal, Arch):
        drawn = perturb_voussoirs(nominal.spans, nominal.thicknesses, nominal.radii, u,
                                  spreads.span, spreads.thickness, spreads.radius)
        if fc is None:
            return drawn
        out = _circular_arches(nominal, *drawn)
    else:
        from ..geometry.irregular import perturb_family

        out = []
        for b in range(len(u)):
            try:
                out.append(perturb_family(nominal, u[b], spreads.span, spreads.thickness,
                                          spreads.radius, spreads.tilt, name=f"run {b}"))
            except ArchInputError as exc:
                out.append(InvalidSampleError(f"not a valid arch: {exc}"))
    if fc is None:
        return out
    # each arch's strength: the nominal's, times 1 + x s_fc with the fc input (when spread)
    col = [k for k, lay in enumerate(layout) if lay[1] == "fc"]
    scale = 1.0 + spreads.fc * x[:, col[0]] if col else np.ones(len(x))
    return [a if isinstance(a, Exception) else a.with_fc(float(fc) * float(f))
            for a, f in zip(out, scale)]


def _circular_arches(nominal, spans, thick, radii) -> list:
    """The circular arches of drawn arrays (B, n), an InvalidSampleError where a row is none."""
    out = []
    for b in range(len(spans)):
        try:
            out.append(Arch(spans[b], radii[b], thick[b], nominal.density, name=f"run {b}"))
        except ArchInputError as exc:
            out.append(InvalidSampleError(f"not a valid arch: {exc}"))
    return out


@dataclass(frozen=True)
class SobolResult:
    """Result of :func:`sobol_indices`.

    outputs: names of the outputs (rows of the index arrays); groups: names of the input
    groups (columns); S1, S1_conf, ST, ST_conf (outputs, groups): first-order and total Sobol
    indices and the half-widths of their ``conf_level`` bootstrap intervals; mean, variance
    (outputs,): of each output over the runs; r2_linear (outputs,): the R^2 of a linear
    regression on every input; samples: N base samples; runs: N (G + 2) arches; unusable: the
    runs whose arch could not stand or was no valid arch (counted k = 0, collapsed).
    """

    nominal: str
    spreads: Spreads
    by: str
    outputs: tuple
    groups: tuple
    S1: np.ndarray
    S1_conf: np.ndarray
    ST: np.ndarray
    ST_conf: np.ndarray
    mean: np.ndarray
    variance: np.ndarray
    r2_linear: np.ndarray
    samples: int
    runs: int
    unusable: int
    seed: int
    conf_level: float
    motion: dict | None = None
    impact: dict | None = None
    seconds: dict = field(default_factory=dict)
    method: str = ""
    #: the support movement (its dict) whose fraction is the input 'support'; None: fixed
    support: dict | None = None

    def __post_init__(self):
        readonly_arrays(self)

    def index(self, output: str, group: str, which: str = "S1") -> float:
        """One index, e.g. ``index('k_l', 'thickness', 'ST')``."""
        if output not in self.outputs or group not in self.groups or which not in (
                "S1", "ST", "S1_conf", "ST_conf"):
            raise ArchInputError(f"index: ({output!r}, {group!r}, {which!r}); allowed outputs "
                                 f"{self.outputs}, groups {self.groups}, S1/ST/S1_conf/ST_conf")
        return float(getattr(self, which)[self.outputs.index(output), self.groups.index(group)])

    @property
    def sum_S1(self) -> np.ndarray:
        return self.S1.sum(axis=1)

    @property
    def sum_ST(self) -> np.ndarray:
        return self.ST.sum(axis=1)

    def to_dict(self) -> dict:
        per = {}
        for o, out in enumerate(self.outputs):
            per[out] = {
                "mean": float(self.mean[o]), "variance": float(self.variance[o]),
                "std": float(math.sqrt(self.variance[o])),
                "sum_S1": float(self.sum_S1[o]), "sum_ST": float(self.sum_ST[o]),
                "r2_linear": float(self.r2_linear[o]),
                "groups": {g: {"S1": float(self.S1[o, k]), "S1_conf": float(self.S1_conf[o, k]),
                               "ST": float(self.ST[o, k]), "ST_conf": float(self.ST_conf[o, k])}
                           for k, g in enumerate(self.groups)},
            }
        return {"nominal": self.nominal, "spreads": self.spreads.to_dict(), "by": self.by,
                "samples": self.samples, "runs": self.runs, "unusable": self.unusable,
                "seed": self.seed, "conf_level": self.conf_level, "motion": self.motion,
                "impact": self.impact, "outputs": per, "seconds": self.seconds,
                "method": self.method, **({} if self.support is None else
                                          {"support": self.support})}


def _groups(layout, by: str):
    if by == "kind":
        return [kind for _, kind, _, _, _ in layout]
    if by == "voussoir":
        return [kind if kind in ("support", "fc") else f"voussoir {i}" if kind != "tilt"
                else f"joint {i}" for _, kind, i, _, _ in layout]
    return [name for name, _, _, _, _ in layout]


def _constant(y: np.ndarray) -> bool:
    """Whether ``y`` is constant up to rounding (its variance is noise, not spread)."""
    return float(np.std(y)) <= _CONSTANT_RTOL * max(float(np.max(np.abs(y))), 1e-300)


def _r2(x: np.ndarray, y: np.ndarray) -> float:
    var = float(np.var(y))
    if _constant(y):
        return math.nan
    a = np.column_stack([np.ones(len(x)), x])
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    return float(1.0 - np.var(y - a @ coef) / var)


def _moved_arches(base, spreads, movement, x) -> list:
    """The arches of input rows ``x`` whose last column is the support input: the random arch
    of the other columns around ``base`` (:func:`arches_from_inputs`) on the supports moved by
    (x + 1) / 2 times ``movement``, re-closed; an InvalidSampleError where the draw is no arch
    or cannot stand on its moved supports."""
    from ..statics.supports import _moved_sample

    drawn = arches_from_inputs(base, spreads, x[:, :-1])
    if isinstance(drawn, tuple):  # a circular arch's arrays
        drawn = _circular_arches(base, *drawn)
    frac = 0.5 * (np.asarray(x, float)[:, -1] + 1.0)
    return [a if isinstance(a, Exception) else
            _moved_sample(a, movement.scaled(float(f)), raise_=False)
            for a, f in zip(drawn, frac)]


def check_sensitivity_work(nominal, samples: int, groups: int, motion, num_resamples: int = 200
                           ) -> float:
    """Estimated seconds of a Sobol study (:mod:`archrock.studies.work`): samples x (groups + 2) random
    arches, each prepared (and with ``motion`` integrated), then SALib's bootstrap.  Refuses a
    study beyond the work bound (LimitExceededError) or whose bootstrap would hold more than
    :data:`MAX_BOOTSTRAP_BYTES` (ArchInputError naming --samples); warns above a minute."""
    import os

    from .work import RECORD_RESPONSE_S_PER_S, SAMPLE_FINITE_S, SAMPLE_RESPONSE_S, check_work

    need = _BOOTSTRAP_ARRAYS * 8.0 * samples * num_resamples
    if need > MAX_BOOTSTRAP_BYTES:
        top = 16
        while _BOOTSTRAP_ARRAYS * 8.0 * (2 * top) * num_resamples <= MAX_BOOTSTRAP_BYTES:
            top *= 2
        raise ArchInputError(f"samples: {samples}; allowed a power of two from 16 to {top} (the "
                             f"bootstrap of {num_resamples} resamples would hold about "
                             f"{need / 1e9:.3g} GB)")
    runs = samples * (groups + 2)
    family = not isinstance(nominal, Arch)
    each = SAMPLE_FAMILY_S if family else SAMPLE_ARCH_S
    if getattr(nominal, "fc", None) is not None:  # the crushing statics, one arch at a time
        each += SAMPLE_FINITE_S
    if motion is not None:
        each += SAMPLE_RESPONSE_S
        if motion.to_dict()["type"] == "record":
            each += RECORD_RESPONSE_S_PER_S * motion.build().duration
    outputs = 3 + (motion is not None)
    each += ANALYSE_S * groups * num_resamples * outputs / (groups + 2)
    cores = 1 if family or getattr(nominal, "fc", None) is not None else (os.cpu_count() or 1)
    return check_work("sensitivity", runs, "arches", each,
                      "reduce --samples (1024 give the indices to a few hundredths), or group "
                      "by kind (--by kind)", cores, kernel=not family)


def sobol_indices(nominal: VoussoirArch, spreads: Spreads | dict | None = DEFAULT_SPREADS,
                  samples: int = 1024, *, by: str = "kind", motion=PAPER_PULSE, impact=None,
                  seed: int = 0, conf_level: float = 0.95, num_resamples: int = 200,
                  settings=None) -> SobolResult:
    """Sobol indices of k_l, k_r, k and (with ``motion``) the collapse indicator over the
    random arches around ``nominal`` (module docstring).

    spreads: :class:`~archrock.geometry.sampling.Spreads` (default the paper's); samples: N base samples,
    a power of two >= 16 (N (G + 2) arches run); by: 'kind', 'voussoir' or 'input'; motion: a
    PulseSpec / RecordSpec or its dict (default the paper's pulse), or None for k only; impact:
    an ImpactSpec or its name (default the paper's practice: the paper's model on the nominal
    arch, its c_v fixed on every arch); seed: of the scrambled Sobol sequence and of the
    bootstrap; conf_level: of the intervals; settings: a
    :class:`~archrock.studies.runner.RunSettings` whose ``progress`` gets one line of text per
    chunk of arches run (:mod:`archrock._progress`); it runs in this process (numba threads).
    """
    settings = RunSettings.from_dict(settings).only("sobol_indices")
    sample, analyze = _salib()
    job = _configure_sobol(nominal, spreads, samples, by, motion, impact, seed, conf_level,
                           num_resamples)
    progress = settings.sink
    t0 = time.perf_counter()
    x = sample.sample(job.problem, job.samples, calc_second_order=False, seed=job.seed)
    x = np.clip(x, -1.0, 1.0)
    if progress is not None:
        progress(f"sensitivity: {len(x)} arches ({job.samples} x ({len(job.names)} groups "
                 f"+ 2))")
    resolved = job.spec.resolved(nominal)  # the nominal's impact law, applied to every arch
    built, dt, t_free = decide_dynamics(nominal, job.motion)
    ys, ok, t_prep, t_sim = _run_arches(job, x, resolved, built, (dt, t_free), progress, t0)
    t_an = time.perf_counter()
    indices = _analyse(analyze, job, x, ys)
    return _sobol_result(job, ys, indices, int((~ok).sum()), len(x),
                         {"prepare": t_prep, "simulate": t_sim,
                          "analyse": time.perf_counter() - t_an})


@dataclass(frozen=True)
class _SobolJob:
    """The checked inputs of :func:`sobol_indices` and SALib's problem."""

    nominal: VoussoirArch
    base: VoussoirArch
    movement: object
    spreads: Spreads
    by: str
    layout: list
    names: list
    problem: dict
    samples: int
    seed: int
    conf_level: float
    num_resamples: int
    motion: object
    spec: object


def _configure_sobol(nominal, spreads, samples, by, motion, impact, seed, conf_level,
                     num_resamples) -> _SobolJob:
    """Every input checked by name, the work bound applied, SALib's problem laid out."""
    from ..groundmotion import RecordSpec, motion_spec_from_dict
    from ..dynamics.impact import ImpactSpec
    from ..statics.supports import moved_parts

    spreads = Spreads.from_dict(spreads)
    # on moved supports: the random arches are drawn around the base arch, and the movement is
    # one more input, the fraction (x + 1) / 2 of it that each arch takes (_moved_arches)
    base, movement = moved_parts(nominal)
    if not (spreads.span or spreads.thickness or spreads.radius or spreads.tilt or spreads.fc
            or movement):
        raise ArchInputError("spreads: all 0 (span, thickness, radius, tilt); allowed at least one "
                             "spread > 0 (--spread-span, --spread-thickness, --spread-radius or "
                             "--spread-tilt): with none every arch is the nominal one and there "
                             "is no variance to share out")
    layout = input_layout(base, spreads)
    if movement is not None:
        layout = layout + [("support", "support", 0, -1, -1)]
    _check_numbers(by, samples, seed, conf_level, num_resamples)
    if isinstance(motion, dict):
        motion = motion_spec_from_dict(motion)
    if motion is not None and not isinstance(motion, (PulseSpec, RecordSpec)):
        raise ArchInputError(f"motion: {motion!r}; allowed None, a PulseSpec or RecordSpec")
    spec = ImpactSpec.parse(impact)
    groups = _groups(layout, by)
    names = list(dict.fromkeys(groups))
    check_sensitivity_work(nominal, int(samples), len(names), motion, int(num_resamples))
    problem = {"num_vars": len(layout), "names": [lay[0] for lay in layout],
               "bounds": [[-1.0, 1.0]] * len(layout)}
    if by != "input":
        problem["groups"] = groups
    return _SobolJob(nominal, base, movement, spreads, by, layout, names, problem, int(samples),
                     int(seed), float(conf_level), int(num_resamples), motion, spec)


def _check_numbers(by, samples, seed, conf_level, num_resamples) -> None:
    """The grouping and the numbers of :func:`sobol_indices`, each refused by name."""
    if by not in GROUPINGS:
        raise ArchInputError(f"by: {by!r}; allowed {', '.join(GROUPINGS)}")
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 16 \
            or samples & (samples - 1):
        raise ArchInputError(f"samples: {samples!r}; allowed a power of two >= 16 (the Sobol "
                             f"sequence's balance needs it)")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ArchInputError(f"seed: {seed!r}; allowed an integer >= 0")
    if not (isinstance(conf_level, float) and 0.0 < conf_level < 1.0):
        raise ArchInputError(f"conf_level: {conf_level!r}; allowed 0 < conf_level < 1")
    if isinstance(num_resamples, bool) or not isinstance(num_resamples, (int, np.integer)) \
            or num_resamples < 2:
        raise ArchInputError(f"num_resamples: {num_resamples!r}; allowed an integer >= 2")


def decide_dynamics(nominal, motion) -> tuple:
    """(the motion built, RK4 step [s], free-motion time [s]) of the study: the four-link
    model under ``motion`` at the nominal arch's default steps; None for k only."""
    from ..dynamics.response import default_steps

    built = motion.build() if motion is not None else None
    dt, t_free = default_steps(nominal)
    return built, dt, t_free


def _run_arches(job: _SobolJob, x, resolved, built, steps, progress, t0) -> tuple:
    """({"k_l", "k_r", "k"[, "collapse"]}: the outputs of the arches of the inputs ``x``,
    usable flags, seconds preparing, seconds integrating), in chunks of :data:`_CHUNK` arches
    so that a long run says how far it got (an unusable arch: k 0, collapsed)."""
    from ..dynamics.batch import prepare_batch, simulate_batch
    from ..dynamics.kernel import ST_COLLAPSED

    nominal, runs = job.nominal, len(x)
    k_l, k_r = np.zeros(runs), np.zeros(runs)
    collapse = np.ones(runs)
    ok = np.zeros(runs, dtype=bool)
    t_prep = t_sim = 0.0
    for start in range(0, runs, _CHUNK):
        sl = slice(start, min(runs, start + _CHUNK))
        ta = time.perf_counter()
        if job.movement is not None:
            pb = prepare_batch(_moved_arches(job.base, job.spreads, job.movement, x[sl]),
                               impact=resolved)
        elif isinstance(nominal, Arch) and getattr(nominal, "fc", None) is None:
            spans, thick, radii = arches_from_inputs(nominal, job.spreads, x[sl])
            pb = prepare_batch(spans, radii, thick, nominal.density, impact=resolved)
        else:
            pb = prepare_batch(arches_from_inputs(nominal, job.spreads, x[sl]), impact=resolved)
        tb = time.perf_counter()
        ok[sl] = pb.ok
        k_l[sl] = np.where(pb.ok, pb.k_l, 0.0)
        k_r[sl] = np.where(pb.ok, pb.k_r, 0.0)
        if built is not None:
            res = simulate_batch(pb, built, dt=steps[0], t_free=steps[1])
            collapse[sl] = np.where(pb.ok, res["status"] == ST_COLLAPSED, True)
        tc = time.perf_counter()
        t_prep += tb - ta
        t_sim += tc - tb
        if progress is not None:
            progress(f"sensitivity: {sl.stop}/{runs} arches [{tc - t0:.1f} s]")
    ys = {"k_l": k_l, "k_r": k_r, "k": np.minimum(k_l, k_r)}
    if built is not None:
        ys["collapse"] = collapse
    return ys, ok, t_prep, t_sim


def _analyse(analyze, job: _SobolJob, x, ys: dict) -> tuple:
    """(S1, S1 interval, ST, ST interval, mean, var, R^2) of each output by SALib (NaN indices
    of a constant output: nothing to decompose)."""
    shape = (len(ys), len(job.names))
    s1, s1c, st, stc = (np.full(shape, np.nan) for _ in range(4))
    mean, var, r2 = (np.empty(len(ys)) for _ in range(3))
    for o, y in enumerate(ys.values()):
        mean[o], var[o] = float(np.mean(y)), float(np.var(y))
        r2[o] = _r2(x, y)
        if _constant(y):
            var[o] = 0.0  # the rest is rounding noise
            continue  # nothing to decompose: indices undefined (NaN)
        with np.errstate(divide="ignore", invalid="ignore"):
            si = analyze.analyze(job.problem, y, calc_second_order=False,
                                 conf_level=job.conf_level, num_resamples=job.num_resamples,
                                 # a Generator, not the int: SALib's `if seed:` drops seed 0 and
                                 # the bootstrap intervals then differ from run to run
                                 seed=np.random.default_rng(job.seed))
        s1[o], s1c[o], st[o], stc[o] = si["S1"], si["S1_conf"], si["ST"], si["ST_conf"]
    return s1, s1c, st, stc, mean, var, r2


def _sobol_result(job: _SobolJob, ys: dict, indices: tuple, failed: int, runs: int,
                  timing: dict) -> SobolResult:
    """The :class:`SobolResult`, with the sentence of how it was computed."""
    G = len(job.names)
    how = (f"Saltelli scheme on a scrambled Sobol sequence (SALib.sample.sobol, "
           f"calc_second_order=False), {job.samples} base samples x ({G} groups + 2) = {runs} "
           f"arches through archrock.dynamics.batch; SALib.analyze.sobol with "
           f"{job.num_resamples} bootstrap resamples, {job.conf_level:.0%} intervals")
    if job.movement is not None:
        how += (f"; the supports moved by U x ({job.movement.describe()}), U = (x + 1) / 2 the "
                f"input 'support', each arch displaced and re-closed "
                f"(statics.supports.on_moved_supports)")
    motion, spec = job.motion, job.spec
    return SobolResult(
        job.nominal.name, job.spreads, job.by, tuple(ys), tuple(job.names), *indices,
        job.samples, runs, failed, job.seed, job.conf_level,
        None if motion is None else {**motion.to_dict(), "description": motion.describe()},
        {**spec.to_dict(), "description": spec.describe()}, timing, how,
        None if job.movement is None else job.movement.to_dict())

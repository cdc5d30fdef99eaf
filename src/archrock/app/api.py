"""What the app's endpoints compute, without the web framework: JSON in, JSON-ready dicts out.

Every function here validates its request as the command line does (the same option names,
the same library checks: :func:`archrock.options.arch_from_args` builds the arch) and calls
the same library functions as the CLI (``limit``, ``respond``, ``ensemble``); nothing here is
physics.  A bad value raises :class:`~archrock.errors.ArchInputError` (or
:class:`~archrock.options.OptionError`, the CLI's ``CLIError``), whose one-line message names
the field; the server turns it into HTTP 400.

Lengths in m, angles in degrees, accelerations in g, times in s, rotations in rad.
"""

from __future__ import annotations

import argparse
import csv
import io
import math
import time

import numpy as np

from ..errors import ArchInputError
from ..options import JOINTS, SHAPES  # the command line's own lists
from .fields import (ARCH_FIELDS, COMPUTE_LOCK, MAX_VOUSSOIRS, choice, number, object_field,
                     only, request_object, xy)
from .drawing import arch_drawing, block_counts
from .fields import friction as friction_field
from .suites import record_motion
from .uploads import MAX_RECORD_T_END_S, MAX_RESPONSE_WORK_S, RecordStore, trace

#: Work bounds of one request (the CLI allows more; an interactive page should answer in
#: about a second): voussoirs of an arch (fields.MAX_VOUSSOIRS), end of a response's output window [s] and the pulse's duration [s] ...
MAX_T_END_S = 20.0
MAX_PULSE_S = 5.0
#: ... |amplitude| [g] of a pulse ...
MAX_AMPLITUDE_G = 10.0
#: ... frames of an animation ...
MAX_FRAMES = 300
#: ... arches of an ensemble, and its estimated time [s] (archrock.studies.work's costs).
MAX_SAMPLES = 20_000
MAX_ENSEMBLE_WORK_S = 120.0
#: Largest uploaded geometry (characters of JSON).
MAX_UPLOAD_CHARS = 2_000_000

PULSE_KINDS = ("oppenheim", "rectangular", "half-sine", "one-sine", "ricker")
#: The fields each request may hold (any other key is refused, naming it: fields.only).
PULSE_FIELDS = ("kind", "amplitude", "duration")
SPREAD_FIELDS = ("span", "thickness", "radius", "tilt", "fc")
LIMIT_FIELDS = ("arch", "friction", "thrust_range")
ENSEMBLE_FIELDS = ("arch", "samples", "seed", "spreads", "pulse", "friction")
CURVE_FIELDS = ("arch", "samples", "seed", "spreads", "durations", "kind", "friction")
REPORT_FIELDS = ("arch", "samples", "seed", "spreads", "contact", "friction")


# ---------------------------------------------------------------------------- field checks
def _random_arches(params: dict, default: int, lo: int, hi: int, where: str):
    """(samples, seed, spreads) of a request's random arches, checked as the CLI checks them:
    ``samples`` an integer lo..hi (``where`` ends the message), the seed an integer >= 0, the
    spreads the CLI's --spread-*."""
    from ..geometry.sampling import Spreads

    samples = number(params, "samples", default, integer=True)
    if not lo <= samples <= hi:
        raise ArchInputError(f"samples: {samples}; allowed {lo} to {hi} {where}")
    seed = number(params, "seed", 0, integer=True)
    if seed < 0:
        raise ArchInputError(f"seed: {seed}; allowed an integer >= 0")
    sp = only(object_field(params, "spreads"), SPREAD_FIELDS, "spreads")
    return samples, seed, Spreads(*(number(sp, k, d) for k, d in (
        ("span", 0.1), ("thickness", 0.1), ("radius", 0.05), ("tilt", 0.0))),
        fc=number(sp, "fc", 0.0))  # each arch's f_c spread (the CLI's --spread-fc)


# ---------------------------------------------------------------------------- the arch
def arch_from_params(params: dict):
    """The arch of ``params`` (the JSON form of the CLI's geometry options):

    ``{"geometry": {...}}`` an uploaded geometry file's JSON (either format), or
    ``{"shape", "span", "rise", "thickness", "thickness_crown", "joints", "voussoirs",
    "density"}`` an arch of a family, or ``{"radius", "embrace", ...}`` a circular arch, each
    with an optional ``"fc"`` (compressive strength [MPa], as --fc; null: infinite); with
    ``"defects": ["3:thickness=0.5", ...]`` and ``"pier_height"``/``"pier_width"``/
    ``"pier_courses"`` as the CLI's --defect and --pier-* options.  Built by the CLI's own
    :func:`~archrock.options.arch_from_args`."""
    from ..options import arch_from_args

    params = only(request_object(params), ARCH_FIELDS, "arch")
    n = number(params, "voussoirs", integer=True)
    if n is not None and n > MAX_VOUSSOIRS:
        raise ArchInputError(f"voussoirs: {n}; the app allows 3 to {MAX_VOUSSOIRS} "
                             f"(the command line up to 2000)")
    defects = params.get("defects") or []
    if not isinstance(defects, list) or not all(isinstance(d, str) for d in defects):
        raise ArchInputError("defects: expected a list of defect specifications such as "
                             "'3:thickness=0.5'")
    if len(defects) > 50:
        raise ArchInputError(f"defects: {len(defects)}; allowed at most 50")
    ns = argparse.Namespace(
        radius=number(params, "radius"), embrace=number(params, "embrace"),
        shape=choice(params, "shape", SHAPES), span=number(params, "span"),
        rise=number(params, "rise"), thickness=number(params, "thickness"),
        thickness_crown=number(params, "thickness_crown"),
        joints=choice(params, "joints", JOINTS), voussoirs=n,
        density=number(params, "density"), geometry=None, defect=defects or None,
        pier_height=number(params, "pier_height"), pier_width=number(params, "pier_width"),
        pier_courses=number(params, "pier_courses", integer=True))
    geometry = params.get("geometry")
    if geometry is not None:
        arch = _uploaded_arch(geometry, ns, params.get("name"))
    else:
        arch = arch_from_args(ns)
    fc = number(params, "fc")
    if fc is not None:  # as --fc: last, on whatever the other fields built
        arch = arch.with_fc(fc)
    if arch.n > MAX_VOUSSOIRS:
        v, p = block_counts(arch)
        field = "pier_courses" if p else "voussoirs"
        raise ArchInputError(f"{field}: {arch.n} blocks in all ({v} voussoirs, {p} pier "
                             f"courses); the app allows up to {MAX_VOUSSOIRS} blocks")
    return arch


def _uploaded_arch(data, ns, name):
    """The arch of an uploaded geometry file's parsed JSON (``archrock random-arch`` writes
    one), with the request's defects and piers; the geometry flags are refused beside it, as
    the CLI refuses them beside --geometry."""
    from ..options import piers_from_args
    from ..geometry import apply_defects, arch_from_dict

    given = [f for f in ("radius", "embrace", "shape", "span", "rise", "thickness",
                         "thickness_crown", "joints", "voussoirs", "density")
             if getattr(ns, f) is not None]
    if given:
        raise ArchInputError(f"geometry: cannot be combined with {', '.join(given)}; the file "
                             f"holds the whole geometry")
    if not isinstance(data, dict):
        raise ArchInputError("geometry: expected the JSON object of a geometry file")
    vs = data.get("voussoirs")
    if isinstance(vs, list) and len(vs) > MAX_VOUSSOIRS:
        raise ArchInputError(f"geometry: {len(vs)} blocks; the app allows up to {MAX_VOUSSOIRS} "
                             f"blocks (voussoirs and pier courses)")
    label = name if isinstance(name, str) and name.strip() else "uploaded"
    try:
        arch = arch_from_dict(data, name=label[:80])
    except ArchInputError as exc:
        raise ArchInputError(f"geometry: {exc}") from None
    except (TypeError, ValueError, KeyError) as exc:  # a malformed file the library did not name
        raise ArchInputError(f"geometry: not a geometry file ({exc})") from None
    if ns.defect:
        arch = apply_defects(arch, ns.defect)
    return piers_from_args(ns, arch)


# ---------------------------------------------------------------------------- statics
def limit(params: dict) -> dict:
    """``archrock limit --json`` of the arch of ``params["arch"]`` (with ``"friction": MU``:
    the multipliers at that friction; ``"thrust_range": true``: the least and greatest
    thrust), plus the drawing: voussoirs, both thrust lines (funicular polygons [m]) and the
    hinge points [m].  ``elapsed_ms``: the server's time."""
    from ..statics.friction import friction_analysis, friction_needed
    from ..statics.limit import limit_analysis
    from ..studies.governing import friction_with_crushing
    from ..reports.limit import limit_summary

    params = only(request_object(params), LIMIT_FIELDS)
    t0 = time.perf_counter()
    arch = arch_from_params(object_field(params, "arch"))
    mu = friction_field(params, None)
    want_thrust = bool(params.get("thrust_range", False))
    with COMPUTE_LOCK:
        result = limit_analysis(arch, verify=True)
        heyman = arch.fc is None  # Heyman's friction analyses assume no crushing
        extra = {"friction": friction_analysis(arch, mu) if mu is not None and heyman else None}
        extra["needed"] = friction_needed(arch) if mu is None and heyman else None
        # with f_c: friction and crushing in one program (the governing capacity's)
        both = None if mu is None or heyman else friction_with_crushing(arch, mu)
        if want_thrust:
            from ..statics.thrust import thrust_range

            extra["thrust"] = thrust_range(arch)
        summary = limit_summary(result, None, **extra)
    if both is not None:
        summary.update(friction_mu=mu, friction_k_l=both.k_l, friction_k_r=both.k_r,
                       sliding_governs_l=both.why["l"] == "sliding governs",
                       sliding_governs_r=both.why["r"] == "sliding governs",
                       friction_with_crushing=True)
    for key in ("geometry", "voussoirs"):
        summary.pop(key, None)  # the drawing below says it at the page's precision
    hinges = {}
    for d in ("l", "r"):
        m = result.mechanism(d)
        pts = _hinge_points(arch, result, d)
        hinges[d] = [{"label": lab, "joint": int(h.joint), "edge": h.edge,
                      "point": xy(pts[h.joint, 0 if h.edge == "intrados" else 1])}
                     for lab, h in m.labelled()]
    lines = {d: xy((result.thrust_l if d == "l" else result.thrust_r).polyline)
             for d in ("l", "r")}
    if want_thrust:
        tr = extra["thrust"]
        lines["min"], lines["max"] = xy(tr.line_min.polyline), xy(tr.line_max.polyline)
    return {"summary": summary, "drawing": arch_drawing(arch), "thrust_lines": lines,
            "hinges": hinges, "fc": arch.fc, "elapsed_ms": 1e3 * (time.perf_counter() - t0)}


def _hinge_points(arch, result, d: str) -> np.ndarray:
    """The joints' end points (n+1, 2, 2) [m] with the hinges of M_d where the statics put
    them: at the edges, or with a finite f_c half a stress block in from them."""
    from ..dynamics.finite import collapse_zones, inset_joint_points

    zones = collapse_zones(result, d)
    if zones is None:
        return np.asarray(arch.joint_points, float)
    return inset_joint_points(arch, result.mechanism(d), zones)


# ---------------------------------------------------------------------------- dynamics
def pulse_spec(params):
    """The :class:`~archrock.groundmotion.PulseSpec` of ``{"kind", "amplitude", "duration"}``
    ([g], [s]), within the app's bounds."""
    from ..groundmotion import PulseSpec

    if not isinstance(params, dict):
        raise ArchInputError("pulse: expected an object with kind, amplitude [g], duration [s]")
    only(params, PULSE_FIELDS, "pulse")
    kind = choice(params, "kind", PULSE_KINDS, "oppenheim")
    a = number(params, "amplitude")
    tp = number(params, "duration")
    if a is None or tp is None:
        raise ArchInputError("pulse: amplitude [g] and duration [s] are both needed")
    if a == 0 or abs(a) > MAX_AMPLITUDE_G:
        raise ArchInputError(f"amplitude: {a:g}; allowed 0 < |amplitude| <= {MAX_AMPLITUDE_G:g} g")
    if not 0 < tp <= MAX_PULSE_S:
        raise ArchInputError(f"duration: {tp:g}; allowed 0 < duration <= {MAX_PULSE_S:g} s")
    return PulseSpec(kind, a, tp)


#: The fields of a response request (pulse or record).
RESPOND_FIELDS = ("arch", "pulse", "record", "t_end", "exaggerate", "friction", "dynamics")


def respond_request(params: dict, records: RecordStore | None = None) -> dict:
    """The checked arguments of a response: the ``arch``, the motion (``params["pulse"]``, or
    ``params["record"]``: ``{"id"}`` of a record loaded in ``records`` by
    :func:`~archrock.app.uploads.load_record_upload`, or ``{"suite_ref", "scale"}`` of a built-in
    suite's, :mod:`.suites`), the window ``t_end`` [s],
    ``exaggerate``, ``friction`` (default :data:`~archrock.statics.friction.DEFAULT_FRICTION`,
    "none": sliding excluded) and ``choice``: the model that answers
    (:func:`archrock.app.engine.choose`: ``dynamics`` auto, fourlink or engine)."""
    from ..statics.friction import DEFAULT_FRICTION
    from . import engine

    params = only(request_object(params), RESPOND_FIELDS)
    t0 = time.perf_counter()
    arch = arch_from_params(object_field(params, "arch"))
    mu = friction_field(params, DEFAULT_FRICTION)
    record = params.get("record")
    info = spec = None
    if record is not None:
        motion, info = record_motion(record, records)
        t_end = number(params, "t_end", min(MAX_RECORD_T_END_S, info["duration_s"] + 2.0))
        if not 0 < t_end <= MAX_RECORD_T_END_S:
            raise ArchInputError(f"t_end: {t_end:g}; allowed 0 < t_end <= "
                                 f"{MAX_RECORD_T_END_S:g} s for a record")
        info = {k: v for k, v in info.items() if k != "warnings"}
    else:
        spec = pulse_spec(params.get("pulse"))
        motion = spec.build()
        t_end = number(params, "t_end", 3.0)
        if not 0 < t_end <= MAX_T_END_S:
            raise ArchInputError(f"t_end: {t_end:g}; allowed 0 < t_end <= {MAX_T_END_S:g} s")
    ex = number(params, "exaggerate", 1.0)
    if not 1 <= ex <= 50:
        raise ArchInputError(f"exaggerate: {ex:g}; allowed 1 to 50 (the drawn rotations' factor)")
    chosen = engine.choose(arch, params, mu)
    if chosen.engine:
        engine.check_engine_work(arch, motion, mu)
    elif info is not None:
        from ..studies.work import format_duration, response_cost_s
        from .._jit import HAVE_NUMBA

        est = response_cost_s(min(t_end, info["duration_s"])) * (1 if HAVE_NUMBA else 50)
        if est > MAX_RESPONSE_WORK_S:
            raise ArchInputError(f"t_end: {t_end:g} s of record, estimated "
                                 f"{format_duration(est)} here; the app allows "
                                 f"{format_duration(MAX_RESPONSE_WORK_S)} (archrock respond "
                                 f"--record for more)")
    return {"arch": arch, "motion": motion, "spec": spec, "record": info, "t_end": t_end,
            "exaggerate": ex, "friction": mu, "choice": chosen, "t0": t0}


def respond(params: dict, records: RecordStore | None = None) -> dict:
    """The four-link response of a request (:func:`respond_request`) whose model is the
    four-link one; where the contact engine answers, ArchInputError: its response is a job
    (``POST /api/respond`` starts it, :func:`archrock.app.engine.run_engine_job`)."""
    req = respond_request(params, records)
    if req["choice"].engine:
        raise ArchInputError(f"dynamics: the contact engine answers this arch "
                             f"({req['choice'].reason}); its response is a job of the page "
                             f"(play), not this call")
    return four_link_response(req)


def four_link_response(req: dict) -> dict:
    """``archrock respond --json`` of a checked request (:func:`respond_request`), with the
    time history (``time`` [s], ``phi`` [rad], signed: + in M_l, - in M_r, null after the
    rotation limit) and the animation: ``frames`` (at most :data:`MAX_FRAMES`), each
    ``[t, phi, row, th1, th2, th3, bx, by, cx, cy]``: the chain row open (-1 at rest) and the
    rotations [rad] of its three links and the moved hinges B, C [m] (the library's four-bar
    kinematics, :func:`archrock.dynamics.fourlink.configuration`) at ``exaggerate`` (1 to 50,
    default 1: to scale) times the rotation; ``chain_links`` gives, per row, the hinge points A,
    B, C, D at rest and the voussoirs of each link.  ``dynamics``: the choice that ran it;
    ``valid`` False (and ``label`` "not valid here: ...") where it ran only because it was
    asked for by name."""
    from ..dynamics.fourlink import configuration
    from ..dynamics.response import prepare
    from ..dynamics.response import respond as respond_
    from ..units import G
    from .engine import four_link_valid

    arch, motion, spec, t_end = req["arch"], req["motion"], req["spec"], req["t_end"]
    ex, t0, chosen = req["exaggerate"], req["t0"], req["choice"]
    dt_out = max(0.002, t_end / 2000)
    with COMPUTE_LOCK:
        model = prepare(arch)
        res = respond_(model, motion, t_end=t_end, dt_out=dt_out)
    out = res.to_dict(samples=False)
    out.pop("arch", None)
    t, phi = np.asarray(res.time, float), np.asarray(res.response, float)
    held = phi.copy()
    finite = np.isfinite(held)
    if not finite.all():  # after the rotation limit: hold the last computed position
        last = np.flatnonzero(finite)
        held[~finite] = held[last[-1]] if last.size else 0.0
    nf = int(min(MAX_FRAMES, max(2, round(t_end * 50))))
    ft = np.linspace(0.0, float(t[-1]), nf)
    rows = np.asarray(res.rows_at(ft), int)
    if res.collapsed and res.t_limit is not None:
        lim = [e for e in res.events if e.kind == "limit"]
        if lim:
            rows[ft >= res.t_limit] = lim[-1].row_before
    frames = []
    chain = model.chain[0]
    for tk, row in zip(ft, rows):
        val = float(np.interp(tk, t, held))
        row = int(row)
        if row < 0:
            frames.append([round(float(tk), 5), round(val, 7), -1, 0, 0, 0, 0, 0, 0, 0])
            continue
        fl = chain[row]
        # the drawn rotation, ``ex`` times the computed one (archrock.reports.animate's exaggerate)
        rot = max(0.0, (1.0 if fl.direction == "l" else -1.0) * val)
        bx, by, cx, cy, th1, th2, th3, ok = configuration(ex * rot, fl.geo)
        if not ok:  # the exaggerated chain would pass its dead point: drawn to scale
            bx, by, cx, cy, th1, th2, th3, ok = configuration(rot, fl.geo)
        frames.append([round(float(tk), 5), round(val, 7), row,
                       *(round(float(x), 8) for x in (th1, th2, th3)),
                       *(round(float(x), 6) for x in (bx, by, cx, cy))])
    step = max(1, len(t) // 1500)
    out.update({
        "drawing": arch_drawing(arch),
        "chain_links": [{"direction": fl.direction, "points": xy(fl.points),
                         "links": [list(map(int, v)) for v in fl.link_voussoirs],
                         "label": lab}
                        for fl, lab in zip(chain, model.labels)],
        "time": xy(t[::step]),
        "phi": [None if not math.isfinite(x) else round(float(x), 7) for x in phi[::step]],
        "ground": trace(motion.times, np.asarray(motion.accel) / G),
        "frames": frames,
        "pulse": spec.to_dict() if spec is not None else None,
        "record": req["record"],
        "exaggerate": ex,
        "model": "fourlink", "valid": four_link_valid(chosen), "dynamics": chosen.to_dict(),
        "fc": arch.fc,  # None: infinite strength; else the hinges are inset (chain_links)
        "label": ("four-link model: " if four_link_valid(chosen)
                  else "four-link model, not valid here: ") + chosen.reason,
        "elapsed_ms": 1e3 * (time.perf_counter() - t0),
    })
    return out


# ---------------------------------------------------------------------------- ensemble
def ensemble_request(params: dict) -> dict:
    """The checked arguments of :func:`run_ensemble_request`: ``config``
    (:func:`ensemble_config`) and, under a pulse, ``dynamics``: the routing's choice at the
    request's ``friction`` (default DEFAULT_FRICTION), refused where the four-link model does
    not hold for the nominal arch (:func:`archrock.app.engine.four_link_study`)."""
    from ..statics.friction import DEFAULT_FRICTION
    from .engine import four_link_study

    config = ensemble_config(params)
    chosen = None
    if config.motion is not None:
        mu = friction_field(params, DEFAULT_FRICTION)
        chosen = four_link_study(config.analysed_nominal, mu, "pulse", "ensemble").to_dict()
    return {"config": config, "dynamics": chosen}


def run_ensemble_request(req: dict, progress, cancelled) -> dict | None:
    """:func:`run_ensemble_job` of ``req["config"]``, its result with ``"dynamics"``."""
    out = run_ensemble_job(req["config"], progress, cancelled)
    return None if out is None else {**out, "dynamics": req["dynamics"]}


def ensemble_config(params: dict):
    """The :class:`~archrock.studies.ensemble.EnsembleConfig` of an ensemble request: ``arch``,
    ``samples`` (1 to :data:`MAX_SAMPLES`), ``seed``, ``spreads`` ({span, thickness, radius,
    tilt}, the CLI's --spread-*), an optional ``pulse``; refused above
    :data:`MAX_ENSEMBLE_WORK_S` by the package's cost of an arch
    (:mod:`archrock.studies.work`)."""
    from .._jit import HAVE_NUMBA
    from ..studies.ensemble import EnsembleConfig
    from ..studies.work import SAMPLE_FINITE_S, SAMPLE_LIMIT_S, SAMPLE_RESPONSE_S, format_duration

    params = only(request_object(params), ENSEMBLE_FIELDS)
    nominal = arch_from_params(object_field(params, "arch"))
    samples, seed, spreads = _random_arches(params, 1000, 1, MAX_SAMPLES,
                                            "in the app (archrock ensemble for more)")
    motion = pulse_spec(params["pulse"]) if params.get("pulse") is not None else None
    each = (SAMPLE_RESPONSE_S if motion is not None else SAMPLE_LIMIT_S) * (1 if HAVE_NUMBA else 50)
    if nominal.fc is not None:  # each arch through the crushing statics, one at a time
        each += SAMPLE_FINITE_S
    est = samples * each
    if est > MAX_ENSEMBLE_WORK_S:
        raise ArchInputError(f"samples: {samples} arches, estimated {format_duration(est)} here; "
                             f"the app runs up to {format_duration(MAX_ENSEMBLE_WORK_S)} "
                             f"(archrock ensemble for more)")
    batch = int(min(500, max(50, math.ceil(samples / 20))))
    return EnsembleConfig.from_arch(nominal, samples=samples, seed=seed, spreads=spreads,
                                    batch_size=batch, motion=motion)


def run_ensemble_job(config, progress, cancelled) -> dict | None:
    """Run ``config`` batch by batch (:func:`archrock.studies.ensemble.compute.run_batches`, as
    ``archrock ensemble`` does in-process), calling ``progress(done, total)`` after each and
    stopping (returning None) once ``cancelled()``; the summary is the CLI's
    (:meth:`~archrock.studies.ensemble.summary.EnsembleResult.summary`) with the histogram of
    k = min(k_l, k_r) [g]."""
    import pandas as pd

    from ..studies.ensemble.compute import run_batches
    from ..studies.ensemble.run import _impact_info, _nominal_info
    from ..studies.ensemble.summary import EnsembleResult

    t0 = time.perf_counter()
    with COMPUTE_LOCK:
        nominal, impact = _nominal_info(config), _impact_info(config)
    frames, done = [], 0
    for b in range(config.n_batches):
        if cancelled():
            return None
        with COMPUTE_LOCK:
            _, df, _ = run_batches(config, [b], parallel=True)[0]
        frames.append(df)
        done += len(df)
        progress(done, config.samples)
    frame = pd.concat(frames, ignore_index=True)
    wall = time.perf_counter() - t0
    summary = EnsembleResult(config, frame, nominal, impact,
                             {"wall_s": wall, "executor": "app (in-process)"}).summary()
    kl, kr = frame["k_l"].to_numpy(float), frame["k_r"].to_numpy(float)
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(kl) & np.isfinite(kr) & (kl > 0) & (kr > 0)
    k = np.minimum(kl, kr)[ok]
    counts, edges = (np.histogram(k, bins=30) if k.size else (np.zeros(0), np.zeros(0)))
    return {"summary": summary, "histogram": {"edges": xy(edges), "counts": counts.tolist(),
                                              "of": "k = min(k_l, k_r) [g]"},
            "wall_s": wall}


# ---------------------------------------------------------------------------- collapse curve
#: Collapse-acceleration curves: random arches, durations, and their product (each arch and
#: duration is one bisection of about 20 responses: 100 x 7 take about 13 s here).
MAX_CURVE_SAMPLES = 200
MAX_CURVE_DURATIONS = 12
MAX_CURVE_WORK = 1500


def curve_request(params: dict) -> dict:
    """The checked arguments of :func:`run_curve_job`: ``arch``, ``samples`` (1 to
    :data:`MAX_CURVE_SAMPLES`), ``seed``, ``spreads`` as the ensemble's, ``durations`` [s]
    (a list, or text such as "0.1,0.2,0.5"), ``kind`` of pulse (negative amplitudes, the
    paper's)."""
    from ..studies.curves import parse_range

    params = only(request_object(params), CURVE_FIELDS)
    nominal = arch_from_params(object_field(params, "arch"))
    samples, seed, spreads = _random_arches(params, 30, 1, MAX_CURVE_SAMPLES, "for a curve in "
                                            "the app (archrock curves for more)")
    d = params.get("durations", "0.1,0.2,0.3,0.5,0.8,1.2")
    if isinstance(d, list):
        d = ",".join(str(x) for x in d)
    if not isinstance(d, str):
        raise ArchInputError("durations: expected numbers such as 0.1,0.2,0.5 [s]")
    parts = d.split(":")
    if len(d) > 300 or (len(parts) == 3 and parts[2].strip().isdigit()
                        and int(parts[2]) > MAX_CURVE_DURATIONS):
        raise ArchInputError(f"durations: {d[:40]!r}; allowed 1 to {MAX_CURVE_DURATIONS} "
                             f"durations")  # checked before parse_range builds the list
    durations = [float(x) for x in parse_range(d, "durations")]
    if not 1 <= len(durations) <= MAX_CURVE_DURATIONS or max(durations) > MAX_PULSE_S:
        raise ArchInputError(f"durations: {len(durations)} of up to {max(durations):g} s; allowed "
                             f"1 to {MAX_CURVE_DURATIONS} durations of at most {MAX_PULSE_S:g} s")
    from .._jit import HAVE_NUMBA

    bound = MAX_CURVE_WORK if HAVE_NUMBA else MAX_CURVE_WORK // 50  # pure Python: ~50x slower
    if samples * len(durations) > bound:
        raise ArchInputError(f"samples: {samples} arches x {len(durations)} durations; the app "
                             f"allows {bound} here (archrock curves for more)")
    kind = choice(params, "kind", PULSE_KINDS, "oppenheim")
    from ..statics.friction import DEFAULT_FRICTION
    from .engine import four_link_study

    chosen = four_link_study(nominal, friction_field(params, DEFAULT_FRICTION), "curve", "curves")
    return {"nominal": nominal, "samples": samples, "seed": seed, "spreads": spreads,
            "durations": durations, "kind": kind, "dynamics": chosen.to_dict()}


def run_curve_job(req: dict, progress, cancelled) -> dict | None:
    """The collapse-acceleration curve of the nominal arch and the 5/50/95% band over
    ``samples`` random arches (:func:`archrock.studies.curves.ensemble_curve`, as
    ``archrock curves --samples``), one duration at a time so that it shows progress and can be
    cancelled between durations (each arch and duration is searched on its own: the same numbers
    as one call).  Amplitudes [g] as magnitudes; null where no collapse up to 10 g."""
    from ..studies.curves import ensemble_curve

    t0 = time.perf_counter()
    out = {"durations": [], "nominal_g": [], "q05_g": [], "q50_g": [], "q95_g": []}
    n_used, failed = None, 0
    total = req["samples"] * len(req["durations"])
    for i, d in enumerate(req["durations"]):
        if cancelled():
            return None
        with COMPUTE_LOCK:
            c = ensemble_curve(req["nominal"], req["samples"], req["seed"], req["spreads"],
                               durations=(d,), kind=req["kind"])
        out["durations"].append(d)
        out["nominal_g"].append(float(c.nominal.amplitudes[0]))
        for key, row in zip(("q05_g", "q50_g", "q95_g"), c.bands):
            out[key].append(float(row[0]))
        n_used, failed = c.n_samples, len(c.failed)
        progress((i + 1) * req["samples"], total)
    return {**out, "samples": req["samples"], "n_used": n_used, "left_out": failed,
            "kind": req["kind"], "dynamics": req["dynamics"], "wall_s": time.perf_counter() - t0}


# ---------------------------------------------------------------------------- export
def export(params: dict, records: RecordStore | None = None) -> tuple[str, str, str]:
    """A download: (file name, media type, text). ``what``: "geometry" (the JSON geometry
    file, as ``archrock random-arch --out`` writes), "limit" (``archrock limit --json``),
    "thrust-csv" (each joint's thrust-line crossings [m], both directions) or
    "response-csv" (t [s], phi [rad] of the pulse response)."""
    import json

    from ..options import json_safe

    params = only(request_object(params),
                  ("what", *dict.fromkeys((*LIMIT_FIELDS, *RESPOND_FIELDS))))
    what = choice(params, "what", ("geometry", "limit", "thrust-csv", "response-csv"))
    if what is None:
        raise ArchInputError("what: needed; allowed one of geometry, limit, thrust-csv, "
                             "response-csv")
    if what == "geometry":
        arch = arch_from_params(object_field(params, "arch"))
        data = {**arch.to_dict(), "metadata": {"generator": "archrock app"}}
        return "arch.json", "application/json", json.dumps(json_safe(data), indent=2) + "\n"
    if what == "limit":
        res = limit({k: v for k, v in params.items() if k in LIMIT_FIELDS})
        return "limit.json", "application/json", json.dumps(json_safe(res["summary"]),
                                                            indent=2) + "\n"
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    if what == "thrust-csv":
        from ..statics.limit import limit_analysis

        arch = arch_from_params(object_field(params, "arch"))
        with COMPUTE_LOCK:
            r = limit_analysis(arch, verify=True)
        w.writerow(["joint", "x_l_m", "y_l_m", "x_r_m", "y_r_m"])
        for j, (pl, pr) in enumerate(zip(r.thrust_l.points, r.thrust_r.points)):
            w.writerow([j, *(f"{v:.6f}" for v in (*pl, *pr))])
        return "thrust.csv", "text/csv", buf.getvalue()
    res = respond({k: v for k, v in params.items() if k in RESPOND_FIELDS}, records)
    w.writerow(["t_s", "phi_rad"])
    for tk, ph in zip(res["time"], res["phi"]):
        w.writerow([f"{tk:.5f}", "" if ph is None else f"{ph:.7f}"])
    return "response.csv", "text/csv", buf.getvalue()


# ---------------------------------------------------------------------------- report
#: The report's estimated work [s] (archrock.studies.work's cost of a response: the curve's
#: amplitude scan over durations x arches) and the random arches of its band.
MAX_REPORT_WORK_S = 20.0
MAX_REPORT_SAMPLES = 50
#: The contact-engine check's time here (pymunk, both directions: about 6 s on Oppenheim's
#: arch), added to the estimate when it is part of the report.
CONTACT_CHECK_S = 6.0


def report_request(params: dict) -> dict:
    """The checked arguments of :func:`run_report_job`: the ``arch``, ``samples`` (0 to
    :data:`MAX_REPORT_SAMPLES`, default 12 as ``archrock assess``), ``seed`` and ``spreads``
    as the ensemble's, ``contact`` (the contact-engine check, default true), ``friction``:
    the page's, as the limit and respond requests send it (default
    :data:`~archrock.statics.friction.DEFAULT_FRICTION`, "none": sliding excluded), the
    report's one friction (``archrock assess --friction``).  The rest is
    ``archrock assess``'s defaults (the paper's pulse, durations 0.1 to 1 s, 60 amplitudes,
    no records: no fragility section, no site spectrum: no verdict)."""
    from ..statics.friction import DEFAULT_FRICTION
    from ..studies.assessment import AssessConfig
    from ..studies.work import format_duration, response_cost_s
    from .._jit import HAVE_NUMBA

    params = only(request_object(params), REPORT_FIELDS)
    arch = arch_from_params(object_field(params, "arch"))
    samples, seed, spreads = _random_arches(params, 12, 0, MAX_REPORT_SAMPLES,
                                            "random arches for the report in the app "
                                            "(archrock assess for more)")
    contact = bool(params.get("contact", True))
    mu = friction_field(params, DEFAULT_FRICTION)
    cfg = AssessConfig(samples=samples, seed=seed, spreads=spreads, friction=mu)
    responses = (samples + 1) * len(cfg.durations) * cfg.n_scan
    est = responses * response_cost_s() * (1 if HAVE_NUMBA else 50)
    if est > MAX_REPORT_WORK_S:
        raise ArchInputError(f"samples: {samples} arches, estimated {format_duration(est)} here; "
                             f"the app's report runs up to {format_duration(MAX_REPORT_WORK_S)} "
                             f"(archrock assess for more)")
    try:
        from ..reports.drawing import _require_matplotlib

        _require_matplotlib()
    except Exception as exc:  # noqa: BLE001 - the extra to install, in one line
        raise ArchInputError(f"report: {' '.join(str(exc).split())}") from None
    return {"arch": arch, "config": cfg, "contact": contact,
            "estimate_s": est + (CONTACT_CHECK_S if contact else 0.0)}


class _Cancelled(Exception):
    """Raised from the report's progress callback between sections once cancelled."""


def run_report_job(req: dict, progress, cancelled) -> dict | None:
    """``archrock assess`` of the request's arch
    (:func:`archrock.studies.assessment.assess`, then
    :func:`archrock.reports.html.render_html`): the section functions of
    :data:`~archrock.studies.assessment.SECTIONS` (without the contact check unless asked),
    each but the contact check under :data:`COMPUTE_LOCK`, counted by ``progress`` and cancelled between sections.
    Returns the summary shown in the page and, under ``"_download"``, the HTML file."""
    import contextlib
    import functools
    import re

    from ..reports.html import render_html
    from ..studies.assessment import SECTIONS, assess

    chosen = [f for f in SECTIONS if req["contact"] or getattr(f, "key", "") != "contact"]
    total = len(chosen) + 1  # the sections, then drawing the figures
    done = [0]

    def counted(func):
        # the contact-engine check (pymunk, about 6 s; no numba kernel: the limit analysis it
        # compares with is computed before) runs without the lock, so the page's statics and
        # responses are answered meanwhile
        lock = (contextlib.nullcontext() if getattr(func, "key", "") == "contact"
                else COMPUTE_LOCK)

        @functools.wraps(func)
        def section(ctx):
            try:
                with lock:
                    return func(ctx)
            finally:
                done[0] += 1
                progress(done[0], total)
        return section

    def said(msg):  # called by assess before each section, outside its error handling
        if cancelled():
            raise _Cancelled

    t0 = time.perf_counter()
    try:
        from ..studies.runner import RunSettings

        result = assess(req["arch"], req["config"], settings=RunSettings(progress=said),
                        sections=[counted(f) for f in chosen])
    except _Cancelled:
        return None
    if cancelled():
        return None
    html = render_html(result)
    progress(total, total)
    safe = re.sub(r"[^A-Za-z0-9._-]", "_", result.arch.name)[:60] or "arch"
    k = result.section("limit").data
    return {"name": result.arch.name, "sections": [s.title for s in result.sections],
            "headline": [list(h) for h in result.headline], "verdict": result.verdict,
            "k": k.get("k") if isinstance(k, dict) else None, "friction": req["config"].friction,
            "seconds": time.perf_counter() - t0, "bytes": len(html.encode("utf-8")),
            "_download": (f"assessment-{safe}.html", "text/html; charset=utf-8", html)}

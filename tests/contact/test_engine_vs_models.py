"""archrock's engine against the other models: the limit analysis (activation, hinges, sliding
at the friction analysis's multiplier), the four-link model before the first impact, Makris and
Vassiliou's rocking frame, and the heavy-pier arch's first collapse."""

import math

import numpy as np
import pytest

from archrock.contact import EngineSettings, RigidArch, engine_respond, ramp
from archrock.dynamics.response import prepare, respond
from archrock.geometry import PolygonArch, family_arch
from archrock.geometry.piers import _polygon_of
from archrock.groundmotion import oppenheim_pulse
from archrock.statics.friction import friction_analysis
from archrock.units import G


def _hinges(mech):
    return tuple(int(h.joint) for h in mech.hinges)


def test_oppenheim_ramp_activates_at_the_limit_multiplier_with_its_hinges(oppenheim):
    """Exact contacts: the engine's activation is the limit analysis's k = 0.370010 (the ramp's
    bracket is 0.5% wide), the same both ways, and its hinges are the limit mechanisms'."""
    r = ramp(oppenheim.arch, EngineSettings(), limit=oppenheim.limit)
    k = oppenheim.limit.k_l
    for d in (r.l, r.r):
        assert d.lower <= k * 1.0005 and abs(d.multiplier / k - 1) < 0.005
        assert d.mode == "rocking"
    assert abs(r.k_l / r.k_r - 1) < 0.002
    assert r.l.hinges == _hinges(oppenheim.limit.mechanism_l)
    assert r.r.hinges == _hinges(oppenheim.limit.mechanism_r)


def test_oppenheim_holds_rest_below_and_move_above_k(oppenheim):
    """Held from rest for 4 T: at 0.999 k every joint stays shut (rotation < 1e-9 rad), at
    1.001 k the arch moves: the threshold is k to 0.1%, not the soft engine's 0.4% below."""
    k = oppenheim.limit.k_l
    moved = {}
    for f in (0.999, 1.001):
        ra = RigidArch(oppenheim.arch)
        ra.step(-f * k * G, 1600)
        moved[f] = float(np.abs(ra.joint_rotations(ra.q[:, 2])).max())
        assert ra.solver_stats()["unconverged_steps"] == 0
    assert moved[0.999] < 1e-9 and moved[1.001] > 1e-3


def test_sliding_where_the_friction_analysis_says_it_governs(oppenheim):
    """At mu = 0.4 sliding governs Oppenheim's arch (friction LP 0.2638 < 0.3700): the engine's
    ramp slides, at the friction analysis's multiplier within 0.5%, the same both ways."""
    fa = friction_analysis(oppenheim.arch, 0.4)
    assert fa.l.sliding_governs
    r = ramp(oppenheim.arch, EngineSettings(friction=0.4), limit=oppenheim.limit)
    for d, ref in ((r.l, fa.l.multiplier), (r.r, fa.r.multiplier)):
        assert d.mode == "sliding" and d.sliding_joints
        assert abs(d.multiplier / ref - 1) < 0.005
    assert abs(r.k_l / r.k_r - 1) < 0.002


@pytest.mark.slow
def test_flat_bridge_arch_activates_at_the_limit_multiplier():
    """The flat bridge arch on which pymunk's engine was 31% low (span 10 m, rise 1.5 m, t 0.5 m,
    15 voussoirs; friction needed 0.72 < 0.8): the engine's k within 0.5% of the limit analysis's
    1.9045 both ways, k_l = k_r within 0.2%, the limit mechanisms' hinges."""
    from archrock.statics.limit import limit_analysis

    arch = family_arch("circular", 10.0, 1.5, 0.5, 15)
    lim = limit_analysis(arch)
    r = ramp(arch, EngineSettings(), limit=lim)
    assert abs(r.k_l / lim.k_l - 1) < 0.005 and abs(r.k_r / lim.k_r - 1) < 0.005
    assert abs(r.k_l / r.k_r - 1) < 0.002
    assert r.l.hinges == _hinges(lim.mechanism_l) and r.r.hinges == _hinges(lim.mechanism_r)


def _links(arch, groups):
    """The arch with each group of voussoirs merged into one block (the four-link's links)."""
    pa = _polygon_of(arch)
    intr, extr = [], []
    for g in groups:
        ii = [np.asarray(pa.intrados[i]) for i in g]
        ee = [np.asarray(pa.extrados[i]) for i in g]
        intr.append(np.vstack([ii[0]] + [x[1:] for x in ii[1:]]).tolist())
        extr.append(np.vstack([ee[0]] + [x[1:] for x in ee[1:]]).tolist())
    return PolygonArch(tuple(intr), tuple(extr), density=pa.density)


def _first_excursion_peak(phi):
    phi = np.nan_to_num(np.asarray(phi, float))
    moving = np.flatnonzero(phi > 1e-9)
    if not moving.size:
        return 0.0
    i0 = moving[0]
    back = np.flatnonzero(phi[i0:] <= 0.0)
    return float(phi[i0:i0 + back[0] if back.size else phi.size].max())


@pytest.mark.parametrize("amplitude", [0.38, 0.387, 0.45])
def test_before_the_first_impact_the_engine_is_the_four_link_model(oppenheim, amplitude):
    """The engine on the four-link's three links (voussoirs 0-2, 3-4, 5-6 of M_l merged) under
    Oppenheim's pulse of t_p = 1 s: the first excursion's peak rotation of link AB is the exact
    four-link model's within 0.5% (0.38 and 0.387 g survive, 0.45 g collapses in it)."""
    model = prepare(oppenheim.arch, "momentum")
    assert _hinges(oppenheim.limit.mechanism_l) == (0, 3, 5, 7)
    links = _links(oppenheim.arch, [(0, 1, 2), (3, 4), (5, 6)])
    motion = oppenheim_pulse(-amplitude, 1.0)
    four = respond(model, motion, t_end=5.0, dt_out=0.001)
    eng = engine_respond(links, motion, EngineSettings(), model=None, t_end=5.0, dt_out=0.001)
    phi = np.nan_to_num(eng.rotations[:, 0]) / model.mech_l.sign
    p4, pe = _first_excursion_peak(four.response), _first_excursion_peak(phi)
    assert p4 > 1e-3
    assert abs(pe / p4 - 1) < 0.005
    assert eng.collapsed == four.collapsed


def _frame(b=0.25, h=2.0, depth=0.5, span=6.0):
    x1, x2, top = 0.0, span, 2 * h
    intr = ([(x1 + b, 0.0), (x1 + b, top)], [(x1 + b, top), (x2 - b, top)],
            [(x2 - b, top), (x2 - b, 0.0)])
    extr = ([(x1 - b, 0.0), (x1 - b, top)],
            [(x1 - b, top), (x1 - b, top + depth), (x2 + b, top + depth), (x2 + b, top)],
            [(x2 + b, top), (x2 + b, 0.0)])
    return PolygonArch(intr, extr, 2000.0, name="rocking frame")


def test_makris_vassiliou_frame_activation_and_frequency_parameter():
    """Two columns 2b x 2h under a free beam: the frame stands at 0.99 tan(alpha) and rocks at
    1.01 tan(alpha); from rest under lambda g its columns start turning at
    theta'' = p^2 (lambda cos(alpha) - sin(alpha)) (read from the rate after 40 small steps) with
    p^2 = 3 g / (4 R) (1 + 2 gamma) /
    (1 + 3 gamma) (gamma = beam mass / both columns' mass), within 1%."""
    b, h = 0.25, 2.0
    frame = _frame(b, h)
    alpha, R = math.atan(b / h), math.hypot(b, h)
    m = frame.masses[0]
    gamma = frame.masses[1] / (2 * m)
    for f, moves in ((0.99, False), (1.01, True)):
        ra = RigidArch(frame)
        ra.step(-f * math.tan(alpha) * G, 800)
        assert bool(abs(ra.q[0, 2]) > 1e-4) is moves
    lam = 1.5 * math.tan(alpha)
    ra = RigidArch(frame, EngineSettings(steps_per_T=4000))
    n = 40
    ra.step(-lam * G, n)
    t = n * ra.dt
    p2 = 3 * G / (4 * R) * (1 + 2 * gamma) / (1 + 3 * gamma)
    expected = p2 * (lam * math.cos(alpha) - math.sin(alpha)) * t  # the rate theta'' t
    assert abs(abs(ra.v[0, 2]) / expected - 1) < 0.01
    assert ra.q[0, 2] == pytest.approx(ra.q[2, 2], rel=1e-6)  # the columns turn together


@pytest.mark.slow
def test_heavy_pier_arch_first_collapse_between_the_peers(heavy_piers_file):
    """The heavy-pier arch under Oppenheim's pulse (t_p 0.2 s, toward +x): the engine's first
    collapse between 0.55 and 0.75 g (the peer's stiff contacts 0.55-0.7 g, pymunk 0.70 g)."""
    from archrock.geometry.files import read_arch
    from archrock.studies.enginestudy import engine_first_collapse

    r = engine_first_collapse(read_arch(heavy_piers_file), 0.2, rtol=0.01)
    assert r.amplitude is not None and 0.55 <= r.amplitude <= 0.75


def test_lift_off_arch_has_an_engine_answer(tmp_path, capsys):
    """The README's squat three-voussoir arch, where a mechanism with lift-off governs and no
    four-link model exists: `respond` answers with the engine (its largest voussoir rotation
    standing for phi) instead of stopping, and `dem` runs it with the four-link run left out."""
    import json

    from archrock.cli import main

    geo = tmp_path / "three.json"
    geo.write_text(json.dumps({"voussoirs": [{"span_deg": 22.5, "radius": 10.0,
                                              "thickness": 1.5}] * 3}))
    pulse = ["--geometry", str(geo), "--pulse", "oppenheim", "--amplitude", "-12",
             "--pulse-duration", "0.2", "--t-end", "1", "--no-progress", "--json"]
    assert main(["respond", *pulse]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["model"] == "engine" and d["status"] == "rest" and 0.01 < d["peak"] < 0.2
    assert main(["dem", *pulse, "--friction", "50"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert "lift-off" in d["four_link_note"] and 0.005 < d["peak"] < 0.2

"""Scale and density invariance: a verdict must not depend on the units.

k is a ratio of virtual works, so similar arches (every length times s) have the same k, hinges
and minimum-thickness factor; the equation of motion divided by M gives phi'' in units of g/R,
so a pulse of the same amplitude in g and durations times sqrt(s) gives the same response as a
function of t / sqrt(s).  Density cancels from both.
"""

import json
import math

import numpy as np
import pytest

from archrock import groundmotion as gm
from archrock.dynamics.batch import prepare_batch, simulate_batch
from archrock.cli import main
from archrock.geometry import nominal_arch, oppenheim_arch, random_arch
from archrock.statics.limit import kinematic_multipliers_batch, limit_analysis, minimum_thickness
from archrock.dynamics.response import default_steps, prepare, respond
from archrock.geometry.sampling import ArchSampler

#: radii of Oppenheim's arch, 1 mm to 1 km (thickness 0.15 R), and the reference R = 10 m
RADII = (1e-3, 1.0, 10.0, 1e3)
FACTORS = (1e-3, 1.0, 1e3)  # scale factors of irregular arches
DENSITIES = (1e-3, 1.0, 2000.0, 1e7)  # kg/m^3
REL = 1e-9


def _oppenheim(radius, density=2000.0):
    return nominal_arch(radius, 157.5, 0.15 * radius, 7, density=density)


def _hinges(result):
    return result.mechanism_l.hinges, result.mechanism_r.hinges


def _assert_same_limit(res, ref):
    assert res.k_l == pytest.approx(ref.k_l, rel=REL)
    assert res.k_r == pytest.approx(ref.k_r, rel=REL)
    assert _hinges(res) == _hinges(ref)
    assert res.static_k_l == pytest.approx(ref.k_l, rel=REL)
    assert res.static_k_r == pytest.approx(ref.k_r, rel=REL)


# ---------------------------------------------------------------------------- limit analysis
def test_oppenheim_multiplier_from_millimetres_to_kilometres():
    ref = limit_analysis(_oppenheim(10.0))
    assert ref.k == pytest.approx(0.3700, abs=5e-5)  # the paper's k to its 4 printed decimals
    for radius in RADII:
        res = limit_analysis(_oppenheim(radius))
        _assert_same_limit(res, ref)
        # the paper's k to its 4 printed decimals, both directions
        assert res.k_l == pytest.approx(0.3700, abs=5e-5)
        assert res.k_r == pytest.approx(0.3700, abs=5e-5)
        # the line of thrust at collapse is the same figure, scaled
        np.testing.assert_allclose(res.thrust_l.radii / radius, ref.thrust_l.radii / 10.0, rtol=REL)
        np.testing.assert_allclose(res.thrust_r.forces, ref.thrust_r.forces, rtol=REL, atol=1e-12)


def test_irregular_arches_scaled_by_1e_3_to_1e3():
    sampler = ArchSampler(oppenheim_arch(), seed=11)
    arches = [sampler.arch(i) for i in range(4)] + [random_arch(seed=s) for s in (3, 8)]
    for arch in arches:
        ref = limit_analysis(arch)
        for f in FACTORS:
            _assert_same_limit(limit_analysis(arch.scaled(f)), ref)
    # the batch enumeration too, with arches of every size in one batch
    spans = np.array([a.spans for a in arches for _ in FACTORS])
    radii = np.array([a.radii * f for a in arches for f in FACTORS])
    thick = np.array([a.thicknesses * f for a in arches for f in FACTORS])
    k_l, k_r, i_l, i_r = kinematic_multipliers_batch(spans, radii, thick)
    m = len(FACTORS)
    for j in range(len(arches)):
        rows = slice(j * m, (j + 1) * m)
        np.testing.assert_allclose(k_l[rows], k_l[j * m + 1], rtol=REL)
        np.testing.assert_allclose(k_r[rows], k_r[j * m + 1], rtol=REL)
        assert len(set(i_l[rows].tolist())) == 1 and len(set(i_r[rows].tolist())) == 1


def test_huge_and_tiny_arches_stand():
    # the static LP's tolerances are absolute: in metres a 50 km arch had no line of thrust
    for radius in (5e4, 1e-3, 1e-6, 1e6):
        res = limit_analysis(_oppenheim(radius))
        assert res.discrepancy < 1e-9
        assert res.k == pytest.approx(0.3700, abs=5e-5)  # the paper's k to its 4 printed decimals


def test_minimum_thickness_factor_is_scale_free():
    for arch in (oppenheim_arch(), random_arch(seed=5), nominal_arch(10.0, 180.0, 1.0, 8)):
        ref = minimum_thickness(arch)
        for f in (1e-3, 1e-1, 1e3, 5e3):
            mt = minimum_thickness(arch.scaled(f))
            assert mt.factor == pytest.approx(ref.factor, rel=REL)
            assert mt.ratio == pytest.approx(ref.ratio, rel=REL)
            np.testing.assert_allclose(mt.thicknesses, ref.thicknesses * f, rtol=REL)


def test_density_changes_nothing():
    ref = limit_analysis(oppenheim_arch())
    mt = minimum_thickness(oppenheim_arch())
    model_ref = prepare(oppenheim_arch())
    pulse = gm.oppenheim_pulse(-1.0, 0.2)
    r_ref = respond(model_ref, pulse, t_end=3.0)
    for rho in DENSITIES:
        arch = oppenheim_arch(density=rho)
        _assert_same_limit(limit_analysis(arch), ref)
        assert minimum_thickness(arch).factor == pytest.approx(mt.factor, rel=REL)
        model = prepare(arch)
        assert model.impact.l_to_r == pytest.approx(model_ref.impact.l_to_r, rel=REL)
        assert model.v_rest == pytest.approx(model_ref.v_rest, rel=REL)
        r = respond(model, pulse, t_end=3.0)
        assert r.peak == pytest.approx(r_ref.peak, rel=REL)
        np.testing.assert_allclose(r.impacts, r_ref.impacts, rtol=REL)
        np.testing.assert_allclose(r.response, r_ref.response, rtol=REL, atol=1e-12)


def test_cli_limit_kilometres_and_millimetres(capsys):
    for radius, thickness in (("5e4", "7500"), ("0.001", "0.00015")):
        assert main(["limit", "--radius", radius, "--embrace", "157.5", "--thickness", thickness,
                     "--voussoirs", "7", "--json"]) == 0
        d = json.loads(capsys.readouterr().out)
        # the paper's k to its 4 printed decimals, both directions
        assert d["k_l"] == pytest.approx(0.3700, abs=5e-5)
        assert d["k_r"] == pytest.approx(0.3700, abs=5e-5)
        assert d["discrepancy"] < 1e-9
        assert main(["limit", "--radius", radius, "--thickness", thickness]) == 0
        assert "k = min(k_l, k_r) = 0.3700" in capsys.readouterr().out


# ---------------------------------------------------------------------------- dynamics
def _scaled_run(radius, pulse_amp, pulse_t, t_end, density=2000.0):
    """Oppenheim's arch of radius R under the pulse of R = 10 m scaled by the similarity law."""
    s = math.sqrt(radius / 10.0)
    model = prepare(_oppenheim(radius, density))
    r = respond(model, gm.oppenheim_pulse(pulse_amp, pulse_t * s), t_end=t_end * s,
                dt_out=0.005 * s, dt=2e-3 * s, t_free=60.0 * s)
    return model, r, s


@pytest.mark.parametrize("amp,tp,t_end", [(-1.0, 0.2, 3.0), (-1.4, 0.3, 2.0)])
def test_similarity_law_from_millimetres_to_kilometres(amp, tp, t_end):
    m0, r0, _ = _scaled_run(10.0, amp, tp, t_end)
    for radius in (1e-3, 1.0, 1e3):
        m, r, s = _scaled_run(radius, amp, tp, t_end)
        assert m.k_l == pytest.approx(m0.k_l, rel=REL)
        assert m.impact.l_to_r == pytest.approx(m0.impact.l_to_r, rel=REL)
        assert m.v_rest * s == pytest.approx(m0.v_rest, rel=REL)  # a rate: 1 / time
        assert m.phi_limit_l == pytest.approx(m0.phi_limit_l, rel=REL)
        assert m.phi_unstable_r == pytest.approx(m0.phi_unstable_r, rel=REL)
        assert r.status == r0.status
        assert r.peak == pytest.approx(r0.peak, rel=REL)
        assert len(r.impacts) == len(r0.impacts)
        np.testing.assert_allclose(np.array(r.impacts) / s, r0.impacts, rtol=REL)
        np.testing.assert_allclose(r.response, r0.response, rtol=1e-7, atol=1e-12)
        assert r.t_final / s == pytest.approx(r0.t_final, rel=REL)
        if r0.collapsed:
            assert r.t_collapse / s == pytest.approx(r0.t_collapse, rel=REL)
    if amp == -1.0:  # the paper's pulse: 0.1.0's published values
        # to the 4 decimals 0.1.0 published (RK4 + tables: ~1e-9 from the exact solution)
        assert r0.status == "rest" and r0.peak == pytest.approx(0.0372, abs=5e-5)
        assert r0.impacts[:3] == pytest.approx([0.6012, 2.2294, 3.3706], abs=5e-5)
    else:
        assert r0.collapsed


def test_similarity_law_in_batches():
    arches = [random_arch(seed=s) for s in (1, 2, 3)]
    base = None
    for f in (1e-4, 1.0, 1e2):
        s = math.sqrt(f)
        pb = prepare_batch(np.array([a.spans for a in arches]),
                           np.array([a.radii * f for a in arches]),
                           np.array([a.thicknesses * f for a in arches]), density=2000.0 * f,
                           impact="paper")
        res = simulate_batch(pb, gm.oppenheim_pulse(-1.3, 0.3 * s), dt=2e-3 * s, t_free=60.0 * s)
        got = (pb.k_l, pb.c_l_to_r, pb.v_rest * s, res["status"], res["peak"],
               res["t_collapse"] / s, res["n_impacts"])
        if base is None:
            base = got
            continue
        for a, b in zip(got, base):
            np.testing.assert_allclose(a, b, rtol=REL)


def test_default_steps_follow_the_size():
    # 0.1.0's 2e-3 s and 60 s for arches of metres
    assert default_steps(oppenheim_arch()) == (2e-3, 60.0)
    dt, t_free = default_steps(_oppenheim(1e-3))
    assert dt < 2e-3 / 10 and t_free == 60.0
    dt, t_free = default_steps(_oppenheim(1e3))
    assert dt == 2e-3 and t_free > 60.0 * 5
    # with the defaults a 1 mm arch is integrated accurately and a 1 km arch rocks to rest
    for radius in (1e-3, 1e3):
        m, ref, s = _scaled_run(radius, -1.0, 0.2, 3.0)
        r = respond(m, gm.oppenheim_pulse(-1.0, 0.2 * s), t_end=3.0 * s, dt_out=0.005 * s)
        assert r.status == ref.status == "rest"
        assert r.peak == pytest.approx(ref.peak, rel=1e-5)
        assert len(r.impacts) == len(ref.impacts)


def test_same_results_without_numba(without_numba):
    code = (
        "import json, math\n"
        "from archrock import groundmotion as gm\n"
        "from archrock.geometry import nominal_arch\n"
        "from archrock.statics.limit import limit_analysis, minimum_thickness\n"
        "from archrock.dynamics.response import respond\n"
        "out = []\n"
        "for R in (1e-3, 1e3):\n"
        "    a = nominal_arch(R, 157.5, 0.15 * R, 7)\n"
        "    res, s = limit_analysis(a), math.sqrt(R / 10)\n"
        "    r = respond(a, gm.oppenheim_pulse(-1.0, 0.2 * s), t_end=3 * s, dt_out=0.005 * s,\n"
        "                dt=2e-3 * s, t_free=60 * s)\n"
        "    out.append([res.k_l, res.static_k_r, minimum_thickness(a).factor, r.peak,\n"
        "                r.impacts[:5]])\n"
        "print(json.dumps(out))\n")
    got = json.loads(without_numba("-c", code))
    for (k_l, s_r, mt, peak, imp), radius in zip(got, (1e-3, 1e3)):
        a = _oppenheim(radius)
        res = limit_analysis(a)
        _, r, _ = _scaled_run(radius, -1.0, 0.2, 3.0)
        # rel=1e-12: pure Python and numba kernels round differently (and SIMD width differs
        # by CPU), so equal to rounding, not to the bit
        assert k_l == pytest.approx(res.k_l, rel=1e-12)
        assert s_r == pytest.approx(res.static_k_r, rel=1e-12)
        assert mt == pytest.approx(minimum_thickness(a).factor, rel=1e-12)
        assert peak == pytest.approx(r.peak, rel=1e-12)
        np.testing.assert_allclose(imp, r.impacts[:5], rtol=1e-12)


# ---------------------------------------------------------------------------- figures
@pytest.mark.parametrize("radius", [1e-3, 1e3])
def test_figures_of_tiny_and_huge_arches(radius, tmp_path):
    pytest.importorskip("matplotlib")
    from archrock.reports.plots import new_figure, plot_limit, save_limit_figure

    res = limit_analysis(_oppenheim(radius))
    fig, axes = new_figure(1, 1)
    ax = plot_limit(res, "l", ax=axes[0][0])
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    # the axes frame the arch (extrados radius 1.075 R), whatever its size
    assert x0 < -1.075 * radius and x1 > 1.075 * radius and x1 - x0 < 3 * radius
    assert y1 > 1.075 * radius and y1 - y0 < 3 * radius
    assert save_limit_figure(res, tmp_path / "limit.png").stat().st_size > 10_000

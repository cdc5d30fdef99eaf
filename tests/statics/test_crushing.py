"""Limit analysis with a finite compressive strength (archrock.statics.crushing): the LP
bracket, the exact optimum, the mechanism at the stress blocks' centres against its virtual work
and Heyman's enumeration on the inset arch, and the limits (f_c large, f_c None)."""

import math

import numpy as np
import pytest

from archrock.errors import NoMechanismError
from archrock.geometry import apply_defect, family_arch, nominal_arch, oppenheim_arch
from archrock.statics.crushing import (crushing_analysis, crushing_bracket, crushing_constant,
                                       crushing_optimum, virtual_work_multiplier)
from archrock.statics.kinematic import _governing
from archrock.statics.limit import limit_analysis
from archrock.statics.lp import _statics
from archrock.units import G

FCS = (1.0, 2.0, 5.0, 10.0)


def flat_bridge_arch():
    """`--shape circular --span 10 --rise 1.5 --thickness 0.5 --voussoirs 15`."""
    return family_arch("circular", 10.0, 1.5, 0.5, 15, name="circular")


ARCHES = {"oppenheim": oppenheim_arch, "flat bridge": flat_bridge_arch}


@pytest.fixture(scope="module")
def results():
    """limit_analysis of both arches at f_c = 1, 2, 5, 10 MPa and infinite."""
    out = {}
    for name, make in ARCHES.items():
        arch = make()
        out[name] = {fc: limit_analysis(arch.with_fc(fc)) for fc in FCS + (None,)}
    return out


@pytest.mark.parametrize("name", list(ARCHES))
def test_k_falls_as_fc_falls(results, name):
    ks = [results[name][fc].k for fc in FCS] + [results[name][None].k]
    assert all(a < b for a, b in zip(ks, ks[1:])), ks
    # weak masonry costs a real share of the capacity, strong masonry little
    assert ks[0] < 0.8 * ks[-1]
    assert ks[3] > 0.95 * ks[-1]


@pytest.mark.parametrize("name", list(ARCHES))
@pytest.mark.parametrize("fc", FCS)
def test_static_bracket_equals_kinematic(results, name, fc):
    r = results[name][fc]
    for d in "lr":
        k, static = getattr(r, f"k_{d}"), getattr(r, f"static_k_{d}")
        lo, hi = getattr(r, f"k_bounds_{d}")
        assert hi - lo <= 1e-6 * abs(hi)
        assert lo - 1e-8 * hi <= static <= hi + 1e-8 * hi
        assert abs(k - static) <= 1e-6 * k
        m = r.mechanism(d)
        assert m.is_four_hinge and m.multiplier == k
    assert r.discrepancy <= 1e-6 * r.k
    assert "confirmed by virtual work" in r.method


@pytest.mark.parametrize("name", list(ARCHES))
def test_enumeration_on_the_inset_arch_agrees(name):
    arch = ARCHES[name]().with_fc(2.0)
    for d in "lr":
        ans = crushing_analysis(arch, d)
        assert ans.how == "four-hinge"
        assert abs(ans.enumeration - ans.static) <= 1e-6 * ans.static
        assert abs(ans.kinematic - ans.static) <= 1e-6 * ans.static


@pytest.mark.parametrize("name", list(ARCHES))
def test_infinite_fc_is_heyman_bit_for_bit(results, name):
    """fc None takes Heyman's path: the same numbers as the governing search itself, and no
    crushing fields in the result or its dict."""
    arch = ARCHES[name]()
    r = results[name][None]
    gov = _governing(arch, static=True)
    assert r.k_l == gov["l"].mechanism.multiplier and r.k_r == gov["r"].mechanism.multiplier
    assert r.k_bounds_l is None and r.zones_l is None
    d = r.to_dict()
    assert not {"fc", "k_bounds_l", "zones_l"} & set(d)
    assert "finite f_c" not in r.method


@pytest.mark.parametrize("name", list(ARCHES))
def test_strong_masonry_tends_to_heyman(results, name):
    arch = ARCHES[name]()
    k_inf = results[name][None].k
    k_1000 = limit_analysis(arch.with_fc(1000.0)).k
    assert k_1000 < k_inf
    assert abs(k_1000 - k_inf) <= 1e-3 * k_inf


@pytest.mark.parametrize("name", list(ARCHES))
def test_hinges_sit_at_the_stress_blocks_centres(results, name):
    """At each hinge the thrust crosses N / (2 f_c) from its edge, N [N/m] from the line of
    thrust's forces times the arch's weight (the units of c checked independently)."""
    r = results[name][2.0]
    arch = r.arch
    weight = G * float(np.sum(arch.masses))
    jp = np.asarray(arch.joint_points, float)
    for d in "lr":
        th = getattr(r, f"thrust_{d}")
        zones = getattr(r, f"zones_{d}")
        st = _statics(arch, d, "joint-line")
        for h in r.mechanism(d).hinges:
            j = h.joint
            e = jp[j, 1] - jp[j, 0]
            nu = np.array([e[1], -e[0]]) / np.hypot(*e)
            n_phys = float(th.forces[j] @ nu) * weight
            end = jp[j, 0] if h.edge == "intrados" else jp[j, 1]
            gap = float(np.hypot(*(th.points[j] - end)))
            assert gap == pytest.approx(n_phys / (2 * 2.0e6), rel=1e-9)
            assert zones[j] == pytest.approx(n_phys / 2.0e6, rel=1e-9)
        assert st.L.size == zones.size


def test_size_and_density_enter_as_w_over_fc():
    """c = W / (2 f_c L): doubling the density is halving f_c; doubling the size too."""
    arch = oppenheim_arch()
    k_a = limit_analysis(nominal_arch(density=4000.0).with_fc(4.0)).k
    k_b = limit_analysis(arch.with_fc(2.0)).k
    k_c = limit_analysis(arch.scaled(2.0).with_fc(4.0)).k
    assert abs(k_a - k_b) <= 1e-8 * k_b and abs(k_c - k_b) <= 1e-8 * k_b
    assert crushing_constant(arch.with_fc(2.0)) == pytest.approx(
        G * float(np.sum(arch.masses)) / (2 * 2.0e6 * arch.reference_length), rel=1e-15)


def test_flat_segment_without_mechanism_gets_a_finite_k():
    """The 60 deg segment of docs/method.md (R = 10 m, t = 1.5 m, 7 voussoirs): no mechanism
    under Heyman's hypotheses; with f_c crushing bounds it, and the static optimum is reported."""
    arch = nominal_arch(10.0, 60.0, 1.5, 7)
    with pytest.raises(NoMechanismError):
        limit_analysis(arch)
    ks = []
    for fc in (1.0, 10.0):
        r = limit_analysis(arch.with_fc(fc))
        assert math.isfinite(r.k) and r.k > 0
        lo, hi = r.k_bounds_l
        assert hi - lo <= 1e-6 * hi and lo <= r.k_l <= hi + 1e-8 * hi
        assert "static optimum" in r.method
        ks.append(r.k)
    assert ks[0] < ks[1]


def test_mirror_symmetry():
    arch = apply_defect(flat_bridge_arch(), "4:thickness=0.7").with_fc(2.0)
    r, m = limit_analysis(arch), limit_analysis(arch.mirrored())
    assert abs(r.k_l - r.k_r) > 1e-4 * r.k  # the defect breaks the symmetry
    assert abs(m.k_l - r.k_r) <= 1e-8 * r.k_r and abs(m.k_r - r.k_l) <= 1e-8 * r.k_l
    np.testing.assert_allclose(m.zones_l, r.zones_r[::-1], rtol=1e-6, atol=1e-12)


def test_virtual_work_at_the_inset_points():
    arch = oppenheim_arch().with_fc(5.0)
    br = crushing_bracket(arch, "l")
    opt = crushing_optimum(arch, br)
    assert opt.exact and len(opt.hinges) == 4 and not opt.crushed
    assert abs(virtual_work_multiplier(arch, opt) - opt.multiplier) <= 1e-9 * opt.multiplier
    assert br.rounds <= 10


def test_conic_solver_agrees_with_the_bracket():
    """The same program as a second-order cone program (Clarabel): c N^2 <= m written as
    ||(2 sqrt(c) N, m - 1)|| <= m + 1, and likewise for L N - m."""
    clarabel = pytest.importorskip("clarabel")
    import scipy.sparse as sp

    for arch in (oppenheim_arch().with_fc(2.0), flat_bridge_arch().with_fc(1.0),
                 nominal_arch(10.0, 60.0, 1.5, 7).with_fc(10.0)):
        st = _statics(arch, "l", "joint-line")
        c = crushing_constant(arch)
        rows, rhs = [], []
        for j in range(st.L.size):
            for a_m, b_m in ((st.A_m[j], st.b_m[j]),
                             (st.L[j] * st.A_N[j] - st.A_m[j], st.L[j] * st.b_N[j] - st.b_m[j])):
                rows += [-a_m, -2 * math.sqrt(c) * st.A_N[j], -a_m]
                rhs += [b_m + 1.0, 2 * math.sqrt(c) * st.b_N[j], b_m - 1.0]
        A = sp.csc_matrix(np.array(rows))
        cones = [clarabel.SecondOrderConeT(3)] * (2 * st.L.size)
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = 1e-10
        sol = clarabel.DefaultSolver(sp.csc_matrix((4, 4)), np.array([0, 0, 0, -1.0]), A,
                                     np.array(rhs), cones, settings).solve()
        assert str(sol.status) == "Solved"
        br = crushing_bracket(arch, "l")
        k = float(sol.x[3])
        assert br.lower - 1e-7 * k <= k <= br.upper + 1e-7 * k, (br.lower, k, br.upper)


def test_minimum_thickness_of_a_semicircle_grows_as_fc_falls():
    """R = 10 m, density 2000 kg/m^3, 18 voussoirs: t/R at f_c = inf, 10, 2, 1 MPa."""
    from archrock.statics.thickness import minimum_thickness

    arch = nominal_arch(10.0, 180.0, 1.0, 18)
    ratios = [minimum_thickness(arch.with_fc(fc), tol=1e-5).ratio for fc in (None, 10.0, 2.0,
                                                                              1.0)]
    assert all(a < b for a, b in zip(ratios, ratios[1:])), ratios
    assert 0.10 < ratios[0] < 0.11 and ratios[-1] > 1.2 * ratios[0]


def test_thrust_range_narrows_as_fc_falls():
    from archrock.statics.thrust import thrust_range

    arch = oppenheim_arch()
    inf, weak = thrust_range(arch), thrust_range(arch.with_fc(1.0))
    assert inf.thrust_min < weak.thrust_min < weak.thrust_max < inf.thrust_max
    assert [(h.joint, h.edge) for h in weak.hinges_min] == [(h.joint, h.edge)
                                                          for h in inf.hinges_min]


def test_displaced_arch_with_fc():
    """A spread of 5 cm: the re-closed arch's k takes f_c; the gaps' closing (point contacts,
    nothing to crush) stays Heyman's."""
    from archrock.geometry.displaced import SupportMovement
    from archrock.statics.reclosing import gap_closing
    from archrock.statics.supports import on_moved_supports

    moved = on_moved_supports(oppenheim_arch(), SupportMovement(0.05, 0.0, "right"))
    heyman, weak = limit_analysis(moved), limit_analysis(moved.with_fc(5.0))
    assert 0.9 * heyman.k < weak.k < heyman.k
    g0, g5 = gap_closing(moved), gap_closing(moved.with_fc(5.0))
    assert g0.k_l == g5.k_l and g0.k_r == g5.k_r


def test_flat_lintel_crushes_at_fc_h_over_w():
    """Closed form: a flat lintel of three rectangular voussoirs (span S, depth h, vertical
    joints) has no mechanism under Heyman's hypotheses; with f_c its springing joint crushes
    through when the horizontal load lambda W reaches f_c h (the thrust at the joint's centre,
    the whole depth compressed), provided W S <= f_c h^2 (the weight's bending then fits inside
    the stress blocks at every joint): lambda = f_c h / W."""
    from archrock.geometry import PolygonArch

    span, h, n = 3.0, 0.5, 3
    xs = [span * i / n for i in range(n + 1)]
    lintel = PolygonArch(tuple([[xs[i], 0.0], [xs[i + 1], 0.0]] for i in range(n)),
                         tuple([[xs[i], h], [xs[i + 1], h]] for i in range(n)), 2000.0, "lintel")
    with pytest.raises(NoMechanismError):
        limit_analysis(lintel)
    weight = 2000.0 * G * span * h
    for fc in FCS:
        assert weight * span <= fc * 1e6 * h * h
        r = limit_analysis(lintel.with_fc(fc))
        expected = fc * 1e6 * h / weight
        for d in "lr":
            assert abs(getattr(r, f"k_{d}") - expected) <= 1e-9 * expected
            assert r.mechanism(d).crushed


def test_limit_command_with_fc(capsys):
    """`archrock limit --fc 2 --json` carries f_c, both bounds and the zones; the friction-limited
    minimum thickness (Heyman's) is refused beside --fc rather than answered without it."""
    import json

    from archrock.cli import main

    assert main(["limit", "--fc", "2", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["fc"] == 2.0 and len(d["zones_l"]) == 8
    lo, hi = d["k_bounds_l"]
    assert lo - 1e-8 <= d["static_k_l"] <= hi + 1e-8 and abs(d["k_l"] - d["static_k_l"]) < 1e-9
    assert main(["limit", "--min-thickness", "--friction", "0.6", "--fc", "2"]) == 2
    assert "--min-thickness: with --friction and --fc" in capsys.readouterr().err

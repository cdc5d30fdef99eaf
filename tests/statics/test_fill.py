"""The fill's mobilised passive pressure in limit analysis (archrock.statics.fill)."""

import math

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import family_arch
from archrock.statics.fill import (FillPressure, _faces, _solve, fill_pressure_analysis,
                                   passive_coefficient)
from archrock.statics.limit import limit_analysis

LEVEL, RHO = 3.6, 1800.0


@pytest.fixture(scope="module")
def bridge():
    """A segmental bridge arch (S = 10 m, F = 3 m, t = 0.5 m) under a fill 0.6 m over its crown."""
    return family_arch("circular", 10.0, 3.0, 0.5, 9, fill={"level": LEVEL, "density": RHO})


@pytest.fixture(scope="module")
def base(bridge):
    return limit_analysis(bridge, verify=True)


@pytest.fixture(scope="module")
def pressed(bridge, base):
    return fill_pressure_analysis(bridge, 0.1, base=base)


def test_passive_coefficient_closed_form():
    assert passive_coefficient(30.0) == pytest.approx(3.0, rel=1e-12)
    assert passive_coefficient(0.0) == pytest.approx(1.0, rel=1e-15)
    s = math.sin(math.radians(35.0))
    assert passive_coefficient(35.0) == pytest.approx((1 + s) / (1 - s), rel=1e-15)


def test_zero_coefficient_is_todays_answer_bit_for_bit(bridge, base):
    r = fill_pressure_analysis(bridge, 0.0)
    today = limit_analysis(bridge, verify=True)
    assert (r.k_l, r.k_r) == (today.k_l, today.k_r)
    assert (r.k0_l, r.k0_r) == (today.k_l, today.k_r)
    assert r.left is None and r.right is None


def test_program_without_pressure_is_the_static_optimum(bridge, base):
    """The extended program with every face's resultant zero is the joint-line LP."""
    vi, sg, R, yh = _faces(bridge, FillPressure(LEVEL, RHO, 0.1))
    fd = _solve(bridge, "l", (vi, sg, 0.0 * R, yh), 1.0)
    assert fd.k == pytest.approx(base.static_k_l, rel=1e-9)


def test_face_resultants_closed_form(bridge):
    """Rising faces (left half) carry c ((L - y_s)^2 - (L - y_c)^2) / 2 with c = kappa K_p rho g,
    y_s the extrados's springing and y_c its crown; both halves balance on a symmetric arch."""
    fp = FillPressure(LEVEL, RHO, 0.5, 30.0)
    vi, sg, R, yh = _faces(bridge, fp)
    ext = np.vstack(bridge.extrados)
    y_s, y_c = float(ext[0, 1]), float(np.max(ext[:, 1]))
    c = 0.5 * 3.0 * RHO * 9.80665
    z_s, z_c = LEVEL - y_s, LEVEL - y_c
    assert np.sum(R[sg > 0]) == pytest.approx(c * (z_s ** 2 - z_c ** 2) / 2, rel=1e-12)
    assert np.sum(R[sg < 0]) == pytest.approx(np.sum(R[sg > 0]), rel=1e-12)
    # the centroid of the pressure on the whole rising side: int (L - y) y dy / int (L - y) dy
    ybar = (LEVEL * (y_c ** 2 - y_s ** 2) / 2 - (y_c ** 3 - y_s ** 3) / 3) / ((z_s ** 2 - z_c ** 2) / 2)
    left = sg > 0
    assert np.sum(R[left] * yh[left]) / np.sum(R[left]) == pytest.approx(ybar, rel=1e-12)


def test_k_grows_with_the_coefficient(bridge, base):
    ks = [fill_pressure_analysis(bridge, kap, base=base).k for kap in (0.0, 0.05, 0.2, 0.5)]
    assert all(b > a + 1e-3 for a, b in zip(ks, ks[1:]))


def test_mechanism_virtual_work_equals_the_program(pressed):
    for fd in (pressed.left, pressed.right):
        assert fd.work_multiplier == pytest.approx(fd.k, rel=1e-9)
        assert fd.consistent
        assert fd.loaded  # the pressure acts somewhere


def test_the_optimum_as_fixed_forces_is_its_own_fixed_point(bridge, pressed):
    """The soil's forces of the optimum, applied as fixed forces (not load-proportional) in the
    plain joint-line program, give the same multiplier: the loaded side is stable."""
    from scipy.optimize import linprog

    from archrock.statics.fill import _Pressed
    from archrock.statics.sums import _origin

    for fd in (pressed.left, pressed.right):
        W = float(np.sum(bridge.masses)) * 9.80665
        r = fd.sign * fd.resultant * 1e3 / W * fd.fraction
        st0 = _Pressed(bridge, fd.direction, np.zeros(bridge.n + 1), 0.0, 0.0)
        y = (fd.height - _origin(bridge)[1]) / bridge.reference_length
        n1 = bridge.n + 1
        left = (fd.voussoir[None, :] < np.arange(n1)[:, None]).astype(float)
        py = -st0.A_m[:, 0]                      # the joints' intrados ends
        st = _Pressed(bridge, fd.direction, left @ r, st0.A_N[:, 0] * (left @ r),
                      left @ (r * y) - py * (left @ r))
        res = linprog([0, 0, 0, -1.0], A_ub=st.A_ub, b_ub=st.b_ub, bounds=[(None, None)] * 4,
                      method="highs")
        assert res.status == 0
        assert res.x[3] == pytest.approx(fd.k, rel=1e-9)


def _rot(w, c, p):
    """Velocity of points p (k, 2) of a body turning at w about c."""
    d = np.asarray(p, float) - c
    return w * np.column_stack([-d[:, 1], d[:, 0]])


def test_four_hinge_virtual_work_by_instant_centres(bridge, pressed):
    """k of the governing four-hinge mechanism, redone by hand: three links turning about the
    two outer hinges and the inner link's instant centre, the pressure integrated along every
    face (Gauss points) on the faces the motion drives into the soil."""
    fd = pressed.left
    m = fd.mechanism
    assert m.is_four_hinge
    jp = np.asarray(bridge.joint_points, float)
    H = [jp[h.joint, 0 if h.edge == "intrados" else 1] for h in m.hinges]
    a, b, c_, d = (h.joint for h in m.hinges)
    # instant centre of the middle link: lines H1H2 and H3H4
    M = np.column_stack([H[1] - H[0], -(H[3] - H[2])])
    s = np.linalg.solve(M, H[2] - H[0])
    ic = H[0] + s[0] * (H[1] - H[0])
    wA = 1.0
    wB = wA * np.dot(H[1] - H[0], H[1] - ic) / np.dot(H[1] - ic, H[1] - ic)
    wC = wB * np.dot(H[2] - ic, H[2] - H[3]) / np.dot(H[2] - H[3], H[2] - H[3])
    motion = []
    for i in range(bridge.n):
        motion.append((wA, H[0]) if i < b else (wB, ic) if i < c_ else (wC, H[3]))
    masses = np.asarray(bridge.masses, float)
    G = np.asarray(bridge.centroids, float)
    v = np.vstack([_rot(w, cc, G[i:i + 1]) for i, (w, cc) in enumerate(motion)])
    horiz = float(masses @ v[:, 0])
    sgn = 1.0 if horiz > 0 else -1.0          # direction 'l': the loads push toward +x
    v, horiz = sgn * v, sgn * horiz
    weight = -float(masses @ v[:, 1])
    # the pressure, per face (a run of rising or falling segments), kappa K_p rho (L - y) [kg/m^2]
    cst = 0.1 * 3.0 * RHO
    gx, gw = np.polynomial.legendre.leggauss(4)
    press = 0.0
    for i, e in enumerate(bridge.extrados):
        w, cc = motion[i]
        for sign in (1.0, -1.0):
            work = 0.0
            for p0, p1 in zip(e[:-1], e[1:]):
                y0, y1 = min(p0[1], LEVEL), min(p1[1], LEVEL)
                if sign * (y1 - y0) <= 0:
                    continue
                t = (gx + 1) / 2
                pts = p0 + t[:, None] * (p1 - p0)
                ys = y0 + t * (y1 - y0)
                vx = sgn * _rot(w, cc, pts)[:, 0]
                # horizontal force sign * p |dy| on the face, pushing toward sign * x
                work += sign * np.sum(gw / 2 * cst * (LEVEL - ys) * vx) * abs(y1 - y0)
            press += min(work, 0.0)           # the soil resists; it never pulls
    k = (-weight - press) / horiz
    assert k == pytest.approx(fd.k, rel=1e-8)


def test_mirror_symmetry():
    """k_l of the mirrored arch is k_r of the arch (an arch made asymmetric by a load)."""
    arch = family_arch("circular", 10.0, 3.0, 0.5, 9, fill={"level": LEVEL, "density": RHO},
                       loads=[{"voussoir": 2, "mass": 800.0, "at": [-3.0, 3.0]}])
    fp = FillPressure(LEVEL, RHO, 0.2, 30.0)
    r = fill_pressure_analysis(arch, 0.2)
    mir = fill_pressure_analysis(arch.mirrored(), 0.2, pressure=fp)
    assert abs(r.k_l - r.k_r) > 1e-3                       # really asymmetric
    assert mir.k_l == pytest.approx(r.k_r, rel=1e-9)
    assert mir.k_r == pytest.approx(r.k_l, rel=1e-9)


def test_errors_name_the_field(bridge):
    with pytest.raises(ArchInputError, match="^fc: 5.0 MPa; the fill's passive pressure"):
        fill_pressure_analysis(bridge.with_fc(5.0), 0.3)
    with pytest.raises(ArchInputError, match="^fill: the arch has no fill"):
        fill_pressure_analysis(family_arch("circular", 10.0, 3.0, 0.5, 9, exact=False), 0.3)
    for kw, field in (({"kappa": -0.1}, "kappa"), ({"kappa": math.nan}, "kappa"),
                      ({"kappa": 0.3, "phi_deg": 90.0}, "phi"),
                      ({"kappa": 0.3, "density": 0.0}, "fill density")):
        args = {"level": LEVEL, "density": RHO, **kw}
        with pytest.raises(ArchInputError, match=f"^{field}: "):
            FillPressure(**args)

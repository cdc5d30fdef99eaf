"""Studies by the contact engine where one degree of freedom cannot follow the arch (issue 19,
archrock.studies.enginestudy, docs/piers-dynamics.md): the routing, the engine ensemble's
summary, the first-collapse bisection, and rigid ground left exactly as it was."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from archrock.cli import main
from archrock.errors import ArchInputError
from archrock.geometry import nominal_arch
from archrock.geometry.files import read_arch
from archrock.groundmotion import PulseSpec
from archrock.studies import enginestudy as es
from archrock.studies.ensemble import engine as ee
from archrock.studies.ensemble import EnsembleConfig, EnsembleResult, run_ensemble
from archrock.studies.fragility import collapse_probability
from archrock.studies.runner import RunSettings

pytest.importorskip("pymunk")


@pytest.fixture(scope="module")
def heavy_arch(heavy_piers_file):
    return read_arch(heavy_piers_file)


def test_routing_picks_the_engine_on_heavy_piers_and_four_link_on_rigid_ground(heavy_arch):
    ch = es.choose_dynamics(heavy_arch)
    assert ch.used == "engine" and ch.engine and ch.requested == "auto"
    assert ch.reason.startswith("single degree of freedom not valid")
    assert ch.single_dof["valid"] is False and ch.single_dof["piers"] == [0, 13]
    rigid = es.choose_dynamics(nominal_arch())
    assert rigid.used == "fourlink" and not rigid.engine and rigid.single_dof is None
    assert "no piers" in rigid.reason
    # asked for: as asked, the check's verdict still said
    forced = es.choose_dynamics(heavy_arch, "fourlink")
    assert forced.used == "fourlink" and "WARNING single degree of freedom not valid" in forced.reason
    assert es.choose_dynamics(nominal_arch(), "engine").used == "engine"
    assert json.loads(json.dumps(ch.to_dict()))["used"] == "engine"


def test_routing_keeps_four_link_where_the_piers_stay_still():
    """Low, wide piers stay still in both limit mechanisms (docs/piers-dynamics.md: 1 x 3 m
    piers under the R = 5 m semicircle): one degree of freedom is valid, so the four-link."""
    from archrock.geometry.piers import with_piers

    arch = with_piers(nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9), 1.0, 3.0)
    ch = es.choose_dynamics(arch)
    assert ch.used == "fourlink" and ch.single_dof["valid"] is True
    assert "stay still" in ch.reason


@pytest.mark.parametrize("bad", ["Engine", "dem", "", None, 1, True])
def test_a_bad_dynamics_value_is_refused_naming_the_field(bad):
    with pytest.raises(ArchInputError, match=r"^dynamics: .*allowed one of auto, fourlink, engine"):
        es.check_dynamics(bad)
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=2)
    with pytest.raises(ArchInputError, match=r"^dynamics: "):
        run_ensemble(cfg, dynamics=bad)


def test_the_cli_refuses_a_bad_dynamics_value(capsys):
    assert main(["ensemble", "--samples", "2", "--dynamics", "dem"]) == 2
    assert "--dynamics: invalid choice: 'dem'" in capsys.readouterr().err


def test_auto_on_rigid_ground_is_the_four_link_ensemble_bit_for_bit():
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=100, seed=3,
                                   motion=PulseSpec("oppenheim", -1.0, 0.2))
    auto = run_ensemble(cfg)
    four = run_ensemble(cfg, dynamics="fourlink")
    assert isinstance(auto, EnsembleResult)
    import pandas as pd

    pd.testing.assert_frame_equal(auto.frame, four.frame, check_exact=True)
    sa = auto.summary()
    assert "dynamics" not in sa["nominal"]  # rigid ground under auto: the summary as before
    assert four.summary()["nominal"]["dynamics"]["requested"] == "fourlink"
    assert sa["p_collapse"] == four.summary()["p_collapse"]
    assert 0 < sa["p_collapse"]["collapses"] < 100


@pytest.mark.slow
def test_auto_keeps_the_published_ten_thousand_arch_ensemble():
    """docs/ensemble.md: 2803 collapses of 10,000 arches around Oppenheim's arch, paper pulse."""
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=10000, seed=0,
                                   motion=PulseSpec("oppenheim", -1.0, 0.2))
    s = run_ensemble(cfg).summary()
    assert s["p_collapse"]["collapses"] == 2803 and s["p_collapse"]["trials"] == 10000


def _check_counts(res, cfg):
    """The engine ensemble's summary: every count from the rows, the interval two ways."""
    s = res.summary()
    n = cfg.samples
    assert s["how"] == "contact engine"
    oc = s["outcomes"]
    assert oc["samples"] == n and oc["integrated"] + oc["failed"] == n
    assert sum(oc["status"].values()) == oc["integrated"]
    pc = s["p_collapse"]
    assert pc["collapses"] == oc["status"]["collapsed"] and pc["trials"] == oc["integrated"]
    assert pc["collapses"] == sum(r["collapsed"] for r in res.rows)
    # the Wilson interval of scipy's binomtest and the fragility module's own agree
    p, lo, hi = collapse_probability(pc["collapses"], pc["trials"], 0.95, "wilson")
    assert math.isclose(pc["p"], p, rel_tol=1e-12)
    assert math.isclose(pc["low"], lo, rel_tol=1e-9, abs_tol=1e-12)
    assert math.isclose(pc["high"], hi, rel_tol=1e-9, abs_tol=1e-12)
    assert [r["index"] for r in res.rows] == list(range(n))
    assert json.loads(json.dumps(s))["samples"] == n
    return s


def test_engine_ensemble_counts_on_a_tiny_coarse_ensemble(heavy_arch):
    """Three irregular arches on the heavy piers, a coarse engine (100 steps per T, 10
    iterations, 3 T of free motion: fast, not converged) so that the test runs in seconds."""
    from archrock.contact import EngineSettings

    cfg = EnsembleConfig.from_arch(heavy_arch, samples=3, seed=1,
                                   motion=PulseSpec("oppenheim", -1.5, 0.2),
                                   spreads={"spread_span": 0.0})
    run = es.EngineRun(EngineSettings(steps_per_T=100, iterations=10), t_free=3.0)
    lines = []
    res = ee.engine_ensemble(cfg, run, progress=lines.append)
    s = _check_counts(res, cfg)
    assert len(lines) == 3 and lines[-1].startswith("engine ensemble: arch 3/3")
    assert s["engine"]["settings"]["steps_per_T"] == 100.0 and s["dynamics"] is None


@pytest.mark.slow
def test_engine_ensemble_summary_counts_are_consistent(heavy_arch):
    """Four irregular arches on the heavy piers under a strong pulse (1.5 g: every one collapses
    within a second or two of simulated time), routed by run_ensemble."""
    from archrock.dynamics.response import prepare
    from archrock.studies.ensemble import sample_arch

    cfg = EnsembleConfig.from_arch(heavy_arch, samples=4, seed=1,
                                   motion=PulseSpec("oppenheim", -1.5, 0.2),
                                   spreads={"spread_span": 0.0})
    lines = []
    res = run_ensemble(cfg, settings=RunSettings(progress=lines.append))
    assert isinstance(res, ee.EngineEnsembleResult)
    s = _check_counts(res, cfg)
    assert s["dynamics"]["used"] == "engine"
    pc = s["p_collapse"]
    # row i is sample i of the four-link ensemble (the same arch)
    assert math.isclose(res.rows[2]["k_l"], prepare(sample_arch(cfg, 2), "momentum").k_l,
                        rel_tol=1e-12)
    assert pc["collapses"] == 4  # 1.5 g is twice the nominal arch's engine first collapse
    assert s["engine"]["settings"]["steps_per_T"] == 400.0
    assert s["timing"]["estimate_s"] > 0 and s["timing"]["wall_s"] > 0


def test_engine_ensemble_refuses_what_it_cannot_run():
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=2)
    with pytest.raises(ArchInputError, match="^motion: None"):
        ee.engine_ensemble(cfg)
    cfg = EnsembleConfig.from_arch(nominal_arch(), samples=2, motion=PulseSpec("oppenheim", -1.0, 0.2))
    with pytest.raises(ArchInputError, match="^engine: "):
        ee.engine_ensemble(cfg, engine={"t_free": 3})
    with pytest.raises(ArchInputError, match="^engine: "):
        run_ensemble(cfg, dynamics="engine", engine="fast")
    with pytest.raises(ArchInputError, match="^progress: "):
        ee.engine_ensemble(cfg, progress="yes")


def test_engine_run_round_trips_and_refuses_bad_fields():
    from archrock.contact import EngineSettings

    run = es.EngineRun(EngineSettings(restitution=0.3), t_free=5, collapse_drop=0.1)
    again = es.EngineRun.from_dict(json.loads(json.dumps(run.to_dict())))
    assert again == run and again.settings.restitution == pytest.approx(0.3, rel=1e-15)
    for bad, field in (({"t_free": -1}, "t_free"), ({"collapse_drop": 0}, "collapse_drop"),
                       ({"settings": 3}, "settings")):
        with pytest.raises(ArchInputError, match=f"^{field}: "):
            es.EngineRun(**bad)
    with pytest.raises(ArchInputError, match="allowed fields settings"):
        es.EngineRun.from_dict({"steps": 3})


class _Step:
    """A stand-in engine: collapse exactly from |a| >= edge (a step function of the amplitude)."""

    def __init__(self, edge):
        self.edge, self.calls = edge, []

    def __call__(self, arch, motion, model=None):
        from types import SimpleNamespace

        from archrock.units import G

        a = float(np.max(np.abs(motion.accel))) / G
        self.calls.append(a)
        return SimpleNamespace(collapsed=a >= self.edge)


def test_first_collapse_bisection_finds_a_known_edge_within_its_relative_tolerance(monkeypatch):
    """The search itself, against an engine that collapses exactly from 0.7 g: the bracket
    holds the edge, is rtol wide relative to it, and the runs stay within the bound."""
    arch = nominal_arch()
    step = _Step(0.7)
    monkeypatch.setattr(es.EngineRun, "respond", lambda self, a, m, model=None: step(a, m))
    for rtol in (0.05, 0.01, 1e-3):
        step.calls.clear()
        r = es.engine_first_collapse(arch, 0.2, a_max=3.0, n_scan=8, rtol=rtol)
        lo, hi = r.bracket
        assert lo < 0.7 <= hi and hi - lo <= rtol * hi
        assert r.amplitude == hi and r.how == "contact engine"
        assert r.n_responses == len(step.calls) <= 8 + math.ceil(math.log2(1 / rtol)) + 1
        assert r.threshold == pytest.approx(0.3700, abs=1e-4)  # k of Oppenheim's arch
        assert r.scan_collapsed[-1] and not any(r.scan_collapsed[:-1])
    # nothing collapses up to a_max: None, the whole scan run
    step.edge = 5.0
    r = es.engine_first_collapse(arch, 0.2, a_max=3.0, n_scan=5, rtol=0.01)
    assert r.amplitude is None and r.bracket is None and r.n_responses == 5
    # collapse at the first grid point: the activation threshold is the lower end
    step.edge = 0.0
    r = es.engine_first_collapse(arch, 0.2, a_max=3.0, n_scan=5, rtol=0.01)
    assert r.bracket[0] == pytest.approx(0.37, abs=1e-3) and r.n_responses == 1


def test_engine_collapse_curve_is_a_collapse_curve(monkeypatch):
    from archrock.studies.curves import CollapseCurve

    step = _Step(0.9)
    monkeypatch.setattr(es.EngineRun, "respond", lambda self, a, m, model=None: step(a, m))
    c = es.engine_collapse_curve(nominal_arch(), (0.2, 0.5), rtol=0.02)
    assert isinstance(c, CollapseCurve) and c.cv is None
    assert np.all(np.abs(c.amplitudes - 0.9) <= 0.02 * 0.92)
    d = c.to_dict()
    assert [p["how"] for p in d["points"]] == ["contact engine"] * 2
    assert "scan_amplitudes_g" not in d["points"][0]


@pytest.mark.parametrize("kw, field", [({"rtol": 0.0}, "rtol"), ({"rtol": 0.9}, "rtol"),
                                       ({"a_max": 0.3}, "a_max"), ({"n_scan": 1}, "n_scan"),
                                       ({"sign": 2}, "sign")])
def test_first_collapse_refuses_bad_input_naming_the_field(kw, field):
    with pytest.raises(ArchInputError, match=f"^{field}"):
        es.engine_first_collapse(nominal_arch(), 0.2, **kw)


@pytest.mark.slow
def test_engine_first_collapse_on_heavy_piers(heavy_arch):
    """docs/piers-dynamics.md: the engine's first collapse under Oppenheim's pulse, t_p = 0.2
    s, 0.71 g (archrock's engine; pymunk's was 0.70 g), against the four-link model's 3.02 g."""
    r = es.engine_first_collapse(heavy_arch, 0.2, a_max=3.0, n_scan=8, rtol=0.01)
    assert 0.68 <= r.amplitude <= 0.72
    assert r.bracket[1] - r.bracket[0] <= 0.01 * r.bracket[1]


@pytest.mark.slow
def test_the_cli_runs_the_engine_on_heavy_piers(heavy_piers_file, capsys):
    heavy = str(heavy_piers_file)
    assert main(["ensemble", "--geometry", heavy, "--spread-span", "0", "--samples", "2",
                 "--pulse", "oppenheim", "--amplitude", "-1.5", "--pulse-duration", "0.2",
                 "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "computed by the contact engine: single degree of freedom not valid" in out
    assert "P(collapse | run) = 1.0000" in out
    assert main(["ensemble", "--geometry", heavy, "--spread-span", "0", "--samples", "2",
                 "--pulse", "oppenheim", "--amplitude", "-1.5", "--pulse-duration", "0.2",
                 "--no-progress", "--dynamics", "fourlink"]) == 0
    out = capsys.readouterr().out
    assert "dynamics: four-link model: asked for" in out and "WARNING" in out


def test_the_curves_command_routes_heavy_piers_to_the_engine(heavy_piers_file, monkeypatch,
                                                              capsys):
    """`archrock curves` on the heavy piers: the engine's bisection (here a stand-in engine
    that collapses from 0.7 g), with the reason; --samples refused; --dynamics fourlink keeps
    the four-link curve."""
    step = _Step(0.7)
    heavy = str(heavy_piers_file)
    monkeypatch.setattr(es.EngineRun, "respond", lambda self, a, m, model=None: step(a, m))
    assert main(["curves", "--geometry", heavy, "--durations", "0.2", "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "by the contact engine" in out and "why the engine: single degree of freedom not valid" in out
    row = [ln for ln in out.splitlines() if ln.strip().startswith("0.2")][0]
    amp = float(row.split()[1])
    assert 0.7 <= amp <= 0.7 / (1 - 0.01)
    assert main(["curves", "--geometry", heavy, "--durations", "0.2", "--no-progress",
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["how"] == "contact engine" and d["dynamics"]["used"] == "engine"
    assert main(["curves", "--geometry", heavy, "--durations", "0.2", "--samples", "2",
                 "--no-progress"]) == 2
    assert "--samples: the engine curve is of the nominal arch only" in capsys.readouterr().err


def test_the_single_dof_reason_points_to_the_engine(heavy_arch):
    from archrock.dynamics.piers import single_dof_check
    from archrock.dynamics.response import prepare

    reason = single_dof_check(prepare(heavy_arch, 0.8)).reason
    assert "3.02 g against the contact engine's 0.71 g" in reason
    assert "studies and the report do so by default" in reason


def test_the_report_takes_the_collapse_curve_from_the_engine_with_the_reason(monkeypatch,
                                                                              heavy_arch):
    from archrock.studies.assessment import AssessConfig, Context, Paragraph, section_curves

    step = _Step(0.7)
    monkeypatch.setattr(es.EngineRun, "respond", lambda self, a, m, model=None: step(a, m))
    sec = section_curves(Context(heavy_arch, AssessConfig(durations=(0.2, 0.5), samples=0)))
    assert sec.key == "curves" and sec.data["how"] == "contact engine"
    assert sec.data["dynamics"]["used"] == "engine"
    text = " ".join(b.text for b in sec.blocks if isinstance(b, Paragraph))
    assert "computed by the contact engine" in text and "single degree of freedom not valid" in text
    amps = sec.data["nominal"]["amplitudes_g"]
    assert len(amps) == 2 and all(0.7 <= a <= 0.7 / (1 - 0.02) for a in amps)
    # the figure draws the engine's curve as any collapse curve
    from archrock.reports.html import FIGURES

    fig = FIGURES["curves"](next(b for b in sec.blocks if hasattr(b, "payload")).payload)
    assert fig.axes[0].get_ylabel().startswith("first collapse")


@pytest.mark.slow
def test_a_four_link_ensemble_on_piers_carries_the_choice():
    """Low wide piers stay still: auto keeps the four-link ensemble, and its summary says why
    (nominal.dynamics); the engine asked for by name runs the engine on the same arches."""
    from archrock.contact import EngineSettings
    from archrock.geometry.piers import with_piers

    arch = with_piers(nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9), 1.0, 3.0)
    cfg = EnsembleConfig.from_arch(arch, samples=2, motion=PulseSpec("oppenheim", -0.3, 0.2),
                                   spreads={"spread_span": 0.0})
    res = run_ensemble(cfg)
    assert isinstance(res, EnsembleResult)
    d = res.summary()["nominal"]["dynamics"]
    assert d["requested"] == "auto" and d["used"] == "fourlink" and d["single_dof"]["valid"]
    eng = run_ensemble(cfg, dynamics="engine",
                       engine=es.EngineRun(EngineSettings(steps_per_T=50, iterations=5),
                                           t_free=1.0))
    s = eng.summary()
    assert s["how"] == "contact engine" and s["dynamics"]["reason"].startswith("asked for")
    assert [r["k_l"] for r in eng.rows] == pytest.approx(res.frame["k_l"].tolist(), rel=1e-9)


def test_choose_dynamics_routes_sliding_joints_to_the_engine(oppenheim):
    """Oppenheim's arch needs mu >= 0.495 to rock without sliding (docs/friction.md): at the
    default 0.8 the four-link model follows it, at 0.4 the engine does, with sliding excluded
    (None) the four-link model again; the four-link model asked for by name at 0.4 is labelled
    not valid."""
    from archrock.studies.enginestudy import choose_dynamics

    default = choose_dynamics(oppenheim.arch)
    assert default.used == "fourlink" and default.friction == pytest.approx(0.8)
    assert default.friction_needed["l"] == pytest.approx(0.49513, abs=1e-4)
    low = choose_dynamics(oppenheim.arch, friction=0.4)
    assert low.used == "engine" and "0.495" in low.reason and "mu = 0.4" in low.reason
    assert choose_dynamics(oppenheim.arch, friction=None).used == "fourlink"
    asked = choose_dynamics(oppenheim.arch, "fourlink", friction=0.4)
    assert asked.used == "fourlink" and "not valid here" in asked.reason
    with pytest.raises(ArchInputError, match="friction"):
        choose_dynamics(oppenheim.arch, friction=-1.0)


def test_the_engine_scan_starts_where_its_joints_move(oppenheim):
    """The first-collapse scan starts at the activation of the engine's friction: at mu = 0.8
    the four-link multipliers themselves, at mu = 0.4 the friction analysis's 0.2638 (the
    joints slide before the hinges open at 0.3700)."""
    from archrock.dynamics.response import prepare

    model = prepare(oppenheim.arch, "momentum")
    high = es.activation(oppenheim.arch, model, 0.8)
    assert high == {"l": float(model.k_l), "r": float(model.k_r)}
    low = es.activation(oppenheim.arch, model, 0.4)
    assert low["l"] == pytest.approx(0.26376, abs=1e-4) and low["r"] == pytest.approx(low["l"], rel=1e-9)

"""Survival windows say the resolution they were searched at, and those found have refined edges
(issue 30: Oppenheim's arch at t_p = 1 s survives between 0.46439 and 0.46508 g, a window the
default grid, stepping 2.2%, steps over)."""

import json

import numpy as np
import pytest

from archrock.dynamics.response import prepare, respond
from archrock.geometry import oppenheim_arch
from archrock.groundmotion import pulse
from archrock.studies.curves import WINDOW_RTOL, collapse_curve

#: the window as a fine scan of respond finds it (issue 30), to 1e-5 g
WINDOW = (0.46439, 0.46508)


@pytest.fixture(scope="module")
def model():
    return prepare(oppenheim_arch())


def fine_scan(model, lo, hi, step=1e-5):
    """The surviving amplitudes of a direct scan of respond (the independent reference)."""
    a = np.arange(lo, hi, step)
    c = np.array([respond(model, pulse("oppenheim", -x, 1.0), t_end=0.5, dt_out=0.5).collapsed
                  for x in a])
    return a[~c]


def coarse_grid_a_max(model, inside=0.46475, n_scan=5):
    """a_max of a 5-point geometric grid from the threshold whose 4th point falls at ``inside``."""
    thr = model.k_l * (1 + 1e-6)
    r = (inside / thr) ** (1.0 / (n_scan - 2))
    return inside * r


@pytest.mark.parametrize("engine", ["batch", "respond"])
def test_a_window_found_on_a_coarse_grid_has_the_edges_of_a_fine_scan(model, engine):
    a_max = coarse_grid_a_max(model)
    curve = collapse_curve(model, [1.0], a_max=a_max, n_scan=5, tol=1e-3, engine=engine)
    p = curve.points[0]
    assert p.scan_amplitudes[3] == pytest.approx(0.46475, rel=1e-12)
    assert list(p.scan_collapsed) == [False, True, True, False, True]
    assert len(p.windows) == 1
    lo, hi = p.windows[0]
    surv = fine_scan(model, 0.4640, 0.4655)
    assert surv.size > 10 and np.all(np.diff(surv) < 1.5e-5)  # one window, no gaps
    edge = WINDOW_RTOL * 0.47 + 1e-5  # the edges' tolerance and the scan's step
    assert lo == pytest.approx(surv[0], abs=edge) and hi == pytest.approx(surv[-1], abs=edge)
    assert lo == pytest.approx(WINDOW[0], abs=edge) and hi == pytest.approx(WINDOW[1], abs=edge)
    # the edges are survivals, and just outside them the arch collapses
    for a in (lo, hi):
        assert not respond(model, pulse("oppenheim", -a, 1.0), t_end=0.5, dt_out=0.5).collapsed
    for a in (lo - edge, hi + edge):
        assert respond(model, pulse("oppenheim", -a, 1.0), t_end=0.5, dt_out=0.5).collapsed
    # a window 0.0007 g wide, narrower than tol = 0.001 g, still has edges of its own
    assert 0.5e-3 < hi - lo < 1e-3


def test_every_list_of_windows_states_its_resolution(model):
    """The default grid steps over the window: the list is empty, and the JSON says the grid
    step (about 2.2%, ~0.0085 g at the first collapse 0.382 g) under which one may be missed."""
    curve = collapse_curve(model, [1.0], a_max=10.0, n_scan=150, tol=1e-3)
    p = curve.points[0]
    assert p.windows == ()
    d = json.loads(json.dumps(curve.to_dict()))
    res = d["windows_resolution"][0]
    assert d["points"][0]["windows_resolution"] == res
    assert res["step_relative"] == pytest.approx((10.0 / (model.k_l * (1 + 1e-6))) ** (1 / 149) - 1,
                                                 rel=1e-9)
    assert 0.02 < res["step_relative"] < 0.025
    assert res["step_g"] == pytest.approx(p.amplitude * res["step_relative"], rel=0.05)
    assert res["step_g"] > WINDOW[1] - WINDOW[0]  # why the window is missed
    assert res["step_g_at_a_max"] == pytest.approx(10.0 * res["step_relative"] / (1 + res["step_relative"]),
                                                   rel=1e-9)
    assert "windows narrower than" in res["note"] and "may be missed" in res["note"]


def test_cli_curves_text_states_the_resolution(capsys):
    from archrock.cli import main

    code = main(["curves", "--durations", "1", "--n-scan", "40", "--a-max", "2", "--no-progress"])
    out = capsys.readouterr().out
    assert code == 0
    line = [x for x in out.splitlines() if x.startswith("survival windows searched")]
    assert len(line) == 1
    assert "geometric grid of 40 points stepping 4.4% of |a|: windows narrower than" in line[0]
    assert line[0].endswith("edges of those found bisected to min(0.001, 0.0001 |a|) g")


def test_curves_progress_ends_at_100_percent(monkeypatch):
    """The curves' total counts ~3 bisections of 11 steps per curve; the count itself is
    smaller and the last line still reads 100% (it stopped at ~80% in 0.6)."""
    import archrock.studies.curves as curves
    from archrock.studies.runner import RunSettings

    monkeypatch.setattr(curves, "PROGRESS_S", -1.0)  # always show progress
    got = []
    curves.ensemble_curve(oppenheim_arch(), 1, durations=[0.5], n_scan=10, a_max=2.0,
                          settings=RunSettings(progress=got.append))
    lines = [x for x in got if x.startswith("curves: ")]
    assert lines[-1].endswith("(100%)"), got
    done, total = map(int, lines[-1].split()[1].split("/"))
    assert done == total < 2 * (10 + 3 * 11)  # below the estimate the bar was sized for

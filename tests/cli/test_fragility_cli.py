"""`archrock fragility`: results written before any figure, and no figure ends a run (issue 30)."""

import json

import numpy as np
import pytest

from archrock.cli import main


@pytest.fixture(scope="module")
def weak_record(tmp_path_factory):
    """A 3 s record of 0.3 g peak at 1.5 Hz that does not collapse the nominal arch up to 2x."""
    t = np.arange(0, 3.0, 0.01)
    rec = tmp_path_factory.mktemp("rec") / "weak.txt"
    np.savetxt(rec, np.column_stack([t, 0.3 * np.sin(2 * np.pi * 1.5 * t)
                                     * np.sin(np.pi * t / 3.0) ** 2]))
    return rec


def _run(capsys, rec, *extra):
    code = main(["fragility", "--records", str(rec), "--scales", "1,2", "--levels", "0.3,0.6",
                 "--bootstrap", "0", "--no-progress", *extra])
    out, err = capsys.readouterr()
    return code, out, err


def test_no_collapse_writes_results_then_a_figure(capsys, tmp_path, weak_record):
    """No record collapses the arch: exit 0, the JSON on stdout, and a figure that states
    'no collapse up to <IM>' (it ended in a traceback after the whole IDA in 0.6)."""
    fig = tmp_path / "f.png"
    code, out, err = _run(capsys, weak_record, "--json", "--plot", str(fig))
    assert code == 0, err
    assert "Traceback" not in err and "warning" not in err
    d = json.loads(out)
    assert d["ida"]["n_censored"] == d["ida"]["n_curves"] == 1
    assert d["ida"]["fit"] is None and d["stripes"]["collapses"] == [0, 0]
    rng = d["ida"]["range_tried"]
    assert rng["n_never"] == rng["n_curves"] == 1
    assert rng["max_im"] == pytest.approx(0.6, rel=1e-3)  # 2 x the record's 0.3 g
    assert rng["p_upper_95"] == pytest.approx(0.95, rel=1e-9)  # 1 - 0.05^(1/1)
    assert fig.stat().st_size > 10_000
    import matplotlib.pyplot as plt
    from archrock.reports.plots import plot_fragility
    from archrock.studies.ida import ida
    from archrock.geometry import nominal_arch
    from archrock.groundmotion.suite import read_records

    res = ida(read_records([str(weak_record)]).records, nominal_arch(), [1.0, 2.0])
    f = plot_fragility(None, None, None, ida=res)
    labels = [t.get_text() for t in f.axes[0].get_legend().get_texts()]
    assert any(lab.startswith("IDA: no collapse up to 0.6") for lab in labels), labels
    plt.close(f)


def test_a_failing_figure_is_a_warning_and_the_results_stay(capsys, tmp_path, weak_record,
                                                             monkeypatch):
    """Whatever a figure raises, the run ends with exit 0, the results printed before it and
    one warning line on stderr."""
    import archrock.reports.plots as plots

    def broken(*a, **k):
        raise ValueError("x and y must have same first dimension")

    monkeypatch.setattr(plots, "plot_fragility", broken)
    code, out, err = _run(capsys, weak_record, "--plot", str(tmp_path / "g.png"))
    assert code == 0
    assert out.startswith("Oppenheim: 1 record(s) x 1 arch(es)") and "stripes: " in out
    assert "IDA: no collapse up to 0.6000 g in 1 curve(s): P(collapse) <= 0.950" in out
    assert err.splitlines() == [f"archrock: warning: figure {tmp_path / 'g.png'} not written "
                                "(ValueError: x and y must have same first dimension); the "
                                "results above are complete"]
    assert not (tmp_path / "g.png").exists()


def test_report_states_the_plateau_and_the_json_carries_it(levelling_ida):
    """Where the data level off, the text gives p_max and the sentence of the test, the JSON
    the fit's p_max and level_off (synthetic IDA: 45% of 300 records never collapse)."""
    from archrock.reports.fragility import format_fragility
    from archrock.studies.fragility import fit_stripes_mle
    from archrock.studies.ida import StripeResult

    x, res = levelling_ida
    curves = res.curves
    lv = np.array([0.2, 0.4, 0.8])
    z = np.array([int(np.sum(x <= v)) for v in lv])
    st = StripeResult(lv, np.full(3, 300), z, np.zeros((3, 1, 300), bool), "pga",
                      fit_stripes_mle(lv, np.full(3, 300), z, plateau="auto"), None,
                      tuple(c.record for c in curves), (0,))
    text = format_fragility(res, st, arch_name="A", n_records=300, n_arches=1, n_requested=0)
    never = int(np.sum(np.isinf(x)))
    assert f"IDA: {never} of 300 curves never collapse up to 1.0000 g" in text
    assert f"IDA: censored_mle theta = {res.fit.theta:.4f} g, beta = {res.fit.beta:.3f}, " \
           f"p_max = {res.fit.p_max:.3f} (n = 300)" in text
    assert "  the data level off below P = 1: fitted with an upper asymptote p_max" in text
    d = json.loads(json.dumps(res.to_dict()))
    assert d["fit"]["p_max"] == pytest.approx(1 - never / 300, abs=0.01)
    assert d["fit"]["level_off"]["levels_off"] is True
    assert d["range_tried"] == {"max_im": 1.0, "n_never": never, "n_curves": 300,
                                "p_upper_95": None}

"""The command line: real values from in-process runs of main(), plus one run of the installed script."""

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from archrock.cli import SUBCOMMANDS, add_geometry_options, arch_from_args, main
from archrock.geometry.files import read_arch
from archrock.geometry import random_arch
from archrock.statics.limit import limit_analysis, minimum_thickness
from archrock.studies.enginestudy import choose_dynamics

OPPENHEIM_FLAGS = ["--radius", "10", "--embrace", "157.5", "--thickness", "1.5", "--voussoirs", "7"]
# Fig. 3 of the paper / docs/method.md, Limit analysis: hinges ordered from the left springing.
HINGES_L = [{"joint": 0, "edge": "intrados"}, {"joint": 3, "edge": "extrados"},
            {"joint": 5, "edge": "intrados"}, {"joint": 7, "edge": "extrados"}]
# M_r is the mirror image of M_l on a symmetric arch (joint j -> 7 - j).
HINGES_R = [{"joint": 0, "edge": "extrados"}, {"joint": 2, "edge": "intrados"},
            {"joint": 4, "edge": "extrados"}, {"joint": 7, "edge": "intrados"}]


def run(capsys, *argv):
    """main(argv) in-process; returns (exit status, stdout, stderr)."""
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv)
    assert code == 0, err
    return json.loads(out)


# ---------------------------------------------------------------------------- limit
def test_limit_json_oppenheim(capsys):
    d = run_json(capsys, "limit", *OPPENHEIM_FLAGS, "--json")
    # the paper's k = 0.3700 to its 4 printed decimals (k is an LP/enumeration result)
    assert d["k_l"] == pytest.approx(0.3700, abs=5e-5)
    assert d["k_r"] == pytest.approx(0.3700, abs=5e-5)
    assert d["mechanism_l"]["hinges"] == HINGES_L
    assert d["mechanism_r"]["hinges"] == HINGES_R
    assert d["mechanism_l"]["multiplier"] == d["k_l"]
    # the static LP is an independent method: it must agree to solver precision
    assert abs(d["static_k_l"] - d["k_l"]) < 1e-9
    assert abs(d["static_k_r"] - d["k_r"]) < 1e-9
    assert d["discrepancy"] < 1e-9
    geo = d["geometry"]["voussoirs"]
    assert len(geo) == 7
    assert all(v == {"span_deg": pytest.approx(22.5), "radius": 10.0, "thickness": 1.5} for v in geo)
    # labels A..D start on the mechanism's leading side: the rightmost hinge for M_r
    assert d["hinge_labels"]["l"][0] == {"label": "A", "joint": 0, "edge": "intrados"}
    assert d["hinge_labels"]["r"][0] == {"label": "A", "joint": 7, "edge": "intrados"}
    assert "min_thickness" not in d


def test_limit_defaults_are_oppenheims_arch(capsys):
    d = run_json(capsys, "limit", "--json")
    assert d["arch"] == "Oppenheim"
    assert d["k"] == pytest.approx(0.3700, abs=5e-5)  # the paper's k to its 4 printed decimals
    assert d["mechanism_l"]["hinges"] == HINGES_L


def test_limit_table_is_readable(capsys):
    code, out, err = run(capsys, "limit")
    assert code == 0 and err == ""
    assert "M_l               0.3700         0.3700  A: 0 intrados, B: 3 extrados, C: 5 intrados, D: 7 extrados" in out
    assert "M_r               0.3700         0.3700  A: 7 intrados, B: 4 extrados, C: 2 intrados, D: 0 extrados" in out
    assert "LP check" in out and "(agree)" in out


def test_limit_min_thickness_matches_the_api(capsys):
    d = run_json(capsys, "limit", "--thickness", "1.0", "--min-thickness", "--json")
    mt = minimum_thickness(arch_from_args(_geometry_args("--thickness", "1.0")))
    assert d["min_thickness"]["factor"] == pytest.approx(mt.factor, rel=1e-12)
    assert d["min_thickness"]["ratio_t_over_R"] == pytest.approx(mt.ratio, rel=1e-12)
    # an arch that carries 0.3 g horizontally stands on well under its own thickness
    assert 0.0 < d["min_thickness"]["factor"] < 1.0


def test_thicker_arch_is_stronger(capsys):
    thin = run_json(capsys, "limit", "--thickness", "1.2", "--json")["k"]
    thick = run_json(capsys, "limit", "--thickness", "1.8", "--json")["k"]
    assert thin < 0.3700 < thick


# ---------------------------------------------------------------------------- random-arch
def test_random_arch_round_trip_matches_the_python_api(capsys, tmp_path):
    path = tmp_path / "ra.json"
    code, out, err = run(capsys, "random-arch", "--seed", "7", "--out", str(path))
    assert code == 0, err
    arch = read_arch(path)
    expected = random_arch(seed=7, spread_span=0.1, spread_thickness=0.1, spread_radius=0.05)
    np.testing.assert_array_equal(arch.radii, expected.radii)
    np.testing.assert_array_equal(arch.thicknesses, expected.thicknesses)
    np.testing.assert_allclose(arch.spans, expected.spans, rtol=0, atol=1e-14)

    d = run_json(capsys, "limit", "--geometry", str(path), "--json")
    api = limit_analysis(read_arch(path))
    assert d["k_l"] == api.k_l and d["k_r"] == api.k_r
    assert d["mechanism_l"] == api.mechanism_l.to_dict()
    assert d["mechanism_r"] == api.mechanism_r.to_dict()
    assert d["static_k_l"] == api.static_k_l and d["static_k_r"] == api.static_k_r
    # an irregular arch: the two directions differ, both near Oppenheim's 0.37
    assert abs(d["k_l"] - d["k_r"]) > 1e-4
    assert 0.25 < d["k"] < 0.5


def test_random_arch_stdout_is_reproducible_and_spreads_apply(capsys):
    a = run_json(capsys, "random-arch", "--seed", "3")
    b = run_json(capsys, "random-arch", "--seed", "3")
    assert a == b
    spans = [v["span_deg"] for v in a["voussoirs"]]
    assert sum(spans) == pytest.approx(157.5, abs=1e-9)
    assert a["metadata"]["seed"] == 3
    flat = run_json(capsys, "random-arch", "--seed", "3", "--spread-span", "0",
                    "--spread-thickness", "0", "--spread-radius", "0")
    assert all(v == {"span_deg": pytest.approx(22.5), "radius": 10.0, "thickness": 1.5}
               for v in flat["voussoirs"])


def test_random_arch_around_a_given_nominal(capsys):
    d = run_json(capsys, "random-arch", "--seed", "1", "--radius", "2", "--thickness", "0.3",
                 "--voussoirs", "9", "--embrace", "180", "--spread-radius", "0")
    assert len(d["voussoirs"]) == 9
    assert all(v["radius"] == 2.0 for v in d["voussoirs"])
    assert all(0.27 <= v["thickness"] <= 0.33 for v in d["voussoirs"])


# ---------------------------------------------------------------------------- bad input
BAD_INPUTS = [
    (["limit", "--thickness", "-1"], "thickness"),
    (["limit", "--thickness", "20"], "thickness"),       # t >= 2R
    (["limit", "--embrace", "360"], "embrace"),          # spans adding to >= 360 deg
    (["limit", "--voussoirs", "2"], "voussoirs"),
    (["limit", "--voussoirs", "3.5"], "--voussoirs"),
    (["limit", "--radius", "nan"], "--radius"),
    (["limit", "--thickness", "inf"], "--thickness"),
    (["limit", "--density", "0"], "density"),
    (["limit", "--radius", "0"], "radius"),
    (["random-arch", "--spread-span", "1.5"], "spread_span"),
    (["random-arch", "--spread-thickness", "-inf"], "--spread-thickness"),
    (["random-arch", "--seed", "-1"], "--seed"),
    (["plot-limit", "--direction", "x"], "--direction"),
    (["limit", "--geometry", "x.json", "--radius", "3"], "--geometry"),
    (["nonsense"], "invalid choice"),
    ([], "command"),
]


@pytest.mark.parametrize("argv, field", BAD_INPUTS)
def test_bad_flags_exit_2_with_one_line(capsys, argv, field):
    code, out, err = run(capsys, *argv)
    assert code == 2
    last = err.strip().splitlines()[-1]
    assert last.startswith("archrock: error: ")
    assert field in last
    assert "Traceback" not in err
    assert out == ""


def _geometry_file(tmp_path, name, voussoirs, raw=None):
    p = tmp_path / name
    p.write_text(raw if raw is not None else json.dumps({"voussoirs": voussoirs}))
    return p


V = {"span_deg": 30.0, "radius": 10.0, "thickness": 1.0}
BAD_FILES = [
    ("gap.json", [V, V, dict(V, radius=12.0), V, V], None, "joint 2"),      # non-overlapping joints
    ("full.json", [dict(V, span_deg=125.0)] * 3, None, "360"),
    ("few.json", [V, V], None, "at least 3"),
    ("nan.json", None, '{"voussoirs": [{"span_deg": NaN, "radius": 10, "thickness": 1}]}',
     "voussoirs[0].span_deg"),
    ("broken.json", None, '{"voussoirs": [\n', "line 2, column 1"),
    ("thick.json", [V, dict(V, thickness=20.0), V], None, "thickness of voussoir 1"),
]


@pytest.mark.parametrize("name, voussoirs, raw, fragment", BAD_FILES)
def test_bad_geometry_files_exit_2(capsys, tmp_path, name, voussoirs, raw, fragment):
    p = _geometry_file(tmp_path, name, voussoirs, raw)
    for cmd in ("limit", "plot-limit", "random-arch"):
        code, out, err = run(capsys, cmd, "--geometry", str(p), *(["--out", str(tmp_path / "o")]
                                                                  if cmd != "limit" else []))
        assert code == 2, (cmd, err)
        assert err.count("\n") == 1 and err.startswith("archrock: error: ")
        assert name in err and fragment in err
        assert "Traceback" not in err


def test_missing_geometry_file_exits_2(capsys, tmp_path):
    code, out, err = run(capsys, "limit", "--geometry", str(tmp_path / "absent.json"))
    assert code == 2
    assert err.strip() == f"archrock: error: {tmp_path / 'absent.json'}: geometry file not found"


# ---------------------------------------------------------------------------- figures, paper
def test_plot_limit_writes_a_png(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "fig" / "limit.png"
    code, stdout, err = run(capsys, "plot-limit", "--out", str(out), "--direction", "both")
    assert code == 0, err
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    # PNG header: width and height (big-endian) -- two panels side by side
    width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    assert width > 1.8 * height
    assert len(data) > 20_000
    assert "k_l = 0.3700, k_r = 0.3700" in stdout


def test_paper_writes_fig3_and_summary(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    code, out, err = run(capsys, "paper", "--out", str(tmp_path / "p"))
    assert code == 0, err
    assert (tmp_path / "p" / "fig3_oppenheim_limit.png").stat().st_size > 20_000
    s = json.loads((tmp_path / "p" / "summary.json").read_text())
    lim = s["limit_oppenheim"]
    assert lim["k"] == pytest.approx(0.3700, abs=5e-5)  # the paper's k to its 4 printed decimals
    assert lim["matches_paper_4_decimals"] is True
    assert [h["joint"] for h in lim["hinges"]["l"]] == [0, 3, 5, 7]
    assert "k_l = 0.3700" in out


# ---------------------------------------------------------------------------- plumbing
def _geometry_args(*argv):
    p = argparse.ArgumentParser()
    add_geometry_options(p)
    return p.parse_args(list(argv))


def test_geometry_helpers_for_other_subcommands():
    a = arch_from_args(_geometry_args())
    assert a.name == "Oppenheim" and a.n == 7
    b = arch_from_args(_geometry_args("--radius", "5", "--voussoirs", "9"))
    assert b.n == 9 and np.all(b.radii == 5.0) and np.all(b.thicknesses == 1.5)
    assert {"limit", "random-arch", "plot-limit", "paper"} <= set(SUBCOMMANDS)


def test_version_and_help_return_0(capsys):
    code, out, _ = run(capsys, "--version")
    assert code == 0 and out.startswith("archrock ")
    code, out, _ = run(capsys, "limit", "--help")
    assert code == 0 and "--geometry FILE" in out


def _installed_script():
    # the console script sits next to the interpreter in a venv; fall back to PATH
    cand = Path(sys.executable).parent / ("archrock.exe" if os.name == "nt" else "archrock")
    return str(cand) if cand.exists() else shutil.which("archrock")


def test_installed_script_runs():
    script = _installed_script()
    if script is None:
        pytest.skip("the archrock console script is not installed")
    proc = subprocess.run([script, "limit", "--json"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert d["k_l"] == pytest.approx(0.3700, abs=5e-5)  # the paper's k to its 4 printed decimals
    bad = subprocess.run([script, "limit", "--thickness", "nan"], capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 2
    assert "Traceback" not in bad.stderr and "archrock: error: argument --thickness" in bad.stderr


def test_python_dash_m():
    proc = subprocess.run([sys.executable, "-m", "archrock", "limit", "--voussoirs", "3", "--json"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert len(d["geometry"]["voussoirs"]) == 3
    assert d["k_l"] == pytest.approx(d["k_r"], rel=1e-9)


# ---------------------------------------------------------------------------- help, reports
@pytest.mark.parametrize("name", list(SUBCOMMANDS))
def test_every_subcommand_help_works(capsys, name):
    code, out, err = run(capsys, name, "--help")
    assert code == 0 and err == ""
    assert out.startswith(f"usage: archrock {name} ")


def test_help_lists_the_subcommands_in_order(capsys):
    code, out, _ = run(capsys, "--help")
    assert code == 0
    order = ["limit", "random-arch", "plot-limit", "respond", "curves", "fragility", "ensemble",
             "paper"]
    assert list(SUBCOMMANDS)[:len(order)] == order
    assert [out.index(f"\n    {n}") for n in order] == sorted(out.index(f"\n    {n}") for n in order)


def test_limit_reports_are_what_the_command_prints(capsys):
    from archrock.statics.friction import friction_needed
    from archrock.reports import format_limit_table, limit_summary

    arch = arch_from_args(_geometry_args("--thickness", "1.2"))
    res, mt = limit_analysis(arch, verify=True), minimum_thickness(arch)
    needed = friction_needed(arch)  # reported by every limit run
    # and the governing answer at the default friction, stated (studies.governing, issue 30)
    from archrock.reports.limit import format_governing
    from archrock.studies.governing import governing_capacity

    gov = governing_capacity(arch, 0.8, limit=res,
                             engine_left_out="not run by limit: archrock dem --ramp")
    stated = "mu = 0.8 (the default; --friction MU|none)"
    code, out, _ = run(capsys, "limit", "--thickness", "1.2", "--min-thickness")
    assert code == 0 and out == (format_limit_table(res, mt, needed=needed) + "\n"
                                 + format_governing(gov, stated) + "\n")
    assert run_json(capsys, "limit", "--thickness", "1.2", "--min-thickness", "--json") == \
        json.loads(json.dumps({**limit_summary(res, mt, needed=needed),
                               "governing": {**gov.to_dict(), "friction_stated": stated}}))


def test_respond_report_is_what_the_command_prints(capsys):
    from archrock.groundmotion import pulse
    from archrock.reports import format_response
    from archrock.dynamics.response import prepare, respond

    model, motion = prepare(arch_from_args(_geometry_args()), "paper"), pulse("oppenheim", -1, 0.2)
    res = respond(model, motion, t_end=3.0, dt_out=0.005)
    code, out, _ = run(capsys, "respond", "--pulse", "oppenheim", "--amplitude", "-1",
                       "--pulse-duration", "0.2")
    # issue 30: then the model that gave it and the friction, stated once
    assert code == 0 and out == format_response(res, model, motion) + (
        "\ndynamics: four-link model (no piers: one degree of freedom (the four-link model) "
        "follows the arch)\nfriction: mu = 0.8 (the default; --friction MU|none)\n")
    assert out.startswith("arch: Oppenheim; k_l = 0.3700") and "outcome: " in out


def test_respond_figures_run_to_the_collapse_past_t_end(capsys, tmp_path, monkeypatch):
    """--plot and --animate draw the run to its end (the rotation limit here, 0.66 s) although
    --t-end is 0.3 s; the JSON keeps --t-end and reports t_collapse beside t_limit."""
    pytest.importorskip("matplotlib")
    import archrock.reports.animate
    import archrock.reports.plots

    seen = {}
    monkeypatch.setattr(archrock.reports.plots, "save_response_figure",
                        lambda rs, path, labels=None: seen.setdefault("plot", rs[0]))
    monkeypatch.setattr(archrock.reports.animate, "animate_response",
                        lambda r, path, **kw: seen.setdefault("animate", r))
    d = run_json(capsys, "respond", "--pulse", "oppenheim", "--amplitude", "-2",
                 "--pulse-duration", "0.3", "--t-end", "0.3", "--json",
                 "--plot", str(tmp_path / "r.png"), "--animate", str(tmp_path / "r.gif"))
    assert d["collapsed"] and d["time"][-1] == pytest.approx(0.3)
    assert d["t_collapse"] == pytest.approx(0.34033348, abs=1e-6) and d["t_limit"] > 0.6
    for r in (seen["plot"], seen["animate"]):
        assert r.time[-1] >= d["t_limit"] and r.time[-1] == pytest.approx(1.05 * d["t_limit"], abs=0.01)
        assert r.t_collapse == d["t_collapse"] and np.isnan(r.response[-1])


def test_figure_t_end_is_capped():
    from types import SimpleNamespace

    from archrock.reports.plots import figure_t_end

    def fake(t_final, duration=0.6, t_end=3.0):
        return SimpleNamespace(time=np.array([0.0, t_end]), t_final=t_final,
                               motion=SimpleNamespace(duration=duration))
    assert figure_t_end(fake(2.0)) == 3.0                       # ended inside the window
    assert figure_t_end(fake(4.0)) == pytest.approx(4.2)        # to the end, plus 5 %
    assert figure_t_end(fake(60.6)) == pytest.approx(10.6)      # free rocking: 10 s past the motion
    assert figure_t_end(fake(60.6), t_end=8.0) == 16.0          # or 2 x t_end
    assert figure_t_end(fake(60.6, duration=40.0)) == 50.0      # a record: 10 s past its end


@pytest.mark.parametrize("samples", [0, 2])
def test_curves_reports_are_what_the_command_prints(capsys, samples):
    from archrock.studies.curves import collapse_curve, ensemble_curve
    from archrock.dynamics.impact import PAPER_PRACTICE, nominal_cv
    from archrock.reports import curves_summary, format_curves
    from archrock.dynamics.response import prepare

    nominal = arch_from_args(_geometry_args())
    cv, durations = nominal_cv(nominal), np.array([0.2, 0.5])
    kw = dict(kind="oppenheim", sign=-1, a_max=10.0, n_scan=12, tol=1e-3)
    band = None
    if samples:
        spreads = {"spread_span": 0.1, "spread_thickness": 0.1, "spread_radius": 0.05}
        band = ensemble_curve(nominal, samples, 0, spreads, durations, impact=PAPER_PRACTICE, **kw)
        curve = band.nominal
    else:
        curve = collapse_curve(prepare(nominal, PAPER_PRACTICE), durations, **kw)
    about = dict(arch_name="Oppenheim", pulse="oppenheim", sign=-1, impact=PAPER_PRACTICE, cv=cv)
    argv = ["curves", "--durations", "0.2,0.5", "--n-scan", "12", "--samples", str(samples)]
    code, out, _ = run(capsys, *argv)
    # issue 30: then the routing of the dynamics at the command's friction, stated once
    choice = choose_dynamics(nominal, "auto", friction=0.8)
    assert code == 0 and out == format_curves(curve, band, **about) + (
        f"\ndynamics: four-link model ({choice.reason}); friction: mu = 0.8 (the default; "
        f"--friction MU|none)\n")
    assert run_json(capsys, *argv, "--json") == json.loads(json.dumps(
        {**curves_summary(curve, band, **about), "dynamics": choice.to_dict()}))


def _record_file(tmp_path, name, freq):
    # a short sine burst under a smooth envelope, PGA 0.3 g: collapses within a few scale steps
    t = np.arange(0, 3.0, 0.01)
    a = 0.3 * np.sin(2 * np.pi * freq * t) * np.sin(np.pi * t / 3.0) ** 2
    p = tmp_path / name
    np.savetxt(p, np.column_stack([t, a]))
    return p


def test_fragility_reports_are_what_the_command_prints(capsys, tmp_path):
    from archrock.groundmotion import load_record
    from archrock.studies.ida import default_stripe_levels, ida, msa
    from archrock.reports import format_fragility, fragility_summary
    from archrock.dynamics.impact import PAPER_PRACTICE, nominal_cv
    from archrock.dynamics.response import prepare

    files = [_record_file(tmp_path, "r1.txt", 1.5), _record_file(tmp_path, "r2.txt", 2.5)]
    argv = ["fragility", "--records", *map(str, files), "--radius", "2", "--thickness", "0.3",
            "--scales", "0.5:6:6", "--bootstrap", "0"]
    nominal = arch_from_args(_geometry_args("--radius", "2", "--thickness", "0.3"))
    records = [load_record(f) for f in files]
    cv = nominal_cv(nominal)
    models = [prepare(nominal, PAPER_PRACTICE)]
    res_ida = ida(records, models, np.linspace(0.5, 6, 6))
    res_msa = msa(records, models, default_stripe_levels(res_ida, np.linspace(0.5, 6, 6), records))
    code, out, _ = run(capsys, *argv)
    assert code == 0 and out == format_fragility(res_ida, res_msa, arch_name="nominal", n_records=2,
                                                 n_arches=1, n_requested=0) + "\n"
    d = run_json(capsys, *argv, "--json")
    from archrock.groundmotion.suite import read_records

    assert d == json.loads(json.dumps(fragility_summary(res_ida, res_msa, arch_name="nominal",
                                                        records=records, n_arches=1, impact=PAPER_PRACTICE,
                                                        cv=cv, suite=read_records(files))))
    assert len(d["stripes"]["levels"]) == 8
    # early stop: the same report (collapse decisions and first collapses unchanged)
    code, out_stop, _ = run(capsys, *argv, "--early-stop")
    assert code == 0 and out_stop == out
    code, _, err = run(capsys, *argv, "--early-stop", "--engine", "respond")
    assert code == 2 and "early-stop" in err


def test_default_stripe_levels_bracket_the_first_collapses_or_fall_back_on_the_scales():
    from types import SimpleNamespace

    from archrock.studies.ida import IDAResult, default_stripe_levels

    recs = [SimpleNamespace(pga_g=0.2), SimpleNamespace(pga_g=0.4)]
    curves = [SimpleNamespace(first_im=x) for x in (0.5, None, 2.0)]
    lv = default_stripe_levels(IDAResult(tuple(curves), "pga", None), [1.0, 3.0], recs)
    assert len(lv) == 8 and lv[0] == pytest.approx(0.3) and lv[-1] == pytest.approx(2.8)
    assert np.allclose(np.diff(np.log(lv)), np.log(lv[1] / lv[0]))
    none = IDAResult((curves[1],), "pga", None)
    assert default_stripe_levels(none, [1.0, 3.0], recs, n=3) == pytest.approx([0.2, 0.24 ** 0.5, 1.2])


def test_ensemble_report_is_what_the_command_prints(capsys):
    from archrock.reports import format_ensemble

    argv = ["ensemble", "--samples", "20", "--pulse", "oppenheim", "--amplitude", "-1",
            "--pulse-duration", "0.2", "--no-progress"]
    summary = run_json(capsys, *argv, "--json")
    code, out, _ = run(capsys, *argv)
    assert code == 0
    # the first line the routing at the command's friction (issue 30); the last the wall time,
    # which differs run to run
    assert out.splitlines()[0] == (f"dynamics: four-link model: {summary['dynamics']['reason']}; "
                                   f"friction: mu = 0.8 (the default; --friction MU|none)")
    assert out.splitlines()[1:-1] == format_ensemble(summary, "Oppenheim").splitlines()[:-1]
    assert out.splitlines()[-1].startswith("time: ")


# ---------------------------------------------------------------------------- edges: parsing
@pytest.mark.parametrize("argv", [["limit", "--bogus"], ["limit", "--voussoirs", "x"],
                                  ["respond", "--amplitude"], ["curves", "--sign", "2"]])
def test_argparse_errors_are_one_line_without_usage(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("archrock: error: "), err
    assert "usage" not in err


def test_negative_numbers_in_any_spelling_are_values(capsys):
    """-5e-1 is a number, -1,2 a list: argparse took both for options ("expected one argument")."""
    d = run_json(capsys, "respond", "--pulse", "rectangular", "--amplitude", "-4e-1",
                 "--pulse-duration", "1e-1", "--json")
    assert d["status"] == "rest"  # 0.4 g is above k = 0.37: it rocks and comes back
    code, _, err = run(capsys, "curves", "--durations", "-1,2")
    assert code == 2 and err.strip() == "archrock: error: durations: '-1,2'; allowed numbers > 0"
    code, _, err = run(capsys, "curves", "--durations", "-.5:1:3")
    assert code == 2 and "durations" in err and "expected one argument" not in err


def test_json_writes_null_for_non_finite_values():
    import io

    from archrock.cli._parser import emit_json

    buf = io.StringIO()
    emit_json({"a": float("nan"), "b": [np.inf, np.float64(-np.inf), np.float32(1.5)],
               "c": np.array([1.0, np.nan]), "d": np.int64(3), "e": (np.nan,)}, buf)
    assert json.loads(buf.getvalue()) == {"a": None, "b": [None, None, 1.5], "c": [1.0, None],
                                          "d": 3, "e": [None]}


def test_ensemble_of_one_sample_prints_strict_json(capsys):
    """The std of one sample is undefined: null, not NaN (which is not JSON)."""
    d = run_json(capsys, "ensemble", "--samples", "1", "--json", "--no-progress")
    assert d["samples"] == 1


# ---------------------------------------------------------------------------- edges: output files
RESPOND_PULSE = ["respond", "--pulse", "oppenheim", "--amplitude", "-1", "--pulse-duration", "0.2"]


@pytest.mark.parametrize("argv, fragment", [
    (RESPOND_PULSE + ["--plot", "r.nope"], "format '.nope' cannot be written"),
    (RESPOND_PULSE + ["--animate", "r.png"], "allowed extensions .gif or .mp4"),
    (["plot-limit", "--out", "l.abc"], "format '.abc' cannot be written"),
    (["plot-limit", "--out", "l.png", "--dpi", "1e7"], "dpi"),
    (["plot-limit", "--out", "l.png", "--dpi", "0.5"], "dpi"),
    (["curves", "--durations", "0.2", "--plot", "c.qqq"], "cannot be written"),
    (["fragility", "--records", "none.txt", "--plot", "f.zz"], "cannot be written"),
    (["ensemble", "--samples", "2", "--plot", "e.q"], "cannot be written"),
    (["ensemble", "--samples", "2", "--out", ""], "--out: ''"),
    (["random-arch", "--out", " "], "--out: ' '"),
    (["paper", "--out", ""], "--out: ''"),
])
def test_bad_output_files_are_refused_before_any_work(capsys, tmp_path, monkeypatch, argv, fragment):
    pytest.importorskip("matplotlib")
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "", err
    assert err.count("\n") == 1 and err.startswith("archrock: error: ") and fragment in err
    assert list(tmp_path.iterdir()) == []  # nothing written, nothing computed into a folder


def test_figure_to_a_folder_is_refused_and_no_extension_gets_png(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    code, _, err = run(capsys, "plot-limit", "--out", str(tmp_path))
    assert code == 2 and "is a folder" in err
    code, out, err = run(capsys, "plot-limit", "--out", str(tmp_path / "adir"))
    assert code == 0, err
    assert out.strip().endswith(f"wrote {tmp_path / 'adir.png'}")  # the file really written
    assert (tmp_path / "adir.png").read_bytes()[:4] == b"\x89PNG"


# ---------------------------------------------------------------------------- edges: work, signals
@pytest.mark.parametrize("argv, fragment", [
    (["ensemble", "--samples", str(10**12), "--no-progress"], "ensemble: about 1e+12 arches"),
    (["curves", "--durations", "0.2", "--n-scan", str(10**9)], "curves: about 1e+09 responses"),
    (["curves", "--durations", "0.2,0.3", "--samples", str(10**7)], "reduce --n-scan"),
])
def test_work_beyond_the_bound_is_refused_up_front_with_exit_3(capsys, argv, fragment):
    code, out, err = run(capsys, *argv)
    assert code == 3 and out == ""
    assert err.count("\n") == 1 and fragment in err and "estimated" in err and "allowed up to" in err


def test_fragility_bounds_scales_bootstrap_and_warns(capsys, tmp_path, monkeypatch):
    rec = tmp_path / "r.txt"
    rec.write_text("".join(f"{k * 0.01:.2f} {0.3 * np.sin(k / 8):.5f}\n" for k in range(300)))
    code, _, err = run(capsys, "fragility", "--records", str(rec), "--scales", "0.1:300:5")
    assert code == 2 and "scales: 300 x record 'r': PGA 90 g; allowed at most 20 g" in err
    code, _, err = run(capsys, "fragility", "--records", str(rec), "--scales", "0.5:1:2",
                       "--bootstrap", str(10**10))
    assert code == 3 and "bootstrap: about 1e+10 fits" in err and "reduce --bootstrap" in err
    import archrock.studies.work as work

    monkeypatch.setattr(work, "WARN_WORK_S", 0.0)  # every run warns: one line on stderr
    code, _, err = run(capsys, "curves", "--durations", "0.2", "--n-scan", "5", "--no-progress")
    assert code == 0 and err.startswith("archrock: warning: curves: about ") and err.count("\n") == 1


def test_cv_without_a_motion_is_refused_where_it_cannot_matter(capsys):
    for flag in (["--cv", "0.8"], ["--impact", "momentum"], ["--literal-cv"]):
        code, _, err = run(capsys, "ensemble", "--samples", "2", *flag)
        assert code == 2 and f"{flag[0]}: unused without a ground motion" in err


def _children(pid):
    kids = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                if int((d / "stat").read_text().rsplit(")", 1)[1].split()[1]) == pid:
                    kids.append(int(d.name))
            except (OSError, IndexError, ValueError):
                pass
    return kids


ENSEMBLE_LONG = ["-m", "archrock", "ensemble", "--samples", "200000", "--batch-size", "2000",
                 "--pulse", "oppenheim", "--amplitude", "-1", "--pulse-duration", "0.2",
                 "--no-progress"]


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
def test_pool_workers_die_with_a_killed_parent():
    import signal
    import time

    pytest.importorskip("pandas")
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).parents[2] / "src"))
    proc = subprocess.Popen([sys.executable, *ENSEMBLE_LONG, "--workers", "2"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while len(kids := _children(proc.pid)) < 2 and time.monotonic() < deadline:
            time.sleep(0.2)
        assert len(kids) >= 2, "the pool did not start"
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
        deadline = time.monotonic() + 10
        alive = kids
        while alive and time.monotonic() < deadline:
            time.sleep(0.2)
            alive = [k for k in kids if Path(f"/proc/{k}").exists()
                     and "Z" not in (Path(f"/proc/{k}/stat").read_text().rsplit(")", 1)[1].split()[:1])]
        assert not alive, f"workers outlived their parent: {alive}"
    finally:
        if proc.poll() is None:
            proc.kill()


@pytest.mark.slow  # a real SIGINT into a running ensemble: timing-dependent on a loaded machine
def test_ctrl_c_in_ensemble_says_what_was_kept_and_exits_130(tmp_path):
    import signal
    import time

    pytest.importorskip("pandas")
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).parents[2] / "src"))
    out = tmp_path / "run"
    proc = subprocess.Popen([sys.executable, *ENSEMBLE_LONG, "--out", str(out)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not list((out / "batches").glob("*.parquet")) and time.monotonic() < deadline:
        time.sleep(0.2)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    kept = len(list((out / "batches").glob("*.parquet")))
    assert proc.returncode == 130 and "Traceback" not in err
    assert f"archrock: interrupted; {kept} of 100 batches kept in {out}; the same command resumes" in err


def test_interrupted_ensemble_with_out_counts_the_kept_batches(capsys, monkeypatch, tmp_path):
    import archrock.studies.ensemble as ens

    out = tmp_path / "run"

    def interrupted(config, out_folder=None, **kw):
        (out / "batches").mkdir(parents=True)
        for b in (0, 1):  # two batches finished before the Ctrl-C
            (out / "batches" / f"batch-{b:05d}.parquet").write_bytes(b"")
        raise KeyboardInterrupt

    monkeypatch.setattr(ens, "run_ensemble", interrupted)
    code, _, err = run(capsys, "ensemble", "--samples", "12", "--batch-size", "4", "--out",
                       str(out), "--no-progress")
    assert code == 130
    assert err == (f"archrock: interrupted; 2 of 3 batches kept in {out}; the same command "
                   f"resumes from them\n")


def test_interrupted_ensemble_without_out_says_nothing_was_kept(capsys, monkeypatch):
    import archrock.studies.ensemble as ens

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(ens, "run_ensemble", interrupted)
    code, out, err = run(capsys, "ensemble", "--samples", "3", "--no-progress")
    assert code == 130 and out == ""
    assert err == "archrock: interrupted; nothing was kept (give --out DIR to keep finished batches and resume)\n"


def test_codecheck_spectrum_in_cm_per_s2_is_refused_with_a_units_hint(capsys, tmp_path):
    """Issue 17: a spectrum file in cm/s^2 was read as 294 g.  Above 20 g it is refused with the
    units that make it plausible; above 5 g (a file in m/s^2) a warning."""
    f = tmp_path / "cms.txt"
    f.write_text("0 294.3\n0.2 735.75\n0.5 735.75\n2 100\n")
    code, out, err = run(capsys, "codecheck", "--spectrum", str(f))
    assert code == 2 and out == ""
    assert err == (f"archrock: error: spectrum file '{f}': Se up to 735.8 g; allowed at most 20 g "
                   f"(units? Se is read in g; if it is in cm/s^2, divide the column by 981 "
                   f"(peak 0.75 g))\n")
    f.write_text("0 2.943\n0.2 7.2\n0.5 7.2\n2 1\n")
    code, out, err = run(capsys, "codecheck", "--spectrum", str(f))
    assert code == 0 and "archrock: warning: spectrum file" in err
    assert "Se up to 7.2 g is above any code spectrum (about 3 g); units? if Se is in m/s^2, " \
           "divide the column by 9.81 (peak 0.734 g)" in err
    f.write_text("0 0.3\n0.2 0.75\n0.5 0.75\n2 0.1\n")
    code, out, err = run(capsys, "codecheck", "--spectrum", str(f))
    assert code == 0 and err == ""


def test_a_record_with_a_repeated_time_is_refused_in_one_line(capsys, tmp_path):
    """Issue 29: a record's times strictly increase; a time twice (a step) was accepted by
    respond although the README says refused.  Increasing times run."""
    f = tmp_path / "step.txt"
    f.write_text("# corners\n0 -1\n0.2 -1\n0.2 0.5\n0.6 0.5\n0.6 0\n")
    code, out, err = run(capsys, "respond", "--record", str(f))
    assert code == 2 and out == ""
    assert err == ("archrock: error: record step.txt: line 4: time 0.2 s repeats line 3; allowed "
                   "strictly increasing times (one value per instant; write a step as a short "
                   "ramp, e.g. '0.2 -1' then '0.2001 0.5')\n")
    f.write_text("# corners\n0 -1\n0.2 -1\n0.2001 0.5\n0.6 0.5\n0.6001 0\n")
    code, out, err = run(capsys, "respond", "--record", str(f))
    assert code == 0 and err == "" and "step" in out


def test_voussoirs_and_lengths_out_of_range_are_one_line(capsys):
    """Issue 17: --voussoirs 1e6 ran 40 s into Python advice; huge or tiny radii leaked numpy
    overflow warnings and a traceback."""
    for argv, msg in (
            (["--voussoirs", "1e6"], "voussoirs: 1000000; allowed 3 to 2000 (a limit analysis of "
                                     "2000 voussoirs takes seconds; no masonry ring has more)"),
            (["--radius", "1e300", "--thickness", "1e299"],
             "radius: 1e+300 m is out of range; allowed 1e-08 m to 1e+08 m (units? lengths are in "
             "metres)"),
            (["--shape", "pointed", "--span", "10", "--rise", "7", "--thickness", "1e-9"],
             "thickness: 1e-09 m is out of range; allowed 1e-08 m to 1e+08 m (units? lengths are "
             "in metres)")):
        code, out, err = run(capsys, "limit", *argv)
        assert code == 2 and out == "" and err == f"archrock: error: {msg}\n"
    code, _, err = run(capsys, "limit", "--voussoirs", "2.5")
    assert code == 2 and "--voussoirs: expected an integer, got '2.5'" in err


def test_no_help_text_shows_a_doubled_percent(capsys):
    """Issue 17: `codecheck --help` and `assess --help` showed "5%% damping" (argparse
    %-formats an argument's help, not a group's description)."""
    from archrock.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert len(sub.choices) > 10
    for name, p in sub.choices.items():
        text = p.format_help()
        assert "%%" not in text, name
    text = sub.choices["codecheck"].format_help()
    assert "elastic spectrum at 5% damping" in " ".join(text.split())


def test_number_lists_have_one_grammar(capsys):
    """verify's --amplitudes/--durations read lists as curves and fragility do (parse_range):
    'lo:hi:n' works there too, a zero amplitude or duration is refused by name."""
    from archrock.cli import build_parser

    args = build_parser().parse_args(["verify", "--amplitudes", "-1:-0.5:3", "--durations", "0.2"])
    assert args.amplitudes == pytest.approx([-1.0, -0.75, -0.5], abs=1e-15)
    assert args.durations == pytest.approx([0.2], abs=1e-15)
    with pytest.raises(SystemExit):
        build_parser().parse_args(["verify", "--durations", "0.2,-0.1"])
    assert "durations: '0.2,-0.1'; allowed numbers > 0" in capsys.readouterr().err

"""The default spreads of a study around an arch whose joints stay where drawn (an arch on
piers): the span spread defaults to 0 there, and the run says which spreads it applied."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main

PIERS = ["--pier-height", "4", "--pier-width", "2"]


def run(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


APPLIED = ("archrock: spreads applied: span 0 (default for 'Oppenheim on piers', an arch on "
           "piers, whose blocks (piers included) are perturbed as a surveyed arch's, whose "
           "joints stay where drawn), thickness 0.1, radius 0.05, tilt 0")


def test_default_spreads_on_piers_draw(capsys):
    """The parsed defaults of ``ensemble ... --pier-height 4 --pier-width 2`` give spreads the
    sampler takes (it refused the span spread 0.1 before), and one line says which."""
    from archrock.cli import build_parser
    from archrock.cli.options import arch_from_args, spreads_for
    from archrock.geometry.sampling import ArchSampler

    args = build_parser().parse_args(["ensemble", *PIERS])
    nominal = arch_from_args(args)
    sp = spreads_for(args, nominal)
    assert capsys.readouterr().err.strip() == APPLIED
    assert abs(sp.span) < 1e-15 and abs(sp.thickness - 0.1) < 1e-15
    assert abs(sp.radius - 0.05) < 1e-15
    arch = ArchSampler(nominal, sp, 0).arch(0)
    assert arch.n == nominal.n
    assert 0 < abs(arch.areas - nominal.areas).max() < 0.2 * nominal.areas.max()


def test_explicit_span_on_piers_still_refused(capsys):
    rc, _, err = run(capsys, "ensemble", "--samples", "2", "--spread-span", "0.1", *PIERS)
    assert rc == 2
    assert err.startswith("archrock: error: spread span and tilt: 0.1 and 0; allowed 0 and 0")


def test_plain_arch_keeps_the_span_spread(capsys):
    rc, out, err = run(capsys, "random-arch", "--seed", "3")
    assert rc == 0, err
    assert "spreads applied" not in err
    assert abs(json.loads(out)["metadata"]["spread_span"] - 0.1) < 1e-15


@pytest.mark.slow
def test_default_ensemble_on_piers_twenty_samples(capsys):
    """The command of the review (about a minute: the nominal's piers are checked with the
    contact engine)."""
    rc, out, err = run(capsys, "ensemble", "--samples", "20", "--no-progress", "--json", *PIERS)
    assert rc == 0, err
    assert APPLIED in err.splitlines()
    d = json.loads(out)
    assert d["samples"] == 20 and abs(d["spreads"]["span"]) < 1e-15

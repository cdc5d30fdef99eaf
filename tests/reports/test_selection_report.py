"""reports.selection: the text table with each rule, the CSV and JSON rows, the events of files
(their names) and the figure on the selection's own grid and beyond it."""

import csv
import io

import numpy as np
import pytest

from archrock.reports.selection import (event_names, format_selection, selection_csv,
                                        selection_figure, selection_json)
from archrock.studies.codecheck import SiteSpectrum
from archrock.studies.selection import SelectionConfig, select_for_site

SITE = SiteSpectrum.ec8(0.2, "C", 1)


@pytest.fixture(scope="module")
def records(noise_records):
    return noise_records(9)


@pytest.fixture(scope="module")
def selection(records):
    return select_for_site(SITE, records, SelectionConfig(period_range=(0.2, 1.5)))


def test_text_csv_and_json(selection):
    text = format_selection(selection)
    lines = text.splitlines()
    assert lines[0].startswith("records scaled for: EN 1998-1 type 1 elastic spectrum")
    assert lines[1].startswith("7 of 9 candidate records (one component per station)")
    for k, (name, f) in enumerate(zip(selection.names, selection.factors)):
        row = lines[3 + k].split()
        assert row[1:3] == name.split() and float(row[-2]) == pytest.approx(f, abs=5e-4)
    assert f"least {selection.ratio_min:.3f} at {selection.ratio_period:.3g} s" in text
    assert text.count("[pass]") == 5 and lines[-1] == "the rules hold"
    # files' records have no P695 metadata: their event is their name
    assert event_names(selection) == selection.names
    rows = list(csv.DictReader(io.StringIO(selection_csv(selection))))
    assert [int(r["index"]) for r in rows] == list(selection.indices)
    np.testing.assert_allclose([float(r["pga_scaled_g"]) for r in rows], selection.pga_g,
                               rtol=1e-5)
    d = selection_json(selection)
    assert [r["event_name"] for r in d["records"]] == list(selection.names)
    assert d["pga_min_g"] == pytest.approx(0.2 * 1.15, rel=1e-12)  # a_g S, soil C


def test_figure_on_its_grid_and_beyond(selection, records, tmp_path):
    pytest.importorskip("matplotlib")
    fig = selection_figure(selection)
    ax = fig.axes[0]
    assert ax.get_xscale() == "log"
    mean = next(line for line in ax.lines if line.get_label() == "mean of 7")
    np.testing.assert_allclose(mean.get_ydata(), selection.mean, rtol=1e-12)
    path = tmp_path / "spectra.png"
    fig = selection_figure(selection, path, motions=records, spectrum=SITE)
    x = fig.axes[0].lines[0].get_xdata()
    assert x[0] == pytest.approx(0.1, rel=1e-12) and x[-1] == pytest.approx(3.0, rel=1e-12)
    assert path.stat().st_size > 10_000

"""select_for_site: records scaled for a site spectrum (NTC 2018, EN 1998-1, a table), its
configuration and the scaled motions the assessment runs."""

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.groundmotion.spectra import response_spectrum
from archrock.studies.codecheck import SiteSpectrum
from archrock.studies.selection import (SelectionConfig, scaled_motions, select_for_site,
                                        site_target)

SITE = SiteSpectrum.ntc(0.25, 2.5, 0.3, "B")


@pytest.fixture(scope="module")
def records(noise_records):
    return noise_records(12)


@pytest.fixture(scope="module")
def selection(records):
    return select_for_site(SITE, records)


def test_the_site_spectrum_is_the_target(selection):
    sel = selection
    assert sel.pga_min_g == pytest.approx(SITE.pga, rel=1e-15)  # a_g S = 0.25 x 1.15
    assert SITE.pga == pytest.approx(0.2875, rel=1e-12)
    np.testing.assert_allclose(sel.target, SITE.se(sel.periods), rtol=1e-12)
    assert sel.description.startswith("NTC 2018 elastic spectrum, ag = 0.25 g, F0 = 2.5")
    assert sel.rules_hold and sel.ratio_min >= 0.90 and sel.pga_mean_g >= SITE.pga
    # the corners are checked at the corners: T_C = C_C Tc* lies on the grid
    assert np.any(np.isclose(sel.periods, SITE.parameters["T_C"], rtol=0, atol=1e-15))


def test_scaled_motions_are_the_selection(records, selection):
    scaled = scaled_motions(selection, records)
    assert len(scaled) == 7
    for m, i, f in zip(scaled, selection.indices, selection.factors):
        assert np.array_equal(m.accel, records[i].accel * f)
        assert m.name == records[i].name
    # their own mean spectrum meets the rule the selection states
    mean = np.mean([response_spectrum(m, selection.periods) for m in scaled], axis=0)
    assert (mean / SITE.se(selection.periods)).min() >= 0.90
    with pytest.raises(ArchInputError, match="^motions: "):
        scaled_motions(selection, records[:3])


def test_config_round_trip_and_its_use(records):
    cfg = SelectionConfig(count=5, period_range=(0.2, 1.5), lower=0.95, scale_bounds=(0.25, 5),
                          one_per_station=False)
    assert SelectionConfig.from_dict(cfg.to_dict()) == cfg
    assert cfg.to_dict()["period_range"] == [0.2, 1.5]
    ec8 = SiteSpectrum.ec8(0.2, "C", 1)
    sel = select_for_site(ec8, records, cfg)
    assert sel.count == 5 and not sel.code_mean_rule
    assert sel.ratio_min >= 0.95 and sel.period_range == (0.2, 1.5)
    assert sel.factors.min() >= 0.25 and sel.factors.max() <= 5.0
    assert sel.description.startswith("EN 1998-1 type 1 elastic spectrum")


def test_a_table_spectrum(records, tmp_path):
    p = tmp_path / "site.txt"
    p.write_text("0 0.2\n0.1 0.5\n0.5 0.5\n2.5 0.1\n")
    spec = SiteSpectrum.from_file(p)
    periods, se = site_target(spec, (0.15, 2.0))
    assert periods[0] == 0.0 and periods[-1] == pytest.approx(2.5, rel=1e-12)
    assert 0.5 in periods  # a row of the table inside the range
    sel = select_for_site(spec, records)
    assert sel.rules_hold and sel.pga_mean_g >= 0.2
    assert sel.description.startswith("spectrum table site.txt")


@pytest.mark.parametrize("kwargs, field", [
    (dict(count=0), "count"), (dict(period_range=(2.0, 1.0)), "period_range"),
    (dict(lower=1.2), "lower"), (dict(scale_bounds=(0.0, 1.0)), "scale_bounds"),
    (dict(one_per_station="yes"), "one_per_station")])
def test_bad_config_names_the_field(kwargs, field):
    with pytest.raises(ArchInputError, match=f"^{field}: "):
        SelectionConfig(**kwargs)
    with pytest.raises(ArchInputError, match="^selection: unknown field 'counts'"):
        SelectionConfig.from_dict({"counts": 7})


def test_bad_arguments(records):
    with pytest.raises(ArchInputError, match="^spectrum: "):
        select_for_site("ntc", records)
    with pytest.raises(ArchInputError, match="^config: "):
        select_for_site(SITE, records, {"count": 7})
    with pytest.raises(ArchInputError, match="^period_range: "):  # beyond EC8's 4 s
        select_for_site(SiteSpectrum.ec8(0.2, "C"), records,
                        SelectionConfig(period_range=(0.15, 5.0)))

"""band_limited_noise: the seeded stand-in record of the tests, benchmarks and figures."""

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.groundmotion import band_limited_noise


def test_noise_has_its_pga_length_and_quiet_ends():
    r = band_limited_noise(6.0, 0.01, (1.0, 5.0), seed=1, pga_g=0.3)
    assert r.name == "noise 1"
    assert r.pga_g == pytest.approx(0.3, rel=1e-12)
    assert len(r.accel) == 600
    assert r.times[1] - r.times[0] == pytest.approx(0.01, rel=1e-12)
    # the sin^2 envelope: the first sample is exactly 0, the edges far below the peak
    assert abs(r.accel[0]) < 1e-12 * r.pga
    assert np.max(np.abs(r.accel[:10])) < 0.05 * r.pga


def test_noise_energy_lies_in_its_band():
    r = band_limited_noise(40.0, 0.01, (1.0, 5.0), seed=7, pga_g=0.3, name="x")
    power = np.abs(np.fft.rfft(r.accel)) ** 2
    f = np.fft.rfftfreq(len(r.accel), 0.01)
    inside = power[(f >= 0.5) & (f <= 8.0)].sum() / power.sum()
    assert inside > 0.95
    assert r.name == "x"


def test_noise_is_reproducible_and_seeded():
    a = band_limited_noise(4.0, 0.01, (0.3, 2.0), seed=3, pga_g=0.2)
    b = band_limited_noise(4.0, 0.01, (0.3, 2.0), seed=3, pga_g=0.2)
    c = band_limited_noise(4.0, 0.01, (0.3, 2.0), seed=4, pga_g=0.2)
    assert np.array_equal(a.accel, b.accel)
    assert not np.allclose(a.accel, c.accel)


@pytest.mark.parametrize("kwargs, field", [
    (dict(duration=0.0), "duration"), (dict(dt=-0.01), "dt"), (dict(seed=-1), "seed"),
    (dict(band=(5.0, 1.0)), "band"), (dict(band=(1.0, 60.0)), "band"),
    (dict(pga_g=0.0), "pga_g"), (dict(duration=0.01), "duration")])
def test_bad_input_names_the_field(kwargs, field):
    args = dict(duration=6.0, dt=0.01, band=(1.0, 5.0), seed=1, pga_g=0.3) | kwargs
    with pytest.raises(ArchInputError, match=f"^{field}: "):
        band_limited_noise(**args)

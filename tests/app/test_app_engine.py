"""``archrock app``: the pulse and record responses answered by the model that holds
(:func:`archrock.studies.enginestudy.choose_dynamics` at the request's friction), the contact
engine as a job where it governs, the four-link answer only when asked for by name (and then
labelled not valid here), and requests with unknown keys refused naming the key."""

import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")
pytest.importorskip("pandas")

import archrock  # noqa: E402
from archrock.app import api  # noqa: E402
from archrock.statics.friction import DEFAULT_FRICTION  # noqa: E402

OPPENHEIM = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
PULSE = {"kind": "oppenheim", "amplitude": -1.0, "duration": 0.2}
#: Oppenheim's arch at mu = 0.4 (its four-link collapse needs 0.495): the engine answers; this
#: pulse collapses it in about 0.66 s of simulated time, under a second of the engine's.
SLIDING = {"arch": OPPENHEIM, "friction": 0.4,
           "pulse": {"kind": "oppenheim", "amplitude": -5.0, "duration": 1.0}}


# ---------------------------------------------------------------------------- the routing
def test_where_one_degree_of_freedom_follows_the_four_link_model_answers_at_once(client):
    r = client.post("/api/respond", json={"arch": OPPENHEIM, "pulse": PULSE})
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["model"] == "fourlink" and d["valid"] is True and "job" not in d
    dyn = d["dynamics"]
    assert dyn["requested"] == "auto" and dyn["used"] == "fourlink"
    assert abs(dyn["friction"] - DEFAULT_FRICTION) < 1e-12  # the package's one default
    assert abs(dyn["friction_needed"]["l"] - 0.49513) < 5e-5
    assert d["status"] == "rest" and abs(d["peak"] - 0.0372) < 5e-5
    assert d["label"].startswith("four-link model: no piers")


def test_the_four_link_answer_asked_for_by_name_where_it_slides_is_labelled_not_valid(client):
    r = client.post("/api/respond", json={**SLIDING, "dynamics": "fourlink"})
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["model"] == "fourlink" and d["valid"] is False
    assert d["label"].startswith("four-link model, not valid here: ")
    assert "WARNING not valid here" in d["dynamics"]["reason"]
    assert abs(d["dynamics"]["friction"] - 0.4) < 1e-12


def test_where_the_joints_slide_the_engine_answers_as_a_job(client, wait_job):
    r = client.post("/api/respond", json=SLIDING)
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["model"] == "engine" and d["dynamics"]["used"] == "engine"
    assert "they slide" in d["dynamics"]["reason"] and d["job"]["state"] == "running"
    s = wait_job(client, d["job"]["id"], timeout=120)
    assert s["state"] == "done", s
    res = s["result"]
    # the engine's own outcome (the library's EngineRun at mu = 0.4: collapse at 0.6588 s here)
    lib = archrock.studies.enginestudy.EngineRun(
        settings=archrock.contact.EngineSettings(friction=0.4)).respond(
            archrock.oppenheim_arch(), archrock.groundmotion.PulseSpec("oppenheim", -5.0, 1.0).build())
    assert res["model"] == "engine" and res["collapsed"] is True and lib.collapsed
    assert abs(res["t_collapse"] - lib.t_collapse) < 0.02
    assert abs(res["friction"] - 0.4) < 1e-12 and res["engine"]["friction"] == 0.4
    assert res["dynamics"]["used"] == "engine" and res["label"].startswith("contact engine")
    assert s["done"] == s["total"] > 1  # progress in tenths of a simulated second, ends at 100%
    bf = res["block_frames"]
    assert len(bf["frames"]) == len(bf["time"]) == len(bf["phi"]) >= 2
    assert len(bf["frames"][0]) == 7 and len(bf["origin"]) == 7
    csv = client.get(f"/api/jobs/{s['id']}/download")
    assert csv.status_code == 200 and csv.text.startswith("t_s,phi_rad\n0.00000,")


def test_the_engine_job_is_cancelled_at_once(client, wait_job):
    heavy = {"arch": {**OPPENHEIM, "pier_height": 30, "pier_width": 5}, "pulse": PULSE}
    r = client.post("/api/respond", json={**heavy, "dynamics": "engine"})
    assert r.status_code == 200, r.text
    job = r.json()["job"]
    c = client.post(f"/api/jobs/{job['id']}/cancel", json={})
    assert c.status_code == 200 and c.json()["state"] == "cancelled"
    assert wait_job(client, job["id"], timeout=10)["state"] == "cancelled"


def test_the_engine_needs_pymunk_only_where_pymunk_is_named(monkeypatch):
    """archrock's own engine runs without pymunk; the soft-contact cross-check names its extra."""
    import archrock.contact.engine
    from archrock.contact import EngineSettings, require_engine

    def missing():
        raise ImportError("the contact engine (archrock dem / verify) needs pymunk: "
                          "pip install \"archrock[dem]\"")

    monkeypatch.setattr(archrock.contact.engine, "import_pymunk", missing)
    require_engine()  # archrock's engine: nothing to import
    require_engine(EngineSettings(engine="archrock"))
    with pytest.raises(ImportError, match=r"archrock\[dem\]"):
        require_engine(EngineSettings(engine="pymunk"))


def test_friction_none_excludes_sliding_and_a_bad_friction_is_400(client):
    d = client.post("/api/respond", json={**SLIDING, "friction": "none"}).json()
    assert d["model"] == "fourlink" and d["dynamics"]["friction"] is None
    r = client.post("/api/respond", json={**SLIDING, "friction": -1})
    assert r.status_code == 400
    assert r.json()["error"] == "friction: -1; allowed a finite number > 0, or none (sliding excluded)"
    assert client.get("/api/limits").json()["default_friction"] == DEFAULT_FRICTION


def test_the_pages_friction_field_starts_at_the_package_default(client):
    page = client.get("/").text
    assert f'id="friction-mu" type="text" size="5" value="{DEFAULT_FRICTION:g}"' in page


def test_response_csv_where_the_engine_governs_points_to_the_job(client):
    r = client.post("/api/export", json={"what": "response-csv", **SLIDING})
    assert r.status_code == 400
    assert r.json()["error"].startswith("dynamics: the contact engine answers this arch (")


@pytest.mark.parametrize("url, body", [
    ("/api/ensemble", {"arch": OPPENHEIM, "samples": 50, "friction": 0.4, "pulse": PULSE}),
    ("/api/curve", {"arch": OPPENHEIM, "samples": 2, "friction": 0.4, "durations": "0.2"}),
], ids=["ensemble", "curve"])
def test_four_link_studies_are_refused_where_the_model_does_not_hold(client, url, body):
    """The app's ensemble under a pulse and its curve run the four-link model: at mu = 0.4 on
    Oppenheim's arch (the joints slide) they answer 422 naming the engine's command, never
    the four-link numbers."""
    r = client.post(url, json=body)
    assert r.status_code == 422 and r.json()["kind"] == "outcome"
    what, cmd = ("pulse", "ensemble") if "ensemble" in url else ("curve", "curves")
    msg = r.json()["error"]
    assert msg.startswith(f"{what}: the app runs it with the four-link model, which does not hold")
    assert msg.endswith(f"archrock {cmd} --dynamics engine runs the contact engine")


def test_a_four_link_ensemble_states_its_dynamics(client, wait_job):
    r = client.post("/api/ensemble", json={"arch": OPPENHEIM, "samples": 50, "pulse": PULSE})
    assert r.status_code == 200, r.text
    s = wait_job(client, r.json()["id"])
    dyn = s["result"]["dynamics"]
    assert s["state"] == "done" and dyn["used"] == "fourlink"
    assert abs(dyn["friction"] - DEFAULT_FRICTION) < 1e-12


# ---------------------------------------------------------------------------- unknown keys
@pytest.mark.parametrize("url, body, said", [
    ("/api/limit", {"arch": OPPENHEIM, "thickness": -3},
     "unknown field 'thickness'; allowed: arch, friction, thrust_range (thickness is a field of "
     "the arch: put it inside \"arch\")"),
    ("/api/limit", {"arch": {**OPPENHEIM, "thicknes": 1.2}}, "unknown field 'arch.thicknes'; "
     "allowed in arch: shape, span, rise,"),
    ("/api/respond", {"arch": OPPENHEIM, "pulse": {**PULSE, "amp": 2}},
     "unknown field 'pulse.amp'; allowed in pulse: kind, amplitude, duration"),
    ("/api/respond", {"arch": OPPENHEIM, "record": {"id": "x", "scale": 2}},
     "unknown field 'record.scale'; allowed in record: id"),
    ("/api/respond", {"arch": OPPENHEIM, "pulse": PULSE, "model": "engine"},
     "unknown field 'model'; allowed: arch, pulse, record, t_end, exaggerate, friction, dynamics"),
    ("/api/ensemble", {"arch": OPPENHEIM, "spreads": {"span": 0.1, "rise": 0.1}},
     "unknown field 'spreads.rise'; allowed in spreads: span, thickness, radius, tilt"),
    ("/api/curve", {"arch": OPPENHEIM, "duration": 0.2},
     "unknown field 'duration'; allowed: arch, samples, seed, spreads, durations, kind, friction"),
    ("/api/report", {"arch": OPPENHEIM, "contacts": False},
     "unknown field 'contacts'; allowed: arch, samples, seed, spreads, contact"),
    ("/api/export", {"what": "geometry", "arch": OPPENHEIM, "format": "svg"},
     "unknown field 'format'; allowed: what, arch, friction, thrust_range, pulse, record,"),
], ids=["limit", "arch", "pulse", "record", "respond", "spreads", "curve", "report", "export"])
def test_unknown_keys_are_refused_naming_the_key(client, url, body, said):
    r = client.post(url, json=body)
    assert r.status_code == 400, r.text
    assert r.json()["error"].startswith(said), r.json()["error"]


def test_unknown_query_fields_of_an_upload_are_refused(client):
    r = client.post("/api/record?name=a.txt&unit=g", content=b"0 0\n0.01 0.1\n",
                    headers={"Content-Type": "application/octet-stream"})
    assert r.status_code == 400
    assert r.json()["error"] == "unknown field 'record.unit'; allowed in record: name, units, scale"


def test_the_arch_fields_are_the_ones_it_reads():
    """fields.ARCH_FIELDS lists what arch_from_params reads: a field it reads is not refused."""
    import inspect

    from archrock.app.fields import ARCH_FIELDS

    src = inspect.getsource(api.arch_from_params) + inspect.getsource(api._uploaded_arch)
    read = {f for f in ARCH_FIELDS if f'"{f}"' in src}
    assert read == set(ARCH_FIELDS)


@pytest.mark.slow
def test_the_heavy_pier_case_is_answered_by_the_engine_collapse_at_095_g(client, wait_job,
                                                                        heavy_piers_file):
    """The issue's case: the four-link model says "at rest" at -0.95 g (unconservative: a pier
    rocks with the arch); the page's play runs the engine, which collapses it."""
    import json

    geometry = json.loads(heavy_piers_file.read_text(encoding="utf-8"))
    body = {"arch": {"geometry": geometry, "name": "heavy piers"},
            "pulse": {"kind": "oppenheim", "amplitude": -0.95, "duration": 0.2}}
    d = client.post("/api/respond", json=body).json()
    assert d["model"] == "engine" and d["dynamics"]["single_dof"]["valid"] is False
    assert "a pier" in d["label"] or "piers rock" in d["label"]
    s = wait_job(client, d["job"]["id"], timeout=300)
    assert s["state"] == "done", s
    assert s["result"]["collapsed"] is True and 1.0 < s["result"]["t_collapse"] < 6.0
    named = client.post("/api/respond", json={**body, "dynamics": "fourlink"}).json()
    assert named["valid"] is False and named["status"] == "rest"
    assert named["label"].startswith("four-link model, not valid here: ")

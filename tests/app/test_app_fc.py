"""The app with a finite compressive strength: the arch's ``fc`` field reaches /api/limit and
/api/respond, whose answers carry it and are the library's (the hinges inset by half a stress
block), and an arch without it answers as before (``fc`` null, edge hinges)."""

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx")

import archrock  # noqa: E402
from archrock.dynamics.finite import inset_joint_points  # noqa: E402

OPPENHEIM = {"radius": 10.0, "embrace": 157.5, "thickness": 1.5, "voussoirs": 7}
PULSE = {"kind": "oppenheim", "amplitude": -1.0, "duration": 0.2}


def test_limit_carries_fc_and_the_inset_hinges(client):
    weak = client.post("/api/limit", json={"arch": {**OPPENHEIM, "fc": 2.0}})
    plain = client.post("/api/limit", json={"arch": OPPENHEIM})
    assert weak.status_code == 200 and plain.status_code == 200, weak.text
    w, p = weak.json(), plain.json()
    assert p["fc"] is None and w["fc"] == pytest.approx(2.0, rel=0, abs=0)
    arch = archrock.oppenheim_arch().with_fc(2.0)
    lim = archrock.limit_analysis(arch)
    assert w["summary"]["k"] == pytest.approx(lim.k, rel=1e-9)
    assert w["summary"]["k"] < p["summary"]["k"] - 0.01
    pts = inset_joint_points(arch, lim.mechanism_l, lim.zones_l)
    for h in w["hinges"]["l"]:
        e = 0 if h["edge"] == "intrados" else 1
        assert np.allclose(h["point"], pts[h["joint"], e], rtol=0, atol=1e-6)
        edge = archrock.oppenheim_arch().joint_point(h["joint"], h["edge"])
        assert np.hypot(*(np.asarray(h["point"]) - edge)) > 0.01  # moved in by a / 2
    for h in p["hinges"]["l"]:
        edge = archrock.oppenheim_arch().joint_point(h["joint"], h["edge"])
        assert np.allclose(h["point"], edge, rtol=0, atol=1e-6)


def test_respond_carries_fc_and_is_the_librarys(client):
    r = client.post("/api/respond", json={"arch": {**OPPENHEIM, "fc": 2.0}, "pulse": PULSE,
                                          "t_end": 3})
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["fc"] == pytest.approx(2.0, rel=0, abs=0)
    model = archrock.prepare(archrock.oppenheim_arch().with_fc(2.0))
    lib = archrock.respond(model, archrock.pulse("oppenheim", -1.0, 0.2), t_end=3.0)
    assert d["status"] == lib.status == "collapsed"
    assert abs(d["peak"] - lib.peak) < 1e-9
    assert np.allclose(d["chain_links"][0]["points"], model.mech_l.points, rtol=0, atol=1e-6)
    plain = client.post("/api/respond", json={"arch": OPPENHEIM, "pulse": PULSE, "t_end": 3})
    assert plain.json()["fc"] is None and plain.json()["status"] == "rest"


def test_ensemble_request_takes_the_strength_spread():
    from archrock.app import api

    cfg = api.ensemble_config({"arch": {**OPPENHEIM, "fc": 3.0}, "samples": 20,
                               "spreads": {"fc": 0.3}})
    assert cfg.sampler.finite and cfg.spreads.fc == pytest.approx(0.3, rel=0, abs=0)
    drawn = [a.fc for a in cfg.sampler.arches(0, 5)]
    assert min(drawn) >= 2.1 - 1e-12 and max(drawn) <= 3.9 + 1e-12 and np.ptp(drawn) > 0
    with pytest.raises(archrock.errors.ArchInputError, match=r"^spread fc: 0\.3"):
        api.ensemble_config({"arch": OPPENHEIM, "samples": 20, "spreads": {"fc": 0.3}})


def test_limit_with_friction_and_fc_solves_both_together(client):
    """Heyman's friction analysis assumes no crushing: with fc the page's friction numbers are
    the graph program's (friction and stress blocks together), below the crushing-only k."""
    from archrock.studies.governing import governing_capacity

    r = client.post("/api/limit", json={"arch": {**OPPENHEIM, "fc": 2.0}, "friction": 0.3})
    assert r.status_code == 200, r.text
    s = r.json()["summary"]
    assert s["friction_with_crushing"] is True
    assert "friction_needed_l" not in s
    cap = governing_capacity(archrock.oppenheim_arch().with_fc(2.0), 0.3)
    both = cap.analyses[-1]
    assert both.hypotheses[1] == "crushing at f_c = 2 MPa"
    assert s["friction_k_l"] == pytest.approx(both.k_l, rel=1e-12)
    assert s["friction_k_l"] <= s["k_l"] * (1 + 1e-9)

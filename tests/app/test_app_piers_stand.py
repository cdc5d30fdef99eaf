"""The app says what the command line says when an arch cannot stand on its piers: the piers
are to blame and the least width that carries it (the library's message; issue 30)."""

from __future__ import annotations

SEMICIRCLE = {"radius": 5.0, "embrace": 180.0, "thickness": 0.8, "voussoirs": 9}


def test_limit_on_slender_piers_names_piers_and_width(client):
    r = client.post("/api/limit", json={"arch": {**SEMICIRCLE, "pier_height": 15.0,
                                                 "pier_width": 1.5}})
    assert r.status_code == 422, r.text
    err = r.json()["error"]
    assert "cannot stand on its piers (two piers 1.5 m wide, 15 m high)" in err
    assert "give the piers a width of 1.712 m or more" in err
    assert "increase the thickness" not in err

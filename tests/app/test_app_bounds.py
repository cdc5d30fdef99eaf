"""The app answers 400 with the library's one line for numbers past the door's bounds (a
401-digit radius answered 500)."""

VOUSSOIRS = [{"span_deg": 22.5, "radius": 10.0, "thickness": 1.5}] * 7


def test_a_401_digit_radius_is_400(client):
    data = {"voussoirs": [{**VOUSSOIRS[0], "radius": int("1" * 401)}] + VOUSSOIRS[1:]}
    r = client.post("/api/limit", json={"arch": {"geometry": data}})
    assert r.status_code == 400
    assert r.json()["error"] == ("geometry: voussoirs[0].radius: a 401-digit number is out of "
                                 "range; allowed 1e-08 m to 1e+08 m")


def test_a_load_past_1e12_kg_is_400_and_a_normal_one_answers(client):
    heavy = {"voussoirs": VOUSSOIRS, "loads": [{"voussoir": 3, "mass": 1e13, "at": [0, 11]}]}
    r = client.post("/api/limit", json={"arch": {"geometry": heavy}})
    assert r.status_code == 400 and "loads[0].mass: 1e+13 is out of range" in r.json()["error"]
    ok = {"voussoirs": VOUSSOIRS, "loads": [{"voussoir": 3, "mass": 8000.0, "at": [0, 11]}]}
    r = client.post("/api/limit", json={"arch": {"geometry": ok}})
    assert r.status_code == 200

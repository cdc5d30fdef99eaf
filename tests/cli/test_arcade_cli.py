"""archrock arcade: several arches on shared piers from flags, geometry files or an arcade
document; the graph LP's k and mechanism, the figure, the refusals."""

from __future__ import annotations

import json

import pytest

from archrock.cli import main
from archrock.geometry import nominal_arch

THREE = ("arcade", "--spans", "10", "10", "10", "--thickness", "0.8", "--pier-height", "8",
         "--pier-width", "2.5", "1.8", "1.8", "2.5")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_three_spans_table_and_json(capsys):
    code, out, err = run(capsys, *THREE)
    assert code == 0, err
    assert out.startswith("arcade: 3 spans, 31 blocks (27 voussoirs, 4 piers), 34 contacts")
    assert "k_l = 0.139911" in out and "k_r = 0.139911" in out
    assert "pier 4 foot, outer face" in out and "pier 1 foot, outer face" in out
    assert "1 degree of freedom" in out
    code, out, err = run(capsys, *THREE, "--json")
    d = json.loads(out)
    assert d["k_l"] == pytest.approx(0.139911, abs=5e-7)
    assert abs(d["l"]["k_virtual_work"] - d["k_l"]) < 1e-9
    assert d["arcade"]["blocks"] == 31 and len(d["arcade"]["piers"]) == 4
    assert {h["place"] for h in d["l"]["mechanism"]["hinges"]} >= {"pier 2 foot, right face",
                                                                  "pier 3 foot, right face"}


@pytest.mark.slow
def test_figure(capsys, tmp_path):
    fig = tmp_path / "arcade.png"
    code, out, err = run(capsys, *THREE, "--plot", str(fig))
    assert code == 0, err
    assert f"wrote {fig}" in out
    assert fig.exists() and fig.stat().st_size > 10_000


def test_flags_file_and_document_agree(capsys, tmp_path):
    """The same arcade from flags, from a repeated geometry file and from its own document:
    the same k and hinges."""
    from archrock.geometry.files import write_arch

    doc = tmp_path / "arc.json"
    code, out_flags, err = run(capsys, "arcade", "--spans", "10", "10", "--thickness", "0.8",
                               "--pier-height", "8", "--pier-width", "2.5", "1.8", "2.5",
                               "--json", "--write", str(doc))
    assert code == 0, err
    arch = tmp_path / "semicircle.json"
    write_arch(nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9), arch)
    code, out_file, err = run(capsys, "arcade", "--geometry", str(arch), "--repeat", "2",
                              "--pier-height", "8", "--pier-width", "2.5", "1.8", "2.5",
                              "--json")
    assert code == 0, err
    code, out_doc, err = run(capsys, "arcade", "--arcade", str(doc), "--json")
    assert code == 0, err
    a, b, c = (json.loads(o) for o in (out_flags, out_file, out_doc))
    for d in ("l", "r"):
        assert b[f"k_{d}"] == pytest.approx(a[f"k_{d}"], abs=1e-9)
        assert c[f"k_{d}"] == a[f"k_{d}"]
        assert b[d]["mechanism"]["hinges"] == a[d]["mechanism"]["hinges"]
        assert c[d]["mechanism"]["hinges"] == a[d]["mechanism"]["hinges"]
    assert a["k_l"] == pytest.approx(0.140874, abs=5e-7)


def test_friction_and_families(capsys):
    code, out, err = run(capsys, "arcade", "--spans", "10", "--shape", "pointed", "--rises",
                         "7", "--thickness", "0.9", "--voussoirs", "10", "--pier-height", "4",
                         "--pier-width", "2", "--json")
    assert code == 0, err
    assert json.loads(out)["k_l"] == pytest.approx(0.196306, abs=5e-7)
    code, out, err = run(capsys, "arcade", "--spans", "10", "--thickness", "0.8",
                         "--pier-height", "4", "--pier-width", "2", "--friction", "0.4",
                         "--json")
    d = json.loads(out)
    assert d["l"]["friction"] == 0.4 and d["k_l"] < 0.168899  # sliding on the far pier's top


@pytest.mark.parametrize("extra, start", [
    (("--spans", "10", "--pier-height", "4"), "--pier-width: needed"),
    (("--spans", "10", "10", "--pier-height", "4", "4", "--pier-width", "2"),
     "--pier-height: 2 values; allowed one for all, or 3"),
    (("--spans", "10", "10", "--pier-height", "4", "--pier-width", "2", "1", "2"),
     "--pier-width: value 2 (pier 2): pier 2 is 1 m wide, narrower than the two springing"),
    (("--spans", "10", "--pier-height", "0", "--pier-width", "2"),
     "--pier-height: value 1 (pier 1): 0 is out of range; allowed > 0 m"),
    (("--spans", "0", "--pier-height", "4", "--pier-width", "2"),
     "--spans: 0 (span 1) is out of range; allowed 1e-8 to 1e8 m"),
    (("--spans", "10", "10", "--thickness", "1", "2", "3", "--pier-height", "4",
      "--pier-width", "2"), "--thickness: 3 values for 2 spans"),
    (("--spans", "10", "--thickness", "12", "--pier-height", "4", "--pier-width", "2"),
     "--thickness (span 1)"),
    (("--spans", "10", "--rises", "5", "--pier-height", "4", "--pier-width", "2"),
     "--rises: needs --shape"),
    (("--pier-height", "4", "--pier-width", "2"), "--spans: needed"),
    (("--spans", "10", "--pier-height", "4", "--pier-width", "2", "--pier-courses", "0"),
     "--pier-courses: value 1 (pier 1): 0 is out of range"),
    (("--spans", "10", "--pier-height", "4", "--pier-width", "2", "--ramp", "--pulse",
      "oppenheim", "--amplitude", "-0.3", "--pulse-duration", "0.2"),
     "--ramp: cannot be combined with a ground motion"),
    (("--arcade", "x.json", "--spans", "10"), "--arcade: cannot be combined with --spans"),
])
def test_bad_input_is_one_line_naming_the_flag(capsys, extra, start):
    code, out, err = run(capsys, "arcade", *extra)
    assert code == 2
    assert err.startswith(f"archrock: error: {start}"), err
    assert len(err.strip().splitlines()) == 1


def test_ramp_and_pulse_run_the_engine(capsys):
    pytest.importorskip("pymunk")
    code, out, err = run(capsys, "arcade", "--spans", "10", "--thickness", "0.8",
                         "--voussoirs", "5", "--pier-height", "2", "--pier-width", "1.5",
                         "--pulse", "oppenheim", "--amplitude", "-0.05", "--pulse-duration",
                         "0.2", "--t-end", "0.5")
    assert code == 0, err
    assert "contact engine under Oppenheim pulse: at rest" in out


def test_an_arcade_that_cannot_stand_says_so(capsys, tmp_path):
    """A heavy load on one haunch (8 t/m on voussoir 6): k_r < 0, and the table says the
    arcade cannot stand under its own weight."""
    from archrock.geometry import Arch, Load
    from archrock.geometry.files import write_arch

    a = nominal_arch(radius=5, embrace_deg=180, thickness=0.8, voussoirs=9)
    loaded = Arch(a.spans, a.radii, a.thicknesses, a.density, "loaded",
                  (Load(6, 8000.0, (2.0, 5.5)),))
    f = write_arch(loaded, tmp_path / "loaded.json")
    code, out, err = run(capsys, "arcade", "--geometry", str(f), "--pier-height", "4",
                         "--pier-width", "2")
    assert code == 0, err
    assert "k_r = -0.083677" in out
    assert "cannot stand under its own weight: k_r < 0 (it needs a horizontal load toward +x" \
        in out


def test_frame_document_under_a_record(capsys, tmp_path):
    """Any graph of blocks from its document (Makris & Vassiliou's frame: two columns 0.6 x 2.4
    m and a beam): k = b/h = 0.25, and the engine under a two-column record (0.1 g for 0.5 s,
    below the activation) leaves it at rest."""
    pytest.importorskip("pymunk")
    from archrock.geometry.arcade import GROUND, Arcade, Block, Contact
    from archrock.geometry.files import write_arcade

    b, h, span = 0.3, 1.2, 6.0
    blocks = (Block([(-b, 0), (b, 0), (b, 2 * h), (-b, 2 * h)], "pier", "column 1"),
              Block([(span - b, 0), (span + b, 0), (span + b, 2 * h), (span - b, 2 * h)],
                    "pier", "column 2"),
              Block([(-b, 2 * h), (span + b, 2 * h), (span + b, 2 * h + 0.3),
                     (-b, 2 * h + 0.3)], "beam", "beam"))
    contacts = (Contact(GROUND, 0, [(-b, 0), (b, 0)], "column 1 foot", ("left", "right")),
                Contact(GROUND, 1, [(span - b, 0), (span + b, 0)], "column 2 foot",
                        ("left", "right")),
                Contact(0, 2, [(-b, 2 * h), (b, 2 * h)], "column 1 top", ("left", "right")),
                Contact(1, 2, [(span - b, 2 * h), (span + b, 2 * h)], "column 2 top",
                        ("left", "right")))
    doc = write_arcade(Arcade(blocks, contacts, 2000.0), tmp_path / "frame.json")
    rec = tmp_path / "rec.txt"
    rec.write_text("".join(f"{0.01 * i:.2f} {0.1 if i <= 50 else 0.0}\n" for i in range(101)))
    code, out, err = run(capsys, "arcade", "--arcade", str(doc), "--record", str(rec),
                         "--units", "g", "--t-end", "1")
    assert code == 0, err
    assert out.startswith("frame: 3 blocks (2 pier blocks, 1 beam), 4 contacts")
    assert "k_l = 0.250000" in out and "column 1 foot, right; column 2 foot, right" in out
    assert "contact engine under rec: at rest" in out


ONE = ("arcade", "--spans", "10", "--thickness", "0.8", "--pier-height", "4", "--pier-width", "2")


def test_strength_flags_and_document(capsys, tmp_path):
    """--fc and --pier-fc: the report names the strengths, the bracket and the stress blocks
    at the hinges; k falls below Heyman's 0.168899 (docs/piers.md) and further with weak
    piers; --write keeps the strengths in the document, which gives the same k back."""
    code, out, err = run(capsys, *ONE, "--fc", "10", "--pier-fc", "1", "--write",
                         str(tmp_path / "a.json"))
    assert code == 0, err
    assert "compressive strength f_c: pier 1 MPa, voussoir 10 MPa" in out
    assert "k_l = 0.133187" in out and "pier 2 foot 284.9 mm" in out
    assert "bracket of the static optimum: [0.1331874" in out
    code, out, err = run(capsys, "arcade", "--arcade", str(tmp_path / "a.json"), "--json")
    d = json.loads(out)
    assert d["arcade"]["fc"] == {"pier": 1.0, "voussoir": 10.0}
    assert d["k_l"] == pytest.approx(0.133187470, abs=1e-8)
    lo, hi = d["l"]["k_bounds"]
    assert lo == d["k_l"] and hi - lo <= 1e-6 * hi
    assert abs(d["l"]["k_virtual_work"] - d["k_l"]) < 1e-9
    code, out, err = run(capsys, "arcade", "--arcade", str(tmp_path / "a.json"), "--fc", "10")
    k_all = float(out.split("k_l = ")[1].split()[0])
    assert 0.133187 < k_all < 0.168899  # --fc replaces the file's pier strength too


@pytest.mark.parametrize("extra, line", [
    (("--fc", "0.01"), "archrock: error: --fc: 0.01 is out of range; allowed 0.1 to 1000 MPa"),
    (("--pier-fc", "5000"), "archrock: error: --pier-fc: 5000 is out of range; allowed 0.1"),
])
def test_bad_strength_is_one_line(capsys, extra, line):
    code, out, err = run(capsys, *ONE, *extra)
    assert code == 2 and err.startswith(line) and len(err.strip().splitlines()) == 1


def test_geometry_files_bring_their_strength(capsys, tmp_path):
    """Arch files with "fc" make an arcade of that strength (voussoirs and piers); --fc
    replaces it."""
    from archrock.geometry.files import write_arch

    f = write_arch(nominal_arch(radius=5, embrace_deg=180, thickness=0.8,
                                voussoirs=9).with_fc(3.0), tmp_path / "g.json")
    base = ("arcade", "--geometry", str(f), "--pier-height", "4", "--pier-width", "2")
    code, out, err = run(capsys, *base)
    assert code == 0, err
    assert "compressive strength f_c: pier 3 MPa, voussoir 3 MPa" in out
    k3 = float(out.split("k_l = ")[1].split()[0])
    code, out, err = run(capsys, *base, "--fc", "1")
    assert "pier 1 MPa, voussoir 1 MPa" in out
    assert float(out.split("k_l = ")[1].split()[0]) < k3 < 0.168899

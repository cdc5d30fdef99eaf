"""Defect maps on an arch on piers: voussoir defects and pier-course defects named and reported
apart, and the map's diverging colours (issue 30)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from archrock.cli import main
from archrock.geometry import ArchOnPiers, apply_defect, nominal_arch, with_piers
from archrock.reports.defects import format_defects
from archrock.studies.defectmap import defect_map

PIERS = ["--radius", "5", "--embrace", "180", "--thickness", "0.8", "--voussoirs", "9",
         "--pier-height", "4", "--pier-width", "2"]


@pytest.fixture(scope="module")
def on_piers():
    return with_piers(nominal_arch(5.0, 180.0, 0.8, 9), 4.0, 2.0)


@pytest.fixture(scope="module")
def pier_map(on_piers):
    return defect_map(on_piers)  # each block keeps 70% of its thickness (a pier: its width)


def test_blocks_are_named_and_grouped_by_kind(pier_map):
    assert pier_map.places[0] == "left pier" and pier_map.places[-1] == "right pier"
    assert pier_map.places[1:-1] == tuple(f"voussoir {i}" for i in range(9))
    assert pier_map.groups == ("piers",) + ("arch",) * 9 + ("piers",)


def test_thinned_piers_are_pier_defects_not_voussoirs(pier_map):
    # the voussoirs' worst (chain 3 and 7 = the arch's voussoirs 2 and 6) and the piers' apart
    assert pier_map.worst_all == (3, 7)
    assert pier_map.worst_pier_all == (0, 10)
    assert pier_map.relative_loss[3] == pytest.approx(0.5012, abs=1e-4)
    assert pier_map.relative_loss[0] == pytest.approx(0.5544, abs=1e-4)
    d = pier_map.to_dict()
    assert d["worst"]["places"] == ["voussoir 2", "voussoir 6"]
    assert d["worst_pier"]["places"] == ["left pier", "right pier"]
    assert d["blocks"] == {"voussoirs": 9, "pier_blocks": 2, "buttress_blocks": 0, "piers": 2,
                           "blocks": 11}
    assert [r["group"] for r in d["rows"]].count("piers") == 2
    text = format_defects(pier_map)
    assert "worst voussoir defect: voussoirs 2, 6 (tied): min(k_l, k_r) 0.1689 -> 0.0842 g" \
        in text
    assert "worst pier defect: left pier, right pier (tied): min(k_l, k_r) 0.1689 -> 0.0753 g, " \
           "-0.0936 g (55.4%)" in text
    assert "voussoirs 0, 10" not in text and "pier courses" in text


def test_joint_map_names_pier_joints(on_piers):
    m = defect_map(on_piers, "tilt", 5.0, indices=[0, 1, 5, 11])
    assert m.places == ("left pier foot", "left springing (pier top)", "arch joint 4",
                        "right pier foot")
    assert m.groups == ("piers", "arch", "arch", "piers")
    assert m.worst_pier_all and set(m.worst_pier_all) <= {0, 11}


def test_a_damaged_arch_on_piers_keeps_its_piers(on_piers):
    d = apply_defect(on_piers, "4:thickness=0.7")
    assert isinstance(d, ArchOnPiers) and d.block_kinds == on_piers.block_kinds


def test_cli_defects_on_piers(capsys):
    assert main(["defects", *PIERS, "--no-progress", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["worst"]["ties"] == [3, 7] and d["worst_pier"]["ties"] == [0, 10]
    assert d["rows"][0]["place"] == "left pier"


# ---------------------------------------------------------------------------- colours
def _faces(fig):
    """The face colours (RGBA) of the damaged blocks, in map order."""
    ax = fig.axes[0]
    return [p.get_facecolor() for p in ax.patches if p.get_zorder() == 1.5]


def test_small_gain_is_pale_and_large_loss_dark(pier_map):
    pytest.importorskip("matplotlib")
    from archrock.reports.plots import defect_norm, plot_defect_map

    # make voussoir 4 (chain 5) gain 0.3% of k: beside a 55% loss it must be near white
    k_l, k_r = pier_map.k_l.copy(), pier_map.k_r.copy()
    k_l[5] = k_r[5] = 1.003 * pier_map.k0
    m = dataclasses.replace(pier_map, k_l=k_l, k_r=k_r)
    assert 100 * m.relative_loss[5] == pytest.approx(-0.3, abs=1e-9)
    fig = plot_defect_map(m)
    faces = _faces(fig)
    assert len(faces) == 11
    gain, loss = np.array(faces[5][:3]), np.array(faces[0][:3])
    assert gain[2] >= gain[0] and gain.min() > 0.9  # blue side, pale
    assert loss[0] > loss[2] and loss.max() < 0.6  # red side, dark
    norm = defect_norm(100 * m.relative_loss)
    assert norm(0.0) == pytest.approx(0.5)  # centred on 0
    assert abs(norm(-0.3) - 0.5) < 0.01 and norm(100 * m.relative_loss.max()) == \
        pytest.approx(1.0)
    bar = fig.axes[1]
    assert "% of undamaged k" in bar.get_ylabel() and "blue: gained" in bar.get_ylabel()
    import matplotlib.pyplot as plt

    plt.close(fig)
